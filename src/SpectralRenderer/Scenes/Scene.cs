using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes;

/// <summary>A named object: a shape (analytic or mesh) with a material.</summary>
public sealed class SceneObject
{
    public required string Name { get; init; }
    public required int Material { get; init; }
    public Geometry.AnalyticShape? Shape { get; init; }
    /// <summary>A triangle mesh in world space.</summary>
    public Geometry.TriangleMesh? Mesh { get; init; }
    /// <summary>Interpolate vertex normals (true) or shade with the face normal.</summary>
    public bool Smooth { get; init; } = true;
}

/// <summary>Output choices of a render (the scene's "output" block, overridable on the command line).</summary>
public sealed class OutputOptions
{
    public RgbSpace Rgb { get; set; } = RgbSpace.Srgb;
    public double Exposure { get; set; } = 1.0;
    /// <summary>Bradford-adapt from the scene's reference white to the RGB space's white (off by default: §3.3 is about seeing the light's colour).</summary>
    public bool Adapt { get; set; }
    /// <summary>A pixel is in a highlight when its specular term's luminance exceeds this fraction of the diffuse term's.</summary>
    public double HighlightFraction { get; set; } = 0.1;
    public HashSet<string> Formats { get; set; } = new(OutputFormats.Default, StringComparer.Ordinal);
    /// <summary>How spectral.exr is compressed: "zip" (deflate the chunks whose samples repeat, store the rest), "zip-all" (deflate every chunk: smallest, slowest) or "none".</summary>
    public string ExrCompression { get; set; } = "zip";
    public static readonly string[] ExrCompressions = ["zip", "zip-all", "none"];
}

public static class OutputFormats
{
    /// <summary>Every format; "lights" (the per-light transfer, lights/) is opt-in: not in the default set.</summary>
    public static readonly string[] All = ["png", "bands", "exr", "envi", "npy", "aov", "lights"];
    public static readonly string[] Default = ["png", "bands", "exr", "envi", "npy", "aov"];
}

/// <summary>
/// The resolved scene: every spectrum already turned into band values on the scene's band grid,
/// ready for the <see cref="Rendering.WhittedIntegrator"/>.
/// </summary>
public sealed class Scene
{
    public required string SourcePath { get; init; }
    public required BandGrid Grid { get; init; }
    public required BandIntegration Integration { get; init; }
    public required Observer Observer { get; init; }
    public required TabulatedSpectrum ReferenceWhite { get; init; }
    public required Colorimeter Colorimeter { get; init; }
    public required Camera Camera { get; set; }
    public required List<Material> Materials { get; init; }
    public required List<Light> Lights { get; init; }
    public required List<SceneObject> Objects { get; init; }
    /// <summary>Radiance of rays that escape, band values.</summary>
    public required float[] Background { get; init; }
    /// <summary>a_glob of eq. 2.</summary>
    public required float[] GlobalAmbient { get; init; }
    public bool HasGlobalAmbient { get; init; }
    public int MaxDepth { get; init; } = 5;
    public required OutputOptions Output { get; init; }
    /// <summary>The resolved scene as JSON (for render.json).</summary>
    public System.Text.Json.Nodes.JsonObject? Resolved { get; init; }

    public int Bands => Grid.Count;
    public int PaddedBands => Rendering.SpectralMath.Padded(Grid.Count);
}
