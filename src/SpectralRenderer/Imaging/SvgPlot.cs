using System.Globalization;
using System.Xml.Linq;

namespace SpectralRenderer.Imaging;

/// <summary>
/// A small line plot written as SVG 1.1 (no dependencies): a title, axis labels with units, "nice" ticks
/// (1, 2, 5 × 10^k), one polyline per series in a fixed palette, and a legend. Built with System.Xml.Linq,
/// so text is escaped and the file is well-formed XML. Used for the paper's Fig. 6b (radiance of labelled
/// pixels) and Fig. 7 (reconstructed reflectances against the truth).
/// </summary>
public sealed class SvgPlot
{
    /// <summary>Tableau 10, colour-blind-aware and distinguishable in print.</summary>
    public static readonly string[] Palette =
        ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"];

    public sealed record Series(string Name, double[] X, double[] Y, bool Dashed, string Colour);

    readonly List<Series> _series = [];

    public required string Title { get; init; }
    public required string XLabel { get; init; }
    public required string YLabel { get; init; }
    public int Width { get; init; } = 720;
    public int Height { get; init; } = 440;
    /// <summary>Forces the y axis to include 0 (spectra are non-negative).</summary>
    public bool YFromZero { get; init; } = true;

    /// <summary>
    /// Adds a series; its colour is <see cref="Palette"/>[<paramref name="colour"/>] (cycling), else the next in it. A curve and
    /// its reference share a colour by passing the same index (solid and dashed).
    /// </summary>
    public SvgPlot Add(string name, IReadOnlyList<double> x, IReadOnlyList<double> y, bool dashed = false, int? colour = null)
    {
        if (x.Count != y.Count) throw new ArgumentException($"series '{name}': {x.Count} x values but {y.Count} y values");
        _series.Add(new Series(name, x.ToArray(), y.ToArray(), dashed, Palette[(colour ?? _series.Count) % Palette.Length]));
        return this;
    }

    public void Write(string path) => AtomicFile.WriteAllText(path, ToSvg());

