using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// How well any linear estimator can recover the ColorChecker over 380–780 nm from each preset's signals, computed
/// without a render: the ideal signals s = A·r of the 24 Ohta patches (band means on 380:780:20, A = channel weights ×
/// D65's band values), so demosaicking, noise and the scene play no part. This is the evidence behind docs/camera.md's
/// statement that the full-range bars are out of reach: the sensors see nothing above ~720 nm and the ColorChecker's
/// near-infrared rise is not predictable from its visible signals, even by an estimator fitted to the chart itself.
/// </summary>
public class RecoveryBoundTests(ITestOutputHelper output)
{
    static readonly BandGrid Grid = new(380, 780, 20);

    internal static double[,] Forward(string preset)
    {
        var sensor = SensorPresets.Get(preset);
        var light = SpectrumLibrary.Resolve("D65");
        var w = ChannelWeights.Compute(sensor, Grid, light, 1);
        var e = BandProjection.Means(light, Grid);
        var a = new double[w.Channels, Grid.Count];
        // Rows normalised to unit peak: the estimators below are invariant to a channel's scale, the conditioning is not.
        for (int c = 0; c < w.Channels; c++)
        {
            double peak = 0;
            for (int b = 0; b < Grid.Count; b++) peak = Math.Max(peak, w[c, b] * e[b]);
            for (int b = 0; b < Grid.Count; b++) a[c, b] = w[c, b] * e[b] / peak;
        }
        return a;
    }

    internal static double Rmse(double[] x, double[] y, int lo, int hi)
    {
        double s = 0;
        for (int b = lo; b < hi; b++) s += (x[b] - y[b]) * (x[b] - y[b]);
        return Math.Sqrt(s / (hi - lo));
    }

    /// <summary>Bands [lo, hi) of 380:780:20 inside 400–700 nm: 1..16.</summary>
    internal const int VisLo = 1, VisHi = 16;

    /// <summary>Mean over the patches of the RMSE, over all bands and over 400–700 nm.</summary>
    internal static (double All, double Visible, double Nir) Score(Func<double[], double[]> estimate, double[,] a, double[][] patches)
    {
        double all = 0, vis = 0, nir = 0;
        foreach (var r in patches)
        {
            var est = estimate(Dense.Multiply(a, r));
            all += Rmse(est, r, 0, Grid.Count);
            vis += Rmse(est, r, VisLo, VisHi);
            nir += Rmse(est, r, 17, 20);
        }
        return (all / patches.Length, vis / patches.Length, nir / patches.Length);
    }

    /// <summary>The affine least-squares map from signals to reflectances fitted on (signals, reflectances), ridge λ relative to the mean
    /// signal power.</summary>
    static Func<double[], double[]> FitAffine(double[,] a, IReadOnlyList<double[]> train, double lambda, double[]? weights = null) =>
        FitAffine(train.Select(r => Dense.Multiply(a, r)).ToArray(), train, lambda, weights);

    static Func<double[], double[]> FitAffine(IReadOnlyList<double[]> signals, IReadOnlyList<double[]> train, double lambda,
        double[]? weights = null)
    {
        int c = signals[0].Length, n = Grid.Count, t = train.Count;
        var x = new double[c + 1, t];
        var r = new double[n, t];
        for (int j = 0; j < t; j++)
        {
            for (int i = 0; i < c; i++) x[i, j] = signals[j][i];
            x[c, j] = 1;
            for (int b = 0; b < n; b++) r[b, j] = train[j][b];
        }
        var xw = (double[,])x.Clone();
        if (weights is not null) for (int j = 0; j < t; j++) for (int i = 0; i <= c; i++) xw[i, j] *= weights[j];
        var xxt = Dense.Multiply(xw, Dense.Transpose(x));
        double unit = Dense.Trace(xxt) / (c + 1);
        for (int i = 0; i < c; i++) xxt[i, i] += lambda * unit;    // the constant term is not penalised
        var g = Dense.SolveRight(Dense.Multiply(r, Dense.Transpose(xw)), xxt);
        return s =>
        {
            var v = new double[n];
            for (int b = 0; b < n; b++) { v[b] = g[b, c]; for (int i = 0; i < c; i++) v[b] += g[b, i] * s[i]; }
            return v;
        };
    }

