using System.Globalization;
using System.Numerics;
using System.Text;
using System.Xml.Linq;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>
/// `spectral illuminance SCENE --plane O:U:V --points NU,NV`: a calculation grid on a work plane, as lighting software
/// has it — the illuminance (lx) at each grid point from every light of the scene (direct, shadow rays honoured), as a
/// CSV and an SVG heat map with its labelled scale.
/// </summary>
public static class IlluminanceCommand
{
    const string Help = """
        usage: spectral illuminance SCENE --plane OX,OY,OZ:UX,UY,UZ:VX,VY,VZ --points NU,NV [-o PREFIX] [--models DIR]

        The illuminance (lx) on a work plane from every light of the scene (physical radiometry): direct light from the
        point, spot, directional and goniometric lights, each shadow ray honoured (no interreflection, area lights or
        sky). The plane is the parallelogram from the origin O spanned by the edge vectors U and V (metres, scene
        coordinates); its grid points are the centres of NU × NV equal cells, O + (i + ½)/NU·U + (j + ½)/NV·V, and the
        illuminance is measured on the side U × V points to (flip U and V for the other). Writes PREFIX.csv (x,y,z,lx:
        one row per point, i fastest) and PREFIX.svg (the grid as a false-colour heat map with its labelled scale);
        prints the minimum, mean and maximum and the uniformity U0 = min/mean. PREFIX defaults to SCENE's name + "-illuminance".

          --plane O:U:V     origin and the two edge vectors, each X,Y,Z in metres
          --points NU,NV    grid points along U and along V (1 to 1000 each)
          -o PREFIX         where to write PREFIX.csv and PREFIX.svg
          --models DIR      a folder to search for mesh files
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("illuminance", argv, ["--plane", "--points", "--output", "--models"], [], new Dictionary<string, string> { ["-o"] = "--output" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1) throw new InputException("command line", "give one scene file", "usage: spectral illuminance SCENE --plane O:U:V --points NU,NV");
        var (origin, u, v) = Plane(a.Value("--plane") ?? throw new InputException("command line", "give the work plane", "e.g. --plane 0,0,0.8:4,0,0:0,3,0"));
        var (nu, nv) = Points(a.Value("--points") ?? throw new InputException("command line", "give the grid's points", "e.g. --points 8,6"));
        var normal = Vector3.Cross(u, v);
        if (!(normal.Length() > 1e-9f)) throw new InputException("--plane", "the edge vectors U and V are parallel (or zero)", "give two edges that span a plane");
        normal = Vector3.Normalize(normal);
        var models = a.Values("--models").ToList();
        foreach (var m in models)
            if (!Directory.Exists(m)) throw new InputException("--models", $"folder {MessageText.Quote(m, 120)} does not exist", "pass the folder that holds the mesh files");
        var path = a.Positionals[0];
        var scene = SceneLoader.Load(path, new SceneOverrides { ModelDirectories = models });
        var illuminance = new Illuminance(scene, new SceneGeometry(scene));
        var points = new Vector3[nu * nv];
        var lux = new double[nu * nv];
        var counters = new RayCounters();
        for (int j = 0; j < nv; j++)
            for (int i = 0; i < nu; i++)
            {
                var p = origin + (i + 0.5f) / nu * u + (j + 0.5f) / nv * v;
                points[j * nu + i] = p;
                lux[j * nu + i] = illuminance.FromLights(p, normal, normal, ref counters);
            }

        var prefix = a.Value("--output") ?? Path.Combine(Path.GetDirectoryName(Path.GetFullPath(path))!, Path.GetFileNameWithoutExtension(path) + "-illuminance");
        var inv = CultureInfo.InvariantCulture;
        var csv = new StringBuilder("x,y,z,lx\n");
        for (int k = 0; k < points.Length; k++)
            csv.Append(inv, $"{points[k].X:R},{points[k].Y:R},{points[k].Z:R},{lux[k]:R}\n");
        AtomicFile.WriteAllText(prefix + ".csv", csv.ToString());
        AtomicFile.WriteAllText(prefix + ".svg", HeatMap(lux, nu, nv, u.Length(), v.Length(), Path.GetFileName(path)));
        double min = lux.Min(), mean = lux.Average(), max = lux.Max();
        stdout.WriteLine(string.Create(inv, $"{nu}×{nv} points on the work plane (normal {normal.X:0.###},{normal.Y:0.###},{normal.Z:0.###}): " +
            $"illuminance min {min:G4} lx, mean {mean:G4} lx, max {max:G4} lx, uniformity U0 = min/mean {(mean > 0 ? min / mean : 0):0.###}"));
        stdout.WriteLine($"wrote {prefix}.csv, {prefix}.svg");
        return CommandLine.Success;
    }

    static (Vector3 O, Vector3 U, Vector3 V) Plane(string text)
    {
        var parts = text.Split(':');
        if (parts.Length != 3) throw new InputException("--plane", $"expected O:U:V, found {MessageText.Quote(text)}", "e.g. --plane 0,0,0.8:4,0,0:0,3,0");
        return (Vector(parts[0], "origin"), Vector(parts[1], "U"), Vector(parts[2], "V"));
    }

    static Vector3 Vector(string text, string what)
    {
        var c = text.Split(',');
        var v = new float[3];
        if (c.Length != 3 || !c.Select((s, i) => float.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out v[i]) && float.IsFinite(v[i])).All(ok => ok))
            throw new InputException("--plane", $"the {what} {MessageText.Quote(text)} is not three numbers X,Y,Z", "e.g. 0,0,0.8 (metres)");
        return new Vector3(v[0], v[1], v[2]);
    }

    static (int U, int V) Points(string text)
    {
        var c = text.Split(',');
        if (c.Length == 2 && int.TryParse(c[0], NumberStyles.None, CultureInfo.InvariantCulture, out int nu) &&
            int.TryParse(c[1], NumberStyles.None, CultureInfo.InvariantCulture, out int nv) && nu is >= 1 and <= 1000 && nv is >= 1 and <= 1000)
            return (nu, nv);
        throw new InputException("--points", $"expected NU,NV (1 to 1000 each), found {MessageText.Quote(text)}", "e.g. --points 8,6");
    }

    /// <summary>The grid as SVG cells (U to the right, V up, each cell's lx in its title) beside its false-colour legend.</summary>
    static string HeatMap(double[] lux, int nu, int nv, float lengthU, float lengthV, string scene)
    {
        var values = lux.Select(x => (float)x).ToArray();
        var scale = FalseColour.For(values, "Illuminance", "lx");
        XNamespace svg = "http://www.w3.org/2000/svg";
        const double area = 480;
        double cell = Math.Min(area * lengthU / Math.Max(lengthU, lengthV) / nu, area * lengthV / Math.Max(lengthU, lengthV) / nv);
        double w = cell * nu, h = cell * nv;
        var inv = CultureInfo.InvariantCulture;
        var root = new XElement(svg + "svg", new XAttribute("width", (int)Math.Ceiling(w + 260)), new XAttribute("height", (int)Math.Ceiling(Math.Max(h + 60, 400))),
            new XAttribute("font-family", "sans-serif"), new XAttribute("font-size", 12),
            new XElement(svg + "text", new XAttribute("x", 10), new XAttribute("y", 20), new XAttribute("font-weight", "bold"),
                $"Illuminance on the work plane — {scene} ({nu} × {nv} points; U → right, V ↑)"));
        for (int j = 0; j < nv; j++)
            for (int i = 0; i < nu; i++)
            {
                double value = lux[j * nu + i];
                var (r, g, b) = FalseColour.Colour(scale.Position(value));
                root.Add(new XElement(svg + "rect", new XAttribute("x", (10 + i * cell).ToString("F2", inv)), new XAttribute("y", (40 + (nv - 1 - j) * cell).ToString("F2", inv)),
                    new XAttribute("width", cell.ToString("F2", inv)), new XAttribute("height", cell.ToString("F2", inv)), new XAttribute("fill", $"#{r:x2}{g:x2}{b:x2}"),
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
