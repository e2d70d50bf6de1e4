using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// "photometry" (physical radiometry): photometry.exr with the channels <c>luminance</c> (cd/m², K_m ∫V·L dλ of what each
/// pixel sees) and <c>illuminance</c> (lx arriving at the surface the pixel-centre ray meets, <see cref="Illuminance"/>:
/// from every light with shadows, and under an integrator that gathers (<see cref="IGatherIntegrator"/>: path) area lights,
/// sky and interreflection), and
/// each as a false-colour PNG with its labelled scale as an SVG legend (<see cref="FalseColour"/>). Shards write their
/// rows; `spectral merge` assembles the whole render's files.
/// </summary>
public sealed class PhotometryProduct : OutputProduct
{
    public const string Exr = "photometry.exr";
    public static readonly string[] Quantities = ["luminance", "illuminance"];

    public override string Name => "photometry";
    public override OutputProducts Flag => OutputProducts.Photometry;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height;
        yield return ("photometry", 2 * 4 * n + 3 * n + 4 * n);
    }

    /// <summary>How the illuminance channel was found, as photometry.exr's illuminanceMethod says.</summary>
    public static string Method(RenderTracer? tracer, Scene scene) => tracer is null
        ? "none: a relit render traces no rays (the channel holds 0); render the scene with --formats photometry"
        : tracer.Integrator is IGatherIntegrator
            ? $"lights (shadow rays) + gather of {Illuminance.GatherRays(scene)} samples: area lights and sky by next-event "
                + "estimation and cosine-weighted path-traced rays combined by MIS (power heuristic), interreflection by the "
                + "rays' paths, at the pixel-centre ray's first hit"
            : $"direct from every light (shadow rays) and every emitting object and the sky ({Illuminance.GatherRays(scene)} "
                + "samples of each, shadow rays), at the pixel-centre ray's first hit; no interreflection or ambient (whitted)";

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        var scene = c.Scene;
        if (scene.Radiometry != Radiometry.Physical)
            throw new Diagnostics.InputException("--formats", "photometry (cd/m², lx) needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene");
        var crop = c.Result.Crop;
        var t = c.Tracer;
        var (luminance, illuminance) = new Illuminance(scene, t?.Geometry)
            .Maps(c.Result, t?.Integrator as IGatherIntegrator, t?.Threads ?? 0, c.Cancel,
                t?.Integrator is IGatherIntegrator ? c.StageProgress("photometry gather") : null);
        var attributes = new Dictionary<string, string>
        {
            ["luminanceUnits"] = "cd.m^-2",
            ["illuminanceUnits"] = "lx",
            ["luminanceMethod"] = "K_m * integral of V(lambda) L(lambda), 683 lm/W, CIE 1924 V; mean over the pixel's samples",
            ["illuminanceMethod"] = Method(c.Tracer, scene),
        };
        ExrChannelWriter.Write(Path.Combine(c.OutDir, Exr), crop.Width, crop.Height,
            [("illuminance", illuminance), ("luminance", luminance)],
            attributes, crop.X0, crop.Y0, scene.Camera.Width, scene.Camera.Height);
        done(Exr);
        WritePictures(c.OutDir, crop.Width, crop.Height, luminance, illuminance, done);
    }

    /// <summary>
    /// luminance.png and illuminance.png (false colour on a scale of the whole picture's values) and their SVG legends;
    /// also what `spectral merge` writes from the shards' photometry.exr assembled (the scale needs the whole image).
    /// </summary>
    public static void WritePictures(string dir, int width, int height, float[] luminance, float[] illuminance, Action<string> done)
    {
        foreach (var (quantity, values, unit) in new[] { ("luminance", luminance, "cd/m²"), ("illuminance", illuminance, "lx") })
        {
            var scale = FalseColour.For(values, char.ToUpperInvariant(quantity[0]) + quantity[1..], unit);
            var rgb = scale.Rgb(values);
            AtomicFile.Write(Path.Combine(dir, $"{quantity}.png"), s => PngWriter.WriteRgb8(s, width, height, rgb));
            done($"{quantity}.png");
            AtomicFile.WriteAllText(Path.Combine(dir, $"{quantity}-scale.svg"),
                scale.Legend($"colours of {quantity}.png; values in {Exr}"));
            done($"{quantity}-scale.svg");
        }
    }

    /// <summary>Shards: photometry.exr's scanline chunks are the whole file's; the pictures are drawn again on the whole image.</summary>
    public override ShardMerging Merging(string file) => file == Exr ? ShardMerging.ExrChunks : ShardMerging.FalseColour;

    public override bool Owns(string file) =>
        file is Exr or "luminance.png" or "illuminance.png" or "luminance-scale.svg" or "illuminance-scale.svg";
}
