using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace SpectralRenderer.Sensor;

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

    /// <summary>The stream of (pixel, channel) in the family <see cref="Family"/>(seed, kind): the same stream as the four-value
    /// constructor, one hash cheaper.</summary>
    public NoiseStream(ulong family, long pixel, int channel)
    {
        _key = Mix(family ^ (ulong)pixel * PixelStep ^ (ulong)channel << 48);
        _counter = 0;
    }

    /// <summary>The part of a stream's key that depends on the seed and the kind of noise only (hoisted out of pixel loops).</summary>
    public static ulong Family(ulong seed, ulong kind) => Mix(Mix(seed ^ 0x9E3779B97F4A7C15UL) ^ kind);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static ulong Mix(ulong z)
    {
        z += 0x9E3779B97F4A7C15UL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        return z ^ (z >> 31);
    }

    /// <summary>The next 64 random bits.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    ulong Next() => Mix(_key + _counter++ * CounterStep);

    internal const ulong PixelStep = 0xD1B54A32D192ED03UL, CounterStep = 0x632BE59BD9B4E019UL;

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
    /// exact, O(1) in μ. Its logarithms and exponential are <see cref="Ln"/> and <see cref="Exp"/>, the functions the
    /// 8-lane sampler (<see cref="NoiseLanes.Poisson"/>) uses, so both give the same count.
    /// </summary>
    public double Poisson(double mu)
    {
        if (mu <= 0) return 0;
        if (mu < 10)
        {
            // P(0) = e^−μ, P(k) = P(k − 1)·μ/k; the first k where the cumulative sum reaches u. The cap at 200
            // (P(k ≥ 200 | μ < 10) < 1e−250) only stops a u above the rounded total sum of the terms.
            double u = Uniform(), p = Exp(-mu);
            int k = 0;
            while (u > p && k < 200) { u -= p; k++; p *= mu / k; }
            return k;
        }
        double slam = Math.Sqrt(mu);
        double b = 0.931 + 2.53 * slam, a = -0.059 + 0.02483 * b;
        double invalpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2);
        while (true)
        {
            double u = Uniform() - 0.5, v = Uniform();
            double us = 0.5 - Math.Abs(u);
            double k = Math.Floor((2 * a / us + b) * u + mu + 0.43);
            if (us >= 0.07 && v <= vr) return k;
            if (k < 0 || (us < 0.013 && v > us)) continue;
            if (Ln(v * invalpha / (a / (us * us) + b)) <= -mu + k * Ln(mu) - LogFactorial(k)) return k;
        }
    }

    /// <summary>ln x: the vectorised logarithm of .NET's <see cref="Vector512.Log(Vector512{double})"/> in one lane where AVX-512 runs the
    /// lanes, else <see cref="Math.Log(double)"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static double Ln(double x) => Vector512.IsHardwareAccelerated ? Vector512.Log(Vector512.Create(x)).ToScalar() : Math.Log(x);

    /// <summary>eˣ, as <see cref="Ln"/>: <see cref="Vector512.Exp(Vector512{double})"/> in one lane, else
    /// <see cref="Math.Exp(double)"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static double Exp(double x) => Vector512.IsHardwareAccelerated ? Vector512.Exp(Vector512.Create(x)).ToScalar() : Math.Exp(x);

    internal const double LnSqrtTwoPi = 0.91893853320467274178;

    internal static readonly double[] SmallLogFactorials = Enumerable.Range(0, 16).Select(k => Enumerable.Range(1, k).Sum(i => Math.Log(i)))
        .ToArray();

    /// <summary>ln k!: a table below 16, else Stirling's series to 1/k⁵ (error &lt; 1e-12).</summary>
    public static double LogFactorial(double k)
    {
        if (k < 16) return SmallLogFactorials[(int)k];
        double k2 = 1 / (k * k);
        return (k + 0.5) * Ln(k) - k + LnSqrtTwoPi + (1.0 / 12 - k2 * (1.0 / 360 - k2 / 1260)) / k;
    }
}

/// <summary>
/// Eight streams of <see cref="NoiseStream"/> at once (AVX-512 lanes): the same integer hashes and the same IEEE
/// double operations in the same order as the scalar stream, so lane l gives bit for bit what stream l gives. Only
/// the common paths are here — a uniform, and a normal whose ziggurat draw lands inside its layer's rectangle —
/// with a mask of the lanes where that path decided; the caller redoes the others with the scalar stream.
/// </summary>
public static class NoiseLanes
{
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector512<ulong> Mix(Vector512<ulong> z)
    {
        z += Vector512.Create(0x9E3779B97F4A7C15UL);
        z = (z ^ Vector512.ShiftRightLogical(z, 30)) * Vector512.Create(0xBF58476D1CE4E5B9UL);
        z = (z ^ Vector512.ShiftRightLogical(z, 27)) * Vector512.Create(0x94D049BB133111EBUL);
        return z ^ Vector512.ShiftRightLogical(z, 31);
    }

