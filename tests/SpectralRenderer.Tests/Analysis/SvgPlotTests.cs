using System.Xml.Linq;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>The SVG line plot is well-formed XML with one polyline per series, escaped text and a legend.</summary>
public class SvgPlotTests
{
    static readonly XNamespace Svg = "http://www.w3.org/2000/svg";

    [Fact]
    public void Plot_parses_as_XML_with_one_polyline_per_series()
    {
        var plot =
            new SvgPlot { Title = "Spectra <of> \"pixels\" & more", XLabel = "wavelength (nm)", YLabel = "radiance (W·m⁻²·sr⁻¹·nm⁻¹)" };
        double[] x = [390, 410, 430, 450];
        plot.Add("lit & <bright>", x, [0.1, 0.2, 0.3, 0.25]);
        plot.Add("shadow", x, [0.01, 0.02, 0.03, 0.025]);
        plot.Add("truth", x, [0.5, 0.5, 0.4, double.NaN], dashed: true);
        var doc = XDocument.Parse(plot.ToSvg());
        Assert.Equal(Svg + "svg", doc.Root!.Name);
        var lines = doc.Descendants(Svg + "polyline").ToList();
        Assert.Equal(3, lines.Count);
        Assert.Equal(4, lines[0].Attribute("points")!.Value.Split(' ').Length);
        Assert.Equal(3, lines[2].Attribute("points")!.Value.Split(' ').Length); // NaN skipped
        Assert.Equal(SvgPlot.Palette[0], lines[0].Attribute("stroke")!.Value);
        Assert.Equal(SvgPlot.Palette[1], lines[1].Attribute("stroke")!.Value);
        Assert.NotNull(lines[2].Attribute("stroke-dasharray"));
        var texts = doc.Descendants(Svg + "text").Select(t => t.Value).ToList();
        Assert.Contains("Spectra <of> \"pixels\" & more", texts);
        Assert.Contains("lit & <bright>", texts);
        Assert.Contains("wavelength (nm)", texts);
        Assert.Contains("radiance (W·m⁻²·sr⁻¹·nm⁻¹)", texts);
        Assert.Contains("400", texts); // a tick label
    }

    [Theory]
    [InlineData(380, 780, 8, 350, 800, 50)]
    [InlineData(0, 0.93, 6, 0, 1, 0.2)]
    [InlineData(0, 0.0123, 6, 0, 0.015, 0.005)]
    public void Ticks_are_nice_steps_covering_the_range(double lo, double hi, int target, double first, double last, double step)
    {
        var t = SvgPlot.Ticks(lo, hi, target);
        Assert.Equal(first, t[0], 12);
        Assert.Equal(last, t[^1], 12);
        Assert.Equal(step, t[1] - t[0], 12);
    }

    [Fact]
    public void An_empty_or_flat_plot_is_still_valid()
    {
        Assert.Empty(XDocument.Parse(new SvgPlot { Title = "t", XLabel = "x", YLabel = "y" }.ToSvg()).Descendants(Svg + "polyline"));
        var flat = new SvgPlot { Title = "t", XLabel = "x", YLabel = "y" }.Add("zero", [1, 2], [0, 0]);
        Assert.Single(XDocument.Parse(flat.ToSvg()).Descendants(Svg + "polyline"));
    }
}
