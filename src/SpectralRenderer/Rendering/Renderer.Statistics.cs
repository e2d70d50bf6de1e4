using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// A render that says how exact it is: each pixel's standard error from its own samples, per band and of luminance, by a
// method right for its sampler (docs/scene-format.md, "Error estimates"), and adaptive sampling that stops a pixel once its
// relative standard error of luminance, by a conservative rule, reaches a target.
public sealed partial class Renderer
{
    /// <summary>Samples a pixel takes before adaptive sampling may stop it (fewer when the cap is lower): the variance of
    /// fewer samples is too uncertain to stop on.</summary>
    public const int MinAdaptiveSamples = 16;

    /// <summary>A worker's tile with per-pixel statistics: its scratch, allocated once per worker.</summary>
    sealed class StatisticsTileState(IIntegrator integrator, PixelSampling sampling, Film film, int padded, float[] noise, int[]? used,
        double target, CancellationToken cancel) : ITileWork
    {
        readonly float[] _scratch = new float[integrator.ScratchLength];
        readonly float[] _sum = new float[padded], _sample = new float[padded];
        readonly float[] _shift = new float[padded], _s1 = new float[padded], _s2 = new float[padded];
        readonly float[] _groups = new float[Sampler.Randomisations * padded];
        readonly float[] _previous = new float[padded], _adjacent = new float[padded];

        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
        {
            var sink = new RadianceSamples(integrator, integrator as IAnalysisIntegrator, film, _sum, _sample, _scratch, sampling.Spp);
            var stats = new SampleStatistics(film, _sample, _shift, _s1, _s2, _groups,
                _previous, _adjacent, sampling.Sampler.Kind == SamplerKind.Sobol, target > 0 ? 0 : sampling.StrataX);
            int cap = sampling.Spp, minimum = Math.Min(cap, MinAdaptiveSamples), budget = sampling.Budget;
            // Sobol: a pixel stops only after whole rounds of its randomisations (each then has as many samples).
            int round = sampling.Sampler.Kind == SamplerKind.Sobol ? Sampler.Randomisations : 1;
            int bands = film.Image.Bands;
            for (int y = y0; y < y1; y++)
                for (int x = x0; x < x1; x++)
                {
                    cancel.ThrowIfCancellationRequested();
                    sink.BeginPixel(x, y, ref counters);
                    _sum.AsSpan().Clear();
                    int n = 0;
                    for (int s = 0; s < cap; s++)
                    {
                        // a stop waits for one camera ray's tree at most
                        if (cancel.IsCancellationRequested) cancel.ThrowIfCancellationRequested();
                        // Non-adaptive: weight 1/spp as the plain loop sums it (the same picture); adaptive: weight 1, scaled at the end.
                        long fallback = counters.Fallback;
                        Camera(ref sink, sampling.Sample(x, y, s), target > 0 ? 1f : sampling.Weight, false, budget, ref counters);
                        stats.Add(n++, counters.Fallback != fallback);
                        if (target > 0 && n >= minimum && n % round == 0 && stats.Converged(n, target)) break;
                    }
                    if (target > 0) SpectralMath.SetScaled(_sum, _sum, 1f / n);
                    int id = sampling.Analysis ? Camera(ref sink, sampling.Centre(x, y), 0f, true, budget, ref counters) : -1;
                    int i = (y - film.Y0) * film.Image.Width + (x - film.X0);
                    stats.StandardErrors(n, noise.AsSpan(i * (bands + 1), bands + 1));
                    if (used is not null) used[i] = n;
                    sink.EndPixel(x, y, id, ref counters);
                }
        }
    }