    [Theory]
    [InlineData("nikon-d5100", 0.05, true)]
    [InlineData("wheel-6", 0.02, true)]
    [InlineData("mosaic-16", 0.005, false)]   // 17 coefficients per band fitted to 24 patches can overfit below the bar
    public void FullRangeBar_IsBeyondEveryLinearEstimator_ThatHasNotSeenThePatch(string preset, double bar, bool beyondEvenInSample)
    {
        var a = Forward(preset);
        var cc = TrainingSet.Load("colorchecker", Grid).Samples;
        var rawtoaces = TrainingSet.Load("rawtoaces-190", Grid);
        int c = a.GetLength(0);

        // 1. Wiener with the rawtoaces prior, no noise (what `spectral recover --method wiener` builds, on ideal signals).
        var wiener = SpectralEstimator.Build(RecoveryMethod.Wiener, a, rawtoaces, new double[c]);
        var wienerScore =
            Score(s => { var r = new double[Grid.Count]; wiener.Apply(s.Select(v => (float)v).ToArray(), r); return r; }, a, cc);

        // 2. The best affine estimator trained on the ColorChecker itself, scored leave-one-out (each patch predicted by a
        //    map fitted on the other 23), the ridge chosen with hindsight as the one that scores best.
        var best = (All: double.PositiveInfinity, Visible: 0.0, Nir: 0.0);
        double bestLambda = 0;
        for (double e = -12; e <= 0; e += 1)
        {
            double lambda = Math.Pow(10, e), all = 0, vis = 0, nir = 0;
            for (int j = 0; j < cc.Length; j++)
            {
                var f = FitAffine(a, cc.Where((_, i) => i != j).ToList(), lambda);
                var est = f(Dense.Multiply(a, cc[j]));
                all += Rmse(est, cc[j], 0, Grid.Count); vis += Rmse(est, cc[j], VisLo, VisHi); nir += Rmse(est, cc[j], 17, 20);
            }
            if (all / cc.Length < best.All) { best = (all / cc.Length, vis / cc.Length, nir / cc.Length); bestLambda = lambda; }
        }

        // 3. A lower bound for every affine estimator r̂ = G·s + h (pinv, Wiener with any prior, the linear model and
        //    Tikhonov are all affine in s), even one fitted to these 24 patches: min over (G, h) of Σ_p ‖r_p − G s_p − h‖
        //    (the mean RMSE × 24·√N) is convex; by weak duality every U = [u_p] with ‖u_p‖ ≤ 1 and Σ_p u_p [s_p; 1]ᵀ = 0
        //    bounds it from below by Σ_p u_pᵀ r_p. U is the unit residuals of an iteratively reweighted least-squares fit
        //    (Weiszfeld's scheme), projected onto the constraint and scaled into the unit ball: a certificate, exact
        //    whether or not the iteration converged.
        var weights = Enumerable.Repeat(1.0, cc.Length).ToArray();
        var fit = FitAffine(a, cc, 1e-12);
        for (int it = 0; it < 100; it++)
        {
            for (int j = 0; j < cc.Length; j++) weights[j] = 1 / Math.Max(1e-5, Rmse(fit(Dense.Multiply(a, cc[j])), cc[j], 0, Grid.Count));
            fit = FitAffine(a, cc, 1e-12, weights);
        }
        var achieved = Score(fit, a, cc).All;
        double lowerBound = DualBound(a, cc, fit);

        output.WriteLine($"{preset}: mean ColorChecker RMSE, all 380–780 / 400–700 / 720–780 nm");
        output.WriteLine(
            $"  wiener (rawtoaces-190 prior, ideal signals): {wienerScore.All:F4} / {wienerScore.Visible:F4} / {wienerScore.Nir:F4}");
        output.WriteLine(
            $"  best affine fitted on the chart, leave-one-out (ridge {bestLambda:G1}): {best.All:F4} / {best.Visible:F4} / {best.Nir:F4}");
        output.WriteLine(
            $"  any affine estimator, fitted to the 24 patches themselves: ≥ {lowerBound:F4} (certified), {achieved:F4} reached");

        // The bar holds on 400–700 nm for the shipped prior but no linear estimator reaches it over 380–780 nm on unseen
        // patches, not even one trained on the other 23 patches of the chart.
        Assert.True(wienerScore.Visible <= bar, $"visible {wienerScore.Visible}");
        Assert.True(wienerScore.All > bar, $"all {wienerScore.All}");
        Assert.True(best.All > bar, $"leave-one-out {best.All}");
        Assert.True(lowerBound <= achieved + 1e-12, $"bound {lowerBound} above an achieved {achieved}");
        if (beyondEvenInSample) Assert.True(lowerBound > bar, $"in-sample bound {lowerBound}");
        else Assert.True(achieved <= bar, $"in-sample fit {achieved}");
    }

