using SpectralRenderer.Sensor;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// The noise generators against their distributions: moments (mean, variance) within four standard errors, and
/// Pearson's χ² of histograms against probabilities computed here another way (the Poisson pmf by its recurrence, the
/// normal density integrated by Simpson's rule), at a significance of 1e-5 (Wilson–Hilferty's χ² quantile).
/// </summary>
public class NoiseStreamTests(Xunit.Abstractions.ITestOutputHelper output)
{
    [Theory]
    [InlineData(0.7)]
    [InlineData(6)]
    [InlineData(9.999)]
    [InlineData(10)]
    [InlineData(40)]
    [InlineData(5000)]
    public void Poisson_HasMeanAndVarianceMu(double mu)
    {
        const int n = 400_000;
        double s = 0, s2 = 0;
        for (int i = 0; i < n; i++)
        {
            var r = new NoiseStream(42, 9, i, 0);
            double k = r.Poisson(mu);
            Assert.Equal(Math.Floor(k), k);
            s += k; s2 += k * k;
        }
        double mean = s / n, variance = (s2 - s * s / n) / (n - 1);
        output.WriteLine($"μ = {mu}: mean {mean:G6}, variance {variance:G6}");
        Assert.InRange(mean, mu - 4 * Math.Sqrt(mu / n), mu + 4 * Math.Sqrt(mu / n));
        // var of the sample variance ≈ (2μ² + μ)/n for a Poisson (fourth central moment μ + 3μ²).
        double se = Math.Sqrt((2 * mu * mu + mu) / n);
        Assert.InRange(variance, mu - 4 * se, mu + 4 * se);
    }

    [Fact]
    public void Normal_HasMeanZeroAndVarianceOne()
    {
        const int n = 400_000;
        double s = 0, s2 = 0;
        for (int i = 0; i < n; i++) { var r = new NoiseStream(7, 5, i, 3); double x = r.Normal(); s += x; s2 += x * x; }
        double mean = s / n, variance = s2 / n - mean * mean;
        Assert.InRange(mean, -4 / Math.Sqrt(n), 4 / Math.Sqrt(n));
        Assert.InRange(variance, 1 - 4 * Math.Sqrt(2.0 / n), 1 + 4 * Math.Sqrt(2.0 / n));
    }

    /// <summary>The χ² quantile of d degrees of freedom at upper tail 1e-5 (Wilson &amp; Hilferty 1931; z = 4.2649).</summary>
    static double ChiSquareCritical(int d) => d * Math.Pow(1 - 2.0 / (9 * d) + 4.2649 * Math.Sqrt(2.0 / (9 * d)), 3);

    /// <summary>Pearson's χ² of counts against expected counts, bins merged from the left until each expects ≥ 20.</summary>
    static (double Chi2, int Dof) Pearson(long[] counts, double[] expected)
    {
        double chi = 0, o = 0, e = 0;
        int bins = 0;
        for (int i = 0; i < counts.Length; i++)
        {
            o += counts[i]; e += expected[i];
            if (e >= 20 || i == counts.Length - 1) { chi += (o - e) * (o - e) / e; bins++; o = 0; e = 0; }
        }
        return (chi, bins - 1);
    }

    [Theory]
    [InlineData(0.05)]
    [InlineData(0.7)]
    [InlineData(6)]
    [InlineData(9.999)]
    [InlineData(10)]
    [InlineData(23.5)]
    [InlineData(5000)]
    public void Poisson_HistogramMatchesThePmf(double mu)
    {
        const int n = 300_000;
        int lo = (int)Math.Max(0, Math.Floor(mu - 8 * Math.Sqrt(mu) - 2)), hi = (int)Math.Ceiling(mu + 8 * Math.Sqrt(mu) + 10);
        var counts = new long[hi - lo + 2];   // [lo−, lo … hi, hi+] folded into the end bins
        for (int i = 0; i < n; i++)
        {
            int k = (int)new NoiseStream(1234, 17, i, 2).Poisson(mu);
            counts[Math.Clamp(k - lo, 0, counts.Length - 1)]++;
        }
        // pmf by p(k) = p(k − 1)·μ/k in logs from ln p(0) = −μ, summed in the same bins.
        var expected = new double[counts.Length];
        double logp = -mu, total = 0;
        for (int k = 0; k <= hi + 200; k++)
        {
            if (k > 0) logp += Math.Log(mu / k);
            double p = Math.Exp(logp);
            expected[Math.Clamp(k - lo, 0, counts.Length - 1)] += p * n;
            total += p;
        }
        Assert.InRange(total, 1 - 1e-9, 1 + 1e-9);
        var (chi, dof) = Pearson(counts, expected);
        output.WriteLine($"μ = {mu}: χ² = {chi:F1} on {dof} degrees of freedom (critical {ChiSquareCritical(dof):F1})");
        Assert.True(chi < ChiSquareCritical(Math.Max(dof, 1)), $"χ² {chi:F1} on {dof} dof");
    }

