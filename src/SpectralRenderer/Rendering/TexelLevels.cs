using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes.Textures;

namespace SpectralRenderer.Rendering;

/// <summary>Up to eight texels of a filtered lookup (two mip levels × bilinear): where each texel's tables start and its weight.</summary>
public struct TexelTaps
{
    public int Count;
    public Ints8 At;
    public Floats8 Weight;

    [InlineArray(8)] public struct Ints8 { int _e; }
    [InlineArray(8)] public struct Floats8 { float _e; }
}

/// <summary>
/// A texture's texels with all their mip levels (Williams 1983), <see cref="Stride"/> floats per texel: level 0 the
/// image, each further level both sides halved (rounded down, at least 1) until 1 × 1, each coarse texel the
/// area-weighted mean of the finer texels it covers (a texel's share by overlap, so every level keeps the mean). A
/// lookup blends the two levels around the footprint's size, bilinear in each (trilinear). What a texel's floats mean
/// is the subclass's: eq. 2's per-light tables (<see cref="TexturedTerms"/>), or a spectrum on the path tracer's fine
/// grid (<see cref="FineTexture"/>). The tables are built once and shared by every thread.
/// </summary>
public abstract class TexelLevels
{
    readonly int[] _width, _height, _offset;
    readonly UvTransform _uv;

    /// <summary>The levels of a <paramref name="width"/> × <paramref name="height"/> image, <paramref name="stride"/> floats per texel, placed by <paramref name="uv"/>.</summary>
    protected TexelLevels(string source, int width, int height, int stride, UvTransform uv)
    {
        _uv = uv;
        Stride = stride;
        var w = new List<int> { width };
        var h = new List<int> { height };
        while (w[^1] > 1 || h[^1] > 1) { w.Add(Math.Max(1, w[^1] / 2)); h.Add(Math.Max(1, h[^1] / 2)); }
        _width = w.ToArray(); _height = h.ToArray();
        _offset = new int[_width.Length];
        long texels = 0;
        for (int l = 0; l < _width.Length; l++) { _offset[l] = (int)texels; texels += (long)_width[l] * _height[l]; }
        long floats = texels * stride;
        if (floats > Array.MaxLength) throw new OutOfMemoryException($"texture {source}: {floats} floats of tables exceed one array");
        Data = new float[floats];
    }

    /// <summary>Floats per texel.</summary>
    public int Stride { get; }
    /// <summary>Every level's texels: texel · <see cref="Stride"/>.</summary>
    public float[] Data { get; }
    public int Levels => _width.Length;
    public int LevelWidth(int level) => _width[level];
    public int LevelHeight(int level) => _height[level];

    /// <summary>Where texel (x, y) of <paramref name="level"/> starts in <see cref="Data"/>.</summary>
    public int At(int level, int x, int y) => (_offset[level] + y * _width[level] + x) * Stride;

    /// <summary>Texels of a w × h image with all its mip levels.</summary>
    public static long TexelsWithMips(int w, int h)
    {
        long n = (long)w * h;
        while (w > 1 || h > 1) { w = Math.Max(1, w / 2); h = Math.Max(1, h / 2); n += (long)w * h; }
        return n;
    }

