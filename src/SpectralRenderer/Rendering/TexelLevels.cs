using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>Up to eight texels of a filtered lookup (two mip levels × bilinear): where each texel's tables start (its
/// chunk and the offset in it, <see cref="TexelLevels.Tap"/>) and its weight.</summary>
public struct TexelTaps
{
    public int Count;
    public Ints8 Chunk;
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
/// is the subclass's: eq. 2's per-light tables (<c>TexturedTerms</c>), or a spectrum on the path tracer's sub-band
/// grid (<see cref="SubBandTexture"/>). The tables are built once and shared by every thread.
/// Storage is tiled: each level is cut into square tiles of <see cref="TileSide"/> texels (the last column and row of
/// tiles clipped to the level, so no texel is padding), a tile's texels row by row and contiguous (a bilinear lookup's
/// four texels mostly share one tile), whole tiles packed into chunks (arrays) of at most <see cref="DefaultChunkFloats"/>
/// floats: the tables' size is bounded by memory, not by the largest array.
/// </summary>
public abstract class TexelLevels
{
    /// <summary>Texels along a tile's side (a power of two; smaller when a tile of it would not fit a chunk).</summary>
    public const int DefaultTileSide = 32;
    /// <summary>Floats a chunk holds at most: 256 MiB, well below the 2 GiB of one array.</summary>
    public const int DefaultChunkFloats = 1 << 26;
    /// <summary>The tile side and chunk size of tables built on this flow (tests: several chunks of a small texture).</summary>
    internal static readonly AsyncLocal<(int TileSide, int ChunkFloats)?> Layout = new();

    readonly int[] _width, _height;
    readonly (int Width, int TilesX, int FirstTile)[] _levels;   // per level, what finding a texel's tile takes
    readonly (int Chunk, int At)[] _tiles;   // per tile (levels in order, each row by row): its chunk and first float there
    readonly float[][] _chunks;
    readonly int _shift, _mask;
    readonly UvTransform _uv;

    /// <summary>The levels of a <paramref name="width"/> × <paramref name="height"/> image, <paramref name="stride"/> floats per texel,
    /// placed by <paramref name="uv"/>.</summary>
    protected TexelLevels(string source, int width, int height, int stride, UvTransform uv)
    {
        _uv = uv;
        Stride = stride;
        var w = new List<int> { width };
        var h = new List<int> { height };
        while (w[^1] > 1 || h[^1] > 1) { w.Add(Math.Max(1, w[^1] / 2)); h.Add(Math.Max(1, h[^1] / 2)); }
        _width = w.ToArray(); _height = h.ToArray();
        var (side, cap) = Layout.Value ?? (DefaultTileSide, DefaultChunkFloats);
        cap = Math.Min(cap, Array.MaxLength);
        if (stride > cap) throw new OutOfMemoryException($"texture {source}: a texel's {stride} floats exceed a chunk");
        while (side > 1 && (long)side * side * stride > cap) side /= 2;
        TileSide = side;
        _shift = BitOperations.Log2((uint)side);
        _mask = side - 1;
        _levels = new (int, int, int)[_width.Length];
        long tiles = 0;
        for (int l = 0; l < _width.Length; l++)
        {
            int across = (_width[l] + _mask) >> _shift;
            _levels[l] = (_width[l], across, checked((int)tiles));
            tiles += (long)across * ((_height[l] + _mask) >> _shift);
        }
        _tiles = new (int, int)[checked((int)tiles)];
        // Whole tiles into chunks, in order, a new chunk where the next tile would overflow the current one.
        var sizes = new List<int>();
        long filled = 0;
        int tile = 0;
        for (int l = 0; l < _width.Length; l++)
            for (int ty = 0; ty < _height[l]; ty += side)
                for (int tx = 0; tx < _width[l]; tx += side)
                {
                    long floats = (long)Math.Min(side, _width[l] - tx) * Math.Min(side, _height[l] - ty) * stride;
                    if (sizes.Count == 0 || filled + floats > cap)
                    {
                        if (sizes.Count > 0) sizes[^1] = (int)filled;
                        sizes.Add(0);
                        filled = 0;
                    }
                    _tiles[tile] = (sizes.Count - 1, (int)filled);
                    filled += floats;
                    tile++;
                }
        sizes[^1] = (int)filled;
        _chunks = new float[sizes.Count][];
        for (int c = 0; c < _chunks.Length; c++) _chunks[c] = new float[sizes[c]];
    }

