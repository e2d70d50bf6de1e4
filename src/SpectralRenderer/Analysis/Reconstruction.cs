using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>
/// Where a pixel lies for the §3.4 analysis (from the render's masks):
/// <list type="bullet">
/// <item>Background — no surface (object id 0);</item>
/// <item>White — a pixel of the white reference itself (the named object or the rectangle);</item>
/// <item>Highlight — mask-highlight set (specular &gt; highlight_fraction × diffuse), whatever the lights;</item>
/// <item>Lit — lit by every light and not a highlight: eq. 2 reduces to (ambient + diffuse) × m_diff, the case
/// white-board calibration gets right when the board sees the same light;</item>
/// <item>Shadow — lit by no light: only the ambient term a_glob·m_amb remains, so the reconstruction is the truth
/// times the ambient/lit irradiance ratio (the paper's "differs by a factor");</item>
/// <item>Partial — lit by some lights but not all (only with two or more lights): the spectrum of the light
/// mixture changes, so it is neither a scale nor exact; reported apart;</item>
/// <item>Unclassified — a surface pixel of a render without masks.</item>
/// </list>
/// </summary>
public enum PixelRegion { Background, White, Lit, Shadow, Partial, Highlight, Unclassified }

/// <summary>The white board's spectrum: the mean radiance over its pixels.</summary>
public sealed record WhiteReference(string Description, double[] Spectrum, bool[] Mask, int Pixels);

/// <summary>One pixel's reconstruction against its ground truth.</summary>
public sealed record PixelReconstruction(int X, int Y, string Label, string Object, PixelRegion Region,
    double[] Radiance, double[] Reflectance, double[] Truth, double Rmse, double Gfc, double DeltaE00, double Scale, double Residual);

/// <summary>Means of the metrics over a region's pixels.</summary>
public sealed record RegionSummary(string Region, int Count, double MeanRmse, double MeanGfc, double MeanDeltaE00, double MeanScale,
    double MeanResidual);

/// <summary>
/// The paper's §3.4 white-board calibration: reflectance(pixel) = pixel radiance ÷ white-board radiance, band by
/// band, where the white board (reflectance 1.0) is seen under the same light. Compared with the ground-truth
/// m_diff by RMSE, GFC, ΔE00 under D65 and the least-squares scale c with its residual (<see cref="SpectralMetrics"/>).
/// Region summaries exclude the background and the white reference's own pixels.
/// </summary>
public sealed class Reconstruction
{
    Reconstruction(RenderFolder folder, RenderAovs aovs, WhiteReference white, SpectralImage reflectance, SpectralImage truth)
    {
        Folder = folder; Aovs = aovs; White = white; Reflectance = reflectance; Truth = truth;
        Colour = ReflectanceDifference.UnderD65(folder.Image.Grid, folder.Integration, folder.ObserverDegrees);
    }

    public RenderFolder Folder { get; }
    public RenderAovs Aovs { get; }
    public WhiteReference White { get; }
    /// <summary>The reconstructed reflectance cube (pixel ÷ white, band by band; 0 where the white is 0).</summary>
    public SpectralImage Reflectance { get; }
    public SpectralImage Truth { get; }
    public ReflectanceDifference Colour { get; }

    public static Reconstruction Compute(RenderFolder folder, RenderAovs aovs, WhiteReference white)
    {
        var truth = aovs.Reflectance
            ?? throw new InputException(folder.Path, "has no ground-truth reflectance (reflectance.npy or reflectance.exr)",
            "render with --formats including aov");
        var image = folder.Image;
        var r = new SpectralImage(image.Width, image.Height, image.Grid);
        int n = image.Bands;
        for (int i = 0; i < image.Width * image.Height; i++)
            for (int b = 0; b < n; b++)
                r.Data[i * n + b] = (float)Divide(image.Data[i * n + b], white.Spectrum[b]);
        return new Reconstruction(folder, aovs, white, r, truth);
    }

    static double Divide(double pixel, double white) => white > 0 ? pixel / white : 0;

    /// <summary>
    /// The mean radiance of the pixels showing the object called <paramref name="name"/>: those lit by
    /// every light and outside highlights when the render has masks (a white board's shadowed part is
    /// not a white reference), else all of them.
    /// </summary>
    public static WhiteReference WhiteObject(RenderFolder folder, string name, RenderAovs? aovs = null)
    {
        int index = folder.ObjectIndex(name);
        if (index < 0)
            throw new InputException("--white-object", $"no object '{name}' in {folder.Path}",
                InputException.DidYouMean(name, folder.ObjectNames) ?? $"objects: {string.Join(", ", folder.ObjectNames.Take(12))}");
        var mask = folder.ObjectIds.Select(id => id == index).ToArray();
        if (aovs is { HasMasks: true })
        {
            var lit = (bool[])mask.Clone();
            for (int i = 0; i < lit.Length; i++)
                lit[i] &= !aovs.Highlight![i] && aovs.Lit!.All(l => l[i]);
            // Inside the lit area only: an anti-aliased pixel on its edge (spp > 1) mixes in shadow or another object,
            // while its masks are those of its centre.
            var inner = Interior(lit, folder.Image.Width);
            if (inner.Any(v => v)) return Mean(folder, inner, $"object '{name}', its fully lit pixels away from edges") with { Mask = lit };
            if (lit.Any(v => v)) return Mean(folder, lit, $"object '{name}', its fully lit pixels");
        }
        return Mean(folder, mask, $"object '{name}'");
    }

