using SpectralRenderer.Camera;

namespace SpectralRenderer.Tests.Camera;

/// <summary>The noise generators against their distributions' moments (mean, variance) within four standard errors.</summary>
public class NoiseStreamTests(Xunit.Abstractions.ITestOutputHelper output)
{
    [Theory]
    [InlineData(0.7)]
    [InlineData(6)]
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
}
