using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>
/// The analysis layers ("aov") a render writes beside its bands, read back: mask-lit-&lt;k&gt;.png per light k
/// (255 = the surface at the pixel centre is lit by light k: n·l &gt; 0, inside its cone, shadow ray unblocked),
/// mask-highlight.png (255 = eq. 2's specular term exceeds highlight_fraction × the diffuse term), and the
/// ground-truth diffuse reflectance m_diff per pixel (reflectance.npy, else reflectance.exr with T.&lt;λ&gt;nm
/// channels). Any of them may be absent (older renders); the properties are then null.
/// </summary>
public sealed class RenderAovs
{
    /// <summary>Per light k, per pixel (row-major): lit by light k.</summary>
    public bool[][]? Lit { get; init; }
    public string[] LightNames { get; init; } = [];
    public bool[]? Highlight { get; init; }
    public double? HighlightFraction { get; init; }
    /// <summary>m_diff of the surface seen at each pixel, 0 for background.</summary>
    public SpectralImage? Reflectance { get; init; }

    public bool HasMasks => Lit is not null && Highlight is not null;

    public static RenderAovs Open(RenderFolder folder)
    {
        var dir = folder.Path;
        var image = folder.Image;
        var names = new List<string>();
        var files = new List<string>();
        foreach (var light in folder.Manifest.Lights)
        {
            names.Add(light.Name);
            files.Add(Path.Combine(dir, $"mask-lit-{light.Index}.png"));
        }
        bool[][]? lit = files.Count > 0 && files.All(File.Exists) ? files.Select(f => ReadMask(f, image)).ToArray() : null;
        var hl = Path.Combine(dir, "mask-highlight.png");
        return new RenderAovs
        {
            Lit = lit,
            LightNames = names.ToArray(),
            Highlight = File.Exists(hl) ? ReadMask(hl, image) : null,
            HighlightFraction = folder.Manifest.HighlightFraction,
            Reflectance = ReadReflectance(dir, image),
        };
    }

    static bool[] ReadMask(string path, SpectralImage image)
    {
        var png = PngReader.Read(path);
        if (png.Width != image.Width || png.Height != image.Height)
            throw new InputException(path, $"is {png.Width}×{png.Height} but the cube is {image.Width}×{image.Height}",
                "the render folder mixes files of different renders: render it again");
        int full = (1 << png.BitDepth) - 1;
        var mask = new bool[png.Width * png.Height];
        for (int i = 0; i < mask.Length; i++) mask[i] = png.Samples[i * png.Channels] * 2 > full;
        return mask;
    }

    static SpectralImage? ReadReflectance(string dir, SpectralImage image)
    {
        var npy = Path.Combine(dir, "reflectance.npy");
        var exr = Path.Combine(dir, "reflectance.exr");
        SpectralImage r;
        if (File.Exists(npy)) r = NpyReader.ReadImage(npy, image.Grid);
        else if (File.Exists(exr)) r = ExrReader.Read(exr).Image;
        else return null;
        if (r.Width != image.Width || r.Height != image.Height || r.Bands != image.Bands)
            throw new InputException(File.Exists(npy) ? npy : exr,
                $"is {r.Width}×{r.Height}×{r.Bands} but the cube is {image.Width}×{image.Height}×{image.Bands}",
                "the render folder mixes files of different renders: render it again");
        return r;
    }
}
