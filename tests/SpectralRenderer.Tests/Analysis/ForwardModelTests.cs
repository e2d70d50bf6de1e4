using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Sensor;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// The recovery's forward model at full resolution (issue 24, the exact route), without a render: its signals and band
/// means against CIE 015's 1 nm sum and 0.1 nm band means computed here, and mosaic-16's ColorChecker recovery from exact
/// signals (that sum, the exact route's signals of the 24 Ohta patches head-on under D65) with it and with the band model.
/// </summary>
public class ForwardModelTests(ITestOutputHelper output)
{
    static readonly BandGrid Grid = new(380, 780, 20);
    static readonly Lazy<TrainingSet> Training = new(() => TrainingSet.Load("rawtoaces-190", Grid));
    static readonly (double[] Wl, double[] V) D65 = ExactSignalsTests.Table("illuminants.csv", "D65");

    /// <summary>The 24 Ohta patches as tabulated (data/colorchecker-ohta.csv).</summary>
    static readonly Lazy<(double[] Wl, double[] V)[]> Patches = new(() =>
    {
        var header = File.ReadLines(Path.Combine(DataDirectory.Path, "colorchecker-ohta.csv")).First().Split(',');
        return Enumerable.Range(1, 24).Select(p => ExactSignalsTests.Table("colorchecker-ohta.csv", header[p])).ToArray();
    });

    /// <summary>The midpoints of 0.1 nm steps over 380–780 nm.</summary>
    const int Steps = 4000;
    static double At(int k) => 380 + (k + 0.5) * 0.1;

    /// <summary>A table's linear interpolant at the midpoints.</summary>
    static double[] Sampled((double[] Wl, double[] V) t) =>
        Enumerable.Range(0, Steps).Select(k => ExactSignalsTests.Lerp(t, At(k))).ToArray();

    static readonly Lazy<double[][]> PatchesSampled = new(() => Patches.Value.Select(Sampled).ToArray());

    /// <summary>
    /// Σ ρ·E·η·λ (nm², E relative, η a quantum efficiency; a per-energy channel's η = R·555 nm/λ), CIE 015's 1 nm sum
    /// (trapezoidal form, <see cref="Cie015.Sum"/>) of the tables' linear interpolants, for each of <paramref name="rho"/>
    /// (null: ρ = 1).
    /// </summary>
    static double[] Integrals(SensorChannel ch, (double[] Wl, double[] V)[]? rho)
    {
        var qe = (ch.QuantumEfficiency.Wavelengths.ToArray(), ch.QuantumEfficiency.Values.ToArray());
        bool zero = ch.QuantumEfficiency.Extrapolation == Extrapolation.Zero;
        double F(int wl)
        {
            if (zero && (wl < qe.Item1[0] || wl > qe.Item1[^1])) return 0;
            double eta = ExactSignalsTests.Lerp(qe, wl);
            if (ch.PerEnergy) eta *= SensorChannel.EnergyReferenceNm / wl;
            return ExactSignalsTests.Lerp(D65, wl) * eta * wl;
        }
        return rho is null ? [Cie015.Sum(F)]
            : rho.Select(r => Cie015.Sum(wl => ExactSignalsTests.Lerp(r, wl) * F(wl))).ToArray();
    }

    /// <summary>The band means on <see cref="Grid"/> (20 nm: 200 midpoints each) of a sampled table.</summary>
    static double[] BandMeans(double[] sampled) =>
        Enumerable.Range(0, Grid.Count).Select(b => sampled.AsSpan(b * 200, 200).ToArray().Average()).ToArray();

    [Theory]
    [InlineData("mosaic-16")]
    [InlineData("nikon-d5100")]
    [InlineData("cie-xyz")]
    public void ExactModel_IsTheExactIntegralOfAKnotSpectrum_AndGivesItsBandMeans(string preset)
    {
        var sensor = SensorPresets.Get(preset);
        var model = ForwardModel.Exact(sensor, 1, 1, SpectrumLibrary.Resolve("D65"), Grid, Training.Value);
        Assert.Equal("exact", model.Route);
        Assert.Equal(81, model.Knots!.Length);   // rawtoaces: 380–780 nm every 5 nm
        var white = model.White();
        var rho = PatchesSampled.Value;
        var s = Patches.Value
            .Select(r => Dense.Multiply(model.A, model.Knots.Select(k => ExactSignalsTests.Lerp(r, k)).ToArray())).ToArray();
        for (int c = 0; c < sensor.ChannelCount; c++)
        {
            double expected = Integrals(sensor.Channels[c], null)[0];
            Assert.True(Math.Abs(white[c] / expected - 1) <= 1e-4, $"{preset} {c}: A·1 {white[c]} vs {expected}");
            // The Ohta patches are tabulated on the same 5 nm knots, so their values there are the model's coordinates.
            var patches = Integrals(sensor.Channels[c], Patches.Value);
            for (int p = 0; p < patches.Length; p++)
                Assert.True(Math.Abs(s[p][c] / patches[p] - 1) <= 1e-4,
                    $"{preset} channel {c}, patch {p + 1}: {s[p][c]} vs the 1 nm sum {patches[p]}");
        }
        for (int p = 0; p < rho.Length; p++)
        {
            var bands = model.ToBands(model.Knots.Select(k => ExactSignalsTests.Lerp(Patches.Value[p], k)).ToArray());
            var means = BandMeans(rho[p]);
            for (int b = 0; b < Grid.Count; b++)
                Assert.True(Math.Abs(bands[b] - means[b]) <= 1e-6, $"{preset} band {b}: {bands[b]} vs {means[b]}");
        }
    }

