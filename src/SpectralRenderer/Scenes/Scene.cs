using System.Numerics;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes;

/// <summary>A named object: a shape (analytic or mesh) with a material.</summary>
public sealed class SceneObject
{
    public required string Name { get; init; }
    public required int Material { get; init; }
    public Geometry.AnalyticShape? Shape { get; init; }
    /// <summary>A triangle mesh: in world space, or for an instance in object space (then shared by every instance of it).</summary>
    public Geometry.TriangleMesh? Mesh { get; init; }
    /// <summary>
    /// An instance's object-to-world transform (System.Numerics' row vectors, p_world = p·M; affine, invertible): the
    /// <see cref="Mesh"/> is then a prototype in object space, traced once through its own BVH for all its instances
    /// (docs/scene-format.md, "prototypes"); null for a mesh in world space.
    /// </summary>
    public Matrix4x4? InstanceTransform { get; init; }

    /// <summary>The mesh in world space: <see cref="Mesh"/> itself, or for an instance a transformed copy of its prototype.</summary>
    public Geometry.TriangleMesh? WorldMesh() => Mesh is not { } m || InstanceTransform is not { } x ? Mesh
        : new Geometry.TriangleMesh([.. m.Positions], [.. m.Indices], m.Indices.Length, m.Normals is null ? null : [.. m.Normals], m.Source,
            m.TexCoords is null ? null : [.. m.TexCoords]).Transform(x);
    /// <summary>Interpolate vertex normals (true) or shade with the face normal.</summary>
    public bool Smooth { get; init; } = true;
    /// <summary>
    /// The medium inside it (an index into <see cref="Scene.Media"/>; −1: its surface bounds no medium, a ray that crosses
    /// it stays in its medium). A closed object with outward normals.
    /// </summary>
    public int Medium { get; set; } = -1;
}

/// <summary>What eq. 2's terms mean (docs/scene-format.md, "Radiometry").</summary>
public enum Radiometry
{
    /// <summary>Eq. 2 as the paper and OpenGL write it: relative units, the diffuse lobe ρ·cosθ, unnormalised specular lobes.</summary>
    Paper,
    /// <summary>
    /// Eq. 2 in units: point/spot spectrum × intensity = radiant intensity (W·sr⁻¹·nm⁻¹, inverse square by default),
    /// directional = irradiance facing it (W·m⁻²·nm⁻¹), diffuse ρ/π, energy-normalised Blinn–Phong ((n+8)/8π) and
    /// Phong ((n+2)/2π), ambient = radiance of a uniform surround (a Lambertian surface returns ρ·a).
    /// Band values are spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹.
    /// </summary>
    Physical,
}

/// <summary>
/// The resolved scene: every spectrum already turned into band values on the scene's band grid,
/// ready for an integrator.
/// </summary>
public sealed class Scene
{
    public required string SourcePath { get; init; }
    public required BandGrid Grid { get; init; }
    public required BandIntegration Integration { get; init; }
    public required Observer Observer { get; init; }
    public required TabulatedSpectrum ReferenceWhite { get; init; }
    public required Colorimeter Colorimeter { get; init; }
    public Radiometry Radiometry { get; init; } = Radiometry.Paper;
    /// <summary>One-line warnings about the scene (reflectances above 1, a scene that can only render black), for stderr.</summary>
    public List<string> Warnings { get; init; } = [];
    /// <summary>
    /// The tabulated spectrum behind each band array of the scene (lights' I_k with their intensity, the ambient and
    /// background radiances, every material lobe), by array identity: the integrator integrates their products exactly.
    /// An array without an entry (a zero lobe, a hand-made scene) is used as band values only.
    /// </summary>
    public IReadOnlyDictionary<float[], TabulatedSpectrum> Spectra { get; init; } =
        new Dictionary<float[], TabulatedSpectrum>(ReferenceEqualityComparer.Instance);
    public required Camera Camera { get; set; }
    public required List<Material> Materials { get; init; }
    public required List<Light> Lights { get; init; }
    public required List<SceneObject> Objects { get; init; }
    /// <summary>Window portals (quads with <c>"portal": true</c>): not objects, rays pass them; the sky is drawn through them.</summary>
    public IReadOnlyList<Portal> Portals { get; init; } = [];
    /// <summary>Radiance of rays that escape, band values.</summary>
    public required float[] Background { get; init; }
    /// <summary>
    /// The sky's image (<c>"sky": { "type": "envmap" }</c>), or null: the path integrator's sky then varies with direction,
    /// and <see cref="Background"/> is its mean (the Whitted integrator's uniform sky).
    /// </summary>
    public EnvironmentMap? Environment { get; init; }
    /// <summary>How the daylight sky's radiance varies with direction (<see cref="Background"/> then the zenith's).</summary>
    public SkyDistribution SkyDistribution { get; init; }
    /// <summary>The unit direction of the zenith, up (+Y unless the sky names another): where a non-uniform sky is brightest.</summary>
    public Vector3 Zenith { get; init; } = Vector3.UnitY;
    /// <summary>The participating media of the objects' interiors and of the scene (none in a scene of today).</summary>
    public IReadOnlyList<Medium> Media { get; init; } = [];
    /// <summary>The medium around the objects, where the camera is (an index into <see cref="Media"/>; −1: vacuum).</summary>
    public int Medium { get; init; } = -1;
    /// <summary>a_glob of eq. 2.</summary>
    public required float[] GlobalAmbient { get; init; }
    public bool HasGlobalAmbient { get; init; }
    public int MaxDepth { get; init; } = 5;
    /// <summary>The scene's "integrator" (null: not given; the command line's choice or the default, whitted).</summary>
    public IntegratorSettings? Integrator { get; init; }
    /// <summary>
    /// Adaptive sampling (<c>camera.target_error</c>, <c>--target-error</c>): a pixel stops once the relative standard error
    /// of its mean luminance is at most this, within the camera's spp as the cap; 0: every pixel takes spp samples.
    /// </summary>
    public double TargetError { get; init; }
    /// <summary>
    /// Adaptive tree depth (Hall &amp; Greenberg 1983): a reflected or refracted ray whose accumulated weight — the
    /// product of the k_r, k_t (and Fresnel factors) along its path, at its largest band — falls below this is not
    /// traced, since it cannot change the pixel by more than this fraction of what a directly seen surface shows.
    /// </summary>
    public float MinRayWeight { get; init; } = DefaultMinRayWeight;
    // Off by default: relighting (the per-light transfer) traces the full tree and must equal a render.
    public const float DefaultMinRayWeight = 0f;
    /// <summary>The most rays one camera ray may cost, itself and its shadow, reflected and refracted rays included; beyond it, its
    /// branches end and the ray is counted.</summary>
    public int RayBudget { get; init; } = DefaultRayBudget;
    public const int DefaultRayBudget = 20_000;
    public required OutputOptions Output { get; init; }
    /// <summary>Work planes whose illuminance a render writes ("calculation_grids"; physical radiometry).</summary>
    public IReadOnlyList<CalculationGrid> CalculationGrids { get; init; } = [];
    /// <summary>The resolved scene as JSON (for render.json).</summary>
    public System.Text.Json.Nodes.JsonObject? Resolved { get; init; }

    public int Bands => Grid.Count;
    /// <summary>Triangles over all meshes of the scene.</summary>
    public int TriangleCount => Objects.Sum(o => o.Mesh?.TriangleCount ?? 0);
    public int PaddedBands => SpectralMath.Padded(Grid.Count);
}
