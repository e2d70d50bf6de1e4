using System.Buffers;
using System.Numerics;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// Locally weighted (adaptive) Wiener estimation: the prior of the Wiener estimate is not the whole training set but its
/// samples weighted by how close their simulated signals s_j = A·r_j are to the measured signal s (after the adaptive
/// Wiener estimation of Shen &amp; Xin 2007, Opt. Express 15(23):15545, which selects the prior's training samples per
/// sample imaged; here every sample is weighted, smoothly, by the distance of its signal). With u = s ⊘ (A·1) the signal relative to a
/// white reflector, its chromaticity q = u/‖u‖ and its intensity ln‖u‖, each training sample gets the Gaussian weight
/// <code>w_j = exp(−½ [‖q − q_j‖²/h_c² + (ln‖u‖ − ln‖u_j‖)²/h_I²])</code>
/// and the estimate is the Wiener estimate with the weighted mean μ_w and the covariance shrunk towards the whole set's,
/// <code>K = (1 − β) K_w + β K_r,  r̂ = μ_w + K Aᵀ (A K Aᵀ + K_n)⁻¹ (s − A μ_w)</code>
/// (A μ_w = Σ w_j s_j / Σ w_j). The estimate is nonlinear in s, so the bound on affine estimators
/// (RecoveryBoundTests) does not apply to it. h_c, h_I and β are chosen on the training set alone, by leave-one-out
/// (each sample estimated from its own noise-free signal by the other samples), minimising the mean over the samples of
/// the RMSE over all bands (the figure the recovery is scored by; the mean squared error lets a few outlying samples
/// choose). Per pixel the work is in the C-dimensional signal space: A K Aᵀ = (1 − β) Σ_j w_j (s_j − s̄)(s_j − s̄)ᵀ/Σw
/// + β A K_r Aᵀ, one C × C Cholesky solve, no N × N matrix.
/// </summary>
public sealed class LocalWiener
{
    /// <summary>The grid leave-one-out searches: h_c (chromaticity distance), h_I (natural-log intensity; ∞: intensity ignored),
    /// β.</summary>
    public static readonly double[] ChromaticityWidths = [0.05, 0.1, 0.2, 0.4];
    public static readonly double[] IntensityWidths = [0.25, 0.5, 1, double.PositiveInfinity];
    public static readonly double[] Shrinkages = [0.03, 0.1, 0.3, 0.5, 0.7];

    /// <summary>Weights below e^(−27.6) ≈ 1e-12 of the largest are dropped (a fixed rule: the estimate stays deterministic).</summary>
    const double MaxExponent = 2 * 27.6;

    readonly int t, c, n;
    // Sample-minor layouts (row b or i holds all T samples), so the per-pixel loops run over the samples in SIMD.
    readonly double[] r;       // N × T training reflectances
    readonly double[] s;       // C × T their signals A·r_j
    readonly double[] q;       // C × T their chromaticities
    readonly double[] logI;    // T: ln‖u_j‖
    readonly double[] white;   // C: A·1
    readonly double[] krAt;    // N × C: K_r Aᵀ
    readonly double[] aKrAt;   // C × C: A K_r Aᵀ
    readonly double[] noise;   // C: the diagonal of K_n

    /// <summary>h_c: the Gaussian width in chromaticity (unit-length white-relative signals).</summary>
    public double ChromaticityWidth { get; private set; }
    /// <summary>h_I: the Gaussian width in ln intensity (∞: the intensity does not weight).</summary>
    public double IntensityWidth { get; private set; }
    /// <summary>β: the weight of the whole training set's covariance K_r in K.</summary>
    public double Shrinkage { get; private set; }
    /// <summary>The training set's leave-one-out error at the chosen widths: the mean over the samples of the RMSE over all bands
    /// (reflectance units).</summary>
    public double LeaveOneOutRmse { get; private set; }

