using System.Globalization;
using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>
/// `spectral illuminance SCENE --plane O:U:V --points NU,NV`: a calculation grid on a work plane, as lighting software
/// has it — the illuminance (lx) at each grid point from every light of the scene (direct, shadow rays honoured), as a
/// CSV and an SVG heat map with its labelled scale (<see cref="CalculationGridFiles"/>); without --plane, the scene's
/// own "calculation_grids".
/// </summary>
public static class IlluminanceCommand
{
    const string Help = """
        usage: spectral illuminance SCENE [--plane OX,OY,OZ:UX,UY,UZ:VX,VY,VZ --points NU,NV] [-o PREFIX] [--models DIR]

        The illuminance (lx) on a work plane from every light of the scene (physical radiometry): direct light from the
        point, spot, directional and goniometric lights (exact), and from emitting objects and the sky (sampled, at
        least 64 shadow rays per point each, or the camera's spp if more), each shadow ray honoured (no
        interreflection). The plane is the parallelogram from the origin O spanned by the edge vectors U and V (metres, scene
        coordinates); its grid points are the centres of NU × NV equal cells, O + (i + ½)/NU·U + (j + ½)/NV·V, and the
        illuminance is measured on the side U × V points to (flip U and V for the other). Writes PREFIX.csv (x,y,z,lx:
        one row per point, i fastest) and PREFIX.svg (the grid as a false-colour heat map with its labelled scale);
        prints the minimum, mean and maximum and the uniformity U0 = min/mean. PREFIX defaults to SCENE's name + "-illuminance".
        Without --plane, the scene's "calculation_grids" (docs/scene-format.md), each to PREFIX-NAME.csv and .svg (a
        render writes them too, with interreflection under the path integrator: grids/NAME.csv and .svg).

          --plane O:U:V     origin and the two edge vectors, each X,Y,Z in metres
          --points NU,NV    grid points along U and along V (1 to 1000 each)
          -o PREFIX         where to write PREFIX.csv and PREFIX.svg
          --models DIR      a folder to search for mesh files
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("illuminance", argv, ["--plane", "--points", "--output", "--models"], [],
            new Dictionary<string, string> { ["-o"] = "--output" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one scene file",
                "usage: spectral illuminance SCENE --plane O:U:V --points NU,NV");
        var models = a.Values("--models").ToList();
        foreach (var m in models)
            if (!Directory.Exists(m))
                throw new InputException("--models", $"folder {MessageText.Quote(m, 120)} does not exist",
                    "pass the folder that holds the mesh files");
        var path = a.Positionals[0];
        CalculationGrid? given = null;
        if (a.Value("--plane") is { } planeText)
        {
            var (origin, u, v) = Plane(planeText);
            var (nu, nv) =
                Points(a.Value("--points") ?? throw new InputException("command line", "give the grid's points", "e.g. --points 8,6"));
            if (!(Vector3.Cross(u, v).Length() > 1e-9f))
                throw new InputException("--plane", "the edge vectors U and V are parallel (or zero)", "give two edges that span a plane");
            given = new CalculationGrid("plane", origin, u, v, nu, nv);
        }
        else if (a.Value("--points") is not null)
            throw new InputException("--points", "--points needs --plane", "e.g. --plane 0,0,0.8:4,0,0:0,3,0 --points 8,6");
        var scene = SceneLoader.Load(path, new SceneOverrides { ModelDirectories = models });
        var grids = given is not null ? [given] : scene.CalculationGrids;
        if (grids.Count == 0)
            throw new InputException("command line", "give the work plane: the scene has no \"calculation_grids\"",
                "e.g. --plane 0,0,0.8:4,0,0:0,3,0 --points 8,6");
        var illuminance = new Illuminance(scene, new SceneGeometry(scene));
        var prefix = a.Value("--output")
            ?? Path.Combine(Path.GetDirectoryName(Path.GetFullPath(path))!, Path.GetFileNameWithoutExtension(path) + "-illuminance");
        foreach (var grid in grids)
        {
            var lux = illuminance.OnGrid(grid, null, 0);
            string file = given is not null ? prefix : $"{prefix}-{grid.Name}";
            CalculationGridFiles.Write(file, grid, lux,
                given is not null ? Path.GetFileName(path) : $"{Path.GetFileName(path)}: {grid.Name}");
            stdout.WriteLine((given is not null ? "" : grid.Name + ": ") + CalculationGridFiles.Summary(grid, lux));
            stdout.WriteLine($"wrote {file}.csv, {file}.svg");
        }
        return CommandLine.Success;
    }

    static (Vector3 O, Vector3 U, Vector3 V) Plane(string text)
    {
        var parts = text.Split(':');
        if (parts.Length != 3)
            throw new InputException("--plane", $"expected O:U:V, found {MessageText.Quote(text)}", "e.g. --plane 0,0,0.8:4,0,0:0,3,0");
        return (Vector(parts[0], "origin"), Vector(parts[1], "U"), Vector(parts[2], "V"));
    }

    static Vector3 Vector(string text, string what)
    {
        var c = text.Split(',');
        var v = new float[3];
        if (c.Length != 3
            || !c.Select((s, i) => float.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out v[i]) && float.IsFinite(v[i]))
                .All(ok => ok))
            throw new InputException("--plane", $"the {what} {MessageText.Quote(text)} is not three numbers X,Y,Z",
                "e.g. 0,0,0.8 (metres)");
        return new Vector3(v[0], v[1], v[2]);
    }

    static (int U, int V) Points(string text)
    {
        var c = text.Split(',');
        if (c.Length == 2 && int.TryParse(c[0], NumberStyles.None, CultureInfo.InvariantCulture, out int nu) &&
            int.TryParse(c[1], NumberStyles.None, CultureInfo.InvariantCulture, out int nv) && nu is >= 1 and <= 1000
                && nv is >= 1 and <= 1000)
            return (nu, nv);
        throw new InputException("--points", $"expected NU,NV (1 to 1000 each), found {MessageText.Quote(text)}", "e.g. --points 8,6");
    }
}
