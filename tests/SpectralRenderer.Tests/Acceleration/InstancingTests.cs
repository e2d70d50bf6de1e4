using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>
/// Instancing (one BVH per prototype mesh, rays taken into each instance's object space) against the second method the
/// loader already has: the same mesh transformed into world space and traced in world space (a "mesh" object with the same
/// "transform").
/// </summary>
public class InstancingTests(ITestOutputHelper output)
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    /// <summary>A UV sphere of unit radius with its vertex normals, as "inline" JSON: 2·<paramref name="rings"/>·<paramref
    /// name="segments"/> triangles (the poles' fans included, each a triangle with one pole corner).</summary>
    internal static string Sphere(int rings, int segments)
    {
        var p = new List<Vector3>();
        for (int i = 0; i <= rings; i++)
            for (int j = 0; j < segments; j++)
            {
                double theta = Math.PI * i / rings, phi = 2 * Math.PI * j / segments;
                p.Add(new Vector3((float)(Math.Sin(theta) * Math.Cos(phi)), (float)Math.Cos(theta),
                    (float)(Math.Sin(theta) * Math.Sin(phi))));
            }
        var idx = new List<int>();
        for (int i = 0; i < rings; i++)
            for (int j = 0; j < segments; j++)
            {
                int a = i * segments + j, b = i * segments + (j + 1) % segments, c = a + segments, d = b + segments;
                idx.AddRange([a, b, c, b, d, c]);
            }
        string F(float x) => x.ToString("R", Inv);
        string list = string.Join(", ", p.Select(v => $"{F(v.X)}, {F(v.Y)}, {F(v.Z)}"));
        return $"{{ \"positions\": [{list}], \"normals\": [{list}], \"indices\": [{string.Join(", ", idx)}] }}";
    }

    /// <summary>Placements: rotations about two axes, uniform and non-uniform scales, a mirror, translations; none overlap.</summary>
    static readonly string[] Transforms =
    [
        """{ "translate": [-2.2, 0, 0] }""",
        """{ "scale": 0.8, "rotate": [30, 45, 0], "translate": [0, 0, 0] }""",
        """{ "scale": [1.3, 0.6, 0.9], "rotate": [0, 0, 20], "translate": [2.3, 0.2, 0] }""",
        """{ "matrix": [-0.9, 0, 0, -1.1, 0, 0.9, 0, 2.1, 0, 0, 0.9, -0.5, 0, 0, 0, 1] }""",
        """{ "scale": 0.5, "rotate": [10, 0, 70], "translate": [1.2, 2.0, 0.3] }""",
    ];

    /// <summary>A scene with the sphere placed by each transform: as instances of one prototype, or as meshes (copies).</summary>
    static string Scene(bool instanced, string[] transforms, string shading, string integrator = "whitted")
    {
        string mesh = Sphere(16, 32);
        var objects = new StringBuilder();
        for (int i = 0; i < transforms.Length; i++)
        {
            string material = i % 2 == 0 ? "red" : "white";
            objects.Append(instanced
                ? $$"""{ "type": "instance", "name": "ball-{{i}}", "prototype": "ball", "material": "{{material}}", """
                : $$"""{ "type": "mesh", "name": "ball-{{i}}", "inline": {{mesh}}, "shading": "{{shading}}", """
                    + $$""" "material": "{{material}}", """);
            objects.Append($$""" "transform": {{transforms[i]}} },""");
            objects.Append('\n');
        }
        string prototypes = instanced ? $$""" "prototypes": { "ball": { "inline": {{mesh}}, "shading": "{{shading}}" } },""" : "";
        return $$"""
        { "bands": "400:700:3", "integrator": "{{integrator}}",{{prototypes}}
          "camera": { "position": [0, 1, 9], "look_at": [0, 0.6, 0], "fov": 40, "width": 64, "height": 48 },
          "materials": { "red": { "diffuse": 0.7, "specular": 0.3, "shininess": 30 }, "white": { "diffuse": 0.9 },
                         "floor": { "diffuse": 0.5 } },
          "ambient": { "name": "D65", "scale": 0.05 },
          "lights": [ { "type": "point", "position": [3, 6, 5], "spectrum": "D65", "intensity": 40 } ],
          "objects": [ {{objects}}
            { "type": "plane", "name": "floor", "point": [0, -1.2, 0], "material": "floor" } ]
        }
        """;
    }

    static Scene Load(string json) => SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(Path.GetTempPath(), "scene.json"));

    /// <summary>
    /// Every ray's closest hit through the instances equals the world-space hit of the transformed mesh: the same object, the
    /// same distance and normals to float rounding (the ray is rounded into object space, the mesh into world space: both at
    /// a few ulps of the coordinates, far below 1e-4 of the distance). Rays that graze an edge may pick the neighbouring
    /// triangle or miss by rounding: at most 0.1 % of them. Occlusion agrees with the closest hit.
    /// </summary>
    [Fact]
    public void TransformedRayHitsEqualWorldSpaceHits()
    {
        var instanced = new SceneGeometry(Load(Scene(true, Transforms, "smooth")));
        var flat = new SceneGeometry(Load(Scene(false, Transforms, "smooth")));
        Assert.Equal(flat.TriangleCount, instanced.TriangleCount);
        Assert.Equal(1, instanced.PrototypeCount);
        var rng = new Random(17);
        int n = 20000, hits = 0, onInstances = 0, differ = 0;
        double worstT = 0, worstN = 0;
        for (int i = 0; i < n; i++)
        {
            var target = new Vector3(-3.5f + 7 * rng.NextSingle(), -1 + 4 * rng.NextSingle(), -1.5f + 3 * rng.NextSingle());
            var from = 12 * Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.2f, rng.NextSingle() - 0.5f));
            var d = (i % 3 == 0 ? 1 : 0.25f) * (target - from);   // unnormalised directions too: t is in units of |d|
            var r1 = new Ray(from, d);
            var r2 = r1;
            bool h1 = instanced.Intersect(ref r1, out var a), h2 = flat.Intersect(ref r2, out var b);
            Assert.Equal(h1, instanced.Occluded(new Ray(from, d)));
            if (h1) Assert.True(instanced.Occluded(new Ray(from, d, a.T * 1.0001f)) && !instanced.Occluded(new Ray(from, d, a.T * 0.999f)));
            if (h1 != h2 || h1 && a.Object != b.Object) { differ++; continue; }
            if (!h1) continue;
            hits++;
            if (a.Kind == 4) onInstances++;
            worstT = Math.Max(worstT, Math.Abs(a.T - b.T) / b.T);
            worstN = Math.Max(worstN, Math.Max((a.GeometricNormal - b.GeometricNormal).Length(), (a.Normal - b.Normal).Length()));
            Assert.Equal(a.Kind == 4 ? 4 : b.Kind, a.Kind);
        }
        output.WriteLine($"{hits} hits ({onInstances} on instances) of {n} rays, {differ} differ; worst relative Δt "
            + $"{worstT:e2}, worst |Δn| {worstN:e2}");
        Assert.True(onInstances > n / 10, $"only {onInstances} hits on the instances");
        Assert.True(differ <= n / 1000, $"{differ} rays differ");
        Assert.True(worstT < 1e-4, $"relative Δt {worstT}");
        Assert.True(worstN < 1e-3, $"|Δn| {worstN}");
    }

    /// <summary>Identity placements: the instanced ray is the world ray bit for bit, and with flat shading the picture (Whitted's
    /// packet path, shadows included) and the object ids are byte-identical to the copied meshes'.</summary>
    [Fact]
    public void IdentityInstancesRenderByteIdenticalToCopies()
    {
        string[] identity = ["""{ "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }"""];
        var a = Render(Scene(true, identity, "flat"));
        var b = Render(Scene(false, identity, "flat"));
        Assert.Equal(b.ObjectIds, a.ObjectIds);
        Assert.Equal(b.Xyz, a.Xyz);
        Assert.Contains(0, a.ObjectIds);
    }

    /// <summary>
    /// The five placed spheres rendered (Whitted, smooth shading, shadows) as instances and as transformed copies: the object
    /// ids agree on all but a few silhouette pixels and the colours of the others agree to float rounding (relative 1e-4),
    /// but for a few pixels at shadow edges.
    /// </summary>
    [Fact]
    public void InstancedSceneRendersAsItsCopies()
    {
        var a = Render(Scene(true, Transforms, "smooth"));
        var b = Render(Scene(false, Transforms, "smooth"));
        int pixels = a.ObjectIds.Length, ids = 0, colours = 0;
        for (int i = 0; i < pixels; i++)
        {
            if (a.ObjectIds[i] != b.ObjectIds[i]) { ids++; continue; }
            for (int c = 0; c < 3; c++)
                if (Math.Abs(a.Xyz![3 * i + c] - b.Xyz![3 * i + c]) > 1e-4 * Math.Max(1e-3, b.Xyz[3 * i + c])) { colours++; break; }
        }
        output.WriteLine($"{ids} of {pixels} object ids differ, {colours} colours differ by more than 1e-4");
        Assert.True(a.ObjectIds.Distinct().Count() >= 6);
        Assert.True(ids <= pixels / 200, $"{ids} object ids differ");
        Assert.True(colours <= pixels / 100, $"{colours} colours differ");
    }

    /// <summary>An instance whose material emits is loaded as a copy in world space (the area light samples world triangles):
    /// its triangles are the prototype's placed by the transform, as the mesh object with that transform has them.</summary>
    [Fact]
    public void EmittingInstanceIsCopiedIntoWorldSpace()
    {
        string json = Scene(true, Transforms, "smooth").Replace("{ \"bands\"", "{ \"radiometry\": \"physical\", \"bands\"")
            .Replace("\"white\": { \"diffuse\": 0.9 }",
            "\"white\": { \"diffuse\": 0.9, \"emission\": { \"spectrum\": \"D65\", \"radiance\": 1 } }");
        var scene = Load(json);
        var copies = Load(Scene(false, Transforms, "smooth"));
        for (int i = 0; i < Transforms.Length; i++)
        {
            var o = scene.Objects[i];
            Assert.Equal(i % 2 == 1, o.InstanceTransform is null);   // the white (emitting) ones are copied
            var world = o.WorldMesh()!;
            var reference = copies.Objects[i].Mesh!;
            Assert.Equal(reference.TriangleCount, world.TriangleCount);
            for (int t = 0; t < world.TriangleCount; t += 97)
                Assert.True((world.Triangle(t).P1 - reference.Triangle(t).P1).Length() < 1e-5f);
        }
    }

    static RenderResult Render(string json)
    {
        var scene = Load(json);
        var integrator = Integrators.Create(scene, new SceneGeometry(scene), scene.Integrator!.Name);
        return Renderer.Render(scene, integrator, threads: 2);
    }
}
