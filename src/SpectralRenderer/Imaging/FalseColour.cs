using System.Globalization;
using System.Xml.Linq;

namespace SpectralRenderer.Imaging;

/// <summary>
/// A false-colour scale as lighting software draws luminance and illuminance: values from <see cref="Low"/> to
/// <see cref="High"/> (a "nice" 1, 2, 5 × 10^k top) mapped linearly, or by their logarithm when <see cref="Log"/>, onto
/// the ramp dark blue → blue → cyan → green → yellow → red (<see cref="Stops"/>, linear in sRGB between stops); 0 and
/// below <see cref="Low"/> on a linear scale is black, values below it on a log scale take the first stop, above
/// <see cref="High"/> the last. Its legend (<see cref="Legend"/>) is an SVG bar with the tick values and the unit.
/// </summary>
public sealed record FalseColour(double Low, double High, bool Log, string Quantity, string Unit)
{
    /// <summary>The ramp's stops, sRGB 8-bit, evenly spaced from t = 0 to 1.</summary>
    public static readonly (byte R, byte G, byte B)[] Stops =
        [(0, 0, 128), (0, 0, 255), (0, 255, 255), (0, 255, 0), (255, 255, 0), (255, 0, 0)];

    /// <summary>
    /// The scale for these values: linear from 0 to the nice top of the largest, or logarithmic over whole decades down to
    /// the 2nd percentile of the positive values (at most 4 decades) when they span more than two decades.
    /// </summary>
    public static FalseColour For(ReadOnlySpan<float> values, string quantity, string unit)
    {
        var positive = new List<float>();
        foreach (float v in values) if (v > 0 && float.IsFinite(v)) positive.Add(v);
        if (positive.Count == 0) return new FalseColour(0, 1, false, quantity, unit);
        positive.Sort();
        double max = positive[^1], low = positive[(int)(0.02 * (positive.Count - 1))];
        if (max / low <= 100) return new FalseColour(0, NiceCeiling(max), false, quantity, unit);
        double top = Math.Ceiling(Math.Log10(max)), bottom = Math.Max(top - 4, Math.Floor(Math.Log10(low)));
        return new FalseColour(Math.Pow(10, bottom), Math.Pow(10, top), true, quantity, unit);
    }

    /// <summary>The smallest 1, 2 or 5 × 10^k at or above <paramref name="v"/>.</summary>
    public static double NiceCeiling(double v)
    {
        double p = Math.Pow(10, Math.Floor(Math.Log10(v)));
        foreach (double m in new[] { 1.0, 2, 5, 10 }) if (m * p >= v * (1 - 1e-12)) return m * p;
        return 10 * p;
    }

    /// <summary>The position of <paramref name="v"/> on the ramp, 0 … 1 (NaN: black).</summary>
    public double Position(double v)
    {
        if (!(v > 0) || (!Log && v < Low)) return double.NaN;
        double t = Log ? (Math.Log10(v) - Math.Log10(Low)) / (Math.Log10(High) - Math.Log10(Low)) : (v - Low) / (High - Low);
        return Math.Clamp(t, 0, 1);
    }

    /// <summary>The colour at ramp position <paramref name="t"/> (NaN: black).</summary>
    public static (byte R, byte G, byte B) Colour(double t)
    {
        if (double.IsNaN(t)) return (0, 0, 0);
        double x = t * (Stops.Length - 1);
        int i = Math.Min((int)x, Stops.Length - 2);
        double f = x - i;
        var (a, b) = (Stops[i], Stops[i + 1]);
        static byte Mix(byte p, byte q, double f) => (byte)Math.Round(p + (q - p) * f);
        return (Mix(a.R, b.R, f), Mix(a.G, b.G, f), Mix(a.B, b.B, f));
    }

    /// <summary>The 8-bit sRGB picture of the values, row-major.</summary>
    public byte[] Rgb(ReadOnlySpan<float> values)
    {
        var rgb = new byte[3 * values.Length];
        for (int i = 0; i < values.Length; i++)
        {
            var (r, g, b) = Colour(Position(values[i]));
            rgb[3 * i] = r; rgb[3 * i + 1] = g; rgb[3 * i + 2] = b;
        }
        return rgb;
    }

