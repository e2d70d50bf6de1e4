using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Color;

/// <summary>"gamut": "desaturate" and "exposure": "auto" against their definitions.</summary>
public class DisplayMappingTests
{
    static (double x, double y) Chromaticity(double r, double g, double b)
    {
        // linear sRGB → XYZ (IEC 61966-2-1 inverse matrix), then x, y
        double X = 0.4124 * r + 0.3576 * g + 0.1805 * b, Y = 0.2126 * r + 0.7152 * g + 0.0722 * b, Z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
        return (X / (X + Y + Z), Y / (X + Y + Z));
    }

    [Theory]
    [InlineData(-0.3, 0.1, 2.5)]     // a blue LED: negative red, blue far above 1
    [InlineData(-0.05, 0.6, 0.2)]    // a saturated green, in range but for red
    [InlineData(0.2, 0.4, 3.0)]      // in the gamut's hue, too bright
    public void Desaturation_keeps_the_hue_luminance_when_it_fits_and_lands_in_the_cube(double r, double g, double b)
    {
        double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        var (mr, mg, mb) = DisplayEncoder.Desaturate(r, g, b, y);
        foreach (var c in new[] { mr, mg, mb }) Assert.InRange(c, 0, 1 + 1e-12);
        // The mapped chromaticity lies on the line from the white (D65) through the original: same dominant hue.
        var (x0, y0) = (0.3127, 0.3290);
        var (x1, y1) = Chromaticity(r, g, b);
        var (x2, y2) = Chromaticity(mr, mg, mb);
        double cross = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
        Assert.True(Math.Abs(cross) < 2e-4, $"chromaticity ({x2:F4}, {y2:F4}) is off the white–({x1:F4}, {y1:F4}) line by {cross:E2}");
        Assert.True((x2 - x0) * (x1 - x0) + (y2 - y0) * (y1 - y0) >= 0, "the hue flipped through the white");
        // Luminance kept unless the colour had to be scaled into the cube.
        double my = 0.2126 * mr + 0.7152 * mg + 0.0722 * mb;
        double min = Math.Min(r, Math.Min(g, b));
        double t = min < 0 ? y / (y - min) : 1;
        double peak = Math.Max(y + t * (r - y), Math.Max(y + t * (g - y), y + t * (b - y)));
        if (peak <= 1) Assert.Equal(y, my, 9);
        else Assert.Equal(y / peak, my, 9);
    }

    [Fact]
    public void Auto_exposure_maps_the_99th_percentile_of_the_maximum_channel_to_one()
    {
        var cm = new Colorimeter(BandGrid.Default, Observer.Cie1931, SpectrumLibrary.Resolve("D65"));
        // 1000 grey pixels of luminance 0.001 … 1 (a grey's channels all equal its Y in sRGB at D65), and 50 black ones.
        var xyz = new List<Xyz>();
        for (int i = 1; i <= 1000; i++) xyz.Add(cm.White * (i / 1000.0));
        for (int i = 0; i < 50; i++) xyz.Add(new Xyz(0, 0, 0));
        double e = DisplayEncoder.AutoExposure(cm, RgbSpace.Srgb, false, xyz.Count, i => xyz[i]);
        // 99th percentile of 1000 sorted values (index floor(0.99·999) = 989) is 0.990; black pixels do not count.
        Assert.Equal(1 / 0.990, e, 2);
    }

    /// <summary>The selection behind auto exposure against sorting and indexing, on the orders and repetitions an image gives.</summary>
    [Theory]
    [InlineData("random", 1000)]
    [InlineData("random", 1)]
    [InlineData("random", 2)]
    [InlineData("random", 7)]
    [InlineData("few-levels", 5000)]
    [InlineData("all-equal", 4096)]
    [InlineData("ascending", 3000)]
    [InlineData("descending", 3000)]
    [InlineData("organ-pipe", 3001)]
    public void Select_gives_the_sorted_array_entry_at_every_rank(string order, int n)
    {
        var rng = new Random(n);
        double[] Make() => order switch
        {
            "random" => Enumerable.Range(0, n).Select(_ => rng.NextDouble()).ToArray(),
            "few-levels" => Enumerable.Range(0, n).Select(_ => (double)rng.Next(4)).ToArray(),
            "all-equal" => Enumerable.Repeat(0.5, n).ToArray(),
            "ascending" => Enumerable.Range(0, n).Select(i => (double)i).ToArray(),
            "descending" => Enumerable.Range(0, n).Select(i => (double)(n - i)).ToArray(),
            _ => Enumerable.Range(0, n).Select(i => (double)Math.Min(i, n - i)).ToArray(),
        };
        var values = Make();
        var sorted = values.OrderBy(v => v).ToArray();
        foreach (int k in new[] { 0, n / 3, n / 2, (int)Math.Floor(0.99 * (n - 1)), n - 1 }.Distinct())
        {
            var copy = (double[])values.Clone();
            Assert.Equal(sorted[k], DisplayEncoder.Select(copy, k));
            Assert.Equal(sorted, copy.OrderBy(v => v).ToArray());   // reordered, nothing lost
        }
    }
}