    LocalWiener(ForwardModel model, double[] noiseVariance)
    {
        var a = model.A;
        var training = model.Training;
        int m = a.GetLength(1);   // the model's coordinates (the bands, or the exact route's knots)
        var p = model.BandMeans;
        c = a.GetLength(0); n = p?.GetLength(0) ?? m; t = training.Count;
        r = new double[t * n]; s = new double[t * c]; q = new double[t * c]; logI = new double[t];
        white = new double[c];
        for (int i = 0; i < c; i++) for (int b = 0; b < m; b++) white[i] += a[i, b];
        Span<double> sj = stackalloc double[c], qj = stackalloc double[c];
        for (int j = 0; j < t; j++)
        {
            var rj = model.ToBands(training.Samples[j]);
            for (int b = 0; b < n; b++) r[b * t + j] = rj[b];
            for (int i = 0; i < c; i++) { double v = 0; for (int b = 0; b < m; b++) v += a[i, b] * training.Samples[j][b]; sj[i] = v; }
            logI[j] = Feature(sj, qj);
            for (int i = 0; i < c; i++) { s[i * t + j] = sj[i]; q[i * t + j] = qj[i]; }
        }
        var kr = training.Covariance();
        var krAtX = new double[m * c];   // K_r Aᵀ in the coordinates, then (exact route) its band means
        for (int b = 0; b < m; b++)
            for (int i = 0; i < c; i++) { double v = 0; for (int k = 0; k < m; k++) v += kr[b, k] * a[i, k]; krAtX[b * c + i] = v; }
        aKrAt = new double[c * c];
        for (int i = 0; i < c; i++)
            for (int k = 0; k < c; k++) { double v = 0; for (int b = 0; b < m; b++) v += a[i, b] * krAtX[b * c + k]; aKrAt[i * c + k] = v; }
        krAt = krAtX;
        if (p is not null)
        {
            krAt = new double[n * c];
            for (int b = 0; b < n; b++)
                for (int i = 0; i < c; i++)
                {
                    double v = 0;
                    for (int k = 0; k < m; k++) v += p[b, k] * krAtX[k * c + i];
                    krAt[b * c + i] = v;
                }
        }
        noise = (double[])noiseVariance.Clone();
    }

    /// <param name="a">C × N forward matrix.</param>
    /// <param name="noiseVariance">per channel, the variance of s.</param>
    /// <param name="widths">(h_c, h_I, β) to use; null: chosen by leave-one-out on the training set.</param>
    public static LocalWiener Build(double[,] a, TrainingSet training, double[] noiseVariance,
        (double Chromaticity, double Intensity, double Shrinkage)? widths = null) =>
        Build(ForwardModel.Bands(a, training), noiseVariance, widths);

    /// <param name="model">the forward model, with the training set in its coordinates; the estimate is of the band means.</param>
    /// <param name="noiseVariance">per channel, the variance of s.</param>
    /// <param name="widths">(h_c, h_I, β) to use; null: chosen by leave-one-out on the training set (RMSE over the bands).</param>
    public static LocalWiener Build(ForwardModel model, double[] noiseVariance,
        (double Chromaticity, double Intensity, double Shrinkage)? widths = null)
    {
        var e = new LocalWiener(model, noiseVariance);
        var grid = widths is { } w ? [w]
            : (from hc in ChromaticityWidths from hi in IntensityWidths from beta in Shrinkages select (hc, hi, beta)).ToArray();
        var score = new double[grid.Length];
        if (widths is null)
        {
            // By widths (h_c, h_I): the weights and the weighted signal covariance of each left-out sample, shared by the βs.
            int nb = Shrinkages.Length;
            Parallel.For(0, grid.Length / nb,
                g => e.LeaveOneOutRmseAt(grid[g * nb].hc, grid[g * nb].hi, Shrinkages, score.AsSpan(g * nb, nb)));
        }
        else e.LeaveOneOutRmseAt(grid[0].hc, grid[0].hi, [grid[0].beta], score);
        int best = 0;
        for (int g = 1; g < grid.Length; g++) if (score[g] < score[best]) best = g;   // the first of equals: deterministic
        (e.ChromaticityWidth, e.IntensityWidth, e.Shrinkage) = grid[best];
        e.LeaveOneOutRmse = score[best];
        return e;
    }