    /// <summary>
    /// The texels to blend at surface coordinates <paramref name="uv"/> for a footprint <paramref name="width"/> wide in uv
    /// units: the mip level where a texel is the footprint's size (log2 of its width in level-0 texels of the longer side),
    /// bilinear in the two levels around it, weighted by the fraction between them (trilinear).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void Lookup(Vector2 uv, float width, out TexelTaps taps)
    {
        taps = default;
        var st = _uv.Apply(uv);
        float texels = width * _uv.Stretch * Math.Max(_width[0], _height[0]);
        float lod = texels > 1 ? MathF.Log2(texels) : 0;
        if (!float.IsFinite(lod)) lod = 0;
        lod = Math.Min(lod, Levels - 1);
        int l0 = (int)lod;
        float f = lod - l0;
        Bilinear(l0, st, 1 - f, ref taps);
        if (f > 0 && l0 + 1 < Levels) Bilinear(l0 + 1, st, f, ref taps);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void Bilinear(int level, Vector2 st, float weight, ref TexelTaps taps)
    {
        int w = _width[level], h = _height[level];
        float s = st.X * w - 0.5f, t = (1 - st.Y) * h - 0.5f;   // v up: row 0 at v = 1
        if (!float.IsFinite(s) || !float.IsFinite(t)) { s = 0; t = 0; }
        float xf = MathF.Floor(s), yf = MathF.Floor(t);
        float fx = s - xf, fy = t - yf;
        int x0 = (int)Math.Clamp(xf, -1e8f, 1e8f), y0 = (int)Math.Clamp(yf, -1e8f, 1e8f);
        var wrap = _uv.Wrap;
        int xa = UvTransform.WrapIndex(x0, w, wrap), xb = UvTransform.WrapIndex(x0 + 1, w, wrap);
        int ya = UvTransform.WrapIndex(y0, h, wrap), yb = UvTransform.WrapIndex(y0 + 1, h, wrap);
        Add(ref taps, At(level, xa, ya), weight * (1 - fx) * (1 - fy));
        Add(ref taps, At(level, xb, ya), weight * fx * (1 - fy));
        Add(ref taps, At(level, xa, yb), weight * (1 - fx) * fy);
        Add(ref taps, At(level, xb, yb), weight * fx * fy);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void Add(ref TexelTaps taps, int at, float weight)
    {
        if (weight == 0) return;
        taps.At[taps.Count] = at;
        taps.Weight[taps.Count] = weight;
        taps.Count++;
    }

    /// <summary>Every level above 0 from the one below it (call once level 0 is filled).</summary>
    protected void BuildMips()
    {
        for (int l = 1; l < _width.Length; l++) Downsample(l);
    }

    /// <summary>Level l from level l − 1: each coarse texel the area-weighted mean of the fine texels it covers (a fine
    /// texel's weights over the coarse ones sum to one, so the level's mean is the finer level's).</summary>
    void Downsample(int l)
    {
        int fw = _width[l - 1], fh = _height[l - 1], cw = _width[l], ch = _height[l];
        var wx = Overlaps(fw, cw);
        var wy = Overlaps(fh, ch);
        int stride = Stride;
        var data = Data;
        Parallel.For(0, ch, cy =>
        {
            var acc = new double[stride];
            for (int cx = 0; cx < cw; cx++)
            {
                Array.Clear(acc);
                foreach (var (fy, wyv) in wy[cy])
                    foreach (var (fx, wxv) in wx[cx])
                    {
                        double wgt = wyv * wxv;
                        var src = data.AsSpan(At(l - 1, fx, fy), stride);
                        for (int i = 0; i < stride; i++) acc[i] += wgt * src[i];
                    }
                var dst = data.AsSpan(At(l, cx, cy), stride);
                for (int i = 0; i < stride; i++) dst[i] = (float)acc[i];
            }
        });
    }

    /// <summary>Per coarse cell i of [i·r, (i + 1)·r) (r = fine/coarse), the fine cells it overlaps and overlap / r.</summary>
    static List<(int, double)>[] Overlaps(int fine, int coarse)
    {
        double r = (double)fine / coarse;
        var result = new List<(int, double)>[coarse];
        for (int i = 0; i < coarse; i++)
        {
            result[i] = [];
            double lo = i * r, hi = (i + 1) * r;
            for (int j = (int)Math.Floor(lo); j < Math.Min(fine, (int)Math.Ceiling(hi)); j++)
            {
                double overlap = Math.Min(hi, j + 1) - Math.Max(lo, j);
                if (overlap > 0) result[i].Add((j, overlap / r));
            }
        }
        return result;
    }
}
