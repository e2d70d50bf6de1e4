using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

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
/// The textured terms of eq. 2 for every material with a diffuse texture: per texel and light the table of
/// I_k ⊙ m_diff (band means and XYZ lanes, × 1/π physical), and when m_amb is the texture too, a_glob ⊙ m_amb and
/// I_amb,k ⊙ m_amb — the same exact products <see cref="TermTables"/> makes for a plain spectrum, for the texel's own
/// spectrum. Band means and colour are linear in the texel's samples, so each light's product is a matrix (bands + XYZ)
/// × samples, built once by projecting the tent function of each sample; a texel's table is that matrix times its
/// samples. Mip levels (Williams 1983) average the tables by area (halving each side, a texel's share by overlap, so
/// every level keeps the mean); a lookup blends the two levels around the footprint's size, bilinear in each.
/// </summary>
public sealed class TextureTables
{
    TextureTables(TexturedTerms?[] of) { Of = of; }

    /// <summary>Per material, its textured terms or null.</summary>
    public TexturedTerms?[] Of { get; }

    /// <summary>The tables of <paramref name="scene"/>'s textured materials, or null when it has none.</summary>
    public static TextureTables? For(Scene scene)
    {
        if (!scene.Materials.Any(m => m.DiffuseTexture is not null)) return null;
        var of = new TexturedTerms?[scene.Materials.Count];
        for (int m = 0; m < of.Length; m++)
        {
            var mat = scene.Materials[m];
            if (mat.DiffuseTexture is not { } binding) continue;
            bool ambient = ReferenceEquals(mat.Ambient, mat.Diffuse);
            of[m] = new TexturedTerms(scene, binding, ambient);
        }
        return new TextureTables(of);
    }

    /// <summary>Bytes the tables of <paramref name="scene"/> take (the pre-render memory check).</summary>
    public static long Bytes(Scene scene)
    {
        long bytes = 0;
        foreach (var m in scene.Materials)
            if (m.DiffuseTexture is { } b)
                bytes += TexturedTerms.TexelsWithMips(b.Texture.Width, b.Texture.Height) * (1 + 2L * scene.Lights.Count) * scene.PaddedBands * sizeof(float);
        return bytes;
    }
}

/// <summary>One material's textured tables: slot 0 a_glob ⊙ m_amb, slot 1 + k I_amb,k ⊙ m_amb, slot 1 + L + k I_k ⊙ m_diff.</summary>
public sealed class TexturedTerms
{
    readonly int _padded;
    readonly int[] _width, _height, _offset;
    readonly UvTransform _uv;

    public TexturedTerms(Scene scene, TextureBinding binding, bool ambient)
    {
        var tex = binding.Texture;
        _uv = binding.Transform;
        _padded = scene.PaddedBands;
        int lights = scene.Lights.Count;
        Slots = 1 + 2 * lights;
        Ambient = ambient;
        // The level sizes: each side halved (rounded down, at least 1) until 1 × 1.
        var w = new List<int> { tex.Width };
        var h = new List<int> { tex.Height };
        while (w[^1] > 1 || h[^1] > 1) { w.Add(Math.Max(1, w[^1] / 2)); h.Add(Math.Max(1, h[^1] / 2)); }
        _width = w.ToArray(); _height = h.ToArray();
        _offset = new int[_width.Length];
        long texels = 0;
        for (int l = 0; l < _width.Length; l++) { _offset[l] = (int)texels; texels += (long)_width[l] * _height[l]; }
        long floats = texels * Slots * _padded;
        if (floats > Array.MaxLength) throw new OutOfMemoryException($"texture {tex.Source}: {floats} floats of tables exceed one array");
        Data = new float[floats];

        // Per slot the (bands + XYZ) × samples matrix of the product with that slot's light.
        bool physical = scene.Radiometry == Radiometry.Physical;
        var matrices = new double[Slots][,];
        var hats = Hats(tex);
        matrices[0] = ambient ? Matrix(scene, scene.GlobalAmbient, hats, 1) : Zero(scene, hats.Length);
        for (int k = 0; k < lights; k++)
        {
            matrices[1 + k] = ambient ? Matrix(scene, scene.Lights[k].Ambient, hats, 1) : Zero(scene, hats.Length);
            matrices[1 + lights + k] = Matrix(scene, scene.Lights[k].Intensity, hats, physical ? 1 / Math.PI : 1);
        }
        int rows = scene.Bands + SpectralMath.ColourLanes, samples = tex.Samples, slots = Slots, padded = _padded;
        var data = Data;
        Parallel.For(0, tex.Height, y =>
        {
            for (int x = 0; x < tex.Width; x++)
            {
                var s = tex.Texel(x, y);
                for (int slot = 0; slot < slots; slot++)
                {
                    var m = matrices[slot];
                    var t = data.AsSpan(((y * tex.Width + x) * slots + slot) * padded, padded);
                    for (int r = 0; r < rows; r++)
                    {
                        double sum = 0;
                        for (int j = 0; j < samples; j++) sum += m[r, j] * s[j];
                        t[r] = (float)sum;
                    }
                }
            }
        });
        for (int l = 1; l < _width.Length; l++) Downsample(l);
    }

