using System.Globalization;
using System.Text.Json.Nodes;
using System.Xml.Linq;
using SpectralRenderer.Tests.Cli;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Output;

/// <summary>
/// Issue 27: a scene's "calculation_grids" (lighting software's calculation grid on a work plane) written with the
/// render as grids/NAME.csv and grids/NAME.svg. Every point's lux against closed forms written here: a point light's
/// E = I·cos θ/r² on a floor and on a wall (inverse square and cosine law), a uniform sky's E = π·L_v gathered by the
/// path integrator; `spectral illuminance SCENE` without --plane writes the same grids.
/// </summary>
public class CalculationGridTests(ITestOutputHelper output)
{
    // 1000 cd (A) at (0.3, 0.2, 2) over a floor z = 0; a floor grid facing +z and a wall grid at x = −1 facing +x.
    const string Grids = """
        "calculation_grids": [
          { "name": "floor", "origin": [-1.5, -1.5, 0], "u": [3, 0, 0], "v": [0, 3, 0], "points": [5, 4] },
          { "name": "wall", "origin": [-1, -1, 0.5], "u": [0, 2, 0], "v": [0, 0, 1], "points": [3, 2] } ],
        """;

    static string Scene(string light, string extra = "") => $$"""
        { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40", {{extra}}
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40, "width": 4, "height": 4 },
          "materials": { "diffuser": { "diffuse": 0.5 } },
          "lights": [ {{light}} ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "diffuser" } ] }
        """;

    const string PointLight = """{ "type": "point", "position": [0.3, 0.2, 2], "spectrum": "A", "luminous_intensity": 1000 }""";

