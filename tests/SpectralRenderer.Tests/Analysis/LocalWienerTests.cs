using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;
using Xunit.Abstractions;
using static SpectralRenderer.Tests.Analysis.RecoveryBoundTests;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// `--method wiener-local` (<see cref="LocalWiener"/>) on the ideal signals s = A·r of the 24 Ohta patches (band means
/// on 380:780:20, D65, no noise, as <see cref="RecoveryBoundTests"/>): its estimate against the Wiener formula computed
/// densely in the test, its limits, and its figures against the textbook (global) Wiener estimate. Its widths are
/// chosen on the rawtoaces-190 training set alone; the ColorChecker only scores.
/// </summary>
public class LocalWienerTests(ITestOutputHelper output)
{
    static readonly BandGrid Grid = new(380, 780, 20);
    static readonly TrainingSet Rawtoaces = TrainingSet.Load("rawtoaces-190", Grid);
    static readonly double[][] Chart = TrainingSet.Load("colorchecker", Grid).Samples;

    static Func<double[], double[]> Estimate(SpectralEstimator e) => s =>
    {
        var r = new double[Grid.Count];
        e.Apply(s.Select(v => (float)v).ToArray(), r);
        return r;
    };

    /// <summary>
    /// The locally weighted prior beats the global one over every range for every preset; over 380–780 nm it meets none
    /// of the issue's bars but closes most of the gap for the wheel (0.051 → 0.024, bar 0.02) — the figures docs/camera.md
    /// gives, asserted as upper limits.
    /// </summary>
    [Theory]
    [InlineData("nikon-d5100", 0.05, 0.065)]
    [InlineData("wheel-6", 0.02, 0.026)]
    [InlineData("mosaic-16", 0.005, 0.019)]
    public void OnIdealSignals_BeatsTheGlobalWiener_OverEveryRange(string preset, double bar, double atMost)
    {
        var a = Forward(preset);
        int c = a.GetLength(0);
        var wiener = Score(Estimate(SpectralEstimator.Build(RecoveryMethod.Wiener, a, Rawtoaces, new double[c])), a, Chart);
        var estimator = SpectralEstimator.Build(RecoveryMethod.WienerLocal, a, Rawtoaces, new double[c]);
        var local = Score(Estimate(estimator), a, Chart);
        var l = estimator.Local!;
        output.WriteLine($"{preset}: mean ColorChecker RMSE, 380–780 / 400–700 / 720–780 nm");
        output.WriteLine($"  wiener:       {wiener.All:F4} / {wiener.Visible:F4} / {wiener.Nir:F4}");
        output.WriteLine($"  wiener-local: {local.All:F4} / {local.Visible:F4} / {local.Nir:F4}  (h_c {l.ChromaticityWidth}, h_I "
            + $"{l.IntensityWidth}, β {l.Shrinkage}; training leave-one-out {l.LeaveOneOutRmse:F4})");
        Assert.True(local.All < wiener.All && local.Visible < wiener.Visible && local.Nir < wiener.Nir, $"{local} vs {wiener}");
        Assert.True(local.All <= atMost, $"all {local.All}");
        Assert.True(local.Visible <= bar, $"visible {local.Visible}");
    }