    /// <summary>Into <paramref name="rmse"/>, for each β of <paramref name="betas"/>: the mean over the samples of the RMSE of each
    /// estimated by the others.</summary>
    void LeaveOneOutRmseAt(double hc, double hi, double[] betas, Span<double> rmse)
    {
        var scratch = new double[ScratchLength];
        var est = new double[n];
        var sj = new double[c];
        var sum = new double[betas.Length];
        for (int j = 0; j < t; j++)
        {
            for (int i = 0; i < c; i++) sj[i] = s[i * t + j];
            double sw = Weigh(sj, j, hc, hi, scratch);
            for (int k = 0; k < betas.Length; k++)
            {
                Finish(sj, sw, betas[k], scratch, est);
                double e2 = 0;
                for (int b = 0; b < n; b++) { double d = est[b] - r[b * t + j]; e2 += d * d; }
                sum[k] += Math.Sqrt(e2 / n);
            }
        }
        for (int k = 0; k < betas.Length; k++) rmse[k] = sum[k] / t;
    }

    int ScratchLength => t * (3 + 2 * c) + 2 * c * c + 3 * c;

    /// <summary>The white-relative chromaticity q = u/‖u‖ (u = s ⊘ A·1) into <paramref name="chroma"/>; returns ln‖u‖.</summary>
    double Feature(ReadOnlySpan<double> signal, Span<double> chroma)
    {
        double norm = 0;
        for (int i = 0; i < c; i++) { chroma[i] = white[i] > 0 ? signal[i] / white[i] : 0; norm += chroma[i] * chroma[i]; }
        // A black or noise-negative pixel: its intensity is floored at 1e-6 of a white's, its chromaticity is then that of u.
        norm = Math.Max(Math.Sqrt(norm), 1e-6 * Math.Sqrt(c));
        for (int i = 0; i < c; i++) chroma[i] /= norm;
        return Math.Log(norm);
    }

    /// <summary>r̂ for one pixel (no allocation: the scratch is stack or pooled memory).</summary>
    public void Apply(ReadOnlySpan<float> signal, Span<double> reflectance)
    {
        int len = ScratchLength + c;
        var rented = ArrayPool<double>.Shared.Rent(len);
        var scratch = rented.AsSpan(0, len);
        var sig = scratch[..c];
        for (int i = 0; i < c; i++) sig[i] = signal[i];
        Estimate(sig, -1, ChromaticityWidth, IntensityWidth, Shrinkage, scratch[c..], reflectance);
        ArrayPool<double>.Shared.Return(rented);
    }

    /// <summary>The estimate from <paramref name="signal"/> with training sample <paramref name="exclude"/> left out (−1: none).</summary>
    void Estimate(ReadOnlySpan<double> signal, int exclude, double hc, double hi, double beta, Span<double> scratch,
        Span<double> reflectance) =>
        Finish(signal, Weigh(signal, exclude, hc, hi, scratch), beta, scratch, reflectance);

