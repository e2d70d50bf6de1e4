using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// A render that says how exact it is: each pixel's standard error from its own samples, per band and of luminance, and
// adaptive sampling that stops a pixel once its relative standard error of luminance reaches a target.
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

        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
        {
            var sink = new RadianceSamples(integrator, integrator as IAnalysisIntegrator, film, _sum, _sample, _scratch, sampling.Spp);
            var stats = new SampleStatistics(film, _sample, _shift, _s1, _s2);
            int cap = sampling.Spp, minimum = Math.Min(cap, MinAdaptiveSamples), budget = sampling.Budget;
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
                        if (target > 0 && n >= minimum && stats.Converged(n, target)) break;
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
    /// colour lanes fell back). s² = (Σd² − (Σd)²/n)/(n − 1), the unbiased sample variance, and the standard error of the
    /// pixel mean s/√n.
    /// </summary>
    readonly struct SampleStatistics(Film film, float[] sample, float[] shift, float[] s1, float[] s2)
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
                return;
            }
            for (int i = 0; i < x.Length; i++)
            {
                var d = x[i] - k[i];
                a[i] += d;
                b[i] += d * d;
            }
        }

        /// <summary>The standard error of the mean of lane <paramref name="lane"/> after n samples (0 for n &lt; 2).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        double StandardError(int lane, int n)
        {
            if (n < 2) return 0;
            double a = s1[lane], variance = Math.Max(0, (s2[lane] - a * a / n) / (n - 1));
            return Math.Sqrt(variance / n);
        }

        /// <summary>Whether the relative standard error of the pixel's mean luminance is at most <paramref name="target"/>.</summary>
        public bool Converged(int n, double target)
        {
            int y = film.Image.Bands + 1;
            double se = StandardError(y, n), mean = shift[y] + (double)s1[y] / n;
            return se == 0 || se <= target * Math.Abs(mean);
        }

        /// <summary>Per band, then of luminance: the standard error of the pixel's mean (band unit; Y's unit).</summary>
        public void StandardErrors(int n, Span<float> into)
        {
            int bands = film.Image.Bands;
            for (int b = 0; b < bands; b++) into[b] = (float)StandardError(b, n);
            into[bands] = (float)StandardError(bands + 1, n);
        }
    }
}
