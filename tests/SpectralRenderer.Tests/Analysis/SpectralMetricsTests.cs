using SpectralRenderer.Analysis;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>RMSE, GFC, least-squares scale and ΔE00 under D65 against hand-computed values.</summary>
public class SpectralMetricsTests
{
    [Fact]
    public void Rmse_is_the_root_mean_square_difference()
    {
        // differences 1, −2, 2 → mean square (1 + 4 + 4) / 3 = 3
        Assert.Equal(Math.Sqrt(3), SpectralMetrics.Rmse([1, 2, 3], [0, 4, 1]), 15);
        Assert.Equal(0, SpectralMetrics.Rmse([0.25, 0.5], [0.25, 0.5]));
    }

    [Fact]
    public void Gfc_is_one_for_proportional_spectra_and_the_cosine_otherwise()
    {
        Assert.Equal(1.0, SpectralMetrics.Gfc([0.1, 0.4, 0.7, 0.2], [0.35, 1.4, 2.45, 0.7]), 15);
        // a = (1, 0), b = (1, 1): 1 / sqrt(1 · 2)
        Assert.Equal(1 / Math.Sqrt(2), SpectralMetrics.Gfc([1, 0], [1, 1]), 15);
        // a = (1, 2, 3), b = (3, 2, 1): 10 / sqrt(14 · 14) = 5/7
        Assert.Equal(5.0 / 7.0, SpectralMetrics.Gfc([1, 2, 3], [3, 2, 1]), 15);
        Assert.Equal(0, SpectralMetrics.Gfc([0, 0], [1, 1]));
        Assert.Equal(1, SpectralMetrics.Gfc([0, 0], [0, 0]));
    }

    [Fact]
    public void Scale_is_the_least_squares_factor_with_its_residual()
    {
        double[] truth = [0.1, 0.4, 0.7, 0.2];
        var (c, residual) = SpectralMetrics.Scale(truth, truth.Select(t => 0.37 * t).ToArray());
        Assert.Equal(0.37, c, 15);
        Assert.Equal(0, residual, 15);
        // truth (1, 1), estimate (1, 3): c = 4 / 2 = 2, c·truth = (2, 2), residual sqrt((1 + 1) / 2) = 1
        (c, residual) = SpectralMetrics.Scale([1, 1], [1, 3]);
        Assert.Equal(2, c, 15);
        Assert.Equal(1, residual, 15);
        Assert.Equal((0.0, Math.Sqrt(0.5)), SpectralMetrics.Scale([0, 0], [1, 0]));
    }

    [Fact]
    public void Delta_E00_under_D65_is_zero_for_equal_reflectances_and_Lab_of_white_is_100()
    {
        var grid = BandGrid.Default;
        var d = ReflectanceDifference.UnderD65(grid);
        var white = Enumerable.Repeat(1.0, grid.Count).ToArray();
        var lab = d.LabOf(white);
        Assert.Equal(100, lab.L, 9);
        Assert.Equal(0, lab.A, 9);
        Assert.Equal(0, lab.B, 9);
        var green = d.Colorimeter.Project(ColorChecker.Patch(14));
        Assert.Equal(0, d.DeltaE00(green, green));
        // A neutral at half reflectance: L* = 116 · 0.5^(1/3) − 16 = 76.0693; ΔE00 to white is lightness only.
        var grey = Enumerable.Repeat(0.5, grid.Count).ToArray();
        Assert.Equal(116 * Math.Cbrt(0.5) - 16, d.LabOf(grey).L, 9);
        double dl = 100 - (116 * Math.Cbrt(0.5) - 16), lBar = (100 + 116 * Math.Cbrt(0.5) - 16) / 2;
        double sl = 1 + 0.015 * (lBar - 50) * (lBar - 50) / Math.Sqrt(20 + (lBar - 50) * (lBar - 50));
        Assert.Equal(dl / sl, d.DeltaE00(white, grey), 9);
        Assert.True(d.DeltaE00(green, white) > 20);
    }
}