    // The scratch: w (T), d = s_j − s̄ (C × T), w_j d_j (C × T), Σ w_j d_j d_jᵀ (C × C, lower), M (C × C), q(s), s̄, x (C each),
    // (s_j − s̄)ᵀx and f (T each).
    Span<double> Weights(Span<double> scratch) => scratch[..t];
    Span<double> Centred(Span<double> scratch) => scratch.Slice(t, c * t);
    Span<double> WeightedCentred(Span<double> scratch) => scratch.Slice(t + c * t, c * t);
    Span<double> Scatter(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c), c * c);
    Span<double> SystemMatrix(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c) + c * c, c * c);
    Span<double> Chroma(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c) + 2 * c * c, c);
    Span<double> MeanSignal(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c) + 2 * c * c + c, c);
    Span<double> Solution(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c) + 2 * c * c + 2 * c, c);
    Span<double> Projection(Span<double> scratch) => scratch.Slice(t * (1 + 2 * c) + 2 * c * c + 3 * c, t);
    Span<double> Factors(Span<double> scratch) => scratch.Slice(t * (2 + 2 * c) + 2 * c * c + 3 * c, t);

    /// <summary>
    /// What the estimate needs of the training samples for this signal, whatever β: the weights w_j, their sum (returned),
    /// the weighted mean signal s̄, the centred signals and the weighted scatter Σ w_j (s_j − s̄)(s_j − s̄)ᵀ, into the scratch.
    /// </summary>
    double Weigh(ReadOnlySpan<double> signal, int exclude, double hc, double hi, Span<double> scratch)
    {
        var w = Weights(scratch);
        var d = Centred(scratch);
        var wd = WeightedCentred(scratch);
        var scatter = Scatter(scratch);
        var qs = Chroma(scratch);
        var sBar = MeanSignal(scratch);

        // Squared distances, then weights relative to the nearest sample (so one weight is 1, whatever the widths).
        double li = Feature(signal, qs);
        double ic = 1 / (hc * hc), ii = double.IsPositiveInfinity(hi) ? 0 : 1 / (hi * hi);
        w.Clear();
        for (int i = 0; i < c; i++) AddSquaredDifference(qs[i], q.AsSpan(i * t, t), w);
        double min = double.PositiveInfinity;
        for (int j = 0; j < t; j++)
        {
            double dl = li - logI[j];
            w[j] = w[j] * ic + dl * dl * ii;
            if (j != exclude && w[j] < min) min = w[j];
        }
        double sw = 0;
        for (int j = 0; j < t; j++)
        {
            double e = w[j] - min;
            w[j] = j != exclude && e <= MaxExponent ? Math.Exp(-0.5 * e) : 0;
            sw += w[j];
        }
        for (int i = 0; i < c; i++)
        {
            var si = s.AsSpan(i * t, t);
            sBar[i] = Dot(w, si) / sw;
            var di = d.Slice(i * t, t);
            var wdi = wd.Slice(i * t, t);
            for (int j = 0; j < t; j++) { di[j] = si[j] - sBar[i]; wdi[j] = w[j] * di[j]; }
        }
        for (int i = 0; i < c; i++)
            for (int k = 0; k <= i; k++) scatter[i * c + k] = Dot(wd.Slice(i * t, t), d.Slice(k * t, t));
        return sw;
    }

    /// <summary>The estimate for shrinkage β from what <see cref="Weigh"/> left in the scratch (its part of the scratch is read, not
    /// changed).</summary>
    void Finish(ReadOnlySpan<double> signal, double sw, double beta, Span<double> scratch, Span<double> reflectance)
    {
        var w = Weights(scratch);
        var d = Centred(scratch);
        var scatter = Scatter(scratch);
        var m = SystemMatrix(scratch);
        var sBar = MeanSignal(scratch);
        var x = Solution(scratch);

        // M = (1 − β) Σ w_j (s_j − s̄)(s_j − s̄)ᵀ / Σw + β A K_r Aᵀ + K_n (lower triangle; two passes, about s̄); a ridge of
        // 1e-12 of each diagonal element keeps noise-free systems solvable and, unlike a multiple of I, does not depend
        // on the channels' scales.
        for (int i = 0; i < c; i++)
        {
            for (int k = 0; k <= i; k++)
                m[i * c + k] = (1 - beta) * scatter[i * c + k] / sw + beta * aKrAt[i * c + k];
            m[i * c + i] = (m[i * c + i] + noise[i]) * (1 + 1e-12);
            x[i] = signal[i] - sBar[i];
        }
        CholeskySolve(m, x, c);

        // r̂ = μ_w + (1 − β) Σ w_j (r_j − μ_w)(s_j − s̄)ᵀx / Σw + β K_r Aᵀ x; as Σ w_j (s_j − s̄) = 0 the μ_w inside drops:
        // r̂_b = Σ_j f_j r_bj + β (K_r Aᵀ x)_b with f_j = w_j (1 + (1 − β)(s_j − s̄)ᵀx) / Σw.
        var f = Factors(scratch);
        var proj = Projection(scratch);
        var d0 = d[..t];
        for (int j = 0; j < t; j++) proj[j] = d0[j] * x[0];
        for (int i = 1; i < c; i++) Axpy(x[i], d.Slice(i * t, t), proj);
        for (int j = 0; j < t; j++) f[j] = w[j] * (1 + (1 - beta) * proj[j]) / sw;
        for (int b = 0; b < n; b++)
        {
            double v = 0;
            for (int i = 0; i < c; i++) v += krAt[b * c + i] * x[i];
            reflectance[b] = beta * v + Dot(f, r.AsSpan(b * t, t));
        }
    }

    /// <summary>Σ x_j y_j.</summary>
    static double Dot(ReadOnlySpan<double> x, ReadOnlySpan<double> y)
    {
        double sum = 0;
        int i = 0;
        if (Vector.IsHardwareAccelerated && x.Length >= Vector<double>.Count)
        {
            var acc = Vector<double>.Zero;
            var vx = MemoryMarshal.Cast<double, Vector<double>>(x);
            var vy = MemoryMarshal.Cast<double, Vector<double>>(y);
            for (int v = 0; v < vx.Length; v++) acc += vx[v] * vy[v];
            sum = Vector.Sum(acc);
            i = vx.Length * Vector<double>.Count;
        }
        for (; i < x.Length; i++) sum += x[i] * y[i];
        return sum;
    }

    /// <summary>y += a·x.</summary>
    static void Axpy(double a, ReadOnlySpan<double> x, Span<double> y)
    {
        int i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var va = new Vector<double>(a);
            var vx = MemoryMarshal.Cast<double, Vector<double>>(x);
            var vy = MemoryMarshal.Cast<double, Vector<double>>(y);
            for (int v = 0; v < vx.Length; v++) vy[v] += va * vx[v];
            i = vx.Length * Vector<double>.Count;
        }
        for (; i < x.Length; i++) y[i] += a * x[i];
    }

    /// <summary>acc_j += (a − row_j)².</summary>
    static void AddSquaredDifference(double a, ReadOnlySpan<double> row, Span<double> acc)
    {
        int i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var va = new Vector<double>(a);
            var vr = MemoryMarshal.Cast<double, Vector<double>>(row);
            var vacc = MemoryMarshal.Cast<double, Vector<double>>(acc);
            for (int v = 0; v < vr.Length; v++) { var e = va - vr[v]; vacc[v] += e * e; }
            i = vr.Length * Vector<double>.Count;
        }
        for (; i < row.Length; i++) { double e = a - row[i]; acc[i] += e * e; }
    }

    /// <summary>x ← M⁻¹x for the symmetric positive definite M given by its lower triangle (overwritten by its Cholesky factor).</summary>
    static void CholeskySolve(Span<double> m, Span<double> x, int c)
    {
        for (int i = 0; i < c; i++)
        {
            for (int k = 0; k <= i; k++)
            {
                double v = m[i * c + k];
                for (int l = 0; l < k; l++) v -= m[i * c + l] * m[k * c + l];
                if (k < i) m[i * c + k] = v / m[k * c + k];
                else m[i * c + i] = Math.Sqrt(Math.Max(v, double.Epsilon));
            }
        }
        for (int i = 0; i < c; i++)
        {
            double v = x[i];
            for (int k = 0; k < i; k++) v -= m[i * c + k] * x[k];
            x[i] = v / m[i * c + i];
        }
        for (int i = c - 1; i >= 0; i--)
        {
            double v = x[i];
            for (int k = i + 1; k < c; k++) v -= m[k * c + i] * x[k];
            x[i] = v / m[i * c + i];
        }
    }
}