    /// <summary>
    /// A pixel's samples, summed shifted by its first sample K (d = x − K, Σd, Σd²: exact 0 for a constant pixel, and no
    /// cancellation of large means), per band and of luminance Y (the colour lane; eq. 3 on the bands for a sample whose
    /// colour lanes fell back), and Σd per randomisation of the Sobol sampler (sample s in randomisation g = s mod R,
    /// <see cref="Sampler.Randomisations"/>). The standard error of the pixel mean:
    /// <list type="bullet">
    /// <item>independent samples (adaptive sampling: no cells): s/√n, s² = (Σd² − (Σd)²/n)/(n − 1) the unbiased sample
    /// variance;</item>
    /// <item>independent samples on the film jitter's m × n cells (one sample each, <see cref="PixelSampling"/>): the mean's
    /// variance is Σσ²_cell/n², not s²/n (s² also holds the spread of the cells' means: the pixel's edges, 2× too much on a
    /// path scene); σ²_cell estimated from neighbours in a row of cells, Σ(x_s − x_{s−1})²/(2P) over its P pairs (the
    /// collapsed-strata estimator; conservative by the difference of neighbouring cells' means, 5–15 % on a path scene);</item>
    /// <item>Sobol: the samples of one scrambled net are not independent (stratified, their errors cancel), so s/√n
    /// overstates the error (by 2–7× on a path scene); its R randomisations are, and the variance of the pixel mean
    /// x̄ = Σ_g n_g·x̄_g/n is estimated from their means x̄_g without bias as V = R′/(R′ − 1)·Σ_g (n_g/n)²·(x̄_g − x̄)²
    /// = R′/(R′ − 1)·Σ_g (D_g − n_g·d̄)²/n² (D_g = Σd of randomisation g, R′ = min(R, n) of them; for equal n_g it is the
    /// textbook Σ(x̄_g − x̄)²/(R(R − 1)); Owen 1997, L'Ecuyer &amp; Lemieux 2002 §3).</item>
    /// </list>
    /// </summary>
    readonly struct SampleStatistics(Film film, float[] sample, float[] shift, float[] s1, float[] s2, float[] groups,
        float[] previous, float[] adjacent, bool sobol, int strataX)
    {
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Add(int index, bool fallback)
        {
            int bands = film.Image.Bands;
            if (fallback) sample[bands + 1] = (float)film.Colorimeter.ToXyz(sample.AsSpan(0, bands)).Y;
            var x = MemoryMarshal.Cast<float, Vector<float>>(sample);
            var k = MemoryMarshal.Cast<float, Vector<float>>(shift);
            var a = MemoryMarshal.Cast<float, Vector<float>>(s1.AsSpan());
            var b = MemoryMarshal.Cast<float, Vector<float>>(s2.AsSpan());
            if (index == 0)
            {
                sample.CopyTo(shift, 0);
                s1.AsSpan().Clear();
                s2.AsSpan().Clear();
                groups.AsSpan().Clear();
                adjacent.AsSpan().Clear();
                sample.CopyTo(previous, 0);
                return;
            }
            var p = MemoryMarshal.Cast<float, Vector<float>>(previous);
            var c = MemoryMarshal.Cast<float, Vector<float>>(adjacent.AsSpan());
            if (strataX > 0 && Neighbours(index))
                for (int i = 0; i < x.Length; i++)
                {
                    var d = x[i] - p[i];
                    c[i] += d * d;
                }
            sample.CopyTo(previous, 0);
            var g = MemoryMarshal.Cast<float, Vector<float>>(groups.AsSpan(index % Sampler.Randomisations * s1.Length, s1.Length));
            for (int i = 0; i < x.Length; i++)
            {
                var d = x[i] - k[i];
                a[i] += d;
                b[i] += d * d;
                g[i] += d;
            }
        }

        /// <summary>The standard error of the mean of lane <paramref name="lane"/> after n samples (0 for n &lt; 2), as the
        /// sampler's samples allow (above).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        double StandardError(int lane, int n) => sobol ? RandomisationError(lane, n)
            : strataX > 0 ? StratifiedError(lane, n) : IndependentError(lane, n);

        /// <summary>Whether sample s's cell and sample s − 1's are neighbours on the film jitter's grid (the same row).</summary>
        bool Neighbours(int s) => strataX == 1 || s % strataX != 0;

        /// <summary>Stratified: √(σ̄²/n), σ̄² from the squared differences of neighbouring cells' samples, Σ(x_s −
        /// x_{s−1})²/(2P).</summary>
        double StratifiedError(int lane, int n)
        {
            int pairs = 0;
            for (int s = 1; s < n; s++) if (Neighbours(s)) pairs++;
            if (pairs == 0) return IndependentError(lane, n);
            return Math.Sqrt(adjacent[lane] / (2.0 * pairs) / n);
        }

        /// <summary>s/√n: the standard error of the mean of n independent samples (0 for n &lt; 2).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        double IndependentError(int lane, int n)
        {
            if (n < 2) return 0;
            double a = s1[lane], variance = Math.Max(0, (s2[lane] - a * a / n) / (n - 1));
            return Math.Sqrt(variance / n);
        }

        /// <summary>√V from the spread of the randomisations' means (0 for n &lt; 2).</summary>
        double RandomisationError(int lane, int n)
        {
            if (n < 2) return 0;
            int r = Math.Min(Sampler.Randomisations, n), stride = s1.Length;
            double mean = (double)s1[lane] / n, sum = 0;
            for (int g = 0; g < r; g++)
            {
                int count = n / Sampler.Randomisations + (g < n % Sampler.Randomisations ? 1 : 0);
                double deviation = groups[g * stride + lane] - count * mean;
                sum += deviation * deviation;
            }
            return Math.Sqrt(r / (r - 1.0) * sum) / n;
        }

        /// <summary>
        /// Whether the pixel may stop: the relative standard error of its mean luminance is at most <paramref name="target"/>
        /// by a conservative rule (docs/scene-format.md, "Adaptive sampling"): the independent samples' s/√n — for the Sobol
        /// sampler an upper bound of its error, for independent samples its estimate — times 1 + 2/√(2(n − 1)), the upper
        /// end of its 95 % confidence band, so a pixel does not stop on a low estimate of its own variance.
        /// </summary>
        public bool Converged(int n, double target)
        {
            int y = film.Image.Bands + 1;
            double se = IndependentError(y, n) * (1 + AdaptiveMargin / Math.Sqrt(2.0 * (n - 1))), mean = shift[y] + (double)s1[y] / n;
            return se == 0 || se <= target * Math.Abs(mean);
        }

        /// <summary>z of the one-sided margin on the standard error (σ̂'s relative standard deviation is ≈ 1/√(2(n − 1))).</summary>
        const double AdaptiveMargin = 2;

        /// <summary>Per band, then of luminance: the standard error of the pixel's mean (band unit; Y's unit).</summary>
        public void StandardErrors(int n, Span<float> into)
        {
            int bands = film.Image.Bands;
            for (int b = 0; b < bands; b++) into[b] = (float)StandardError(b, n);
            into[bands] = (float)StandardError(bands + 1, n);
        }
    }
}