    /// <summary>
    /// The estimate equals the Wiener formula with the weighted prior written out densely: the weights from the
    /// white-relative chromaticity and intensity, μ_w and K_w as N × N sums over the training set, K = (1 − β)K_w + βK_r,
    /// r̂ = μ_w + K Aᵀ (A K Aᵀ + K_n)⁻¹ (s − A μ_w) by Gaussian elimination — not the C × C sample-space form the code uses.
    /// A noise term exercises K_n; one channel scaled by 1000 checks the features are white-relative.
    /// </summary>
    [Theory]
    [InlineData("nikon-d5100")]
    [InlineData("mosaic-16")]
    public void Estimate_IsTheWienerFormula_WithTheWeightedPrior(string preset)
    {
        var a = Forward(preset);
        int c = a.GetLength(0), n = Grid.Count, t = Rawtoaces.Count;
        for (int b = 0; b < n; b++) a[0, b] *= 1000;
        var kr = Rawtoaces.Covariance();
        var akat = Dense.Multiply(a, Dense.Multiply(kr, Dense.Transpose(a)));
        var noise = Enumerable.Range(0, c).Select(i => 1e-4 * akat[i, i]).ToArray();
        var local = LocalWiener.Build(a, Rawtoaces, noise);
        double hc = local.ChromaticityWidth, hi = local.IntensityWidth, beta = local.Shrinkage;
        var white = Dense.Multiply(a, Enumerable.Repeat(1.0, n).ToArray());
        (double[] Q, double LogI) Feature(double[] s)
        {
            var u = s.Select((v, i) => v / white[i]).ToArray();
            double norm = Math.Sqrt(u.Sum(v => v * v));
            return (u.Select(v => v / norm).ToArray(), Math.Log(norm));
        }
        var train = Rawtoaces.Samples.Select(r => Feature(Dense.Multiply(a, r))).ToArray();

        double worst = 0;
        foreach (var patch in Chart)
        {
            var sf = Dense.Multiply(a, patch).Select(v => (double)(float)v).ToArray();
            var (q, li) = Feature(sf);
            var w = train.Select(f =>
            {
                double dq = q.Zip(f.Q, (x, y) => (x - y) * (x - y)).Sum(), dl = li - f.LogI;
                return Math.Exp(-0.5 * (dq / (hc * hc) + (double.IsPositiveInfinity(hi) ? 0 : dl * dl / (hi * hi))));
            }).ToArray();
            double sw = w.Sum();
            var mu = new double[n];
            for (int j = 0; j < t; j++) for (int b = 0; b < n; b++) mu[b] += w[j] * Rawtoaces.Samples[j][b] / sw;
            var k = new double[n, n];
            for (int j = 0; j < t; j++)
                for (int p = 0; p < n; p++)
                    for (int r = 0; r < n; r++)
                        k[p, r] += (1 - beta) * w[j] * (Rawtoaces.Samples[j][p] - mu[p]) * (Rawtoaces.Samples[j][r] - mu[r]) / sw;
            k = Dense.Add(k, Dense.Multiply(Dense.Identity(n, beta), kr));
            var kat = Dense.Multiply(k, Dense.Transpose(a));
            var m = Dense.Multiply(a, kat);
            for (int i = 0; i < c; i++) m[i, i] += noise[i];
            var g = Dense.SolveRight(kat, m);
            var amu = Dense.Multiply(a, mu);
            var reference = Enumerable.Range(0, n).Select(b => mu[b] + Enumerable.Range(0, c).Sum(i => g[b, i] * (sf[i] - amu[i])))
                .ToArray();

            var got = new double[n];
            local.Apply(sf.Select(v => (float)v).ToArray(), got);
            for (int b = 0; b < n; b++) worst = Math.Max(worst, Math.Abs(got[b] - reference[b]));
        }
        output.WriteLine($"{preset}: largest difference from the dense formula {worst:E2} (h_c {hc}, h_I {hi}, β {beta})");
        Assert.True(worst < 1e-7, $"{worst}");
    }

    /// <summary>
    /// With weights that do not depend on the signal (an infinitely wide kernel) the prior is the whole set's, so without
    /// noise the estimate is the textbook Wiener estimate (K's scale cancels in K Aᵀ (A K Aᵀ)⁻¹); and it does not depend on
    /// the channels' scales (an exposure or gain per channel), which the features divide out.
    /// </summary>
    [Fact]
    public void InfinitelyWideWeights_GiveTheTextbookWiener_AndChannelScalesDoNotMatter()
    {
        var a = Forward("wheel-6");
        int c = a.GetLength(0), n = Grid.Count;
        var wide = LocalWiener.Build(a, Rawtoaces, new double[c], (1e9, double.PositiveInfinity, 0.3));
        var wiener = SpectralEstimator.Build(RecoveryMethod.Wiener, a, Rawtoaces, new double[c]);
        var scaled = (double[,])a.Clone();
        for (int i = 0; i < c; i++) for (int b = 0; b < n; b++) scaled[i, b] *= Math.Pow(10, i - 2);
        var local = LocalWiener.Build(a, Rawtoaces, new double[c]);
        var localScaled = LocalWiener.Build(scaled, Rawtoaces, new double[c]);
        Assert.Equal((local.ChromaticityWidth, local.IntensityWidth, local.Shrinkage),
            (localScaled.ChromaticityWidth, localScaled.IntensityWidth, localScaled.Shrinkage));
        double wideDiff = 0, scaleDiff = 0;
        foreach (var patch in Chart)
        {
            var s = Dense.Multiply(a, patch).Select(v => (float)v).ToArray();
            var ss = Dense.Multiply(scaled, patch).Select(v => (float)v).ToArray();
            var (x, y, z, u) = (new double[n], new double[n], new double[n], new double[n]);
            wide.Apply(s, x);
            wiener.Apply(s, y);
            local.Apply(s, z);
            localScaled.Apply(ss, u);
            for (int b = 0; b < n; b++)
            {
                wideDiff = Math.Max(wideDiff, Math.Abs(x[b] - y[b]));
                scaleDiff = Math.Max(scaleDiff, Math.Abs(z[b] - u[b]));
            }
        }
        output.WriteLine($"infinitely wide vs wiener {wideDiff:E2}; channels scaled by 10^(i−2) {scaleDiff:E2}");
        Assert.True(wideDiff < 1e-6, $"{wideDiff}");
        Assert.True(scaleDiff < 1e-5, $"{scaleDiff}");
    }