    /// <summary>The keys of streams (pixel, channel) of a family: <see cref="NoiseStream(ulong, long, int)"/> lane by lane.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<ulong> Keys(ulong family, Vector512<ulong> pixel, Vector512<ulong> channel) =>
        Mix(Vector512.Create(family) ^ pixel * Vector512.Create(NoiseStream.PixelStep) ^ Vector512.ShiftLeft(channel, 48));

    /// <summary>The random bits number <paramref name="counter"/> (per lane) of each stream.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<ulong> Bits(Vector512<ulong> keys, Vector512<ulong> counter) =>
        Mix(keys + counter * Vector512.Create(NoiseStream.CounterStep));

    /// <summary><see cref="NoiseStream.Uniform"/> as number <paramref name="counter"/> of each stream.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<double> Uniform(Vector512<ulong> keys, Vector512<ulong> counter) =>
        (Vector512.ConvertToDouble(Vector512.ShiftRightLogical(Bits(keys, counter), 11)) + Vector512.Create(0.5)) * Vector512.Create(
            1.0 / (1UL << 53));

    /// <summary>
    /// <see cref="NoiseStream.Normal"/> drawn with number <paramref name="counter"/>, in the lanes where
    /// <paramref name="decided"/> is set (the draw fell inside its layer's rectangle, ~99 %); other lanes are undefined.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static unsafe Vector512<double> Normal(Vector512<ulong> keys, Vector512<ulong> counter, out Vector512<double> decided)
    {
        var bits = Bits(keys, counter);
        var layer = Vector512.Narrow((bits & Vector512.Create(0xFFUL)).AsInt64(), Vector512<long>.Zero).GetLower();   // 8 × int32
        Vector512<double> edge, next;
        if (Avx2.IsSupported)
        {
            double* x = Ziggurat.Pinned;
            edge = Vector512.Create(Avx2.GatherVector256(x, layer.GetLower(), 8), Avx2.GatherVector256(x, layer.GetUpper(), 8));
            next = Vector512.Create(Avx2.GatherVector256(x + 1, layer.GetLower(), 8), Avx2.GatherVector256(x + 1, layer.GetUpper(), 8));
        }
        else
        {
            var x = Ziggurat.X;
            edge = Vector512.Create(x[layer[0]], x[layer[1]], x[layer[2]], x[layer[3]], x[layer[4]], x[layer[5]], x[layer[6]], x[layer[7]]);
            next = Vector512.Create(x[layer[0] + 1], x[layer[1] + 1], x[layer[2] + 1], x[layer[3] + 1], x[layer[4] + 1], x[layer[5] + 1],
                x[layer[6] + 1], x[layer[7] + 1]);
        }
        var value = Vector512.ConvertToDouble(Vector512.ShiftRightLogical(bits, 11)) * Vector512.Create(1.0 / (1UL << 53)) * edge;
        decided = Vector512.LessThan(value, next);
        var negative = Vector512.Equals(bits & Vector512.Create(0x100UL), Vector512.Create(0x100UL)).AsDouble();
        return Vector512.ConditionalSelect(negative, -value, value);
    }

