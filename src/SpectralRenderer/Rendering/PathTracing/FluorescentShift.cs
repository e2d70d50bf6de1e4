using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// A fluorescent material's shifted diffuse lobe on the path tracer's sub-band grid (<see cref="SubBandGrid"/>): the re-radiation
/// matrix's off-diagonal part as f_s[o, i] = S[o, i]/π (a Lambertian re-emission, 1/sr; emission sub-band o, excitation i)
/// integrated exactly over sub-band × sub-band (<see cref="ReradiationMatrix.ShiftOnBands(int, Func{int, double}, Func{int, double})"/>),
/// beside the reflective diagonal that the material's BSDF already carries. Next-event estimation adds β ⊙ (f_s·L_e) for a
/// light sample (<see cref="AddEmitted"/>); the path's continuation may choose this lobe (PathIntegrator.Fluorescence.cs),
/// whose throughput then maps every camera sub-band onto the excitation sub-bands (<see cref="Start"/>, <see cref="Chain"/>).
/// Rows are padded to the grid's SIMD length, their padding 0.
/// </summary>
sealed class FluorescentShift
{
    readonly float[] _s;   // [o * padded + i], 1/π folded in
    readonly int _n, _padded;
    readonly int[] _first, _end;   // per row, the SIMD vectors [first, end) that hold its non-zero entries (a shift is band-limited)
    readonly float[] _rowSum;      // Σ_i f_s[o, i]
    readonly float[] _emittedFlat; // S·1 = π·Σ_i f_s[o, i], padded (padding 0): the lobe's albedo under flat light

    public FluorescentShift(ReradiationMatrix matrix, SubBandGrid grid)
    {
        _n = grid.Count;
        _padded = grid.Padded;
        var s = matrix.ShiftOnBands(_n, f => grid.Lower[f], f => grid.Upper[f]);
        _s = new float[_n * _padded];
        var emitted = new float[_padded];   // S·1: the emission per sub-band under unit irradiance in every sub-band
        for (int o = 0; o < _n; o++)
            for (int i = 0; i < _n; i++)
            {
                _s[o * _padded + i] = (float)(s[o * _n + i] / Math.PI);
                emitted[o] += (float)s[o * _n + i];
            }
        // The lobe's share in the continuation's lobe choice, as the smooth lobes' is their albedo's channel value: that of S·1
        // (its albedo under light flat in every band), but at least its largest band — a lobe that turns UV into a few blue
        // bands has little channel value yet carries all of those bands' light (as Russian roulette, too, goes by the largest
        // band); at least 1e-6.
        Share = Math.Max(Math.Max(grid.Luminance(emitted), emitted.Max()), 1e-6f);
        _rowSum = new float[_n];
        for (int o = 0; o < _n; o++) _rowSum[o] = (float)(emitted[o] / Math.PI);
        _emittedFlat = emitted;
        _first = new int[_n];
        _end = new int[_n];
        int width = Vector<float>.Count;
        for (int o = 0; o < _n; o++)
        {
            int lo = -1, hi = -1;
            for (int i = 0; i < _n; i++) if (_s[o * _padded + i] != 0) { if (lo < 0) lo = i; hi = i; }
            if (lo >= 0) { _first[o] = lo / width; _end[o] = hi / width + 1; }
        }
        // The sub-bands it re-emits into (rows with a non-zero entry) and those that excite it (columns with one).
        int rowStart = _n, rowEnd = 0, columnStart = _n, columnEnd = 0;
        for (int o = 0; o < _n; o++)
            for (int i = 0; i < _n; i++)
            {
                if (_s[o * _padded + i] == 0) continue;
                rowStart = Math.Min(rowStart, o); rowEnd = Math.Max(rowEnd, o + 1);
                columnStart = Math.Min(columnStart, i); columnEnd = Math.Max(columnEnd, i + 1);
            }
        Extent = rowEnd > rowStart ? new ShiftSpan(rowStart, rowEnd - rowStart, columnStart, columnEnd - columnStart) : default;
    }

    /// <summary>The emission sub-bands × excitation sub-bands that hold its non-zero entries (the per-light transfer's block).</summary>
    public ShiftSpan Extent { get; }

