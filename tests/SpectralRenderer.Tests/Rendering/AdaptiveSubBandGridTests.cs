using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path tracer's adaptive sub-band grid (issue 42; SubBandGrid.Adaptive.cs) as a grid: as many sub-bands as the uniform
/// 5 nm grid, tiling every output band in equal parts no finer than 1 nm, finer where the white booth's white ramps up
/// (380–440 nm); the film's reduction on it against analytic band means and CIE integrals; and which scenes keep the
/// uniform grid. Its accuracy against the 1 nm grid is SpectralGridBiasTests' (Slow).
/// </summary>
public class AdaptiveSubBandGridTests
{
    static Scene Booth(string integrator)
    {
        var text = File.ReadAllText(Repo.PathOf("scenes", "path-white-booth.json"))
            .Replace("\"integrator\": \"path\"", $"\"integrator\": {integrator}", StringComparison.Ordinal);
        return SceneLoader.Parse(Encoding.UTF8.GetBytes(text), Repo.PathOf("scenes", "path-white-booth.json"));
    }

    static SubBandGrid GridOf(Scene scene) => PathIntegrator.GridOf(scene, PathIntegrator.SettingsOf(scene).SpectralGrid);

    [Fact]
    public void WhiteBooth_DefaultGrid_IsAdaptive_SameSize_FinerInTheBlue()
    {
        var grid = GridOf(Booth("\"path\""));
        Assert.False(grid.Uniform);
        Assert.Equal(80, grid.Count);   // 20 bands × 4: the per-path cost of the 5 nm grid
        for (int b = 0; b < grid.Bands; b++)
        {
            int n = grid.BandStart[b + 1] - grid.BandStart[b];
            Assert.True(n >= 1, $"band {b + 1} has no sub-band");
            double lo = 380 + 20 * b;
            Assert.Equal(lo, grid.Lower[grid.BandStart[b]], 9);
            Assert.Equal(lo + 20, grid.Upper[grid.BandStart[b + 1] - 1], 9);
            for (int f = grid.BandStart[b]; f < grid.BandStart[b + 1]; f++)
            {
                Assert.Equal(20.0 / n, grid.Upper[f] - grid.Lower[f], 9);
                Assert.True(grid.Upper[f] - grid.Lower[f] >= 1 - 1e-9, $"sub-band {f} finer than 1 nm");
            }
        }
        // The white's ramp: ρ 0.15 → 0.84 over 380–420 nm (ColorChecker, Ohta), flat (0.89) above 440 nm.
        Assert.True(grid.BandStart[2] >= 30, $"380–420 nm: {grid.BandStart[2]} sub-bands");
        Assert.True(grid.BandStart[grid.Bands] - grid.BandStart[4] <= 4 * (grid.Bands - 4) / 2, "the flat bands keep most");
    }

    [Fact]
    public void AdaptiveGrid_Reduce_BandsAreTheMeansOfALinearSpectrum_XyzTheCieIntegrals()
    {
        var scene = Booth("\"path\"");
        var grid = GridOf(scene);
        // L(λ) = λ/100: a sub-band's exact mean is its centre/100, and a band's mean (lo + 10)/100 whatever its split.
        var fine = new float[grid.Padded];
        for (int f = 0; f < grid.Count; f++) fine[f] = (float)((grid.Lower[f] + grid.Upper[f]) / 200);
        var result = new float[scene.PaddedBands];
        grid.Reduce(fine, result);
        for (int b = 0; b < grid.Bands; b++) Assert.Equal((380 + 20 * b + 10) / 100.0, result[b], 5);
        // L = 1: X = κ·∫x̄ over 380–780 nm (and Y, Z).
        Array.Fill(fine, 1f, 0, grid.Count);
        grid.Reduce(fine, result);
        double kappa = scene.Colorimeter.Kappa;
        var obs = scene.Observer;
        Assert.Equal(1, result[grid.Bands] / (kappa * obs.XBar.Integrate(380, 780)), 5);
        Assert.Equal(1, result[grid.Bands + 1] / (kappa * obs.YBar.Integrate(380, 780)), 5);
        Assert.Equal(1, result[grid.Bands + 2] / (kappa * obs.ZBar.Integrate(380, 780)), 5);
    }

    [Fact]
    public void GivenWidth_OrSmoothSpectra_KeepTheUniformGrid()
    {
        var given = GridOf(Booth("{ \"type\": \"path\", \"spectral_grid\": 5 }"));
        Assert.True(given.Uniform);
        Assert.Equal(4, given.PerBand);
        // Constant reflectances (0.9, no sub-band structure): nothing to refine, the uniform 5 nm grid.
        var text = File.ReadAllText(Repo.PathOf("scenes", "path-white-booth.json"))
            .Replace("\"reflectance\": \"colorchecker:white\"", "\"reflectance\": 0.9", StringComparison.Ordinal);
        var smooth = SceneLoader.Parse(Encoding.UTF8.GetBytes(text), Repo.PathOf("scenes", "path-white-booth.json"));
        var grid = GridOf(smooth);
        Assert.True(grid.Uniform);
        Assert.Equal(4, grid.PerBand);
    }
}
