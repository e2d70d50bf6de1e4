using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 27's goniometric bar: a luminaire's candela come back from a render. The candela tables are written here (with
/// their symmetries: IES axial, quadrant and full, EULUMDAT bilateral C0–C180 and C90–C270); for each of the table's
/// angles (and their mirror images) a one-pixel camera at the luminaire looks along (C, γ) at a white plane 3 m away,
/// tilted by α; the pixel's luminance (Y with κ = 683 lm/W) × π is the illuminance, which must be I(C, γ)·cos α/r²
/// within 0.5 %.
/// </summary>
public class GoniometricLightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    /// <summary>An LM-63-2002 file: multiplier 2, ballast factor 0.9, relative photometry (1 lamp of 1000 lm).</summary>
    static string Ies(double[] vertical, double[] horizontal, Func<double, double, double> cd) =>
        $"""
        IESNA:LM-63-2002
        [TEST] written by GoniometricLightTests
        [MANUFAC] none
        TILT=NONE
        1 1000 2 {vertical.Length} {horizontal.Length} 1 2 0.1 0.1 0
        0.9 1 50
        {string.Join(" ", vertical.Select(F))}
        {string.Join(" ", horizontal.Select(F))}
        {string.Join("\n", horizontal.Select(h => string.Join(" ", vertical.Select(v => F(cd(h, v))))))}
        """;

    /// <summary>An EULUMDAT file: planes every 30°, γ every 15°, values cd/klm of 2000 lm of lamps, CFLI 1.</summary>
    static string Ldt(int isym, Func<double, double, double> cdPerKlm)
    {
        int mc = 12, ng = 13;
        var c = Enumerable.Range(0, mc).Select(i => i * 30.0).ToArray();
        var g = Enumerable.Range(0, ng).Select(i => i * 15.0).ToArray();
        var planes = isym switch
        {
            2 => Enumerable.Range(0, mc / 2 + 1),
            3 => Enumerable.Range(3 * mc / 4, mc / 2 + 1).Select(i => i % mc),
            _ => Enumerable.Range(0, mc),
        };
        var sb = new StringBuilder();
        foreach (var l in new[] { "test", "1", $"{isym}", $"{mc}", "30", $"{ng}", "15", "report", "luminaire", "0", "t.ldt", "today",
                     "100", "100", "50", "100", "100", "0", "0", "0", "0", "100", "80", "1", "0", "1", "1", "LED", "2000", "4000K", "80",
                         "20" })
            sb.Append(l).Append('\n');
        for (int i = 0; i < 10; i++) sb.Append("0.5\n");
        foreach (var x in c) sb.Append(F(x)).Append('\n');
        foreach (var x in g) sb.Append(F(x)).Append('\n');
        foreach (var p in planes) foreach (var x in g) sb.Append(F(cdPerKlm(c[p], x))).Append('\n');
        return sb.ToString();
    }

    // Distributions with structure in C and γ, equal in every plane at the nadir and the zenith.
    static double Down(double c, double g) =>
        800 * Math.Cos(g * Math.PI / 180) * (1 + 0.4 * Math.Sin(g * Math.PI / 180) * Math.Cos(2 * c * Math.PI / 180)) + 50;
    static double Round(double c, double g) =>
        300 + 200 * Math.Cos(g * Math.PI / 180) + 60 * Math.Sin(g * Math.PI / 180) * (1 + Math.Cos(c * Math.PI / 180));

    /// <summary>Illuminance π·L on a white plane 3 m from the luminaire along (C, γ), the plane tilted by α.</summary>
    static double Measured(string file, double c, double g, double alpha, string rotate = "")
    {
        var l =
            new GoniometricLight(new LightEmission("x", [], [], false), new CandelaTable([0], [0], [[1]], CandelaSymmetry.Axial, "x"), 1);
        var d = l.Direction(c, g);
        var target = 3 * d;
        // Tilt the plane's normal from −d by α about an axis perpendicular to d.
        var axis = Vector3.Normalize(Vector3.Cross(d, Math.Abs(d.Y) > 0.9f ? Vector3.UnitX : Vector3.UnitY));
        var n = Vector3.Transform(-d, Quaternion.CreateFromAxisAngle(axis, (float)(alpha * Math.PI / 180)));
        var up = Math.Abs(d.Y) > 0.9f ? "[1, 0, 0]" : "[0, 1, 0]";
        string V(Vector3 v) => $"[{F(v.X)}, {F(v.Y)}, {F(v.Z)}]";
        var json = $$"""
            { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40",
              "camera": { "position": [0, 0, 0], "look_at": {{V(target)}}, "up": {{up}}, "fov": 1, "width": 1, "height": 1 },
              "materials": { "white": { "diffuse": 1 } },
              "lights": [ { "type": "goniometric", "position": [0, 0, 0], "file": "{{file}}", "spectrum": "D65"{{rotate}} } ],
              "objects": [ { "type": "plane", "point": {{V(target)}}, "normal": {{V(n)}}, "material": "white" } ] }
            """;
        return Math.PI * SceneText.Render(json).Xyz![1];
    }

    void Check(string what, string file, IEnumerable<(double C, double G)> angles, Func<double, double, double> candela)
    {
        double worst = 0;
        int n = 0, i = 0;
        foreach (var (c, g) in angles)
        {
            double alpha = (i++ % 3) * 20;   // 0°, 20°, 40°
            double expected = candela(c, g) * Math.Cos(alpha * Math.PI / 180) / 9;
            double e = Measured(file, c, g, alpha);
            double rel = Math.Abs(e - expected) / expected;
            worst = Math.Max(worst, rel);
            n++;
            Assert.True(rel <= 5e-3, $"{what} C {c}° γ {g}° α {alpha}°: {e:G6} lx vs I·cos α/r² = {expected:G6} ({rel:E2})");
        }
        output.WriteLine($"{what}: {n} angles, worst {worst:E2} relative");
    }

    static string Write(string name, string text)
    {
        var path = Path.Combine(Reference.TempDir(), name);
        File.WriteAllText(path, text);
        return path;
    }

    static readonly double[] Gamma0To90 = [0, 15, 30, 45, 60, 75, 90];
    static readonly double[] Gamma0To180 = [0, 22.5, 45, 67.5, 90, 112.5, 135, 157.5, 180];

    [Fact]
    public void An_axial_IES_file_gives_its_candela_in_every_plane()
    {
        var file = Write("axial.ies", Ies(Gamma0To180, [0], (_, g) => Round(0, g)));
        Check("IES axial", file, from c in new[] { 0.0, 100, 250 } from g in Gamma0To180 select (c, g), (_, g) => 1.8 * Round(0, g));
    }

    [Fact]
    public void A_quadrant_IES_file_mirrors_into_all_four_quadrants()
    {
        double[] h = [0, 30, 60, 90];
        var file = Write("quadrant.ies", Ies(Gamma0To90, h, Down));
        // Angles in the file, and their images: C, 180 − C, 180 + C, 360 − C.
        var angles =
            from c in h from image in new[] { c, 180 - c, 180 + c, 360 - c } from g in Gamma0To90.SkipLast(1) select (image % 360, g);
        Check("IES quadrant", file, angles.Distinct(),
            (c, g) => 1.8 * Down(c > 180 ? (c > 270 ? 360 - c : c - 180) : (c > 90 ? 180 - c : c), g));
    }

    [Fact]
    public void A_full_IES_file_gives_every_plane_its_own_candela()
    {
        double[] h = [0, 60, 120, 180, 240, 300, 360];
        var file = Write("full.ies", Ies(Gamma0To180, h, Round));
        Check("IES full", file, from c in h.SkipLast(1) from g in Gamma0To180 select (c, g), (c, g) => 1.8 * Round(c, g));
    }

    [Theory]
    [InlineData(2)]
    [InlineData(3)]
    public void An_EULUMDAT_file_with_a_plane_of_symmetry_gives_its_candela_and_their_mirror_images(int isym)
    {
        // Isym 2: C0–C180 given, C mirrored as 360 − C; Isym 3: C270–C90 given, C mirrored as 180 − C.
        Func<double, double, double> shape = isym == 2 ? Round : (c, g) => Round(c + 90, g);
        var file = Write($"isym{isym}.ldt", Ldt(isym, shape));
        var angles = from i in Enumerable.Range(0, 12) from g in new[] { 0.0, 30, 60, 90, 120, 150, 180 } select (i * 30.0, g);
        double Source(double c) => isym == 2 ? (c > 180 ? 360 - c : c) : (c > 90 && c < 270 ? (540 - c) % 360 : c);
        Check($"EULUMDAT Isym {isym}", file, angles, (c, g) => 2 * shape(Source(c), g));
    }

    [Fact]
    public void The_flux_of_a_table_and_luminous_flux_and_lamp_lumens_scale_it()
    {
        // Axial I(γ) = 300 + 200 cos γ over the sphere: Φ = 4π·300 (the cos term integrates to 0), by the closed form.
        var file = Write("axial.ies", Ies(Gamma0To180, [0], (_, g) => 300 + 200 * Math.Cos(g * Math.PI / 180)));
        var table = IesReader.Parse(File.ReadAllText(file), file).Table;
        double phi = 1.8 * 4 * Math.PI * 300;
        Assert.True(Math.Abs(table.Flux() - phi) / phi < 5e-3, $"Φ {table.Flux()} vs {phi}");   // piecewise-linear in γ between 22.5° knots
        double direct = Measured(file, 0, 0, 0);
        double half = MeasuredWith(file, "\"luminous_flux\": " + F(table.Flux() / 2));
        Assert.True(Math.Abs(half / direct - 0.5) < 1e-4, $"luminous_flux = Φ/2 gives {half / direct} of the file's illuminance");
        double lamp = MeasuredWith(file, "\"lamp_lumens\": 1500");
        Assert.True(Math.Abs(lamp / direct - 1.5) < 1e-4, $"lamp_lumens 1500 of the file's 1000 gives {lamp / direct}");
    }

    static double MeasuredWith(string file, string extra) => Measured(file, 0, 0, 0, ", " + extra);

    [Fact]
    public void Rotating_the_luminaire_turns_its_distribution()
    {
        double[] h = [0, 30, 60, 90];
        var file = Write("quadrant.ies", Ies(Gamma0To90, h, Down));
        // Turned 90° about x: the nadir (−y) now points along −z... measured along the turned direction it is the nadir value.
        var l = new GoniometricLight(new LightEmission("x", [], [], false), new CandelaTable([0], [0], [[1]], CandelaSymmetry.Axial, "x"),
            1)
        { Orientation = Matrix4x4.CreateRotationX(MathF.PI / 2) };
        var d = l.Direction(0, 0);
        Assert.True(Vector3.Distance(d, -Vector3.UnitZ) < 1e-6, $"nadir turned to {d}");
        var (c, g) = l.Angles(-Vector3.UnitZ);
        Assert.True(g < 1e-4, $"γ {g}");
        _ = c;
    }

    [Theory]
    [InlineData("t.ies", "IESNA:LM-63-2002\n1 2 3\n", "t.ies:2", "no TILT= line")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 20\n", "t.ies:7",
        "ends before a candela value")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 90 45\n0\n10 20 30\n", "t.ies:5", "not ascending")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 2 2 0 0 0\n1 1 0\n0 90\n0\n10 20\n", "t.ies:3", "photometric type 2")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 2 1 2 0 0 0\n1 1 0\n0 90\n0 90\n10 20\n1 x\n", "t.ies:8",
        "'x', not a number")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=lamp.tlt\n", "t.ies:2", "not supported")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 4 1 2 0 0 0\n1 1 0\n0 90\n0 90 180 270\n1 2\n1 2\n1 2\n1 2\n", "t.ies:6",
        "horizontal angles 0 … 270 match no LM-63 symmetry")]
    [InlineData("t.ies", "IESNA:LM-63-2002\nTILT=INCLUDE\n4\n", "t.ies:3", "lamp-to-luminaire geometry")]
    [InlineData("t.ldt", "test\n1\n1\n1\n0\n2\n90\nr\nl\n0\nf\nd\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n", "t.ldt:24",
        "the conversion factor CFLI is 0")]
    [InlineData("t.ldt", "test\n1\n5\n", "t.ldt:3", "symmetry indicator")]
    [InlineData("t.ldt", "test\n1\n1\n12\n30\n3\n", "t.ldt:6", "ends before")]
    public void A_malformed_photometric_file_is_one_line_with_file_line_and_hint(string name, string text, string where, string what)
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, name), text);
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, $$"""
            { "radiometry": "physical",
              "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 4, "height": 4 },
              "materials": { "white": { "diffuse": 1 } },
              "lights": [ { "type": "goniometric", "position": [0, 0, 2], "file": "{{name}}", "spectrum": "D65" } ],
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "white" } ] }
            """);
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains(where, err);
        Assert.Contains(what, err);
        Assert.Contains("hint", err);
        var e = Assert.Throws<InputException>(() => name.EndsWith(".ldt") ? EulumdatReader.Parse(text, name) : IesReader.Parse(text, name));
        Assert.Contains(what, e.Message);
    }

    /// <summary>
    /// LM-63's TILT=INCLUDE: an axial file whose lamp factors are 1, 0.9, 0.6, 0.2 at 0°, 30°, 60°, 90° of tilt. Turned by
    /// 40°, the lamp's tilt is 40° when the turn moves its axis (factor 0.9 + (0.6 − 0.9)·10/30 = 0.8, by hand) and 0°
    /// when the axis keeps its measured position (factor 1): geometry 1's vertical lamp tilts under any turn from the
    /// vertical, geometry 2's lamp along C90–C270 (z) only about x, geometry 3's along C0–C180 (x) only about z.
    /// </summary>
    [Theory]
    [InlineData(1, "[40, 0, 0]", 0.8)]
    [InlineData(1, "[0, 0, 40]", 0.8)]
    [InlineData(1, "[0, 40, 0]", 1.0)]
    [InlineData(2, "[40, 0, 0]", 0.8)]
    [InlineData(2, "[0, 0, 40]", 1.0)]
    [InlineData(3, "[0, 0, 40]", 0.8)]
    [InlineData(3, "[40, 0, 0]", 1.0)]
    public void A_tilt_factor_multiplies_the_candela_at_the_lamps_installed_tilt(int geometry, string rotate, double factor)
    {
        string none = Ies(Gamma0To180, [0], (_, g) => Round(0, g));
        string include = none.Replace("TILT=NONE", $"TILT=INCLUDE\n{geometry}\n4\n0 30 60 90\n1 0.9 0.6 0.2");
        string a = Write($"tilt-none-{geometry}.ies", none), b = Write($"tilt-include-{geometry}.ies", include);
        string r = $", \"rotate\": {rotate}";
        foreach (var (c, g) in new[] { (0.0, 30.0), (90.0, 60.0), (200.0, 20.0) })
        {
            double ratio = Measured(b, c, g, 0, r) / Measured(a, c, g, 0, r);
            Assert.True(Math.Abs(ratio - factor) <= 1e-5,
                $"geometry {geometry}, rotate {rotate}, C {c} γ {g}: ratio {ratio:R}, factor {factor}");
        }
    }

    [Fact]
    public void A_goniometric_light_in_paper_radiometry_is_refused_with_a_hint()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "a.ies"), Ies(Gamma0To90, [0], (_, g) => 100));
        File.WriteAllText(Path.Combine(dir, "scene.json"), """
            { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 4, "height": 4 },
              "lights": [ { "type": "goniometric", "position": [0, 0, 2], "file": "a.ies", "spectrum": "D65" } ],
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": 1 } ] }
            """);
        var (code, _, err) = CliRunner.Run("render", Path.Combine(dir, "scene.json"), "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Contains("needs physical radiometry", err);
    }
}