    public string ToSvg()
    {
        XNamespace ns = "http://www.w3.org/2000/svg";
        const double left = 78, top = 40, bottom = 56, legendFont = 12;
        // The legend column holds the longest label (its width bounded above, LegendTextWidth), up to 45 % of the width; a
        // longer label is fitted into the column by textLength (squeezed, never cut at the edge).
        double labelWidth = _series.Count == 0 ? 0 : _series.Max(s => LegendTextWidth(s.Name, legendFont));
        double right = Math.Clamp(LegendText + labelWidth + LegendPad, 170, Math.Max(170, 0.45 * Width));
        double labelRoom = right - LegendText - LegendPad;
        double pw = Width - left - right, ph = Height - top - bottom;
        var finite = _series.SelectMany(s => s.X.Zip(s.Y)).Where(p => double.IsFinite(p.First) && double.IsFinite(p.Second)).ToList();
        double x0 = finite.Count > 0 ? finite.Min(p => p.First) : 0, x1 = finite.Count > 0 ? finite.Max(p => p.First) : 1;
        double y0 = finite.Count > 0 ? finite.Min(p => p.Second) : 0, y1 = finite.Count > 0 ? finite.Max(p => p.Second) : 1;
        if (YFromZero) { y0 = Math.Min(0, y0); y1 = Math.Max(0, y1); }
        var xt = Ticks(x0, x1, 8);
        var yt = Ticks(y0, y1, 6);
        if (x1 > x0) xt = xt.Where(t => t >= x0 - 1e-9 * (x1 - x0) && t <= x1 + 1e-9 * (x1 - x0)).ToArray(); // x: the data's range
        else { x0 = xt[0]; x1 = xt[^1]; }
        y0 = Math.Min(y0, yt[0]); y1 = Math.Max(y1, yt[^1]);
        double Sx(double v) => left + (x1 > x0 ? (v - x0) / (x1 - x0) : 0.5) * pw;
        double Sy(double v) => top + ph - (y1 > y0 ? (v - y0) / (y1 - y0) : 0.5) * ph;

        XElement Text(double x, double y, string s, string anchor = "middle", int size = 12, string? transform = null)
        {
            var e = new XElement(ns + "text", new XAttribute("x", F(x)), new XAttribute("y", F(y)),
                new XAttribute("text-anchor", anchor), new XAttribute("font-size", size), s);
            if (transform is not null) e.Add(new XAttribute("transform", transform));
            return e;
        }
        XElement Line(double xa, double ya, double xb, double yb, string stroke, double width = 1) =>
            new(ns + "line", new XAttribute("x1", F(xa)), new XAttribute("y1", F(ya)), new XAttribute("x2", F(xb)),
                new XAttribute("y2", F(yb)), new XAttribute("stroke", stroke), new XAttribute("stroke-width", F(width)));

        var svg =
            new XElement(ns + "svg", new XAttribute("version", "1.1"), new XAttribute("width", Width), new XAttribute("height", Height),
            new XAttribute("viewBox", $"0 0 {Width} {Height}"), new XAttribute("font-family", "Helvetica, Arial, sans-serif"));
        svg.Add(new XElement(ns + "title", Title));
        svg.Add(
            new XElement(ns + "rect", new XAttribute("width", Width), new XAttribute("height", Height), new XAttribute("fill", "white")));
        svg.Add(Text(left + pw / 2, 24, Title, size: 15));

        var axes = new XElement(ns + "g", new XAttribute("class", "axes"));
        foreach (var t in xt)
        {
            axes.Add(Line(Sx(t), top, Sx(t), top + ph, "#e6e6e6"));
            axes.Add(Line(Sx(t), top + ph, Sx(t), top + ph + 5, "black"));
            axes.Add(Text(Sx(t), top + ph + 19, Label(t, xt)));
        }
        foreach (var t in yt)
        {
            axes.Add(Line(left, Sy(t), left + pw, Sy(t), "#e6e6e6"));
            axes.Add(Line(left - 5, Sy(t), left, Sy(t), "black"));
            axes.Add(Text(left - 8, Sy(t) + 4, Label(t, yt), anchor: "end"));
        }
        axes.Add(new XElement(ns + "rect", new XAttribute("x", F(left)), new XAttribute("y", F(top)), new XAttribute("width", F(pw)),
            new XAttribute("height", F(ph)), new XAttribute("fill", "none"), new XAttribute("stroke", "black")));
        axes.Add(Text(left + pw / 2, Height - 14, XLabel, size: 13));
        axes.Add(Text(18, top + ph / 2, YLabel, size: 13, transform: $"rotate(-90 18 {F(top + ph / 2)})"));
        svg.Add(axes);

        var lines = new XElement(ns + "g", new XAttribute("class", "series"), new XAttribute("fill", "none"));
        var legend = new XElement(ns + "g", new XAttribute("class", "legend"));
        for (int i = 0; i < _series.Count; i++)
        {
            var s = _series[i];
            var pts = string.Join(" ", s.X.Zip(s.Y).Where(p => double.IsFinite(p.First) && double.IsFinite(p.Second))
                .Select(p => $"{F(Sx(p.First))},{F(Sy(p.Second))}"));
            var pl = new XElement(ns + "polyline", new XAttribute("points", pts), new XAttribute("stroke", s.Colour),
                new XAttribute("stroke-width", 2), new XAttribute("stroke-linejoin", "round"), new XElement(ns + "title", s.Name));
            if (s.Dashed) pl.Add(new XAttribute("stroke-dasharray", "6 4"));
            lines.Add(pl);
            double ly = top + 10 + i * 20, lx = left + pw + 14;
            var mark = Line(lx, ly, lx + 24, ly, s.Colour, 2);
            if (s.Dashed) mark.Add(new XAttribute("stroke-dasharray", "6 4"));
            legend.Add(mark);
            var label = Text(left + pw + LegendText, ly + 4, s.Name, anchor: "start", size: (int)legendFont);
            if (LegendTextWidth(s.Name, legendFont) > labelRoom)
                label.Add(new XAttribute("textLength", F(labelRoom)), new XAttribute("lengthAdjust", "spacingAndGlyphs"));
            legend.Add(label);
        }
        svg.Add(lines);
        svg.Add(legend);
        return new XDocument(new XDeclaration("1.0", "utf-8", null), svg).Declaration + "\n" + svg.ToString() + "\n";
    }