    /// <summary>
    /// mosaic-16 and the 24 Ohta patches head-on under D65: their exact signals (the 1 nm sum, e⁻/s), the band route's
    /// signals (A·r_b, r_b their band means: what a band cube gives), the band means, the capture's noise-free K_n (the
    /// 1/12 DN² quantisation floor at the auto exposure: the brightest signal at 0.8 of the full well, one frame), and the
    /// two forward models.
    /// </summary>
    sealed record Mosaic(double[][] ExactSignals, double[][] BandSignals, double[][] Truth, double[] Kn, ForwardModel Exact,
        ForwardModel Bands);

    static readonly Lazy<Mosaic> MosaicCase = new(() =>
    {
        var sensor = SensorPresets.Get("mosaic-16");
        var d65 = SpectrumLibrary.Resolve("D65");
        double factor = ChannelWeights.FactorOf(sensor, 1);
        var patches = PatchesSampled.Value;
        int c = sensor.ChannelCount;
        var perChannel = sensor.Channels.Select(ch => Integrals(ch, Patches.Value)).ToArray();
        var exactSignals = Enumerable.Range(0, patches.Length)
            .Select(p => Enumerable.Range(0, c).Select(k => factor * perChannel[k][p]).ToArray()).ToArray();
        var truth = patches.Select(BandMeans).ToArray();
        var w = ChannelWeights.Compute(sensor, Grid, d65, 1);
        var e = BandProjection.Means(d65, Grid);
        var a = new double[c, Grid.Count];
        for (int k = 0; k < c; k++) for (int b = 0; b < Grid.Count; b++) a[k, b] = w[k, b] * e[b];
        var bandSignals = truth.Select(r => Dense.Multiply(a, r)).ToArray();
        double t = sensor.AutoExposureFraction * sensor.FullWellElectrons / exactSignals.Max(s => s.Max());
        var kn = Enumerable.Repeat(1.0 / 12 / (sensor.SystemGain * t * sensor.SystemGain * t), c).ToArray();
        return new Mosaic(exactSignals, bandSignals, truth, kn, ForwardModel.Exact(sensor, factor, 1, d65, Grid, Training.Value),
            ForwardModel.Bands(a, Training.Value));
    });

    delegate void Estimate(ReadOnlySpan<float> signal, Span<double> reflectance);

    /// <summary>The mean over the patches of the RMSE over 400–700 nm of an estimate from each patch's signal.</summary>
    static double Score(Estimate estimate, double[][] signals, double[][] truth)
    {
        double sum = 0;
        var r = new double[Grid.Count];
        for (int p = 0; p < signals.Length; p++)
        {
            estimate(signals[p].Select(v => (float)v).ToArray(), r);
            sum += RecoveryBoundTests.Rmse(r, truth[p], RecoveryBoundTests.VisLo, RecoveryBoundTests.VisHi);
        }
        return sum / signals.Length;
    }

    /// <summary>
    /// Issue 24's open point closed: mosaic-16's 24 patches recovered from their exact signals, noise-free, mean ColorChecker
    /// RMSE over 400–700 nm. With the band model (A_c,b = w_c,b·E_b, reflectance constant in each band) the Wiener estimate
    /// misses the bar 0.005 (0.0055); with the model at full resolution it meets it (0.0011) and does better than the band
    /// route on its own band-constant signals (0.0013). These are the figures of the rendered chart (docs/camera.md).
    /// </summary>
    [Fact]
    public void Mosaic16_FromExactSignals_WienerWithTheFullResolutionModel_MeetsTheBar()
    {
        var m = MosaicCase.Value;
        var right = SpectralEstimator.Build(RecoveryMethod.Wiener, m.Exact, m.Kn);
        var band = SpectralEstimator.Build(RecoveryMethod.Wiener, m.Bands, m.Kn);
        double exact = Score(right.Apply, m.ExactSignals, m.Truth), wrong = Score(band.Apply, m.ExactSignals, m.Truth);
        double bandRoute = Score(band.Apply, m.BandSignals, m.Truth);
        output.WriteLine($"Wiener: exact signals, full-resolution model {exact:F5}, band model {wrong:F5}; band route {bandRoute:F5}");
        Assert.True(wrong > 0.005, $"the band model on exact signals {wrong}: the gap this fixes");
        Assert.True(exact <= 0.005 && exact <= bandRoute,
            $"Wiener on exact signals {exact} vs the bar 0.005 and the band route's {bandRoute}");
    }

    /// <summary>
    /// The other methods on the same signals: each does better with the model at full resolution than with the band model
    /// (wiener-local at fixed widths; its leave-one-out search is RecoveryTests').
    /// </summary>
    [Fact]
    public void Mosaic16_FromExactSignals_EveryOtherMethodGainsFromTheFullResolutionModel()
    {
        var m = MosaicCase.Value;
        foreach (var method in new[] { RecoveryMethod.Pinv, RecoveryMethod.Linear, RecoveryMethod.Tikhonov, RecoveryMethod.WienerLocal })
        {
            Estimate Estimator(ForwardModel model) => method == RecoveryMethod.WienerLocal
                ? LocalWiener.Build(model, m.Kn, (0.2, 0.25, 0.03)).Apply
                : SpectralEstimator.Build(method, model, m.Kn).Apply;
            double right = Score(Estimator(m.Exact), m.ExactSignals, m.Truth), wrong = Score(Estimator(m.Bands), m.ExactSignals, m.Truth);
            output.WriteLine($"{method}: exact signals, full-resolution model {right:F5}, band model {wrong:F5}");
            Assert.True(right < wrong, $"{method}: the full-resolution model {right} vs the band model {wrong} on exact signals");
        }
    }
}