    /// <summary>The dual certificate of item 3: a lower bound on the mean RMSE of every affine estimator on these patches.</summary>
    static double DualBound(double[,] a, double[][] patches, Func<double[], double[]> fit) =>
        DualBound(patches.Select(r => Dense.Multiply(a, r)).ToArray(), patches, fit);

    static double DualBound(double[][] signals, double[][] patches, Func<double[], double[]> fit)
    {
        int c = signals[0].Length, n = Grid.Count, t = patches.Length;
        var x = new double[c + 1, t];
        var u = new double[n, t];
        for (int j = 0; j < t; j++)
        {
            var s = signals[j];
            for (int i = 0; i < c; i++) x[i, j] = s[i];
            x[c, j] = 1;
            var e = fit(s);
            double norm = Math.Sqrt(Enumerable.Range(0, n).Sum(b => (patches[j][b] - e[b]) * (patches[j][b] - e[b])));
            for (int b = 0; b < n; b++) u[b, j] = (patches[j][b] - e[b]) / norm;
        }
        // U ← U − U Xᵀ (X Xᵀ)⁻¹ X: now Σ_p u_p x_pᵀ = 0.
        var xt = Dense.Transpose(x);
        var proj = Dense.Multiply(Dense.SolveRight(Dense.Multiply(u, xt), Dense.Multiply(x, xt)), x);
        double maxNorm = 0;
        for (int j = 0; j < t; j++)
        {
            double s2 = 0;
            for (int b = 0; b < n; b++) { u[b, j] -= proj[b, j]; s2 += u[b, j] * u[b, j]; }
            maxNorm = Math.Max(maxNorm, Math.Sqrt(s2));
        }
        double dual = 0;
        for (int j = 0; j < t; j++) for (int b = 0; b < n; b++) dual += u[b, j] / maxNorm * patches[j][b];
        return dual / Math.Sqrt(n) / t;
    }

    /// <summary>
    /// The signals as the render makes them: a band value is the band mean of E(λ)·R(λ) ("integration": "exact"), not
    /// E_b·R_b, and the channel weights meet it as `spectral camera` does; rows scaled as in <see cref="Forward"/>.
    /// </summary>
    static double[][] RenderSignals(string preset, IEnumerable<TabulatedSpectrum> reflectances)
    {
        var sensor = SensorPresets.Get(preset);
        var light = SpectrumLibrary.Resolve("D65");
        var w = ChannelWeights.Compute(sensor, Grid, light, 1);
        var e = BandProjection.Means(light, Grid);
        var peak = new double[w.Channels];
        for (int c = 0; c < w.Channels; c++) for (int b = 0; b < Grid.Count; b++) peak[c] = Math.Max(peak[c], w[c, b] * e[b]);
        return reflectances.Select(r =>
        {
            var l = BandProjection.MeansOfProduct(light, r, Grid);
            var s = new double[w.Channels];
            for (int c = 0; c < w.Channels; c++) { for (int b = 0; b < Grid.Count; b++) s[c] += w[c, b] * l[b]; s[c] /= peak[c]; }
            return s;
        }).ToArray();
    }

    static TabulatedSpectrum[] Spectra(string file)
    {
        var t = SpectrumLibrary.DataTable(file);
        return t.Columns.Select(c => t[c]).ToArray();
    }