    /// <summary>
    /// The training set does not contain the chart (the nearest rawtoaces spectrum to each Ohta patch is 0.0036 RMSE away at
    /// best — the black and the neutral 3.5 — and 0.02 or more for 13 of the 24), so the figures above are not a
    /// lookup. And the chart's near infrared is not that of its visible look-alikes there: given the true 380–700 nm
    /// reflectance, the 700–780 nm rise taken from the training spectrum nearest over 400–700 nm (joined at 700 nm)
    /// still misses by 0.027 mean RMSE over all bands — above the wheel's and the mosaic's bars (an illustration, not
    /// a bound: wiener-local does better for the wheel).
    /// </summary>
    [Fact]
    public void TrainingSet_DoesNotHoldTheChart_AndItsNearestNeighboursMissTheNearInfrared()
    {
        var t = Rawtoaces.Samples;
        var nearest = Chart.Select(p => t.Min(r => Rmse(p, r, 0, Grid.Count))).ToArray();
        output.WriteLine($"nearest training spectrum per patch (RMSE 380–780): {string.Join(" ", nearest.Select(v => v.ToString("F4")))}");
        Assert.True(nearest.Min() > 0.003, $"{nearest.Min()}");
        Assert.Equal(13, nearest.Count(v => v >= 0.02));

        double oracle = 0;
        foreach (var p in Chart)
        {
            var nn = t.MinBy(r => Rmse(p, r, VisLo, VisHi))!;
            var e = (double[])p.Clone();
            for (int b = VisHi; b < Grid.Count; b++) e[b] = nn[b] - nn[VisHi - 1] + p[VisHi - 1];
            oracle += Rmse(e, p, 0, Grid.Count) / Chart.Length;
        }
        output.WriteLine($"true 380–700 nm + the near infrared of the training spectrum nearest over 400–700 nm: {oracle:F4}");
        Assert.True(oracle > 0.02, $"{oracle}");
    }

    /// <summary>
    /// Not fooling ourselves: with the 11 training spectra that lie within 0.02 RMSE of a chart patch removed (179 left),
    /// the local estimate loses some of its gain (it is local: near neighbours are what it uses) but still beats the
    /// global Wiener estimate over all bands for every preset.
    /// </summary>
    [Fact]
    public void WithoutTheTrainingSpectraNearestTheChart_ItStillBeatsTheGlobalWiener()
    {
        var drop = new HashSet<int>();
        foreach (var p in Chart)
        {
            int nearest = Enumerable.Range(0, Rawtoaces.Count).MinBy(j => Rmse(p, Rawtoaces.Samples[j], 0, Grid.Count));
            if (Rmse(p, Rawtoaces.Samples[nearest], 0, Grid.Count) < 0.02) drop.Add(nearest);
        }
        var lines = File.ReadAllLines(DataDirectory.File_("reflectances-rawtoaces-190.csv"));
        var keep = Enumerable.Range(0, lines[0].Split(',').Length).Where(k => k == 0 || !drop.Contains(k - 1)).ToArray();
        var csv = Path.Combine(Reference.TempDir(), "rawtoaces-without-chart-neighbours.csv");
        File.WriteAllLines(csv, lines.Select(l => { var f = l.Split(','); return string.Join(",", keep.Select(k => f[k])); }));
        var reduced = TrainingSet.Load(csv, Grid);
        Assert.Equal(Rawtoaces.Count - drop.Count, reduced.Count);
        output.WriteLine($"{drop.Count} training spectra removed, {reduced.Count} left; mean ColorChecker RMSE 380–780 / 400–700 nm:");
        foreach (var preset in new[] { "nikon-d5100", "wheel-6", "mosaic-16" })
        {
            var a = Forward(preset);
            int c = a.GetLength(0);
            var wiener = Score(Estimate(SpectralEstimator.Build(RecoveryMethod.Wiener, a, reduced, new double[c])), a, Chart);
            var local = Score(Estimate(SpectralEstimator.Build(RecoveryMethod.WienerLocal, a, reduced, new double[c])), a, Chart);
            output.WriteLine($"  {preset}: wiener {wiener.All:F4} / {wiener.Visible:F4}, wiener-local {local.All:F4} / {local.Visible:F4}");
            Assert.True(local.All < wiener.All && local.Visible < wiener.Visible, preset);
        }
    }
}