    /// <summary>The pixels of the mask whose eight neighbours are in it too (the mask eroded by one pixel).</summary>
    static bool[] Interior(bool[] mask, int width)
    {
        int height = mask.Length / width;
        var inner = new bool[mask.Length];
        for (int y = 1; y < height - 1; y++)
            for (int x = 1; x < width - 1; x++)
            {
                bool all = true;
                for (int dy = -1; dy <= 1 && all; dy++)
                    for (int dx = -1; dx <= 1 && all; dx++) all = mask[(y + dy) * width + x + dx];
                inner[y * width + x] = all;
            }
        return inner;
    }

    /// <summary>
    /// The mean radiance over the rectangle X0,Y0,X1,Y1 of whole-image pixels: columns x0 … x1 − 1, rows y0 … y1 − 1
    /// (X1 and Y1 exclusive, as --crop writes a rectangle).
    /// </summary>
    public static WhiteReference WhiteRegion(RenderFolder folder, int x0, int y0, int x1, int y1, string where = "--white-region")
    {
        var img = folder.Image;
        if (x0 < 0 || y0 < 0 || x1 > img.Width || y1 > img.Height || x1 <= x0 || y1 <= y0)
            throw new InputException(where, $"{x0},{y0},{x1},{y1} is not a non-empty rectangle inside the {img.Width}×{img.Height} image",
                $"X1 and Y1 are exclusive (as for --crop): 0 ≤ X0 < X1 ≤ {img.Width}, 0 ≤ Y0 < Y1 ≤ {img.Height}");
        var mask = new bool[img.Width * img.Height];
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) mask[y * img.Width + x] = true;
        return Mean(folder, mask, $"region {x0},{y0},{x1},{y1} (columns {x0}–{x1 - 1}, rows {y0}–{y1 - 1})");
    }

    static WhiteReference Mean(RenderFolder folder, bool[] mask, string description)
    {
        var img = folder.Image;
        var sum = new double[img.Bands];
        int count = 0;
        for (int i = 0; i < mask.Length; i++)
        {
            if (!mask[i]) continue;
            for (int b = 0; b < sum.Length; b++) sum[b] += img.Data[i * img.Bands + b];
            count++;
        }
        if (count == 0)
            throw new InputException(folder.Path, $"{description} covers no pixel", "choose an object that is visible, or a rectangle");
        for (int b = 0; b < sum.Length; b++) sum[b] /= count;
        if (sum.All(v => v <= 0)) throw new InputException(folder.Path, $"{description} is black", "the white reference must be lit");
        return new WhiteReference(description, sum, mask, count);
    }

    public PixelRegion RegionOf(int i)
    {
        if (Folder.ObjectIds[i] < 0) return PixelRegion.Background;
        if (White.Mask[i]) return PixelRegion.White;
        if (!Aovs.HasMasks) return PixelRegion.Unclassified;
        if (Aovs.Highlight![i]) return PixelRegion.Highlight;
        int lit = Aovs.Lit!.Count(m => m[i]);
        return lit == Aovs.Lit!.Length ? PixelRegion.Lit : lit == 0 ? PixelRegion.Shadow : PixelRegion.Partial;
    }

    public PixelReconstruction At(int x, int y, string label)
    {
        var img = Folder.Image;
        int i = y * img.Width + x, n = img.Bands;
        var radiance = new double[n];
        var est = new double[n];
        var truth = new double[n];
        for (int b = 0; b < n; b++)
        {
            radiance[b] = img.Data[i * n + b];
            est[b] = Divide(radiance[b], White.Spectrum[b]);
            truth[b] = Truth.Data[i * n + b];
        }
        var (c, residual) = SpectralMetrics.Scale(truth, est);
        int id = Folder.ObjectIds[i];
        return new PixelReconstruction(x, y, label, id >= 0 && id < Folder.ObjectNames.Length ? Folder.ObjectNames[id] : "background",
            RegionOf(i),
            radiance, est, truth, SpectralMetrics.Rmse(est, truth), SpectralMetrics.Gfc(est, truth), Colour.DeltaE00(est, truth), c,
                residual);
    }

    /// <summary>Every surface pixel's metrics, excluding the background and the white reference.</summary>
    public List<PixelReconstruction> SurfacePixels()
    {
        var img = Folder.Image;
        var list = new List<PixelReconstruction>();
        for (int y = 0; y < img.Height; y++)
            for (int x = 0; x < img.Width; x++)
                if (RegionOf(y * img.Width + x) is not (PixelRegion.Background or PixelRegion.White)) list.Add(At(x, y, ""));
        return list;
    }

    /// <summary>Per-region means (in <see cref="PixelRegion"/> order, non-empty regions only) and "all" surfaces.</summary>
    public static List<RegionSummary> Summarise(IReadOnlyList<PixelReconstruction> pixels)
    {
        static RegionSummary Of(string name, IReadOnlyCollection<PixelReconstruction> p) => new(name, p.Count,
            p.Average(q => q.Rmse), p.Average(q => q.Gfc), p.Average(q => q.DeltaE00), p.Average(q => q.Scale), p.Average(q => q.Residual));
        var rows = pixels.GroupBy(p => p.Region).OrderBy(g => g.Key).Select(g => Of(Name(g.Key), g.ToList())).ToList();
        if (pixels.Count > 0) rows.Add(Of("all", pixels.ToList()));
        return rows;
    }

    /// <summary>For a figure without chosen pixels: per region, the pixel of median RMSE.</summary>
    public static List<PixelReconstruction> Representatives(IReadOnlyList<PixelReconstruction> pixels) =>
        pixels.GroupBy(p => p.Region).OrderBy(g => g.Key).Select(g =>
        {
            var sorted = g.OrderBy(p => p.Rmse).ToList();
            var m = sorted[sorted.Count / 2];
            return m with { Label = $"{Name(g.Key)} ({m.X},{m.Y})" };
        }).ToList();

    public static string Name(PixelRegion r) => r.ToString().ToLowerInvariant();
}