    /// <summary>The tick values of the legend: every decade (log), or 0 to the top in fifths (linear).</summary>
    public double[] Ticks()
    {
        if (!Log) return Enumerable.Range(0, 6).Select(i => Low + (High - Low) * i / 5).ToArray();
        int lo = (int)Math.Round(Math.Log10(Low)), hi = (int)Math.Round(Math.Log10(High));
        return Enumerable.Range(lo, hi - lo + 1).Select(k => Math.Pow(10, k)).ToArray();
    }

    static string Number(double v) => v.ToString("G4", CultureInfo.InvariantCulture);

    /// <summary>
    /// The legend as SVG 1.1: a vertical bar of the ramp (bottom = <see cref="Low"/>, top = <see cref="High"/>), each tick
    /// labelled with its value, the title "quantity (unit)" and the scale's kind; the bar's stops and the ticks'
    /// positions are data-* attributes too, so a program reads the scale back.
    /// </summary>
    public string Legend(string? note = null)
    {
        XNamespace svg = "http://www.w3.org/2000/svg";
        const int barX = 20, barY = 40, barW = 30, barH = 300, width = 220, height = 380;
        var gradient = new XElement(svg + "linearGradient", new XAttribute("id", "ramp"),
            new XAttribute("x1", "0"), new XAttribute("y1", "1"), new XAttribute("x2", "0"), new XAttribute("y2", "0"));
        for (int i = 0; i < Stops.Length; i++)
        {
            var (r, g, b) = Stops[i];
            gradient.Add(new XElement(svg + "stop", new XAttribute("offset", Number((double)i / (Stops.Length - 1))),
                new XAttribute("stop-color", $"#{r:x2}{g:x2}{b:x2}")));
        }
        var root = new XElement(svg + "svg", new XAttribute("width", width), new XAttribute("height", height),
            new XAttribute("viewBox", $"0 0 {width} {height}"), new XAttribute("font-family", "sans-serif"),
                new XAttribute("font-size", 12),
            new XAttribute("data-quantity", Quantity), new XAttribute("data-unit", Unit),
                new XAttribute("data-scale", Log ? "log10" : "linear"),
            new XAttribute("data-low", Number(Low)), new XAttribute("data-high", Number(High)),
            new XElement(svg + "defs", gradient),
            new XElement(svg + "text", new XAttribute("x", barX), new XAttribute("y", 18), new XAttribute("font-weight", "bold"),
                $"{Quantity} ({Unit})"),
            new XElement(svg + "text", new XAttribute("x", barX), new XAttribute("y", 32), new XAttribute("font-size", 10),
                Log ? "logarithmic scale" : "linear scale; 0 is black"),
            new XElement(svg + "rect", new XAttribute("x", barX), new XAttribute("y", barY), new XAttribute("width", barW),
                new XAttribute("height", barH), new XAttribute("fill", "url(#ramp)"), new XAttribute("stroke", "#000")));
        foreach (double v in Ticks())
        {
            double y = barY + barH * (1 - Position(v));
            if (double.IsNaN(y)) y = barY + barH;
            string at = y.ToString("F1", CultureInfo.InvariantCulture);
            root.Add(new XElement(svg + "line", new XAttribute("x1", barX + barW), new XAttribute("x2", barX + barW + 6),
                new XAttribute("y1", at), new XAttribute("y2", at), new XAttribute("stroke", "#000")));
            root.Add(new XElement(svg + "text", new XAttribute("x", barX + barW + 10), new XAttribute("y", at),
                new XAttribute("dominant-baseline", "middle"), new XAttribute("class", "tick"),
                    new XAttribute("data-value", v.ToString("R", CultureInfo.InvariantCulture)),
                $"{Number(v)} {Unit}"));
        }
        if (note is not null)
            root.Add(
                new XElement(svg + "text", new XAttribute("x", 4), new XAttribute("y", height - 8), new XAttribute("font-size", 9), note));
        return new XDocument(root).ToString();
    }
}