    static string Write(string json)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "room.json");
        File.WriteAllText(scene, json);
        return scene;
    }

    static (double X, double Y, double Z, double Lx)[] Csv(string path)
    {
        var lines = File.ReadAllLines(path);
        // a gathered grid (path) has the points' standard errors in a fifth column
        Assert.Contains(lines[0], new[] { "x,y,z,lx", "x,y,z,lx,stderr_lx" });
        return lines.Skip(1).Select(l => l.Split(',').Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray())
            .Select(v => (v[0], v[1], v[2], v[3])).ToArray();
    }

    void Close(string what, double value, double expected, double tolerance)
    {
        double err = Math.Abs(value - expected) / expected;
        output.WriteLine($"{what}: {value:G7} vs {expected:G7} lx ({err:E1})");
        Assert.True(err <= tolerance, $"{what}: {value} vs {expected} lx");
    }

    /// <summary>E = I·(n·d)/r³ for 1000 cd at (0.3, 0.2, 2), d from the point to the light.</summary>
    static double InverseSquareCosine(double x, double y, double z, double nx, double nz)
    {
        double dx = 0.3 - x, dy = 0.2 - y, dz = 2 - z, r = Math.Sqrt(dx * dx + dy * dy + dz * dz);
        return 1000 * (nx * dx + nz * dz) / (r * r * r);
    }

    /// <summary>The rows at the cell centres O + (i + ½)/NU·U + (j + ½)/NV·V, i fastest, each against the closed form.</summary>
    void CheckGrid(string name, (double X, double Y, double Z, double Lx)[] rows, double[] o, double[] u, double[] v, int nu, int nv,
        double nx, double nz)
    {
        Assert.Equal(nu * nv, rows.Length);
        for (int k = 0; k < rows.Length; k++)
        {
            double s = (k % nu + 0.5) / nu, t = (k / nu + 0.5) / nv;
            Assert.Equal(o[0] + s * u[0] + t * v[0], rows[k].X, 5);
            Assert.Equal(o[1] + s * u[1] + t * v[1], rows[k].Y, 5);
            Assert.Equal(o[2] + s * u[2] + t * v[2], rows[k].Z, 5);
            Close($"{name} ({k % nu}, {k / nu})", rows[k].Lx, InverseSquareCosine(rows[k].X, rows[k].Y, rows[k].Z, nx, nz), 1e-4);
        }
    }

    [Fact]
    public void A_render_writes_each_grid_with_the_inverse_square_and_cosine_law_at_every_point()
    {
        var scene = Write(Scene(PointLight, Grids));
        var dir = Path.Combine(Path.GetDirectoryName(scene)!, "out");
        // --formats png only: the scene's grids are written all the same.
        var (code, _, err) = CliRunner.Run("render", scene, "-o", dir, "--quiet", "--formats", "png");
        Assert.True(code == 0, err);
        CheckGrid("floor", Csv(Path.Combine(dir, "grids", "floor.csv")), [-1.5, -1.5, 0], [3, 0, 0], [0, 3, 0], 5, 4, 0, 1);
        CheckGrid("wall", Csv(Path.Combine(dir, "grids", "wall.csv")), [-1, -1, 0.5], [0, 2, 0], [0, 0, 1], 3, 2, 1, 0);
        var files = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "render.json")))!["files"]!.AsArray().Select(f => (string)f!)
            .ToArray();
        Assert.Contains("grids/floor.csv", files);
        Assert.Contains("grids/wall.svg", files);
        // The heat map: one cell per point holding its lx, and a legend in lx.
        var svg = XDocument.Load(Path.Combine(dir, "grids", "floor.svg"));
        var cells = svg.Descendants().Where(e => e.Attribute("data-lx") is not null).ToArray();
        Assert.Equal(20, cells.Length);
        Assert.Contains(svg.Descendants(), e => (string?)e.Attribute("data-unit") == "lx");
    }

    [Fact]
    public void The_illuminance_command_without_a_plane_writes_the_scenes_grids()
    {
        var scene = Write(Scene(PointLight, Grids));
        var prefix = Path.Combine(Path.GetDirectoryName(scene)!, "calc");
        var (code, stdout, err) = CliRunner.Run("illuminance", scene, "-o", prefix);
        Assert.True(code == 0, err);
        Assert.Contains("floor: 5×4 points", stdout);
        Assert.Contains("wall: 3×2 points", stdout);
        CheckGrid("floor", Csv(prefix + "-floor.csv"), [-1.5, -1.5, 0], [3, 0, 0], [0, 3, 0], 5, 4, 0, 1);
        CheckGrid("wall", Csv(prefix + "-wall.csv"), [-1, -1, 0.5], [0, 2, 0], [0, 0, 1], 3, 2, 1, 0);
    }

    [Fact]
    public void Under_the_path_integrator_a_uniform_sky_gives_every_point_pi_times_its_luminance()
    {
        // Background 0.01 W·m⁻²·sr⁻¹·nm⁻¹ flat over 380–780 nm: L_v = 683·0.01·∫V dλ, and an open upward grid above the
        // floor sees it over its whole hemisphere: E = π·L_v (the gather's rays; no delta light in the scene).
        var v = SpectralRenderer.Color.Observer.Cie1931.YBar;
        double integral = 0;
        for (int i = 0; i < 40000; i++) integral += v.Evaluate(380 + (i + 0.5) * 0.01) * 0.01;
        double lv = 683 * 0.01 * integral;
        var json = Scene("", """
            "background": 0.01, "integrator": "path",
            "calculation_grids": [ { "name": "open", "origin": [-1, -1, 0.5], "u": [2, 0, 0], "v": [0, 2, 0], "points": [3, 3] } ],
            """).Replace("\"white\": \"D65\"", "\"white\": \"E\"");
        var scene = Write(json);
        var dir = Path.Combine(Path.GetDirectoryName(scene)!, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", dir, "--quiet", "--formats", "png");
        Assert.True(code == 0, err);
        foreach (var row in Csv(Path.Combine(dir, "grids", "open.csv")))
            Close($"sky at ({row.X:0.##}, {row.Y:0.##})", row.Lx, Math.PI * lv, 2e-3);
    }

    [Theory]
    [InlineData("\"v\": [0, 3, 0]", "\"v\": [6, 0, 0]", "$.calculation_grids[0].v", "parallel")]
    [InlineData("\"points\": [5, 4]", "\"points\": [5, 0]", "$.calculation_grids[0].points", "[NU, NV]")]
    [InlineData("\"points\": [5, 4]", "\"points\": [5, \"4\"]", "$.calculation_grids[0].points", "[NU, NV]")]
    [InlineData("\"name\": \"wall\"", "\"name\": \"Floor\"", "$.calculation_grids[1].name", "two calculation grids")]
    [InlineData("\"name\": \"wall\"", "\"name\": \"../x\"", "$.calculation_grids[1].name", "letters, digits")]
    [InlineData("\"origin\": [-1, -1, 0.5]", "\"origin\": [-1, -1, 0.5], \"size\": 2", "$.calculation_grids[1].size", "unknown field")]
    public void A_bad_grid_is_one_line_with_its_json_path_and_exit_2(string from, string to, string where, string what)
    {
        var scene = Write(Scene(PointLight, Grids).Replace(from, to));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(Path.GetDirectoryName(scene)!, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains(where, err);
        Assert.Contains(what, err);
    }

    [Fact]
    public void A_grid_in_paper_radiometry_is_refused_with_a_hint()
    {
        var json = Scene("""{ "type": "point", "position": [0.3, 0.2, 2], "spectrum": "A", "intensity": 1 }""", Grids)
            .Replace("\"radiometry\": \"physical\", \"scaling\": \"absolute\", ", "");
        var (code, _, err) = CliRunner.Run("render", Write(json), "-o", Path.Combine(Reference.TempDir(), "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains("$.calculation_grids", err);
        Assert.Contains("\"radiometry\": \"physical\"", err);
    }

    [Fact]
    public void Inside_an_integrating_sphere_a_grid_gets_the_direct_light_plus_rho_over_one_minus_rho_of_the_walls()
    {
        // A point source of Φ at the centre of a closed Lambertian sphere of radius R, reflectance ρ: the walls receive
        // E_w = E₀/(1 − ρ), E₀ = Φ/(4πR²), and glow uniformly with L = ρE_w/π, so any plane inside receives π·L = ρE₀/(1 − ρ)
        // from them on either side, besides the source's own I·cos θ/d² (I = Φ/4π).
        const double rho = 0.5, r = 1, flux = 1000;
        var json = $$"""
            { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "400:700:6", "integrator": "path",
              "camera": { "position": [0, 0, 0.5], "look_at": [0, 0, -1], "fov": 60, "width": 2, "height": 2, "spp": 1 },
              "materials": { "wall": { "diffuse": {{rho}} } },
              "lights": [ { "type": "point", "position": [0, 0, 0], "spectrum": "D65", "luminous_flux": {{flux}} } ],
              "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": {{r}}, "material": "wall" } ],
              "calculation_grids": [ { "name": "inside", "origin": [-0.3, -0.3, -0.5], "u": [0.6, 0, 0], "v": [0, 0.6, 0], "points": [3,
                3] } ] }
            """;
        var scene = Write(json);
        var dir = Path.Combine(Path.GetDirectoryName(scene)!, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", dir, "--quiet", "--formats", "png");
        Assert.True(code == 0, err);
        double e0 = flux / (4 * Math.PI * r * r), walls = rho * e0 / (1 - rho), indirect = 0;
        var rows = Csv(Path.Combine(dir, "grids", "inside.csv"));
        foreach (var (x, y, z, lx) in rows)
        {
            double d2 = x * x + y * y + z * z, direct = flux / (4 * Math.PI) * -z / Math.Sqrt(d2) / d2;
            Close($"sphere at ({x:0.#}, {y:0.#}): direct + walls", lx, direct + walls, 0.03);
            indirect += (lx - direct) / rows.Length;
        }
        Close("sphere: mean of the walls' share", indirect, walls, 0.03);
    }

    [Fact]
    public void A_relit_render_traces_its_grids_again_under_the_new_lights()
    {
        var scene = Write(Scene(PointLight.Replace("\"type\": \"point\",", "\"type\": \"point\", \"name\": \"key\","), Grids));
        var dir = Path.GetDirectoryName(scene)!;
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "npy,lights");
        Assert.True(code == 0, err);
        // Under D65 the light keeps its 1000 cd (the spectrum gives the shape only): the same closed form.
        (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "-o", Path.Combine(dir, "d65"), "--quiet", "--light", "key=D65");
        Assert.True(code == 0, err);
        CheckGrid("relit floor", Csv(Path.Combine(dir, "d65", "grids", "floor.csv")), [-1.5, -1.5, 0], [3, 0, 0], [0, 3, 0], 5, 4, 0, 1);
        // Switched off, the grid is dark: its files are traced again, not copied from the source.
        (code, _, err) =
            CliRunner.Run("relight", Path.Combine(dir, "r"), "-o", Path.Combine(dir, "off"), "--quiet", "--intensity", "key=0");
        Assert.True(code == 0, err);
        Assert.All(Csv(Path.Combine(dir, "off", "grids", "wall.csv")), row => Assert.Equal(0, row.Lx));
    }
}
