using System.Numerics;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Color;

/// <summary>How a display colour outside [0, 1]³ is brought inside.</summary>
public enum GamutMapping
{
    /// <summary>Clip each channel to [0, 1] (colorimetric where in gamut; the paper's and sRGB's behaviour).</summary>
    Clip,
    /// <summary>
    /// Keep the hue: a colour with a negative channel is desaturated toward the display white at constant luminance
    /// (c' = Y + t·(c − Y), the largest t ≥ 0 that makes every channel ≥ 0), then a colour with a channel above 1
    /// is scaled down so that its largest channel is 1 (hue and saturation kept, luminance lowered).
    /// </summary>
    Desaturate,
}

/// <summary>
/// Pixel colours → display RGB: XYZ (eq. 3 through the scene's <see cref="Colorimeter"/>, or the exact XYZ of a pixel),
/// exposure, optional Bradford adaptation from the scene white to the RGB space's white, then eq. 4
/// (paper) or sRGB, gamut-mapped (<see cref="GamutMapping"/>) and encoded.
/// </summary>
public sealed class DisplayEncoder
{
    readonly Colorimeter _colorimeter;
    readonly double[,] _toRgb;
    readonly double _exposure;
    readonly GamutMapping _gamut;

    public DisplayEncoder(Colorimeter colorimeter, RgbSpace space, double exposure = 1, bool adapt = false,
        GamutMapping gamut = GamutMapping.Clip)
    {
        _colorimeter = colorimeter;
        Space = space;
        _exposure = exposure;
        _gamut = gamut;
        // The scene white is taken at Y = 1 for the adaptation, so absolute scaling keeps its luminance.
        var white = colorimeter.White * (1 / colorimeter.White.Y);
        _toRgb = adapt ? Matrix3.Multiply(space.FromXyz, ChromaticAdaptation.BradfordMatrix(white, space.White)) : space.FromXyz;
    }

    public RgbSpace Space { get; }
    public double Exposure => _exposure;
    public GamutMapping Gamut => _gamut;

    /// <summary>The colorimeter of eq. 3, whose <see cref="Colorimeter.ToXyz(ReadOnlySpan{float})"/> <see cref="Encode8(Xyz)"/>
    /// expects.</summary>
    public Colorimeter Colorimeter => _colorimeter;

    public Xyz Xyz(ReadOnlySpan<float> bands) => _colorimeter.ToXyz(bands) * _exposure;

    /// <summary>Linear RGB (unclipped, not gamut-mapped) of a pixel spectrum.</summary>
    public (double R, double G, double B) Linear(ReadOnlySpan<float> bands)
    {
        var v = Matrix3.Apply(_toRgb, Xyz(bands));
        return (v.X, v.Y, v.Z);
    }

    /// <summary>8-bit display RGB of a pixel spectrum.</summary>
    public (byte R, byte G, byte B) Encode8(ReadOnlySpan<float> bands) => Encode8(_colorimeter.ToXyz(bands));

    /// <summary>8-bit display RGB of a pixel whose XYZ (before exposure) is <paramref name="xyz"/>.</summary>
    public (byte R, byte G, byte B) Encode8(Xyz xyz)
    {
        var (r, g, b) = Mapped(xyz * _exposure);
        return (Space.Encode8(r), Space.Encode8(g), Space.Encode8(b));
    }

    /// <summary>Display-linear RGB of an XYZ (exposure already applied) after the gamut mapping (still unclipped under
    /// <see cref="GamutMapping.Clip"/>).</summary>
    public (double R, double G, double B) Mapped(Xyz xyz)
    {
        var v = Matrix3.Apply(_toRgb, xyz);
        if (_gamut == GamutMapping.Clip) return (v.X, v.Y, v.Z);
        return Desaturate(v.X, v.Y, v.Z, xyz.Y);
    }

    /// <summary><see cref="GamutMapping.Desaturate"/> of linear RGB whose luminance is <paramref name="y"/> (the display white at luminance
    /// y is (y, y, y)).</summary>
    public static (double R, double G, double B) Desaturate(double r, double g, double b, double y)
    {
        if (!(y > 0)) return (0, 0, 0);
        double min = Math.Min(r, Math.Min(g, b));
        if (min < 0)
        {
            double t = y / (y - min);   // the mix with the white that lifts the lowest channel to 0, luminance kept
            r = y + t * (r - y); g = y + t * (g - y); b = y + t * (b - y);
        }
        double max = Math.Max(r, Math.Max(g, b));
        if (max > 1) { r /= max; g /= max; b /= max; }
        return (Math.Max(r, 0), Math.Max(g, 0), Math.Max(b, 0));
    }

    /// <summary>
    /// The exposure of <c>"exposure": "auto"</c>: 1 / the <paramref name="percentile"/> of the display-linear maximum channel
    /// (after the hue-keeping desaturation, before scaling) over the pixels that are not black; 1 for a black image.
    /// </summary>
    public static double AutoExposure(Colorimeter colorimeter, RgbSpace space, bool adapt, int count, Func<int, Xyz> xyzOf,
        double percentile = 0.99)
    {
        var probe = new DisplayEncoder(colorimeter, space, 1, adapt, GamutMapping.Clip);
        var maxima = new List<double>(count);
        for (int i = 0; i < count; i++)
        {
            var xyz = xyzOf(i);
            var (r, g, b) = probe.Mapped(xyz);
            if (!(xyz.Y > 0)) continue;
            double min = Math.Min(r, Math.Min(g, b));
            if (min < 0)
            {
                double t = xyz.Y / (xyz.Y - min);
                r = xyz.Y + t * (r - xyz.Y); g = xyz.Y + t * (g - xyz.Y); b = xyz.Y + t * (b - xyz.Y);
            }
            double m = Math.Max(r, Math.Max(g, b));
            if (m > 0 && double.IsFinite(m)) maxima.Add(m);
        }
        if (maxima.Count == 0) return 1;
        double p = Select(CollectionsMarshal.AsSpan(maxima), Math.Min(maxima.Count - 1, (int)Math.Floor(percentile * (maxima.Count - 1))));
        return p > 0 ? 1 / p : 1;
    }

    /// <summary>
    /// The k-th smallest value (k from 0) — what sorting and indexing give — by selection in linear expected time
    /// (Hoare's FIND with a median-of-three pivot and a three-way partition, so runs of equal values cost one pass);
    /// after 2·log₂n + 8 rounds the rest of the range is sorted. Reorders <paramref name="values"/>.
    /// </summary>
    internal static double Select(Span<double> values, int k)
    {
        int lo = 0, hi = values.Length - 1, rounds = 2 * BitOperations.Log2((uint)values.Length) + 8;
        while (lo < hi)
        {
            if (--rounds < 0) { values[lo..(hi + 1)].Sort(); return values[k]; }
            double a = values[lo], b = values[lo + (hi - lo) / 2], c = values[hi];
            double pivot = Math.Max(Math.Min(a, b), Math.Min(Math.Max(a, b), c));
            // [lo, lt) < pivot, [lt, i) == pivot, (gt, hi] > pivot.
            int lt = lo, i = lo, gt = hi;
            while (i <= gt)
            {
                double v = values[i];
                if (v < pivot) { values[i++] = values[lt]; values[lt++] = v; }
                else if (v > pivot) { values[i] = values[gt]; values[gt--] = v; }
                else i++;
            }
            if (k < lt) hi = lt - 1;
            else if (k > gt) lo = gt + 1;
            else return pivot;
        }
        return values[k];
    }
}