    /// <summary>Floats per texel.</summary>
    public int Stride { get; }
    public int Levels => _width.Length;
    public int LevelWidth(int level) => _width[level];
    public int LevelHeight(int level) => _height[level];
    /// <summary>Texels along a tile's side.</summary>
    public int TileSide { get; }
    /// <summary>The arrays the tiles are packed in.</summary>
    public int Chunks => _chunks.Length;
    /// <summary>Bytes of the tables as allocated (every chunk's floats).</summary>
    public long AllocatedBytes => _chunks.Sum(c => (long)c.Length) * sizeof(float);

    /// <summary>Where texel (x, y) of <paramref name="level"/> is: its chunk and its first float there.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int At(int level, int x, int y, out int chunk)
    {
        var (width, across, first) = _levels[level];
        int tx = x >> _shift;
        var (c, at) = _tiles[first + (y >> _shift) * across + tx];
        int tw = Math.Min(_mask + 1, width - (tx << _shift));   // the last column of tiles is clipped
        chunk = c;
        return at + ((y & _mask) * tw + (x & _mask)) * Stride;
    }

    /// <summary>Texel (x, y) of <paramref name="level"/>: its <see cref="Stride"/> floats.</summary>
    public Span<float> Texel(int level, int x, int y)
    {
        int at = At(level, x, y, out int chunk);
        return _chunks[chunk].AsSpan(at, Stride);
    }

    /// <summary>Tap <paramref name="i"/>'s texel: its <see cref="Stride"/> floats.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public ReadOnlySpan<float> Tap(in TexelTaps taps, int i) => _chunks[taps.Chunk[i]].AsSpan(taps.At[i], Stride);

    /// <summary>Every texel of every level, in storage order (<paramref name="apply"/> gets each chunk's run of whole texels).</summary>
    protected void ForEachChunk(Action<Span<float>> apply)
    {
        foreach (var c in _chunks) apply(c);
    }

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
        var (w, across, first) = _levels[level];
        int h = _height[level];
        float s = st.X * w - 0.5f, t = (1 - st.Y) * h - 0.5f;   // v up: row 0 at v = 1
        if (!float.IsFinite(s) || !float.IsFinite(t)) { s = 0; t = 0; }
        float xf = MathF.Floor(s), yf = MathF.Floor(t);
        float fx = s - xf, fy = t - yf;
        int x0 = (int)Math.Clamp(xf, -1e8f, 1e8f), y0 = (int)Math.Clamp(yf, -1e8f, 1e8f);
        var wrap = _uv.Wrap;
        int xa = UvTransform.WrapIndex(x0, w, wrap), xb = UvTransform.WrapIndex(x0 + 1, w, wrap);
        int ya = UvTransform.WrapIndex(y0, h, wrap), yb = UvTransform.WrapIndex(y0 + 1, h, wrap);
        // The two columns' tiles and widths (the last column of tiles clipped), the two rows' first tiles.
        int txa = xa >> _shift, txb = xb >> _shift;
        int twa = Math.Min(_mask + 1, w - (txa << _shift)), twb = Math.Min(_mask + 1, w - (txb << _shift));
        int ra = first + (ya >> _shift) * across, rb = first + (yb >> _shift) * across;
        int la = ya & _mask, lb = yb & _mask;
        Add(ref taps, ra + txa, la * twa + (xa & _mask), weight * (1 - fx) * (1 - fy));
        Add(ref taps, ra + txb, la * twb + (xb & _mask), weight * fx * (1 - fy));
        Add(ref taps, rb + txa, lb * twa + (xa & _mask), weight * (1 - fx) * fy);
        Add(ref taps, rb + txb, lb * twb + (xb & _mask), weight * fx * fy);
    }

    /// <summary>The texel <paramref name="texel"/> places into tile <paramref name="tile"/>, weighted, unless the weight is 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void Add(ref TexelTaps taps, int tile, int texel, float weight)
    {
        if (weight == 0) return;
        var (chunk, at) = _tiles[tile];
        taps.Chunk[taps.Count] = chunk;
        taps.At[taps.Count] = at + texel * Stride;
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
                        var src = Texel(l - 1, fx, fy);
                        for (int i = 0; i < stride; i++) acc[i] += wgt * src[i];
                    }
                var dst = Texel(l, cx, cy);
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

    /// <summary>The tent functions of the texture's samples (1 at sample j, 0 at the others, the texture's extrapolation).</summary>
    internal static TabulatedSpectrum[] Hats(SpectralTexture tex)
    {
        var hats = new TabulatedSpectrum[tex.Samples];
        for (int j = 0; j < hats.Length; j++)
        {
            var v = new double[tex.Samples];
            v[j] = 1;
            hats[j] = new TabulatedSpectrum($"{tex.Source} sample {j}", tex.Wavelengths, v, tex.Extrapolation);
        }
        return hats;
    }
}
