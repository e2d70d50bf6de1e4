using SpectralRenderer.Color;

namespace SpectralRenderer.Scenes;

/// <summary>The products a render can write (the scene's "output.formats", or --formats), as flags.</summary>
[Flags]
public enum OutputProducts
{
    None = 0,
    /// <summary>preview.png: eq. 3 then eq. 4 / sRGB, 8 bits.</summary>
    Png = 1,
    /// <summary>bands/: one 16-bit PNG per band, and the mosaic bands.png (Fig. 2).</summary>
    Bands = 2,
    /// <summary>spectral.exr: the spectral OpenEXR layout with R, G, B and X, Y, Z.</summary>
    Exr = 4,
    /// <summary>spectral.hdr / spectral.img: the ENVI cube.</summary>
    Envi = 8,
    /// <summary>spectral.npy: the H × W × N NumPy array.</summary>
    Npy = 16,
    /// <summary>object-id.png and the analysis images (lit and highlight masks, ground-truth reflectance).</summary>
    Aov = 32,
    /// <summary>lights/: the per-light transfer for relighting (opt-in: not in <see cref="All"/>; "light_groups" in a scene).</summary>
    Lights = 64,
    /// <summary>photometry.exr and false-colour maps: luminance (cd/m²) seen and illuminance (lx) at the surface seen (opt-in).</summary>
    Photometry = 128,
    /// <summary>noise.npy, noise.img/.hdr and stderr channels in spectral.exr: each pixel's standard error per band and of
    /// luminance (opt-in: not in <see cref="All"/>; needs spp ≥ 2).</summary>
    Noise = 256,
    /// <summary>grids/NAME.csv and .svg: the illuminance (lx) on the scene's calculation grids (set by "calculation_grids").</summary>
    Grids = 512,
    All = Png | Bands | Exr | Envi | Npy | Aov,
}

/// <summary>How spectral.exr is compressed.</summary>
public enum ExrCompressionChoice
{
    /// <summary>"zip": deflate the chunks whose samples repeat, store the rest.</summary>
    Zip,
    /// <summary>"zip-all": deflate every chunk (smallest, slowest).</summary>
    ZipAll,
    /// <summary>"none": no compression.</summary>
    None,
}

/// <summary>The names a scene file and the command line use for <see cref="OutputProducts"/> and
/// <see cref="ExrCompressionChoice"/>.</summary>
public static class OutputNames
{
    public static readonly IReadOnlyList<(OutputProducts Product, string Name)> Products =
    [
        (OutputProducts.Png, "png"), (OutputProducts.Bands, "bands"), (OutputProducts.Exr, "exr"),
        (OutputProducts.Envi, "envi"), (OutputProducts.Npy, "npy"), (OutputProducts.Aov, "aov"), (OutputProducts.Lights, "lights"),
        (OutputProducts.Photometry, "photometry"),
        (OutputProducts.Noise, "noise"), (OutputProducts.Grids, "grids"),
    ];

    public static readonly IReadOnlyList<(ExrCompressionChoice Choice, string Name)> ExrCompressions =
        [(ExrCompressionChoice.Zip, "zip"), (ExrCompressionChoice.ZipAll, "zip-all"), (ExrCompressionChoice.None, "none")];

    public static string[] ProductNames => Products.Select(p => p.Name).ToArray();
    public static string[] ExrCompressionNames => ExrCompressions.Select(p => p.Name).ToArray();

    /// <summary>The scene-file name of an EXR compression choice.</summary>
    public static string Name(ExrCompressionChoice c) => ExrCompressions.First(p => p.Choice == c).Name;
}

/// <summary>Output choices of a render (the scene's "output" block, overridable on the command line).</summary>
public sealed class OutputOptions
{
    public RgbSpace Rgb { get; set; } = RgbSpace.Srgb;
    /// <summary>The preview's exposure (XYZ multiplier before the RGB matrix); see <see cref="ExposureAuto"/>.</summary>
    public double Exposure { get; set; } = 1.0;
    /// <summary><c>"exposure": "auto"</c>: the 99th percentile of the display-linear maximum channel of the non-black pixels maps to
    /// 1.</summary>
    public bool ExposureAuto { get; set; }

    /// <summary>
    /// --exposure's text as the preview's exposure: (true, 1) for "auto", else (false, the multiplier: a finite number in
    /// 0–1e12, the range of the scene's "exposure"); bad input under <paramref name="where"/>.
    /// </summary>
    public static (bool Auto, double Exposure) ParseExposure(string text, string where = "--exposure")
    {
        if (string.Equals(text.Trim(), "auto", StringComparison.OrdinalIgnoreCase)) return (true, 1);
        if (!double.TryParse(text, System.Globalization.NumberStyles.Float, System.Globalization.CultureInfo.InvariantCulture,
                out double e) || !double.IsFinite(e) || e < 0 || e > 1e12)
            throw new Diagnostics.InputException(where, $"{Diagnostics.MessageText.Quote(text)} is neither auto nor a number in 0–1e12",
                "e.g. --exposure 0.01 (a multiplier on XYZ) or --exposure auto");
        return (false, e);
    }
    /// <summary>How the preview brings out-of-gamut colours inside (<c>"gamut": "clip"</c>, the default, or <c>"desaturate"</c>).</summary>
    public GamutMapping Gamut { get; set; } = GamutMapping.Clip;
    /// <summary>Bradford-adapt from the scene's reference white to the RGB space's white (off by default: §3.3 is about seeing the light's
    /// colour).</summary>
    public bool Adapt { get; set; }
    /// <summary>A pixel is in a highlight when its specular term's luminance exceeds this fraction of the diffuse term's.</summary>
    public double HighlightFraction { get; set; } = 0.1;
    public OutputProducts Products { get; set; } = OutputProducts.All;
    public ExrCompressionChoice ExrCompression { get; set; } = ExrCompressionChoice.Zip;
}
