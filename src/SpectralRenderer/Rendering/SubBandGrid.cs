using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>
/// The path tracer's internal spectral grid: every output band split into <see cref="PerBand"/> equal sub-bands no wider
/// than the requested width (5 nm by default), so an output band is exactly the mean of its sub-bands; or, adaptive (the
/// default width when a scene does not set one), as many sub-bands in all but more of them in the bands where the scene's
/// spectra change fast and fewer where they are smooth (SubBandGrid.Adaptive.cs), equal within each band. A spectrum's value
/// on a sub-band is its exact mean there (<see cref="TabulatedSpectrum.Mean"/>); products along a path are taken
/// sub-band by sub-band, so multi-bounce products are products at this resolution, not of output-band means. Colour is
/// integrated on this grid: X = κ·Σ_f L_f·∫_f x̄ dλ (and Y, Z). Spectra are padded float arrays (<see cref="Padded"/>
/// lanes, a multiple of <see cref="Vector{T}.Count"/>) for whole-vector arithmetic.
/// </summary>
[CompiledAtFirstCall]
internal sealed partial class SubBandGrid
{
    readonly Scene _scene;
    readonly float[] _wx, _wy, _wz;
    readonly float[] _bandMean;   // 1/n of each output band's n sub-bands

    /// <summary>
    /// The grid of <paramref name="scene"/> at <paramref name="width"/> nm: uniform, or with <paramref name="adaptive"/> the
    /// same number of sub-bands spread over the output bands where the scene's spectra need them (SubBandGrid.Adaptive.cs),
    /// when the uniform grid's predicted error calls for it.
    /// </summary>
    public SubBandGrid(Scene scene, double width, bool adaptive = false)
    {
        _scene = scene;
        var grid = scene.Grid;
        Bands = grid.Count;
        int perBand = Math.Max(1, (int)Math.Ceiling(grid.Width / width - 1e-9));
        var counts = adaptive ? AdaptiveCounts(scene, perBand) : null;
        PerBand = counts is null ? perBand : 0;
        BandStart = new int[Bands + 1];
        for (int b = 0; b < Bands; b++) BandStart[b + 1] = BandStart[b] + (counts is null ? perBand : counts[b]);
        Count = BandStart[Bands];
        _bandMean = new float[Bands];
        for (int b = 0; b < Bands; b++) _bandMean[b] = 1f / (BandStart[b + 1] - BandStart[b]);
        Padded = SpectralMath.Padded(Count);
        Lower = new double[Count];
        Upper = new double[Count];
        for (int b = 0; b < Bands; b++)
        {
            int n = BandStart[b + 1] - BandStart[b], f0 = BandStart[b];
            double lo = grid.Lower(b), w = (grid.Upper(b) - lo) / n;
            for (int j = 0; j < n; j++)
            {
                Lower[f0 + j] = lo + j * w;
                Upper[f0 + j] = j == n - 1 ? grid.Upper(b) : lo + (j + 1) * w;
            }
        }
        // Colour weights κ·∫_f x̄ dλ per sub-band (CIE 015 eq. 7.1 on the sub-band grid) and the luminance-like channel.
        var obs = scene.Observer;
        double kappa = scene.Colorimeter.Kappa;
        _wx = new float[Padded]; _wy = new float[Padded]; _wz = new float[Padded];
        Channel = new float[Padded];
        double peak = 0;
        for (int f = 0; f < Count; f++)
        {
            _wx[f] = (float)(kappa * obs.XBar.Integrate(Lower[f], Upper[f]));
            _wy[f] = (float)(kappa * obs.YBar.Integrate(Lower[f], Upper[f]));
            _wz[f] = (float)(kappa * obs.ZBar.Integrate(Lower[f], Upper[f]));
            peak = Math.Max(peak, _wy[f] / (Upper[f] - Lower[f]));
        }
        // Sampling decisions (lobe choice, Russian roulette) weigh sub-bands by ȳ with a floor of a tenth of its peak, so a band
        // outside the visible still keeps its path alive; the weights sum to 1, so a spectrum of ones has channel value 1.
        double sum = 0;
        var c = new double[Count];
        for (int f = 0; f < Count; f++)
        {
            double y = peak > 0 ? _wy[f] / (Upper[f] - Lower[f]) / peak : 0;
            c[f] = (0.1 + y) * (Upper[f] - Lower[f]);
            sum += c[f];
        }
        for (int f = 0; f < Count; f++) Channel[f] = (float)(c[f] / sum);
    }