    /// <summary>Floats per texel per slot, padded; slots per texel (1 + 2 × lights).</summary>
    public int Slots { get; }
    /// <summary>Is m_amb the texture (it defaulted to m_diff)?</summary>
    public bool Ambient { get; }
    /// <summary>Every level's tables: (texel · <see cref="Slots"/> + slot) · padded.</summary>
    public float[] Data { get; }
    public int Levels => _width.Length;
    public int LevelWidth(int level) => _width[level];
    public int LevelHeight(int level) => _height[level];

    /// <summary>Where texel (x, y) of <paramref name="level"/> starts in <see cref="Data"/>.</summary>
    public int At(int level, int x, int y) => (_offset[level] + y * _width[level] + x) * Slots * _padded;

    /// <summary>The offset of <paramref name="slot"/> within a texel's tables.</summary>
    public int SlotOffset(int slot) => slot * _padded;

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

    /// <summary>Level l from level l − 1: each coarse texel the area-weighted mean of the fine texels it covers (a fine
    /// texel's weights over the coarse ones sum to one, so the level's mean is the finer level's).</summary>
    void Downsample(int l)
    {
        int fw = _width[l - 1], fh = _height[l - 1], cw = _width[l], ch = _height[l];
        var wx = Overlaps(fw, cw);
        var wy = Overlaps(fh, ch);
        int stride = Slots * _padded;
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

    /// <summary>The tent functions of the texture's samples (1 at sample j, 0 at the others, the texture's extrapolation).</summary>
    static TabulatedSpectrum[] Hats(SpectralTexture tex)
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

    static double[,] Zero(Scene scene, int samples) => new double[scene.Bands + SpectralMath.ColourLanes, samples];

    /// <summary>
    /// Column j: the band values and XYZ of light ⊙ tent_j × factor, as <see cref="TermTables"/> makes them for a material
    /// spectrum — exact (<see cref="Colorimeter.ProjectProduct"/>, <see cref="Colorimeter.XyzOfProduct"/>) when the light's
    /// spectrum is known, else the band product and its XYZ.
    /// </summary>
    static double[,] Matrix(Scene scene, float[] light, TabulatedSpectrum[] hats, double factor)
    {
        var cm = scene.Colorimeter;
        int n = scene.Bands;
        var m = new double[n + SpectralMath.ColourLanes, hats.Length];
        if (!SpectralMath.Any(light)) return m;
        bool known = scene.Spectra.TryGetValue(light, out var e);
        for (int j = 0; j < hats.Length; j++)
        {
            double[] bands;
            Xyz xyz;
            if (known)
            {
                bands = cm.ProjectProduct(e!, hats[j]);
                xyz = cm.XyzOfProduct(e!, hats[j]);
            }
            else
            {
                var hatBands = cm.Scheme == BandIntegration.Exact ? BandProjection.Means(hats[j], scene.Grid) : cm.Project(hats[j]);
                bands = new double[n];
                for (int i = 0; i < n; i++) bands[i] = light[i] * hatBands[i];
                xyz = cm.ToXyz(bands);
            }
            for (int i = 0; i < n; i++) m[i, j] = bands[i] * factor;
            m[n, j] = xyz.X * factor; m[n + 1, j] = xyz.Y * factor; m[n + 2, j] = xyz.Z * factor;
        }
        return m;
    }
}
