using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Spectra;

public class BandTests
{
    [Theory]
    [InlineData("380:780:20", 380, 780, 20, 20.0)]
    [InlineData("400:700:31", 400, 700, 31, 300.0 / 31)]
    [InlineData("380:780:401", 380, 780, 401, 400.0 / 401)]
    public void Grids_parse_with_equal_bands(string text, double start, double end, int count, double width)
    {
        var g = BandGrid.Parse(text);
        Assert.Equal((start, end, count), (g.Start, g.End, g.Count));
        Assert.Equal(width, g.Width, 12);
        Assert.Equal(start, g.Edges()[0]);
        Assert.Equal(end, g.Edges()[^1]);
        Assert.Equal(start + width / 2, g.Centre(0), 12);
    }

    [Theory]
    [InlineData("380:780")]
    [InlineData("a:780:20")]
    [InlineData("780:380:20")]
    [InlineData("380:780:0")]
    [InlineData("380:780:5000")]
    public void Bad_grids_are_rejected(string text)
    {
        var e = Assert.Throws<InputException>(() => BandGrid.Parse(text));
        Assert.StartsWith("--bands:", e.Message);
    }

    [Fact]
    public void Band_mean_of_a_constant_is_the_constant()
    {
        var s = new TabulatedSpectrum("c", [380, 385, 390, 780], [0.25, 0.25, 0.25, 0.25]);
        foreach (var v in BandProjection.Means(s, BandGrid.Parse("380:780:7"))) Assert.Equal(0.25, v, 14);
    }

    [Fact]
    public void Band_mean_of_a_linear_ramp_is_its_value_at_the_band_centre()
    {
        // v = 2 + 0.01 λ tabulated at uneven knots: the interpolant is the ramp itself.
        double[] wl = [380, 383, 397, 450, 601, 780];
        var s = new TabulatedSpectrum("ramp", wl, wl.Select(l => 2 + 0.01 * l).ToArray());
        var g = BandGrid.Parse("380:780:13");
        var m = BandProjection.Means(s, g);
        for (int b = 0; b < g.Count; b++) Assert.Equal(2 + 0.01 * g.Centre(b), m[b], 12);
    }

    [Fact]
    public void A_band_straddling_two_samples_is_the_weighted_mean_of_the_pieces()
    {
        // Samples 0 at 400, 1 at 410, 0 at 420: a tent. Band [405, 415]:
        // ∫405..410 of the rising half = 5·(0.5+1)/2 = 3.75; ∫410..415 = 3.75; mean = 7.5 / 10 = 0.75.
        var s = new TabulatedSpectrum("tent", [400, 410, 420], [0, 1, 0]);
        Assert.Equal(0.75, s.Mean(405, 415), 14);
        // Band [402, 410]: ∫ = 8·(0.2+1)/2 = 4.8; mean 0.6 (not the centre sample 0.6 by accident: check [400,412]).
        Assert.Equal(0.6, s.Mean(402, 410), 14);
        // [400, 412]: ∫400..410 = 5, ∫410..412 = 2·(1+0.8)/2 = 1.8 → 6.8/12.
        Assert.Equal(6.8 / 12, s.Mean(400, 412), 14);
        // A centre sample would give s(406) = 0.6 ≠ 0.5667.
        Assert.NotEqual(s.Evaluate(406), s.Mean(400, 412), 3);
    }

    [Fact]
    public void Product_integral_is_exact_for_two_ramps()
    {
        // ∫_0^10 x · (10 − x) dx = 500 − 1000/3.
        var a = new TabulatedSpectrum("a", [0, 10], [0, 10]);
        var b = new TabulatedSpectrum("b", [0, 3, 10], [10, 7, 0]);
        Assert.Equal(500 - 1000.0 / 3, TabulatedSpectrum.IntegrateProduct(a, b, 0, 10), 10);
    }

    [Fact]
    public void A_spectrum_that_does_not_cover_the_bands_is_an_error_unless_a_policy_is_chosen()
    {
        var s = new TabulatedSpectrum("short", [400, 700], [1, 1]);
        var e = Assert.Throws<InputException>(() => s.RequireCoverage(380, 780, "scene.json: $.spectra.short"));
        Assert.Contains("covers 400–700 nm but the bands need 380–780 nm", e.Message);
        s.WithExtrapolation(Extrapolation.Clamp).RequireCoverage(380, 780, "x");
        Assert.Equal(1.0, s.WithExtrapolation(Extrapolation.Clamp).Mean(380, 400), 14);
        Assert.Equal(0.5, s.WithExtrapolation(Extrapolation.Zero).Mean(380, 420), 14);
    }

    // The ColorChecker rows are values of the published Ohta (1997) table (MCSL; the paper's ref. [10]):
    // patch 14 green 0.070 at 450 nm, 0.323 at 550 nm, 0.124 at 600 nm; patch 19 white 0.886 at 550 nm.
    [Theory]
    [InlineData("D65", 100.0, 560)]
    [InlineData("colorchecker:14", 0.070, 450)]
    [InlineData("colorchecker:14", 0.323, 550)]
    [InlineData("colorchecker:green", 0.323, 550)]
    [InlineData("colorchecker:green", 0.124, 600)]
    [InlineData("colorchecker:19", 0.886, 550)]
    [InlineData("colorchecker:white", 0.886, 550)]
    [InlineData("constant:0.5", 0.5, 600)]
    public void Named_spectra_resolve(string name, double expected, double at)
    {
        Assert.Equal(expected, SpectrumLibrary.Resolve(name).Evaluate(at), 10);
    }

    [Fact]
    public void Patch_names_and_numbers_agree_and_typos_get_a_hint()
    {
        Assert.Equal("green", ColorChecker.Name(14));
        Assert.Equal(ColorChecker.Patch(19).Values.ToArray(), SpectrumLibrary.Resolve("colorchecker:white").Values.ToArray());
        Assert.Equal(ColorChecker.Patch(20).Values.ToArray(), SpectrumLibrary.Resolve("colorchecker:neutral-8").Values.ToArray());
        var e = Assert.Throws<InputException>(() => SpectrumLibrary.Resolve("colorchecker:gren"));
        Assert.Contains("did you mean 'green'?", e.Message);
        e = Assert.Throws<InputException>(() => SpectrumLibrary.Resolve("D66"));
        Assert.Contains("did you mean 'D65'?", e.Message);
        e = Assert.Throws<InputException>(() => SpectrumLibrary.Resolve("constant:-1"));
        Assert.Contains("non-negative", e.Message);
    }

    [Fact]
    public void The_LED_peaks_where_the_data_README_says()
    {
        // Scaled by luminous flux (docs/scene-format.md), so the peak is where the table's maximum is, not 1.
        foreach (var (name, peak) in new[] { ("led-blue", 465), ("led-green", 525) })
        {
            var s = SpectrumLibrary.Resolve(name);
            double top = s.Evaluate(peak);
            for (int l = 360; l <= 830; l++) Assert.True(s.Evaluate(l) <= top * (1 + 1e-12), $"{name} at {l} nm above its {peak} nm peak");
        }
    }
}
