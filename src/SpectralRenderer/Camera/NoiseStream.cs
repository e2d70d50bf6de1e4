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

    public NoiseStream(ulong seed, ulong kind, long pixel, int channel) : this(Family(seed, kind), pixel, channel) { }

    /// <summary>The stream of (pixel, channel) in the family <see cref="Family"/>(seed, kind): the same stream as the four-value constructor, one hash cheaper.</summary>
    public NoiseStream(ulong family, long pixel, int channel)
    {
        _key = Mix(family ^ (ulong)pixel * 0xD1B54A32D192ED03UL ^ (ulong)channel << 48);
        _counter = 0;
    }

    /// <summary>The part of a stream's key that depends on the seed and the kind of noise only (hoisted out of pixel loops).</summary>
    public static ulong Family(ulong seed, ulong kind) => Mix(Mix(seed ^ 0x9E3779B97F4A7C15UL) ^ kind);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static ulong Mix(ulong z)
    {
        z += 0x9E3779B97F4A7C15UL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        return z ^ (z >> 31);
    }

    /// <summary>The next 64 random bits.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    ulong Next() => Mix(_key + _counter++ * 0x632BE59BD9B4E019UL);

    /// <summary>Uniform on (0, 1): 53 random bits, never exactly 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Uniform() => ((Next() >> 11) + 0.5) * (1.0 / (1UL << 53));

    /// <summary>
    /// Standard normal, by Marsaglia &amp; Tsang's ziggurat (J. Stat. Softw. 5(8), 2000) with 256 layers of equal area
    /// (<see cref="Ziggurat"/>): one 64-bit hash gives the layer (8 bits), the sign (1 bit) and the abscissa (53 bits),
    /// disjoint bits, as Doornik (2005) requires. About 99 % of draws are that one hash and a comparison; the rest test
    /// the wedge under exp(−x²/2) or sample the tail beyond r (Marsaglia 1964). Exact: no approximation of the density.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Normal()
    {
        ulong bits = Next();
        int i = (int)(bits & 0xFF);
        double x = (bits >> 11) * (1.0 / (1UL << 53)) * Ziggurat.X[i];
        if (x < Ziggurat.X[i + 1]) return (bits & 0x100) != 0 ? -x : x;
        return NormalSlow(i, x, (bits & 0x100) != 0);
    }

    double NormalSlow(int i, double x, bool negative)
    {
        while (true)
        {
            if (i == 0)
            {
                // The tail beyond r: x = r + e₁/r with e₁, e₂ exponential, accepted when 2e₂ > (e₁/r)².
                double t, e;
                do { t = -Math.Log(Uniform()) / Ziggurat.R; e = -Math.Log(Uniform()); } while (e + e < t * t);
                x = Ziggurat.R + t;
                return negative ? -x : x;
            }
            // The wedge of layer i: y uniform between the layer's bottom f(xᵢ) and top f(xᵢ₊₁), accepted under the density
            if (Ziggurat.F[i] + Uniform() * (Ziggurat.F[i + 1] - Ziggurat.F[i]) < Math.Exp(-0.5 * x * x)) return negative ? -x : x;
            ulong bits = Next();
            i = (int)(bits & 0xFF);
            negative = (bits & 0x100) != 0;
            x = (bits >> 11) * (1.0 / (1UL << 53)) * Ziggurat.X[i];
            if (x < Ziggurat.X[i + 1]) return negative ? -x : x;
        }
    }

    /// <summary>
    /// A Poisson deviate of mean μ: inversion by sequential search from 0 (one uniform, Devroye 1986 §X.3) below
    /// μ = 10, else Hörmann's transformed rejection with squeeze, PTRS (Insurance: Math. Econ. 12, 39–45, 1993) —
    /// exact, O(1) in μ; ln μ is taken only when the squeeze does not decide (about one draw in five).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Poisson(double mu)
    {
        if (mu <= 0) return 0;
        if (mu < 10)
        {
            // P(0) = e^−μ, P(k) = P(k − 1)·μ/k; the first k where the cumulative sum reaches u. The cap at 200
            // (P(k ≥ 200 | μ < 10) < 1e−250) only stops a u above the rounded total sum of the terms.
            double u = Uniform(), p = Math.Exp(-mu);
            int k = 0;
            while (u > p && k < 200) { u -= p; k++; p *= mu / k; }
            return k;
        }
        return Ptrs(mu);
    }

    double Ptrs(double mu)
    {
        double slam = Math.Sqrt(mu);
        double b = 0.931 + 2.53 * slam, a = -0.059 + 0.02483 * b;
        double vr = 0.9277 - 3.6224 / (b - 2);
        while (true)
        {
            double u = Uniform() - 0.5, v = Uniform();
            double us = 0.5 - Math.Abs(u);
            double k = Math.Floor((2 * a / us + b) * u + mu + 0.43);
            if (us >= 0.07 && v <= vr) return k;
            if (k < 0 || (us < 0.013 && v > us)) continue;
            double invalpha = 1.1239 + 1.1328 / (b - 3.4);
            if (Math.Log(v * invalpha / (a / (us * us) + b)) <= -mu + k * Math.Log(mu) - LogFactorial(k)) return k;
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

/// <summary>
/// The 256-layer ziggurat of the standard normal's f(x) = exp(−x²/2) (Marsaglia &amp; Tsang 2000): layer 0 is the
/// base strip [0, X₀] × [0, f(r)] of area v (the rectangle up to r plus the tail beyond it), layer i ≥ 1 the
/// rectangle [0, Xᵢ] × [f(Xᵢ), f(Xᵢ₊₁)], also of area v, with X₁ = r and X₂₅₆ = 0. r is found here by bisection
/// so the 255th layer closes exactly at f(0) = 1; the tail area is e^(−r²/2) times Mills' ratio (a continued
/// fraction). Marsaglia &amp; Tsang give r = 3.6541528853610088, v = 0.00492867323399.
/// </summary>
public static class Ziggurat
{
    public const int Layers = 256;
    /// <summary>r: where the tail starts.</summary>
    public static readonly double R;
    /// <summary>v: the area of every layer.</summary>
    public static readonly double V;
    /// <summary>Xᵢ, i = 0 … 256.</summary>
    public static readonly double[] X = new double[Layers + 1];
    /// <summary>f(Xᵢ), with F₀ = 0 unused and F₂₅₆ = 1.</summary>
    public static readonly double[] F = new double[Layers + 1];

    static Ziggurat()
    {
        // Top-layer mismatch as a function of r: positive when r is too small (the layers reach x = 0 too soon).
        double lo = 3, hi = 4;
        for (int it = 0; it < 200 && hi - lo > 0; it++)
        {
            double mid = 0.5 * (lo + hi);
            if (mid <= lo || mid >= hi) break;
            if (Build(mid, null) > 0) lo = mid; else hi = mid;
        }
        R = 0.5 * (lo + hi);
        V = Area(R);
        Build(R, X);
        X[0] = V / Math.Exp(-0.5 * R * R);
        X[Layers] = 0;
        F[0] = 0;
        for (int i = 1; i <= Layers; i++) F[i] = Math.Exp(-0.5 * X[i] * X[i]);
    }

    /// <summary>v(r) = r·f(r) + ∫_r^∞ f: the base strip's area.</summary>
    static double Area(double r) => Math.Exp(-0.5 * r * r) * (r + MillsRatio(r));

    /// <summary>∫_r^∞ e^(−t²/2) dt / e^(−r²/2) = 1/(r + 1/(r + 2/(r + 3/(r + …)))), evaluated from the 200th term up.</summary>
    static double MillsRatio(double r)
    {
        double d = r;
        for (int k = 200; k >= 1; k--) d = r + k / d;
        return 1 / d;
    }

    /// <summary>
    /// Stacks layers of area v(r) from X₁ = r upwards; returns how much the top layer (up to f = 1) lacks of v
    /// (positive: r too small), or +1 when the layers reach the top before the 256th.
    /// </summary>
    static double Build(double r, double[]? x)
    {
        double v = Area(r), xi = r;
        if (x is not null) x[1] = r;
        for (int i = 1; i < Layers - 1; i++)
        {
            double fNext = v / xi + Math.Exp(-0.5 * xi * xi);
            if (fNext >= 1) return 1;
            xi = Math.Sqrt(-2 * Math.Log(fNext));
            if (x is not null) x[i + 1] = xi;
        }
        return v - xi * (1 - Math.Exp(-0.5 * xi * xi));
    }
}
