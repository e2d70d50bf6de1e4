using System.Globalization;
using System.Xml.Linq;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// Issue 27: `spectral illuminance SCENE --plane O:U:V --points NU,NV`, a calculation grid on a work plane. Every grid
/// point's lux in the CSV against the closed forms written here: a point light's E = I·cos θ/r² (inverse square and
/// cosine law), a goniometric (IES) light's I(γ)·cos θ/r² at the table's own angles, and 0 behind an occluder.
/// </summary>
public class IlluminanceCommandTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    static string Scene(string light, string objects = "") => $$"""
        { "radiometry": "physical", "white": "D65", "bands": "380:780:20",
          "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "materials": { "grey": { "diffuse": 0.5 } },
          "lights": [ {{light}} ],
          "objects": [ {{objects}} ] }
        """;

    /// <summary>Runs the command; the CSV's rows (x, y, z, lx).</summary>
    static (double X, double Y, double Z, double Lx)[] Run(string json, string plane, string points, out string prefix)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "room.json");
        File.WriteAllText(scene, json);
        prefix = Path.Combine(dir, "grid");
        var (code, stdout, err) = CliRunner.Run("illuminance", scene, "--plane", plane, "--points", points, "-o", prefix);
        Assert.True(code == 0, err);
        Assert.Contains("uniformity U0", stdout);
        var lines = File.ReadAllLines(prefix + ".csv");
        Assert.Equal("x,y,z,lx", lines[0]);
        return lines.Skip(1).Select(l => l.Split(',').Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray())
            .Select(v => (v[0], v[1], v[2], v[3])).ToArray();
    }

    void Close(string what, double value, double expected, double tolerance = 1e-4)
    {
        double err = Math.Abs(value - expected) / Math.Max(expected, 1e-9);
        output.WriteLine($"{what}: {value:G7} vs {expected:G7} lx ({err:E1})");
        Assert.True(err <= tolerance, $"{what}: {value} vs {expected} lx");
    }

    [Fact]
    public void A_point_light_follows_the_inverse_square_and_cosine_laws_at_every_grid_point()
    {
        // 1000 cd at (0.3, 2, 0.2) over the floor y = 0 (normal +y = U × V): E = I·h/r³ at each cell centre.
        var rows = Run(Scene("""{ "type": "point", "position": [0.3, 2, 0.2], "spectrum": "A", "luminous_intensity": 1000 }"""),
            "-1.5,0,1.5:3,0,0:0,0,-3", "5,4", out var prefix);
        Assert.Equal(20, rows.Length);
        for (int k = 0; k < rows.Length; k++)
        {
            int i = k % 5, j = k / 5;
            double x = -1.5 + (i + 0.5) * 3 / 5, z = 1.5 - (j + 0.5) * 3 / 4;
            Assert.Equal(x, rows[k].X, 5);
            Assert.Equal(z, rows[k].Z, 5);
            double dx = x - 0.3, dz = z - 0.2, h = 2, r = Math.Sqrt(dx * dx + dz * dz + h * h);
            Close($"point ({i}, {j})", rows[k].Lx, 1000 * h / (r * r * r));
        }
        // The heat map holds one cell per point with its lx, and a legend in lx.
        var svg = XDocument.Load(prefix + ".svg");
        var cells = svg.Descendants().Where(e => e.Attribute("data-lx") is not null).ToArray();
        Assert.Equal(20, cells.Length);
        Assert.Contains(svg.Descendants(), e => (string?)e.Attribute("data-unit") == "lx");
        Assert.Contains("Illuminance (lx)", svg.Root!.Value);
    }

    [Fact]
    public void A_box_between_the_light_and_some_points_leaves_them_unlit()
    {
        // A slab under the light covers the points with |x| < 0.5: 0 lx there, the closed form elsewhere.
        var rows = Run(Scene("""{ "type": "point", "position": [0, 2, 0], "spectrum": "D65", "luminous_intensity": 500 }""",
            """{ "type": "box", "center": [0, 1, 0], "size": [1, 0.1, 10], "material": "grey" }"""), "-2,0,0.5:4,0,0:0,0,-1", "8,1", out _);
        foreach (var (x, _, z, lx) in rows)
        {
            double r = Math.Sqrt(x * x + z * z + 4);
            // The slab's shadow on the floor spans |x| < 0.5·2/(2 − 1.05) = 1.05: points inside it see no light.
            if (Math.Abs(x) < 1.0) Assert.Equal(0, lx);
            else Close($"x = {x}", lx, 500 * 2 / (r * r * r));
        }
    }

    [Fact]
    public void A_goniometric_light_gives_its_table_candela_times_cos_over_r2_at_the_table_angles()
    {
        // An axially symmetric IES file whose vertical angles are exactly those under which the luminaire at height 2
        // sees the grid points (γ = atan(ρ/2)), so each point's intensity is a table value, no interpolation:
        // E = I(γ)·cos³γ/h² with I in the file (multiplier 1, absolute photometry).
        const double h = 2;
        var xs = new[] { -1.125, -0.375, 0.375, 1.125 };
        var rho = xs.SelectMany(x => xs.Select(z => Math.Sqrt(x * x + z * z))).Distinct().OrderBy(r => r).ToArray();
        var gammas = new[] { 0.0 }.Concat(rho.Select(r => Math.Atan(r / h) * 180 / Math.PI)).Append(90).ToArray();
        double Candela(double g) => 1200 * Math.Cos(g * Math.PI / 180) + 100;
        var ies = $"""
            IESNA:LM-63-2002
            [TEST] IlluminanceCommandTests
            TILT=NONE
            1 -1 1 {gammas.Length} 1 1 2 0.1 0.1 0
            1 1 20
            {string.Join(" ", gammas.Select(F))}
            0
            {string.Join(" ", gammas.Select(g => F(Candela(g))))}
            """;
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "lum.ies"), ies);
        var json = Scene(
            $$"""{ "type": "goniometric", "position": [0, {{h}}, 0], "file": "{{Path.Combine(dir, "lum.ies")}}", "spectrum": "D65" }""");
        var rows = Run(json, "-1.5,0,1.5:3,0,0:0,0,-3", "4,4", out _);
        Assert.Equal(16, rows.Length);
        foreach (var (x, _, z, lx) in rows)
        {
            double r = Math.Sqrt(x * x + z * z), g = Math.Atan(r / h), d2 = r * r + h * h;
            Close($"ρ = {r:0.###} m, γ = {g * 180 / Math.PI:0.##}°", lx, Candela(g * 180 / Math.PI) * Math.Cos(g) / d2, 5e-3);
        }
    }

    [Theory]
    [InlineData("0,0,0:1,0,0", "4,4", "--plane", "O:U:V")]
    [InlineData("0,0,0:1,0,0:2,0,0", "4,4", "--plane", "parallel")]
    [InlineData("0,0,0:1,0,0:0,0,1", "4", "--points", "NU,NV")]
    [InlineData("0,0,0:1,x,0:0,0,1", "4,4", "--plane", "three numbers")]
    public void Bad_options_are_one_line_with_exit_2(string plane, string points, string where, string what)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "room.json");
        File.WriteAllText(scene, Scene("""{ "type": "point", "position": [0, 2, 0], "spectrum": "D65", "luminous_intensity": 1 }"""));
        var (code, _, err) = CliRunner.Run("illuminance", scene, "--plane", plane, "--points", points);
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains(where, err);
        Assert.Contains(what, err);
    }
}