    /// <summary>
    /// <see cref="NoiseStream.Poisson"/> of mean μ in each lane, from number 0 of each stream: inversion below μ = 10,
    /// PTRS above, every lane until it is accepted (PTRS takes 1.3 tries on average). <paramref name="next"/> is the
    /// number of each stream's next draw. A lane is left undecided (for the scalar sampler) only when PTRS has not
    /// accepted within <see cref="MaxTries"/> tries.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<double> Poisson(Vector512<ulong> keys, Vector512<double> mu, out Vector512<ulong> next,
        out Vector512<double> decided)
    {
        var zero = Vector512<double>.Zero;
        var ten = Vector512.Create(10.0);
        var positive = Vector512.GreaterThan(mu, zero);
        var small = positive & Vector512.LessThan(mu, ten);
        var large = Vector512.GreaterThanOrEqual(mu, ten);
        var count = zero;
        next = Vector512<ulong>.Zero;
        decided = ~large;
        if (Any(small))
        {
            // Inversion: u from draw 0; P(0) = e^−μ, P(k) = P(k − 1)·μ/k while u > P.
            var u = Uniform(keys, Vector512<ulong>.Zero);
            var p = Vector512.Exp(-mu);
            var searching = small & Vector512.GreaterThan(u, p);
            for (int k = 1; Any(searching) && k <= 200; k++)
            {
                u = Vector512.ConditionalSelect(searching, u - p, u);
                count = Vector512.ConditionalSelect(searching, Vector512.Create((double)k), count);
                p = Vector512.ConditionalSelect(searching, p * (mu / Vector512.Create((double)k)), p);
                searching &= Vector512.GreaterThan(u, p);
            }
            next = Vector512.ConditionalSelect(small.AsUInt64(), Vector512.Create(1UL), next);
        }
        if (!Any(large)) return count;

        var slam = Vector512.Sqrt(mu);
        var b = Vector512.Create(0.931) + Vector512.Create(2.53) * slam;
        var a = Vector512.Create(-0.059) + Vector512.Create(0.02483) * b;
        var invalpha = Vector512.Create(1.1239) + Vector512.Create(1.1328) / (b - Vector512.Create(3.4));
        var vr = Vector512.Create(0.9277) - Vector512.Create(3.6224) / (b - Vector512.Create(2.0));
        var pending = large;
        var draw = Vector512<ulong>.Zero;
        Vector512<double> logMu = zero;
        bool haveLogMu = false;
        for (int tries = 0; tries < MaxTries && Any(pending); tries++)
        {
            var u = Uniform(keys, draw) - Vector512.Create(0.5);
            var v = Uniform(keys, draw + Vector512<ulong>.One);
            var us = Vector512.Create(0.5) - Vector512.Abs(u);
            var k = Vector512.Floor((Vector512.Create(2.0) * a / us + b) * u + mu + Vector512.Create(0.43));
            var accept = pending & Vector512.GreaterThanOrEqual(us, Vector512.Create(0.07)) & Vector512.LessThanOrEqual(v, vr);
            var test = pending & ~accept & ~(
                Vector512.LessThan(k, zero) | (Vector512.LessThan(us, Vector512.Create(0.013)) & Vector512.GreaterThan(v, us)));
            if (Any(test))
            {
                if (!haveLogMu) { logMu = Vector512.Log(mu); haveLogMu = true; }
                // ln k! as NoiseStream.LogFactorial: Stirling's series from k = 16, the table below.
                var k2 = Vector512.Create(1.0) / (k * k);
                var logFactorial = (k + Vector512.Create(0.5)) * Vector512.Log(k) - k + Vector512.Create(NoiseStream.LnSqrtTwoPi)
                    + (Vector512.Create(1.0 / 12) - k2 * (Vector512.Create(1.0 / 360) - k2 / Vector512.Create(1260.0))) / k;
                var table = test & Vector512.LessThan(k, Vector512.Create(16.0));
                if (Any(table))
                {
                    var t = NoiseStream.SmallLogFactorials;
                    var i = Vector512.ConvertToInt64(Vector512.Max(Vector512.Min(k, Vector512.Create(15.0)), zero));
                    var fromTable = Vector512.Create(t[i[0]], t[i[1]], t[i[2]], t[i[3]], t[i[4]], t[i[5]], t[i[6]], t[i[7]]);
                    logFactorial = Vector512.ConditionalSelect(table, fromTable, logFactorial);
                }
                var lhs = Vector512.Log(v * invalpha / (a / (us * us) + b));
                accept |= test & Vector512.LessThanOrEqual(lhs, -mu + k * logMu - logFactorial);
            }
            count = Vector512.ConditionalSelect(accept, k, count);
            decided |= accept;
            pending &= ~accept;
            draw += Vector512.Create(2UL);
            next = Vector512.ConditionalSelect(accept.AsUInt64(), draw, next);
        }
        return count;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static bool Any(Vector512<double> mask) => mask.ExtractMostSignificantBits() != 0;

    /// <summary>PTRS tries in lanes before a lane is left to the scalar sampler (P(more) ≈ 0.23⁶ ≈ 1.5e-4).</summary>
    public const int MaxTries = 6;
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
    public static readonly double[] X = GC.AllocateArray<double>(Layers + 1, pinned: true);
    /// <summary><see cref="X"/>'s address (the array is pinned), for gathers.</summary>
    internal static readonly unsafe double* Pinned;
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
        unsafe { Pinned = (double*)System.Runtime.CompilerServices.Unsafe.AsPointer(ref X[0]); }
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