    /// <summary>From the plot's right edge to a legend label's start (after its line sample), and the space kept after it.</summary>
    const double LegendText = 44, LegendPad = 8;

    /// <summary>
    /// An upper bound of a label's width in px at <paramref name="size"/> px: each character at the widest advance of its class
    /// in Helvetica/Arial (Adobe's core-font metrics) and DejaVu Sans (the usual sans-serif fallback): narrow (i l j I . , : ;
    /// ' |) 0.34 em, medium (f t r space ( ) [ ] - / \ !) 0.42 em, wide (m w M W % @) 1.05 em, other capitals, &amp; and the
    /// maths signs (# + = &lt; &gt; ~ ^) 0.84 em, other ASCII 0.64 em, anything else 1.05 em.
    /// </summary>
    public static double LegendTextWidth(string text, double size)
    {
        double em = 0;
        foreach (char c in text)
            em += c switch
            {
                'i' or 'l' or 'j' or 'I' or '.' or ',' or ':' or ';' or '\'' or '|' => 0.34,
                'f' or 't' or 'r' or ' ' or '(' or ')' or '[' or ']' or '-' or '/' or '\\' or '!' => 0.42,
                'm' or 'w' or 'M' or 'W' or '%' or '@' => 1.05,
                (>= 'A' and <= 'Z') or '&' or '#' or '+' or '=' or '<' or '>' or '~' or '^' => 0.84,
                < (char)128 => 0.64,
                _ => 1.05,
            };
        return em * size;
    }

    /// <summary>Tick positions at a "nice" step (1, 2 or 5 × 10^k) covering [lo, hi] with about <paramref name="target"/>
    /// intervals.</summary>
    public static double[] Ticks(double lo, double hi, int target)
    {
        if (!(hi > lo)) { double pad = lo == 0 ? 1 : Math.Abs(lo) * 0.1; lo -= pad; hi += pad; }
        double raw = (hi - lo) / Math.Max(1, target);
        double mag = Math.Pow(10, Math.Floor(Math.Log10(raw)));
        double norm = raw / mag;
        double step = (norm <= 1 ? 1 : norm <= 2 ? 2 : norm <= 5 ? 5 : 10) * mag;
        double first = Math.Floor(lo / step + 1e-9) * step, last = Math.Ceiling(hi / step - 1e-9) * step;
        var ticks = new List<double>();
        for (int k = 0; first + k * step <= last + step * 1e-9; k++) ticks.Add(Math.Round(first + k * step, 12));
        return ticks.ToArray();
    }

    static string Label(double v, double[] ticks)
    {
        double step = ticks.Length > 1 ? ticks[1] - ticks[0] : 1;
        int decimals = Math.Clamp((int)Math.Ceiling(-Math.Log10(step) - 1e-9), 0, 12);
        if (Math.Abs(v) < step * 1e-9) v = 0;
        return (Math.Abs(step) < 1e-3 || Math.Abs(v) >= 1e6) ? v.ToString("0.###E+0", CultureInfo.InvariantCulture)
            : v.ToString("F" + decimals, CultureInfo.InvariantCulture);
    }

    static string F(double v) => v.ToString("0.##", CultureInfo.InvariantCulture);
}