    [Fact]
    public void Ziggurat_HasMarsagliaAndTsangsConstants_AndLayersOfEqualArea()
    {
        // Marsaglia & Tsang (2000), 256 layers: r = 3.6541528853610088, v = 0.00492867323399.
        Assert.InRange(Ziggurat.R, 3.6541528853610088 - 1e-12, 3.6541528853610088 + 1e-12);
        // Their v, printed to 12 digits, is 1.5e-14 above v(r) = r·f(r) + ∫_r^∞ f evaluated here: agreement to 3e-12 relative.
        Assert.InRange(Ziggurat.V, 0.00492867323399 - 1e-13, 0.00492867323399 + 1e-13);
        double f(double x) => Math.Exp(-0.5 * x * x);
        Assert.Equal(0, Ziggurat.X[Ziggurat.Layers]);
        for (int i = 1; i < Ziggurat.Layers; i++)
            Assert.InRange(Ziggurat.X[i] * (f(Ziggurat.X[i + 1]) - f(Ziggurat.X[i])), Ziggurat.V * (1 - 1e-9), Ziggurat.V * (1 + 1e-9));
    }

    [Fact]
    public void Normal_HistogramMatchesTheDensity_IncludingTheTailBeyondR()
    {
        const int n = 2_000_000, bins = 100;
        const double range = 5;   // bins of 0.1 on [−5, 5], plus both outer tails
        var counts = new long[bins + 2];
        long tail = 0;
        for (int i = 0; i < n; i++)
        {
            double x = new NoiseStream(99, 4, i, 1).Normal();
            if (Math.Abs(x) > Ziggurat.R) tail++;
            counts[x < -range ? 0 : x >= range ? bins + 1 : 1 + (int)Math.Floor((x + range) / (2 * range) * bins)]++;
        }
        // Bin probabilities: the density (2π)^−½ e^(−x²/2) integrated by composite Simpson (1000 steps per bin);
        // beyond ±5 and beyond ±r from the same integral, as 1/2 minus the integral from 0.
        static double Integral(double a, double b)
        {
            const int m = 1000;
            double h = (b - a) / m, s = 0;
            for (int j = 0; j <= m; j++) s += (j == 0 || j == m ? 1 : j % 2 == 1 ? 4 : 2) * Math.Exp(-0.5 * Math.Pow(a + j * h, 2));
            return s * h / 3 / Math.Sqrt(2 * Math.PI);
        }
        var expected = new double[bins + 2];
        for (int b = 0; b < bins; b++) expected[b + 1] = n * Integral(-range + b * 2 * range / bins, -range + (b + 1) * 2 * range / bins);
        expected[0] = expected[bins + 1] = n * (0.5 - Integral(0, range));
        var (chi, dof) = Pearson(counts, expected);
        output.WriteLine($"χ² = {chi:F1} on {dof} dof (critical {ChiSquareCritical(dof):F1}); |x| > r: {tail} of {n}");
        Assert.True(chi < ChiSquareCritical(dof), $"χ² {chi:F1} on {dof} dof");
        double pTail = 2 * (0.5 - Integral(0, Ziggurat.R));   // 2.58e-4: ~516 expected
        Assert.InRange(tail, n * pTail - 4 * Math.Sqrt(n * pTail), n * pTail + 4 * Math.Sqrt(n * pTail));
    }
}