    /// <summary>f_s[o, i] (1/sr).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float At(int o, int i) => _s[o * _padded + i];

    /// <summary>Row o of f_s (padded).</summary>
    public ReadOnlySpan<float> Row(int o) => _s.AsSpan(o * _padded, _padded);

    /// <summary>
    /// A fixed share of the lobe in the lobe choice (beside the smooth lobes' albedo channel value): only for a path whose
    /// throughput is spent; a path weighs the lobes by their albedos under its β (PathIntegrator.Fluorescence.cs LobeShares).
    /// </summary>
    public float Share { get; }

    /// <summary>S·1 per camera sub-band (padded, padding 0): the lobe's albedo under light flat in every excitation band.</summary>
    public ReadOnlySpan<float> Flat => _emittedFlat;

    /// <summary>Whether wi leaves on the side wo arrives from (the diffuse lobe's hemisphere, as <c>Eq2Bsdf</c> decides it).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool Reflects(Vector3 wo, Vector3 wi, Vector3 n)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        return Vector3.Dot(front, wi) > 0 && Vector3.Dot(front, wo) > 0;
    }

    /// <summary>f_s·E of each light source's fixed spectrum E, keyed by the array itself (<see cref="Prepare"/>).</summary>
    readonly Dictionary<float[], float[]> _emitted = new(ReferenceEqualityComparer.Instance);

    /// <summary>
    /// Computes f_s·E once for each source spectrum of the scene (delta lights, emitters, the sky), so a next-event sample
    /// costs N products instead of N² — up to <paramref name="maxFloats"/> floats; further spectra are multiplied per sample.
    /// </summary>
    public void Prepare(IEnumerable<float[]> spectra, int maxFloats = 1 << 22)
    {
        foreach (var e in spectra)
        {
            if (_emitted.ContainsKey(e)) continue;
            if ((_emitted.Count + 1) * _padded > maxFloats) break;
            var se = new float[_padded];
            var r = V(e.AsSpan(0, _padded));
            for (int o = 0; o < _n; o++) se[o] = Dot(V(_s.AsSpan(o * _padded, _padded)), r, _first[o], _end[o]);
            _emitted[e] = se;
        }
    }

    /// <summary>l[o] += β[o]·Σ_i f_s[o, i]·radiance[i]·scale.</summary>
    public void AddEmitted(Span<float> l, ReadOnlySpan<float> beta, ReadOnlySpan<float> radiance, float scale)
    {
        // The precomputed f_s·E of a source spectrum, found by identity (a light's, an emitter's or the sky's array; an
        // emitter's texel is computed in full).
        ref float r0 = ref MemoryMarshal.GetReference(radiance);
        foreach (var (e, se) in _emitted)
        {
            if (!Unsafe.AreSame(ref MemoryMarshal.GetArrayDataReference(e), ref r0)) continue;
            var vl = V(l[.._padded]);
            var vb = V(beta[.._padded]);
            var ve = V(se.AsSpan());
            var vs = new Vector<float>(scale);
            for (int k = 0; k < vl.Length; k++) vl[k] += vb[k] * ve[k] * vs;
            return;
        }
        AddShifted(l, beta, radiance, scale);
    }

    /// <summary>l[o] += β[o]·Σ_i f_s[o, i]·x[i]·scale, over each row's non-zero span.</summary>
    public void AddShifted(Span<float> l, ReadOnlySpan<float> beta, ReadOnlySpan<float> x, float scale)
    {
        var r = V(x[.._padded]);
        for (int o = 0; o < _n; o++)
        {
            if (beta[o] == 0) continue;
            l[o] += beta[o] * Dot(V(_s.AsSpan(o * _padded, _padded)), r, _first[o], _end[o]) * scale;
        }
    }

    /// <summary>
    /// ‖diag(β·w)·f_s‖∞ = max_o β[o]·w·Σ_i f_s[o, i]: how much a shifted bounce can amplify the light beyond it on its way to
    /// the film (the product over a path's shifted bounces bounds its camera-side transform, for Russian roulette).
    /// </summary>
    public float Gain(ReadOnlySpan<float> beta, float w)
    {
        float g = 0;
        for (int o = 0; o < _n; o++) g = MathF.Max(g, beta[o] * _rowSum[o]);
        return g * w;
    }

    /// <summary>The first shifted bounce of a path: M[o, ·] = β[o]·w·f_s[o, ·] (camera sub-band o, excitation ·).</summary>
    public void Start(Span<float> m, ReadOnlySpan<float> beta, float w)
    {
        for (int o = 0; o < _n; o++)
        {
            var row = V(m.Slice(o * _padded, _padded));
            var s = V(_s.AsSpan(o * _padded, _padded));
            var c = new Vector<float>(beta[o] * w);
            for (int k = 0; k < row.Length; k++) row[k] = s[k] * c;
        }
    }

    /// <summary>A further shifted bounce: M ← M·diag(β·w)·f_s, one row at a time through <paramref name="row"/>.</summary>
    public void Chain(Span<float> m, ReadOnlySpan<float> beta, float w, Span<float> row)
    {
        var r = V(row[.._padded]);
        for (int o = 0; o < _n; o++)
        {
            var mo = m.Slice(o * _padded, _padded);
            r.Clear();
            for (int j = 0; j < _n; j++)
            {
                float c = mo[j] * beta[j] * w;
                if (c == 0) continue;
                var s = V(_s.AsSpan(j * _padded, _padded));
                var vc = new Vector<float>(c);
                for (int k = _first[j]; k < _end[j]; k++) r[k] += s[k] * vc;
            }
            r.CopyTo(V(mo));
        }
    }

    /// <summary>dst[o] += Σ_i M[o, i]·x[i] for the <paramref name="rows"/> camera sub-bands (M's rows padded to x's length).</summary>
    public static void AddProduct(Span<float> dst, ReadOnlySpan<float> m, ReadOnlySpan<float> x, int rows)
    {
        var vx = V(x);
        for (int o = 0; o < rows; o++) dst[o] += Dot(V(m.Slice(o * x.Length, x.Length)), vx, 0, vx.Length);
    }

    /// <summary>dst += x (padded spectra).</summary>
    public static void Add(Span<float> dst, ReadOnlySpan<float> x)
    {
        var d = V(dst);
        var vx = V(x);
        for (int k = 0; k < d.Length; k++) d[k] += vx[k];
    }

    /// <summary>Σ a[k]·b[k] over the vectors [from, end) (the rest of a is 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float Dot(ReadOnlySpan<Vector<float>> a, ReadOnlySpan<Vector<float>> b, int from, int end)
    {
        var s = Vector<float>.Zero;
        for (int k = from; k < end; k++) s += a[k] * b[k];
        return Vector.Sum(s);
    }

    static Span<Vector<float>> V(Span<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);
    static ReadOnlySpan<Vector<float>> V(ReadOnlySpan<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);
}

/// <summary>
/// A block of the sub-band grid's sub-bands: emission rows [Row0, Row0 + Rows) × excitation columns [Column0, Column0 + Columns)
/// — where a scene's fluorescent shifts have non-zero entries (the union's bounding block), so every product of shifted
/// bounces maps excitation in the columns to emission in the rows. Empty (0 × 0) without a shift.
/// </summary>
public readonly record struct ShiftSpan(int Row0, int Rows, int Column0, int Columns)
{
    /// <summary>Floats of one block.</summary>
    public int Size => Rows * Columns;
    public bool IsEmpty => Rows == 0 || Columns == 0;

    /// <summary>The bounding block of two.</summary>
    public ShiftSpan Union(ShiftSpan b)
    {
        if (IsEmpty) return b;
        if (b.IsEmpty) return this;
        int r0 = Math.Min(Row0, b.Row0), r1 = Math.Max(Row0 + Rows, b.Row0 + b.Rows);
        int c0 = Math.Min(Column0, b.Column0), c1 = Math.Max(Column0 + Columns, b.Column0 + b.Columns);
        return new ShiftSpan(r0, r1 - r0, c0, c1 - c0);
    }
}