    /// <summary>Output bands.</summary>
    public int Bands { get; }
    /// <summary>Sub-bands per output band of a uniform grid; 0 when the grid is adaptive (see <see cref="BandStart"/>).</summary>
    public int PerBand { get; }
    /// <summary>Output band b's sub-bands are [BandStart[b], BandStart[b + 1]), of equal width within the band.</summary>
    public int[] BandStart { get; }
    /// <summary>Every output band split into the same number of sub-bands.</summary>
    public bool Uniform => PerBand > 0;
    /// <summary>Sub-bands in all.</summary>
    public int Count { get; }
    /// <summary>The length of a sub-band spectrum (padded for SIMD).</summary>
    public int Padded { get; }
    public double[] Lower { get; }
    public double[] Upper { get; }
    /// <summary>The luminance-like channel's weights (sum 1).</summary>
    public float[] Channel { get; }

    /// <summary>
    /// A scene spectrum (padded band values) on this grid: the exact sub-band means of the tabulated spectrum behind it
    /// (<see cref="Scene.Spectra"/>), else each band value repeated over its sub-bands (the band means are kept either way).
    /// </summary>
    public float[] Resample(float[] bands)
    {
        var fine = new float[Padded];
        if (_scene.Spectra.TryGetValue(bands, out var s))
            for (int f = 0; f < Count; f++) fine[f] = (float)s.Mean(Lower[f], Upper[f]);
        else
            for (int b = 0; b < Bands; b++)
                for (int f = BandStart[b]; f < BandStart[b + 1]; f++) fine[f] = bands[b];
        return fine;
    }

    /// <summary>The channel value Σ c_f·v_f of a sub-band spectrum.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Luminance(ReadOnlySpan<float> v)
    {
        var a = MemoryMarshal.Cast<float, Vector<float>>(v[..Padded]);
        var c = MemoryMarshal.Cast<float, Vector<float>>(Channel.AsSpan());
        var s = Vector<float>.Zero;
        for (int i = 0; i < a.Length; i++) s += a[i] * c[i];
        return Vector.Sum(s);
    }

    /// <summary>
    /// A sub-band radiance to the film: each output band the mean of its sub-bands, and X, Y, Z integrated on the sub-band grid
    /// into the colour lanes after the bands.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void Reduce(ReadOnlySpan<float> fine, Span<float> result)
    {
        result.Clear();
        float inv = 1f / PerBand;
        ref float f = ref MemoryMarshal.GetReference(fine[..Count]);
        ref float r = ref MemoryMarshal.GetReference(result[..Bands]);
        if (!Uniform)
        {   // an adaptive grid: each band the mean of its own count of equal sub-bands (1/n kept per band: no division here)
            ref int end = ref MemoryMarshal.GetArrayDataReference(BandStart);
            ref float mean = ref MemoryMarshal.GetArrayDataReference(_bandMean);
            for (int b = 0, j = 0; b < Bands; b++)
            {
                float s = 0;
                for (int stop = Unsafe.Add(ref end, b + 1); j < stop; j++) s += Unsafe.Add(ref f, j);
                Unsafe.Add(ref r, b) = s * Unsafe.Add(ref mean, b);
            }
        }
        else if (PerBand == 4)   // the default 5-nm grid under 20-nm bands: the same sums, unrolled and without bounds checks
            for (int b = 0; b < Bands; b++)
            {
                ref float q = ref Unsafe.Add(ref f, 4 * b);
                Unsafe.Add(ref r, b) = (0 + q + Unsafe.Add(ref q, 1) + Unsafe.Add(ref q, 2) + Unsafe.Add(ref q, 3)) * inv;
            }
        else
            for (int b = 0; b < Bands; b++)
            {
                float s = 0;
                for (int j = 0; j < PerBand; j++) s += Unsafe.Add(ref f, b * PerBand + j);
                Unsafe.Add(ref r, b) = s * inv;
            }
        var l = MemoryMarshal.Cast<float, Vector<float>>(fine[..Padded]);
        var x = MemoryMarshal.Cast<float, Vector<float>>(_wx.AsSpan());
        var y = MemoryMarshal.Cast<float, Vector<float>>(_wy.AsSpan());
        var z = MemoryMarshal.Cast<float, Vector<float>>(_wz.AsSpan());
        Vector<float> sx = default, sy = default, sz = default;
        for (int i = 0; i < l.Length; i++) { sx += l[i] * x[i]; sy += l[i] * y[i]; sz += l[i] * z[i]; }
        result[Bands] = Vector.Sum(sx);
        result[Bands + 1] = Vector.Sum(sy);
        result[Bands + 2] = Vector.Sum(sz);
    }
}
