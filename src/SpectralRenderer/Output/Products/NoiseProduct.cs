using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// "noise": how exact the render is, per pixel — the standard error of the pixel's mean from its own samples, s/√n (s² the
/// unbiased sample variance of its n samples), per band (W·m⁻²·sr⁻¹·nm⁻¹ in physical radiometry, as the bands) and of
/// luminance Y (the unit of render.json's colour.xyz): noise.npy (H × W × (N + 1), the bands then Y), noise.img/.hdr (ENVI,
/// the same N + 1 bands) and, when spectral.exr is written, its channels stderr.S0.&lt;λ&gt;nm and stderr.Y beside the bands.
/// render.json's sampling.noise sums it up (mean and max relative error of luminance).
/// </summary>
public sealed class NoiseProduct : OutputProduct
{
    public override string Name => "noise";
    public override OutputProducts Flag => OutputProducts.Noise;

    /// <summary>The EXR layer of the standard errors beside the bands.</summary>
    public const string ExrLayer = "stderr.";

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height;
        yield return ("noise", 2 * 4 * n * (scene.Bands + 1));
    }

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        var noise = c.Result.Noise ?? throw new InvalidOperationException("the noise product needs a render with per-pixel statistics");
        var image = c.Image;
        int w = image.Width, h = image.Height, channels = image.Bands + 1;
        NpyWriter.Write(Path.Combine(c.OutDir, "noise.npy"), noise, [h, w, channels]);
        done("noise.npy");
        var planes = Planes(noise, w * h, channels);
        var g = image.Grid;
        var names = Enumerable.Range(0, g.Count)
            .Select(b => FormattableString.Invariant($"stderr {g.Lower(b):0.###}-{g.Upper(b):0.###} nm"))
            .Append("stderr luminance Y").ToList();
        EnviWriter.WritePlanes(Path.Combine(c.OutDir, "noise.img"), w, h, planes, names,
            $"SpectralRenderer standard error of each pixel's mean from its samples (s/sqrt(n)) for "
                + $"{Path.GetFileName(c.Scene.SourcePath)}: " +
            $"bands 1-{g.Count} in {RenderOutputWriter.RadianceUnit(c.Scene)}, band {channels} of luminance Y (as "
                + $"render.json radiometry.xyz states it)",
            new Dictionary<string, string> { ["radiometry"] = c.Scene.Radiometry.ToString().ToLowerInvariant() });
        done("noise.img");
        done("noise.hdr");
    }

    /// <summary>Pixel-interleaved values (pixels × channels) as band-sequential planes.</summary>
    internal static float[] Planes(float[] interleaved, int pixels, int channels)
    {
        var planes = new float[interleaved.Length];
        for (int i = 0; i < pixels; i++)
            for (int k = 0; k < channels; k++) planes[k * pixels + i] = interleaved[i * channels + k];
        return planes;
    }

    /// <summary>spectral.exr's channels of the standard errors: stderr.S0.&lt;λ&gt;nm per band and stderr.Y.</summary>
    internal static List<(string Name, float[] Plane)> ExrChannels(Scene scene, float[] noise, int pixels)
    {
        int channels = scene.Bands + 1;
        var planes = Planes(noise, pixels, channels);
        var list = new List<(string, float[])>();
        for (int k = 0; k < channels; k++)
            list.Add((ExrLayer + (k < scene.Bands ? ExrWriter.SpectralChannelName(scene.Grid.Centre(k)) : "Y"),
                planes.AsSpan(k * pixels, pixels).ToArray()));
        return list;
    }

    public override bool Owns(string file) => file is "noise.npy" or "noise.img" or "noise.hdr";

    public override ShardMerging Merging(string file) => file switch
    {
        "noise.npy" => ShardMerging.NoiseNpy,
        "noise.img" => ShardMerging.NoiseEnvi,
        _ => ShardMerging.NoiseEnviHeader,
    };
}
