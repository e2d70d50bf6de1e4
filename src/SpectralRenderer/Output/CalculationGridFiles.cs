using System.Globalization;
using System.Text;
using System.Xml.Linq;
using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output;

/// <summary>
/// A calculation grid's illuminance as lighting software writes it: PREFIX.csv (x,y,z,lx, one row per point, i fastest;
/// a gathered grid adds stderr_lx, the point's standard error)
/// and PREFIX.svg (the grid as a false-colour heat map with its labelled scale, each cell's lx in its title and data-lx);
/// and the summary figures a designer checks (minimum, mean, maximum, uniformity U0 = min/mean, EN 12464-1 §4.4).
/// Written by `spectral illuminance` and by a render of a scene with "calculation_grids" (grids/NAME.*).
/// </summary>
public static class CalculationGridFiles
{
    /// <summary>The render's folder for its grids' files.</summary>
    public const string Folder = "grids";

    /// <summary>Writes PREFIX.csv and PREFIX.svg; <paramref name="title"/> heads the heat map. With
    /// <paramref name="standardError"/> (a gathered grid) the CSV has a fifth column, stderr_lx: each point's standard error.</summary>
    public static void Write(string prefix, CalculationGrid grid, double[] lux, string title, double[]? standardError = null)
    {
        var points = grid.Points();
        var inv = CultureInfo.InvariantCulture;
        var csv = new StringBuilder(standardError is null ? "x,y,z,lx\n" : "x,y,z,lx,stderr_lx\n");
        for (int k = 0; k < points.Length; k++)
        {
            csv.Append(inv, $"{points[k].X:R},{points[k].Y:R},{points[k].Z:R},{lux[k]:R}");
            if (standardError is not null) csv.Append(inv, $",{standardError[k]:R}");
            csv.Append('\n');
        }
        AtomicFile.WriteAllText(prefix + ".csv", csv.ToString());
        AtomicFile.WriteAllText(prefix + ".svg", HeatMap(lux, grid.PointsU, grid.PointsV, grid.U.Length(), grid.V.Length(), title));
    }

    /// <summary>One line: the grid's size and normal, min, mean and max lx and U0.</summary>
    public static string Summary(CalculationGrid grid, double[] lux)
    {
        double min = lux.Min(), mean = lux.Average(), max = lux.Max();
        var n = grid.Normal;
        return string.Create(CultureInfo.InvariantCulture,
            $"{grid.PointsU}×{grid.PointsV} points on the work plane (normal {n.X:0.###},{n.Y:0.###},{n.Z:0.###}): " +
            $"illuminance min {min:G4} lx, mean {mean:G4} lx, max {max:G4} lx, uniformity U0 = min/mean "
                + $"{(mean > 0 ? min / mean : 0):0.###}");
    }

    /// <summary>The grid as SVG cells (U to the right, V up, each cell's lx in its title) beside its false-colour legend.</summary>
    static string HeatMap(double[] lux, int nu, int nv, float lengthU, float lengthV, string title)
    {
        var values = lux.Select(x => (float)x).ToArray();
        var scale = FalseColour.For(values, "Illuminance", "lx");
        XNamespace svg = "http://www.w3.org/2000/svg";
        const double area = 480;
        double cell = Math.Min(area * lengthU / Math.Max(lengthU, lengthV) / nu, area * lengthV / Math.Max(lengthU, lengthV) / nv);
        double w = cell * nu, h = cell * nv;
        var inv = CultureInfo.InvariantCulture;
        var root = new XElement(svg + "svg", new XAttribute("width", (int)Math.Ceiling(w + 260)),
            new XAttribute("height", (int)Math.Ceiling(Math.Max(h + 60, 400))),
            new XAttribute("font-family", "sans-serif"), new XAttribute("font-size", 12),
            new XElement(svg + "text", new XAttribute("x", 10), new XAttribute("y", 20), new XAttribute("font-weight", "bold"),
                $"Illuminance on the work plane — {title} ({nu} × {nv} points; U → right, V ↑)"));
        for (int j = 0; j < nv; j++)
            for (int i = 0; i < nu; i++)
            {
                double value = lux[j * nu + i];
                var (r, g, b) = FalseColour.Colour(scale.Position(value));
                root.Add(new XElement(svg + "rect", new XAttribute("x", (10 + i * cell).ToString("F2", inv)),
                    new XAttribute("y", (40 + (nv - 1 - j) * cell).ToString("F2", inv)),
                    new XAttribute("width", cell.ToString("F2", inv)), new XAttribute("height", cell.ToString("F2", inv)),
                        new XAttribute("fill", $"#{r:x2}{g:x2}{b:x2}"),
                    new XAttribute("data-lx", value.ToString("R", inv)),
                    new XElement(svg + "title", $"point ({i}, {j}): {value.ToString("G4", inv)} lx")));
            }
        var legend = XElement.Parse(scale.Legend());
        legend.SetAttributeValue("x", (int)Math.Ceiling(w + 30));
        legend.SetAttributeValue("y", 20);
        root.Add(legend);
        return new XDocument(root).ToString();
    }
}
