using System.Runtime.CompilerServices;

namespace SpectralRenderer.Camera;

/// <summary>
/// A counter-based random stream: the k-th number of stream (seed, kind, pixel, channel) is a hash of those
/// values and k (SplitMix64's finaliser, Steele, Lea &amp; Flood 2014), so each pixel's noise is fixed by the seed
/// alone — the same whatever the thread count, tile order or image crop.
/// </summary>
public struct NoiseStream
{
    ulong _key;
    ulong _counter;

    public NoiseStream(ulong seed, ulong kind, long pixel, int channel)
    {
        _key = Mix(Mix(Mix(seed ^ 0x9E3779B97F4A7C15UL) ^ kind) ^ (ulong)pixel * 0xD1B54A32D192ED03UL ^ (ulong)channel << 48);
        _counter = 0;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static ulong Mix(ulong z)
    {
        z += 0x9E3779B97F4A7C15UL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        return z ^ (z >> 31);
    }

    /// <summary>Uniform on (0, 1): 53 random bits, never exactly 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Uniform() => ((Mix(_key + _counter++ * 0x632BE59BD9B4E019UL) >> 11) + 0.5) * (1.0 / (1UL << 53));

    /// <summary>Standard normal (Box–Muller, one of the pair).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Normal()
    {
        double u = Uniform(), v = Uniform();
        return Math.Sqrt(-2 * Math.Log(u)) * Math.Cos(2 * Math.PI * v);
    }

    /// <summary>
    /// A Poisson deviate of mean μ: multiplication of uniforms (Knuth) below μ = 10, else Hörmann's transformed
    /// rejection with squeeze, PTRS (Insurance: Math. Econ. 12, 39–45, 1993) — exact, O(1) in μ.
    /// </summary>
    public double Poisson(double mu)
    {
        if (mu <= 0) return 0;
        if (mu < 10)
        {
            double limit = Math.Exp(-mu), p = 1;
            int k = -1;
            do { k++; p *= Uniform(); } while (p > limit);
            return k;
        }
        double slam = Math.Sqrt(mu), loglam = Math.Log(mu);
        double b = 0.931 + 2.53 * slam, a = -0.059 + 0.02483 * b;
        double invalpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2);
        while (true)
        {
            double u = Uniform() - 0.5, v = Uniform();
            double us = 0.5 - Math.Abs(u);
            double k = Math.Floor((2 * a / us + b) * u + mu + 0.43);
            if (us >= 0.07 && v <= vr) return k;
            if (k < 0 || (us < 0.013 && v > us)) continue;
            if (Math.Log(v) + Math.Log(invalpha) - Math.Log(a / (us * us) + b) <= -mu + k * loglam - LogFactorial(k)) return k;
        }
    }

    static readonly double[] SmallLogFactorials = Enumerable.Range(0, 16).Select(k => Enumerable.Range(1, k).Sum(i => Math.Log(i))).ToArray();

    /// <summary>ln k!: a table below 16, else Stirling's series to 1/k⁵ (error &lt; 1e-12).</summary>
    public static double LogFactorial(double k)
    {
        if (k < 16) return SmallLogFactorials[(int)k];
        double k2 = 1 / (k * k);
        return (k + 0.5) * Math.Log(k) - k + 0.91893853320467274178 + (1.0 / 12 - k2 * (1.0 / 360 - k2 / 1260)) / k;
    }
}
