using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path tracer's internal spectral grid against a finer discretisation of the same renderer: every band's mean at the
/// default grid (adaptive: as many sub-bands as 5 nm gives, placed where the scene's spectra change fast; exact sub-band
/// means of each spectrum, products per sub-band) against the uniform 1 nm grid (<c>"spectral_grid": 1</c>), the same seed
/// and samples. Products of sub-band means over many bounces miss the covariance of the spectra inside a sub-band, so a
/// coarse grid is biased where the spectra change fast; the uniform 5 nm grid (<c>"spectral_grid": 5</c>) shows it in the
/// white booth. The figures asserted are the ones docs/scene-format.md (Path tracing) states.
/// </summary>
[Trait("Category", "Slow")]
public class SpectralGridBiasTests(ITestOutputHelper output)
{
    /// <summary>
    /// Per band: (mean at <paramref name="grid"/> (a "spectral_grid" value, or null for the default) / mean at 1 nm − 1, its
    /// 1σ from the per-pixel differences).
    /// </summary>
    (double Bias, double Sigma)[] BiasAgainstOneNanometre(string sceneFile, string? grid)
    {
        var dir = Reference.TempDir();
        var text = File.ReadAllText(Repo.PathOf("scenes", sceneFile));
        float[] Render(string? g)
        {
            var name = g ?? "default";
            var scene = Path.Combine(dir, $"{name}.json");
            string key = g is null ? "" : $"\"spectral_grid\": {g}, ";
            File.WriteAllText(scene, text.Replace("\"integrator\": \"path\"",
                $"\"integrator\": {{ \"type\": \"path\", {key}\"seed\": 3 }}", StringComparison.Ordinal));
            var outDir = Path.Combine(dir, $"r{name}");
            var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--width", "8", "--height", "6", "--spp", "256",
                "--formats", "npy", "--quiet");
            Assert.True(code == 0, err);
            return NpyReader.Read(File.OpenRead(Path.Combine(outDir, "spectral.npy"))).Data;
        }
        var coarse = Render(grid);
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
        output.WriteLine($"{sceneFile}, grid {grid ?? "default"} vs 1 nm, per band (%): "
            + string.Join(" ", result.Select(r => $"{100 * r.Item1:F3}")));
        return result;
    }

    [Fact]
    public void CornellRoom_EveryBandWithin0_2PercentOfTheOneNanometreGrid()
    {
        var bias = BiasAgainstOneNanometre("path-cornell-room.json", null);
        for (int b = 0; b < bias.Length; b++)
            Assert.True(Math.Abs(bias[b].Bias) <= 0.002 + 3 * bias[b].Sigma,
                $"band {b + 1}: {100 * bias[b].Bias:F3} % (σ {100 * bias[b].Sigma:F3} %)");
    }

    [Fact]
    public void WhiteBooth_EveryBandWithin0_2PercentOfTheOneNanometreGrid()
    {
        var bias = BiasAgainstOneNanometre("path-white-booth.json", null);
        for (int b = 0; b < bias.Length; b++)
            Assert.True(Math.Abs(bias[b].Bias) <= 0.002 + 3 * bias[b].Sigma,
                $"band {b + 1}: {100 * bias[b].Bias:F3} % (σ {100 * bias[b].Sigma:F3} %)");
    }

    [Fact]
    public void WhiteBooth_TheUniformFiveNanometreGridIsBiasedBelow420nm()
    {
        // What the adaptive default removes (and what this comparison can see): measured −0.74 % at 380–400 nm and −1.23 %
        // at 400–420 nm, −0.06 % at 420–440 nm, under 0.01 % elsewhere (docs/scene-format.md).
        var bias = BiasAgainstOneNanometre("path-white-booth.json", "5");
        Assert.True(bias[0].Bias < -0.005 && bias[1].Bias < -0.009,
            $"{100 * bias[0].Bias:F3} %, {100 * bias[1].Bias:F3} %: the documented bias of the uniform 5 nm grid is gone");
        for (int b = 3; b < bias.Length; b++)
            Assert.True(Math.Abs(bias[b].Bias) <= 0.002 + 3 * bias[b].Sigma, $"band {b + 1}: {100 * bias[b].Bias:F3} %");
    }
}
