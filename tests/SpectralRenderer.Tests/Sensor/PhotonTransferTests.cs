using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// The EMVA 1288 (release 4.0) photon-transfer method on simulated frames of a uniformly lit 64 × 64 region:
/// temporal variance from the difference of two frames, σ²_y = var(A − B)/2, which cancels PRNU and DSNU; the
/// system gain K from the slope (through the origin) of σ²_y − σ²_y,dark against μ_y − μ_y,dark below 70 % of saturation; the read
/// noise from the dark variance, σ_d = √(σ²_y,dark − 1/12)/K; the dark current from the slope of the dark mean
/// against the exposure time. The photon count is computed here from the radiometry, not from the code's weights.
/// </summary>
public class PhotonTransferTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const int Size = 64, Pairs = 8;
    // 500–600 nm, one band; flat QE 1: photons/s = L·A·ff·πT/(1+4N²)·∫λ/(hc)dλ.
    static readonly BandGrid Grid = new(500, 600, 1);
    static readonly TabulatedSpectrum Flat = TabulatedSpectrum.Constant(1);

    static SensorModel Sensor(double? exposure) => SensorPresets.Get("isetcam") with
    {
        PrnuPercent = 1,
        DsnuVolts = 1e-3,
        AnalogGain = 0.8,
        BlackLevel = 64,
        ExposureSeconds = exposure,
    };

    static float[] Frame(SensorModel sensor, double radiance, ulong seed)
    {
        var data = new float[Size * Size];
        Array.Fill(data, (float)radiance);
        return SensorSimulation.Run(sensor, new RadianceCube(Size, Size, Grid, data, 1), Flat, new SimulationOptions { Seed = seed }).Dn;
    }

    /// <summary>Mean of both frames of each pair and the temporal variance var(A − B)/2, averaged over the pairs.</summary>
    static (double Mean, double Variance) Stats(SensorModel sensor, double radiance, ulong seed)
    {
        double mean = 0, variance = 0;
        for (int k = 0; k < Pairs; k++)
        {
            var a = Frame(sensor, radiance, seed + 2 * (ulong)k);
            var b = Frame(sensor, radiance, seed + 2 * (ulong)k + 1);
            double m = 0, d = 0, dd = 0;
            for (int i = 0; i < a.Length; i++) { m += a[i] + b[i]; double x = a[i] - b[i]; d += x; dd += x * x; }
            int n = a.Length;
            mean += m / (2 * n);
            variance += (dd - d * d / n) / (n - 1) / 2;
        }
        return (mean / Pairs, variance / Pairs);
    }

    static double ElectronRate(SensorModel s, double radiance)
    {
        double etendue =
            Math.Pow(s.PixelSizeMicrons * 1e-6, 2) * s.FillFactor * Math.PI * s.OpticsTransmittance / (1 + 4 * s.FNumber * s.FNumber);
        double photonsPerWatt = (600.0 * 600 - 500.0 * 500) / 2 * 1e-9 / (6.62607015e-34 * 299792458);   // ∫ λ/(hc) dλ, λ in m, dλ in nm
        return radiance * etendue * photonsPerWatt;
    }

    static (double Slope, double Intercept) Fit(IReadOnlyList<double> x, IReadOnlyList<double> y)
    {
        double mx = x.Average(), my = y.Average(), sxy = 0, sxx = 0;
        for (int i = 0; i < x.Count; i++) { sxy += (x[i] - mx) * (y[i] - my); sxx += (x[i] - mx) * (x[i] - mx); }
        return (sxy / sxx, my - sxy / sxx * mx);
    }

    [Fact]
    public void PhotonTransfer_GivesBackConversionGainAndReadNoise()
    {
        const double radiance = 0.05;   // W·m⁻²·sr⁻¹·nm⁻¹
        var baseSensor = Sensor(null);
        double rate = ElectronRate(baseSensor, radiance);
        double tSat = baseSensor.FullWellElectrons / rate;
        var mu = new List<double>();
        var var = new List<double>();
        var mus = new List<double>();
        double darkMean = 0, darkVar = 0;
        for (int level = 0; level < 10; level++)
        {
            double t = tSat * (0.05 + 0.1 * level);   // 5 % … 95 % of the full well
            var s = Sensor(t);
            var (m, v) = Stats(s, radiance, 1000 + 100 * (ulong)level);
            var (md, vd) = Stats(s, 0, 5000 + 100 * (ulong)level);
            if (level == 0) { darkMean = md; darkVar = vd; }
            mus.Add(m - md);
            if (m - md < 0.7 * (s.WhiteLevel - s.BlackLevel) * s.AnalogGain) { mu.Add(m - md); var.Add(v - vd); }
        }
        // EMVA 1288's model σ²_y − σ²_y,dark = K (μ_y − μ_y,dark) has no offset: least squares through the origin.
        double k = mu.Zip(var, (x, y) => x * y).Sum() / mu.Sum(x => x * x);
        double configuredK = baseSensor.SystemGain;
        output.WriteLine($"K measured {k:G5} DN/e⁻, configured {configuredK:G5} ({k / configuredK - 1:P2})");
        Assert.InRange(k / configuredK, 0.98, 1.02);

        // Electrons counted from the radiometry: μ_e = ė·t, so μ_y − μ_y,dark = K·μ_e.
        double t5 = tSat * 0.05;
        Assert.InRange(mus[0] / (configuredK * rate * t5), 0.995, 1.005);

        double readNoise = Math.Sqrt(darkVar - 1.0 / 12) / k;   // electrons (dark shot noise is negligible at these exposures)
        output.WriteLine($"read noise measured {readNoise:G5} e⁻, configured {baseSensor.ReadNoiseElectrons:G5} "
            + $"({readNoise / baseSensor.ReadNoiseElectrons - 1:P2})");
        Assert.InRange(readNoise / baseSensor.ReadNoiseElectrons, 0.98, 1.02);
        Assert.True(darkMean > baseSensor.BlackLevel - 1);
    }

    [Fact]
    public void DarkFrames_GiveBackTheDarkCurrent()
    {
        var times = Enumerable.Range(0, 10).Select(i => 10.0 * i).ToList();   // 0 … 90 s: 0 … 900 dark electrons
        var means = times.Select((t, i) => Stats(Sensor(t), 0, 9000 + 10 * (ulong)i).Mean).ToList();
        var (slope, _) = Fit(times, means);
        var s = Sensor(1);
        double darkCurrent = slope / s.SystemGain;   // e⁻/s
        output.WriteLine($"dark current measured {darkCurrent:G5} e⁻/s, configured {s.DarkCurrentElectronsPerSecond:G5} "
            + $"({darkCurrent / s.DarkCurrentElectronsPerSecond - 1:P2})");
        Assert.InRange(darkCurrent / s.DarkCurrentElectronsPerSecond, 0.95, 1.05);
    }

    [Fact]
    public void FullWell_PlateauIsWhereConfigured()
    {
        const double radiance = 0.05;
        var s0 = Sensor(null);
        double tSat = s0.FullWellElectrons / ElectronRate(s0, radiance);
        double plateau = s0.BlackLevel + s0.SystemGain * s0.FullWellElectrons;   // below the ADC's white with analog gain 0.8
        Assert.True(plateau < s0.WhiteLevel - 50);
        var (m2, v2) = Stats(Sensor(2 * tSat), radiance, 77);
        var (m4, v4) = Stats(Sensor(4 * tSat), radiance, 99);
        var (m5, v5) = Stats(Sensor(0.5 * tSat), radiance, 55);
        output.WriteLine($"plateau configured {plateau:F2} DN; measured {m2:F2} (2× saturation), {m4:F2} (4×); variance {v2:F2} DN² vs "
            + $"read+quantisation {Math.Pow(s0.SystemGain * s0.ReadNoiseElectrons, 2) + 1.0 / 12:F2}");
        Assert.InRange(m2, plateau - 1, plateau + 1);
        Assert.InRange(m4, plateau - 1, plateau + 1);
        // At the plateau only read noise and quantisation remain: far below the shot-noise variance at half the well.
        double readVar = Math.Pow(s0.SystemGain * s0.ReadNoiseElectrons, 2) + 1.0 / 12;
        Assert.InRange(v2, 0.9 * readVar, 1.1 * readVar);
        Assert.True(v5 > 50 * v2);
    }
}
