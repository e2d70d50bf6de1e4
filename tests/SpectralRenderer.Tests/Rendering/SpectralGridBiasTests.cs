using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path tracer's internal spectral grid against a finer discretisation of the same renderer: every band's mean at the
/// default grid (5 nm sub-bands, exact sub-band means of each spectrum, products per sub-band) against the 1 nm grid
/// (<c>"spectral_grid": 1</c>), the same seed and samples. Products of sub-band means over many bounces miss the
/// covariance of the spectra inside a sub-band, so the default grid is biased where the spectra change fast. The figures
/// asserted are the ones docs/scene-format.md (Path tracing) states.
/// </summary>
[Trait("Category", "Slow")]
public class SpectralGridBiasTests(ITestOutputHelper output)
{
    /// <summary>Per band: (mean at the default grid / mean at 1 nm − 1, its 1σ from the per-pixel differences).</summary>
    (double Bias, double Sigma)[] BiasAgainstOneNanometre(string sceneFile)
    {
        var dir = Reference.TempDir();
        var text = File.ReadAllText(Repo.PathOf("scenes", sceneFile));
        float[] Render(string grid)
        {
            var scene = Path.Combine(dir, $"{grid}.json");
            File.WriteAllText(scene, text.Replace("\"integrator\": \"path\"",
                $"\"integrator\": {{ \"type\": \"path\", \"spectral_grid\": {grid}, \"seed\": 3 }}", StringComparison.Ordinal));
            var outDir = Path.Combine(dir, $"r{grid}");
            var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--width", "8", "--height", "6", "--spp", "256",
                "--formats", "npy", "--quiet");
            Assert.True(code == 0, err);
            return NpyReader.Read(File.OpenRead(Path.Combine(outDir, "spectral.npy"))).Data;
        }
        var coarse = Render("5");
        var fine = Render("1");
        const int bands = 20, n = 8 * 6;
        Assert.Equal(n * bands, fine.Length);
        var result = new (double, double)[bands];
        for (int b = 0; b < bands; b++)
        {
            double sf = 0, sd = 0, sdd = 0;
            for (int i = 0; i < n; i++)
            {
                double d = coarse[i * bands + b] - fine[i * bands + b];
                sf += fine[i * bands + b]; sd += d; sdd += d * d;
            }
            double mean = sf / n, md = sd / n, se = Math.Sqrt(Math.Max(0, sdd / n - md * md) / (n - 1));
            result[b] = (md / mean, se / mean);
        }
        output.WriteLine($"{sceneFile}, default grid vs 1 nm, per band (%): "
            + string.Join(" ", result.Select(r => $"{100 * r.Item1:F2}")));
        return result;
    }

    [Fact]
    public void CornellRoom_EveryBandWithin0_2PercentOfTheOneNanometreGrid()
    {
        var bias = BiasAgainstOneNanometre("path-cornell-room.json");
        for (int b = 0; b < bias.Length; b++)
            Assert.True(Math.Abs(bias[b].Bias) <= 0.002 + 3 * bias[b].Sigma,
                $"band {b + 1}: {100 * bias[b].Bias:F3} % (σ {100 * bias[b].Sigma:F3} %)");
    }

    [Fact]
    public void WhiteBooth_BiasedOnlyBelow440nm_WithinTheDocumentedFigures()
    {
        // Measured: −0.74 % at 380–400 nm, −1.23 % at 400–420, −0.06 % at 420–440, below 0.01 % elsewhere. The issue 42 bar
        // (0.2 %) is not met below 420 nm yet: these bounds pin the stated error until a finer grid there lands.
        var bias = BiasAgainstOneNanometre("path-white-booth.json");
        double[] documented = [0.010, 0.015, 0.002];
        for (int b = 0; b < bias.Length; b++)
        {
            double bound = b < documented.Length ? documented[b] : 0.002;
            Assert.True(Math.Abs(bias[b].Bias) <= bound + 3 * bias[b].Sigma,
                $"band {b + 1}: {100 * bias[b].Bias:F3} % (σ {100 * bias[b].Sigma:F3} %), documented ≤ {100 * bound} %");
        }
        Assert.True(bias[0].Bias < -0.004 && bias[1].Bias < -0.008, "the blue bias the docs describe is gone: update them");
    }
}
