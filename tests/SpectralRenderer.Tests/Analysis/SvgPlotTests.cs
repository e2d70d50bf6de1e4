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

    /// <summary>Helvetica's advance widths (1/1000 em) for ASCII 32–126, from Adobe's core-font metrics (Helvetica.afm; Arial
    /// shares them).</summary>
    static readonly int[] HelveticaAfm =
    [
        278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278, // space … /
        556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556, // 0 … ?
        1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778, // @ … O
        667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556, // P … _
        333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556, // ` … o
        556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584,      // p … ~
    ];

    static double Helvetica(string s, double size) => s.Sum(c => c is >= ' ' and <= '~' ? HelveticaAfm[c - ' '] : 1000) * size / 1000;

    [Fact]
    public void The_legend_width_bound_is_at_least_Helveticas_width_of_every_ASCII_character()
    {
        for (char c = ' '; c <= '~'; c++)
            Assert.True(SvgPlot.LegendTextWidth(c.ToString(), 12) >= Helvetica(c.ToString(), 12), $"'{c}'");
    }

    [Theory]
    [InlineData("truth: neutral 6.5 (.44 D)")]   // issue 42: drawn as "neutral 6.5 (.44 D" before
    [InlineData("truth: 21 neutral 6.5 (.44 D) under Mitsuba's WWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWW")]
    public void Legend_labels_end_inside_the_picture(string label)
    {
        var plot = new SvgPlot { Title = "t", XLabel = "x", YLabel = "y" };
        plot.Add("white 9.5 (.05 D)", [400, 500], [0.9, 0.9]).Add(label, [400, 500], [0.36, 0.36], dashed: true);
        var doc = XDocument.Parse(plot.ToSvg());
        double width = double.Parse(doc.Root!.Attribute("width")!.Value, System.Globalization.CultureInfo.InvariantCulture);
        var legend = doc.Descendants(Svg + "g").Single(g => (string?)g.Attribute("class") == "legend").Elements(Svg + "text").ToList();
        Assert.Equal(2, legend.Count);
        foreach (var t in legend)
        {
            static double A(XElement e, string n) =>
                double.Parse(e.Attribute(n)!.Value, System.Globalization.CultureInfo.InvariantCulture);
            double x = A(t, "x"), size = A(t, "font-size");
            // Drawn at Helvetica's widths, or squeezed into textLength by the renderer whatever the font.
            double drawn = t.Attribute("textLength") is null ? Helvetica(t.Value, size) : A(t, "textLength");
            Assert.True(x + drawn <= width, $"'{t.Value}' ends at {x + drawn} px in a {width} px picture");
        }
        // The plot keeps at least 55 % of the width however long a label is.
        var frame = doc.Descendants(Svg + "rect").Single(r => (string?)r.Attribute("stroke") == "black");
        Assert.True(double.Parse(frame.Attribute("width")!.Value, System.Globalization.CultureInfo.InvariantCulture) >= 0.55 * width - 78
            - 0.01);
    }
}