    /// <summary>
    /// On the signals the render itself produces (band means of E·R, not E_b·R_b): the shipped Wiener (training mean and
    /// covariance, an affine estimate) and the classical correlation-matrix form of spectral imaging (prior E[r rᵀ], no
    /// intercept: G = E[r sᵀ] E[s sᵀ]⁻¹ from the 190 training spectra's own render signals) both meet the bar over
    /// 400–700 nm and both miss it over 380–780 nm; the correlation form is nearer (it scales the unseen near infrared
    /// with the signal instead of predicting the training set's mean there). The in-sample affine bound is unchanged.
    /// </summary>
    [Theory]
    [InlineData("nikon-d5100", 0.05, true)]
    [InlineData("wheel-6", 0.02, true)]
    [InlineData("mosaic-16", 0.005, false)]
    public void NeitherWienerForm_ReachesTheFullRangeBar_OnTheRendersOwnSignals(string preset, double bar, bool beyondEvenInSample)
    {
        var ccSpectra = Spectra(ColorChecker.File);
        var cc = ccSpectra.Select(r => BandProjection.Means(r, Grid).Select(v => Math.Max(0, v)).ToArray()).ToArray();
        var ccSignals = RenderSignals(preset, ccSpectra);
        var rawtoaces = TrainingSet.Load("rawtoaces-190", Grid);
        var trainSignals = RenderSignals(preset, Spectra("reflectances-rawtoaces-190.csv"));
        int c = ccSignals[0].Length, n = Grid.Count, t = rawtoaces.Count;

        (double All, double Visible) Score(Func<double[], double[]> f)
        {
            double all = 0, vis = 0;
            for (int p = 0; p < cc.Length; p++)
            {
                var est = f(ccSignals[p]);
                all += Rmse(est, cc[p], 0, n);
                vis += Rmse(est, cc[p], VisLo, VisHi);
            }
            return (all / cc.Length, vis / cc.Length);
        }

        var wiener = SpectralEstimator.Build(RecoveryMethod.Wiener, Forward(preset), rawtoaces, new double[c]);
        var shipped = Score(s => { var r = new double[n]; wiener.Apply(s.Select(v => (float)v).ToArray(), r); return r; });

        // E[r sᵀ] and E[s sᵀ] over the training set (moments about zero), a 1e-12 ridge.
        var rs = new double[n, c];
        var ss = new double[c, c];
        for (int j = 0; j < t; j++)
        {
            for (int b = 0; b < n; b++) for (int k = 0; k < c; k++) rs[b, k] += rawtoaces.Samples[j][b] * trainSignals[j][k] / t;
            for (int k = 0; k < c; k++) for (int l = 0; l < c; l++) ss[k, l] += trainSignals[j][k] * trainSignals[j][l] / t;
        }
        double unit = Dense.Trace(ss) / c;
        for (int k = 0; k < c; k++) ss[k, k] += 1e-12 * unit;
        var g = Dense.SolveRight(rs, ss);
        var correlation = Score(s =>
        {
            var v = new double[n];
            for (int b = 0; b < n; b++) for (int k = 0; k < c; k++) v[b] += g[b, k] * s[k];
            return v;
        });

        var weights = Enumerable.Repeat(1.0, cc.Length).ToArray();
        var fit = FitAffine(ccSignals, cc, 1e-12);
        for (int it = 0; it < 100; it++)
        {
            for (int j = 0; j < cc.Length; j++) weights[j] = 1 / Math.Max(1e-5, Rmse(fit(ccSignals[j]), cc[j], 0, n));
            fit = FitAffine(ccSignals, cc, 1e-12, weights);
        }
        double achieved = Enumerable.Range(0, cc.Length).Average(j => Rmse(fit(ccSignals[j]), cc[j], 0, n));
        double lowerBound = DualBound(ccSignals, cc, fit);

        output.WriteLine($"{preset}, render signals: mean ColorChecker RMSE over 380–780 / 400–700 nm");
        output.WriteLine($"  wiener as shipped (mean + covariance, affine): {shipped.All:F4} / {shipped.Visible:F4}");
        output.WriteLine($"  wiener, correlation-matrix prior (linear):     {correlation.All:F4} / {correlation.Visible:F4}");
        output.WriteLine($"  any affine estimator fitted to the 24 patches: ≥ {lowerBound:F4} (certified), {achieved:F4} reached");

        Assert.True(shipped.Visible <= bar && correlation.Visible <= bar, $"visible {shipped.Visible} / {correlation.Visible}");
        Assert.True(shipped.All > bar && correlation.All > bar, $"all {shipped.All} / {correlation.All}");
        Assert.True(correlation.All < shipped.All);
        Assert.True(lowerBound <= achieved + 1e-12);
        if (beyondEvenInSample) Assert.True(lowerBound > bar, $"in-sample bound {lowerBound}");
    }
}
