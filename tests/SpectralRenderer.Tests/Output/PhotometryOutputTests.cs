using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using System.Text.RegularExpressions;
using System.Xml.Linq;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Imaging;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Output;

/// <summary>
/// Issue 27: `--formats …,photometry` writes photometry.exr (luminance in cd/m², illuminance in lx) and false-colour PNGs
/// with SVG legends. The photometric laws read back from those files (E = I/r², L = ρE/π, a directional light's E⊥, a
/// uniform sky's E = πL, an integrating sphere's E = E₀/(1 − ρ)), each value parsed from the file by this test's own
/// OpenEXR reader (and by oiiotool/exrheader where installed).
/// </summary>
public class PhotometryOutputTests(ITestOutputHelper output)
{
    public static TheoryData<string> Spectra => new() { "D65", "A", "led-blue" };

    static string Scene(string light, string rho = "1", string extra = "", int size = 1) => $$"""
        { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40", {{extra}}
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 1, "width": {{size}}, "height": {{size}} },
          "materials": { "diffuser": { "diffuse": {{rho}} } },
          "lights": [ {{light}} ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "diffuser" } ] }
        """;

    /// <summary>Renders <paramref name="json"/> with the photometry product; the folder.</summary>
    static string Render(string json, params string[] more)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, json);
        var (code, _, err) =
            CliRunner.Run(["render", scene, "-o", Path.Combine(dir, "out"), "--quiet", "--formats", "png,photometry", .. more]);
        Assert.True(code == 0, err);
        return Path.Combine(dir, "out");
    }

    /// <summary>
    /// A scanline OpenEXR of uncompressed FLOAT channels read by the layout's rules (header attributes to the null byte,
    /// the offset table, per chunk y, size and each channel's row): channel name → values, and the string attributes.
    /// </summary>
    internal static (Dictionary<string, float[]> Channels, Dictionary<string, string> Strings, int Width, int Height) ReadExr(string path)
    {
        var b = File.ReadAllBytes(path);
        Assert.Equal(20000630, BinaryPrimitives.ReadInt32LittleEndian(b));
        int at = 8;
        string Z() { int e = Array.IndexOf(b, (byte)0, at); var s = Encoding.UTF8.GetString(b, at, e - at); at = e + 1; return s; }
        var names = new List<string>();
        var strings = new Dictionary<string, string>();
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0, compression = -1;
        while (b[at] != 0)
        {
            string name = Z(), type = Z();
            int size = BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(at)); at += 4;
            var v = b.AsSpan(at, size);
            if (type == "chlist")
                for (int p = 0; v[p] != 0;)
                {
                    int e = v[p..].IndexOf((byte)0);
                    names.Add(Encoding.UTF8.GetString(v.Slice(p, e)));
                    Assert.Equal(2, BinaryPrimitives.ReadInt32LittleEndian(v[(p + e + 1)..]));   // FLOAT
                    p += e + 1 + 16;
                }
            else if (type == "string") strings[name] = Encoding.UTF8.GetString(v);
            else if (name == "compression") compression = v[0];
            else if (name == "dataWindow")
                (x0, y0, x1, y1) = (BinaryPrimitives.ReadInt32LittleEndian(v), BinaryPrimitives.ReadInt32LittleEndian(v[4..]),
                    BinaryPrimitives.ReadInt32LittleEndian(v[8..]), BinaryPrimitives.ReadInt32LittleEndian(v[12..]));
            at += size;
        }
        at++;
        Assert.Equal(0, compression);
        int w = x1 - x0 + 1, h = y1 - y0 + 1;
        var channels = names.ToDictionary(n => n, _ => new float[w * h]);
        for (int y = 0; y < h; y++)
        {
            int chunk = (int)BinaryPrimitives.ReadUInt64LittleEndian(b.AsSpan(at + 8 * y));
            Assert.Equal(y0 + y, BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(chunk)));
            int p = chunk + 8;
            foreach (var n in names)
                for (int x = 0; x < w; x++, p += 4) channels[n][y * w + x] = BinaryPrimitives.ReadSingleLittleEndian(b.AsSpan(p));
        }
        return (channels, strings, w, h);
    }

    static (double Luminance, double Illuminance) Mean(string folder)
    {
        var exr = ReadExr(Path.Combine(folder, "photometry.exr"));
        return (exr.Channels["luminance"].Average(v => (double)v), exr.Channels["illuminance"].Average(v => (double)v));
    }

    void Check(string what, double value, double expected, double tolerance = 1e-3)
    {
        double rel = Math.Abs(value - expected) / expected;
        output.WriteLine($"{what}: {value:G7} vs {expected:G7} ({rel:E2} relative)");
        Assert.True(rel <= tolerance, $"{what}: {value} vs {expected}, {rel:E2} relative");
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_point_light_of_1000_cd_at_2_m_reads_back_250_lx_and_250_over_pi_cd_per_m2(string spectrum)
    {
        foreach (var integrator in new[] { "whitted", "path" })
        {
            // The path tracer's internal grid at 1 nm: its colour of a narrow LED is then as exact as the bands' tables.
            string settings = integrator == "path" ? "\"integrator\": { \"type\": \"path\", \"spectral_grid\": 1 }," : "";
            var (l, e) = Mean(
                Render(Scene($$"""{ "type": "point", "position": [0, 0, 2], "spectrum": "{{spectrum}}", "luminous_intensity": 1000 }""",
                extra: settings)));
            Check($"{spectrum} {integrator}: illuminance (lx)", e, 250);
            Check($"{spectrum} {integrator}: luminance (cd/m²)", l, 250 / Math.PI);
        }
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_directional_light_of_500_lx_on_reflectance_half_reads_back_500_lx_and_500_times_half_over_pi(string spectrum)
    {
        var (l,
            e) = Mean(Render(
                Scene($$"""{ "type": "directional", "direction": [0, 0, -1], "spectrum": "{{spectrum}}", "illuminance": 500 }""", "0.5")));
        Check($"{spectrum}: illuminance (lx)", e, 500);
        Check($"{spectrum}: luminance (cd/m²)", l, 500 * 0.5 / Math.PI);
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_sphere_light_of_1000_lm_gives_1000_over_4_pi_r2_lux_at_distance_r(string spectrum)
    {
        // An emitting sphere (radius 0.1 m) of "luminous_flux": 1000 lm, 2 m in front of a white diffuser, seen from the
        // side: a Lambertian sphere's illuminance on a surface facing its centre is Φ/(4πr²), so L = ρ·Φ/(4πr²)/π.
        var json = Scene("", extra: "\"integrator\": { \"type\": \"path\", \"spectral_grid\": 1 },")
            .Replace("\"position\": [0, 0, 5]", "\"position\": [2, 0, 5], \"spp\": 16")
            .Replace("\"diffuser\": { \"diffuse\": 1 } }", $$"""
                "diffuser": { "diffuse": 1 }, "bulb": { "diffuse": 0, "emission": { "spectrum": "{{spectrum}}", "luminous_flux": 1000 } } }
                """)
            .Replace("\"material\": \"diffuser\" } ]",
                "\"material\": \"diffuser\" }, { \"type\": \"sphere\", \"center\": [0, 0, 2], \"radius\": 0.1, \"material\": \"bulb\" } ]");
        var (l, _) = Mean(Render(json));
        double e = 1000 / (4 * Math.PI * 2 * 2);
        Check($"{spectrum} sphere of 1000 lm at 2 m: illuminance π·L/ρ (lx)", Math.PI * l, e);
    }

    [Fact]
    public void Illuminance_follows_the_cosine_law_and_shadows_across_the_picture()
    {
        // A directional light of 400 lx at 60° from the normal: E = 400·cos 60° = 200 lx everywhere lit; a box between
        // it and part of the quad leaves 0 lx there (the luminance there too: no other light).
        var json = Scene("""{ "type": "directional", "direction": [0, -0.8660254, -0.5], "spectrum": "D65", "illuminance": 400 }""",
            size: 8)
            .Replace("\"fov\": 1", "\"fov\": 40")
            .Replace("\"material\": \"diffuser\" } ]",
                "\"material\": \"diffuser\" }, { \"type\": \"box\", \"center\": [0, 1.2, 0.6], \"size\": [4, 0.4, 0.4], "
                    + "\"material\": \"diffuser\" } ]");
        var exr = ReadExr(Path.Combine(Render(json), "photometry.exr"));
        var e = exr.Channels["illuminance"];
        var lit = e.Where(v => v > 1).ToArray();
        Assert.NotEmpty(lit);
        Assert.Contains(e, v => v == 0);
        foreach (var v in lit.Where(v => Math.Abs(v - 200) < 50)) Check("lit quad (lx)", v, 200, 1e-4);
    }

    [Fact]
    public void A_uniform_sky_lights_an_open_plane_with_pi_times_its_luminance_under_the_path_integrator()
    {
        // Background = 0.01 W·m⁻²·sr⁻¹·nm⁻¹ flat over the bands (380–780 nm): L_v = 683·0.01·∫V dλ (a midpoint sum here), E = π·L_v.
        var v = SpectralRenderer.Color.Observer.Cie1931.YBar;
        double integral = 0;
        for (int i = 0; i < 40000; i++) integral += v.Evaluate(380 + (i + 0.5) * 0.01) * 0.01;
        double lv = 683 * 0.01 * integral;
        var json = Scene("", extra: "\"background\": 0.01, \"integrator\": \"path\",")
            .Replace("\"white\": \"D65\"", "\"white\": \"E\"");
        var (_, e) = Mean(Render(json));
        Check("sky: illuminance (lx)", e, Math.PI * lv, 2e-3);
    }

    /// <summary>
    /// Issue 42: a long gather is not silent. The path render's photometry gather and its grid's gather report progress
    /// after the render's tiles, as rows: every row of the 7-pixel-high film and of the 5-point-deep grid reported once,
    /// ending at all of them.
    /// </summary>
    [Fact]
    public void The_photometry_and_grid_gathers_report_their_rows_after_the_render()
    {
        var json = Scene("{ \"type\": \"point\", \"position\": [0, 0, 2], \"spectrum\": \"D65\", \"intensity\": 1 }",
                extra: "\"integrator\": \"path\", \"calculation_grids\": [{ \"name\": \"desk\", \"origin\": [-1, -1, 0], "
                    + "\"u\": [2, 0, 0], \"v\": [0, 2, 0], \"points\": [3, 5] }],", size: 7)
            .Replace("\"width\": 7, \"height\": 7", "\"width\": 9, \"height\": 7, \"spp\": 2");
        var events = new System.Collections.Concurrent.ConcurrentQueue<SpectralRenderer.Rendering.RenderProgress>();
        var job = SpectralRenderer.Pipeline.RenderJob.Load(new SpectralRenderer.Pipeline.RenderRequest
        {
            SceneText = Encoding.UTF8.GetBytes(json),
            ScenePath = "gather.json",
            OutDir = Path.Combine(Reference.TempDir(), "out"),
            Products = ["photometry"],
        });
        job.Execute(new SpectralRenderer.Pipeline.RenderObserver(Progress: events.Enqueue));
        var stages = events.GroupBy(e => e.Stage ?? "tiles").ToDictionary(g => g.Key, g => g.ToList());
        Assert.Contains("tiles", stages.Keys);
        foreach (var (stage, rows) in new[] { ("photometry gather", 7), ("grid desk gather", 5) })
        {
            Assert.True(stages.ContainsKey(stage), $"no '{stage}' progress: {string.Join(", ", stages.Keys)}");
            var seen = stages[stage];
            Assert.All(seen, e => Assert.Equal(rows, e.Tiles));
            Assert.Equal(Enumerable.Range(1, rows), seen.Select(e => e.TilesDone).Order());
        }
    }

    [Fact]
    public void An_integrating_sphere_multiplies_the_direct_illuminance_by_one_over_one_minus_rho()
    {
        // A point source of Φ at the centre of a closed Lambertian sphere of radius R, reflectance ρ: direct E₀ = Φ/(4πR²)
        // on every point, and every reflection adds ρ times the last, E = E₀/(1 − ρ) (the integrating-sphere relation).
        const double rho = 0.5, r = 1, flux = 1000;
        var json = $$"""
            { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "400:700:6", "integrator": "path",
              "camera": { "position": [0, 0, 0.5], "look_at": [0, 0, -1], "fov": 60, "width": 6, "height": 6, "spp": 1 },
              "materials": { "wall": { "diffuse": {{rho}} } },
              "lights": [ { "type": "point", "position": [0, 0, 0], "spectrum": "D65", "luminous_flux": {{flux}} } ],
              "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": {{r}}, "material": "wall" } ] }
            """;
        var (_, e) = Mean(Render(json));
        double e0 = flux / (4 * Math.PI * r * r);
        Check("integrating sphere (lx)", e, e0 / (1 - rho), 0.03);
    }

    [Fact]
    public void The_false_colour_pictures_map_back_to_the_exr_through_their_labelled_scale()
    {
        // Reads the legend's scale (data-scale, data-low, data-high, the stops) and each pixel's colour, inverts the ramp
        // and compares with the EXR's value: the scale the SVG states is the one the PNG uses.
        var json = Scene("""{ "type": "point", "position": [0.5, 0.3, 1.5], "spectrum": "A", "luminous_intensity": 800 }""", size: 8)
            .Replace("\"fov\": 1", "\"fov\": 30");
        var folder = Render(json);
        var exr = ReadExr(Path.Combine(folder, "photometry.exr"));
        foreach (var (quantity, unit) in new[] { ("luminance", "cd/m²"), ("illuminance", "lx") })
        {
            var svg = XDocument.Load(Path.Combine(folder, $"{quantity}-scale.svg")).Root!;
            Assert.Equal(unit, (string?)svg.Attribute("data-unit"));
            Assert.Contains($"({unit})", svg.Value);
            bool log = (string?)svg.Attribute("data-scale") == "log10";
            double low = double.Parse((string)svg.Attribute("data-low")!, CultureInfo.InvariantCulture);
            double high = double.Parse((string)svg.Attribute("data-high")!, CultureInfo.InvariantCulture);
            var stops = svg.Descendants().Where(x => x.Name.LocalName == "stop")
                .Select(s => Convert.FromHexString(((string)s.Attribute("stop-color")!)[1..])).ToArray();
            var ticks = svg.Descendants().Where(x => (string?)x.Attribute("class") == "tick").ToArray();
            Assert.True(ticks.Length >= 2);
            foreach (var t in ticks) Assert.EndsWith(unit, t.Value);
            var png = PngReader.Read(Path.Combine(folder, $"{quantity}.png"));
            var values = exr.Channels[quantity];
            for (int i = 0; i < values.Length; i++)
            {
                var c = new[] { png.Samples[3 * i], png.Samples[3 * i + 1], png.Samples[3 * i + 2] };
                // Nearest point on the ramp's piecewise-linear path through the stops.
                double best = double.MaxValue, tBest = 0;
                for (int k = 0; k + 1 < stops.Length; k++)
                    for (int j = 0; j <= 1000; j++)
                    {
                        double f = j / 1000.0, d = 0;
                        for (int ch = 0; ch < 3; ch++)
                        {
                            double x = stops[k][ch] + (stops[k + 1][ch] - stops[k][ch]) * f - c[ch];
                            d += x * x;
                        }
                        if (d < best) { best = d; tBest = (k + f) / (stops.Length - 1); }
                    }
                double value =
                    log ? Math.Pow(10, Math.Log10(low) + tBest * (Math.Log10(high) - Math.Log10(low))) : low + tBest * (high - low);
                double v = Math.Clamp(values[i], low, high);
                double err = log
                    ? Math.Abs(Math.Log10(value) - Math.Log10(v)) / (Math.Log10(high) - Math.Log10(low))
                    : Math.Abs(value - v) / (high - low);
                Assert.True(err < 0.01, $"{quantity} pixel {i}: colour {string.Join(",", c)} reads {value}, the EXR holds {values[i]}");
            }
        }
    }

    [Theory, MemberData(nameof(Spectra))]
    public void An_area_light_given_in_cd_per_m2_is_seen_with_that_luminance_and_lights_a_plane_facing_it(string spectrum)
    {
        // An emitting quad of 300 cd/m² fills the view: the luminance channel reads 300. A sky of 1000 cd/m² over an open
        // plane gives E = π·1000 lx on it (∫ L cos θ dω over the hemisphere), the plane itself seen with ρE/π = 0.5·1000.
        var area = $$"""
            { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40",
              "integrator": { "type": "path", "spectral_grid": 1 },
              "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 1, "width": 1, "height": 1 },
              "materials": { "panel": { "diffuse": 0, "emission": { "spectrum": "{{spectrum}}", "luminance": 300 } } },
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "panel" } ] }
            """;
        Check($"{spectrum}: area light luminance (cd/m²)", Mean(Render(area)).Luminance, 300);
        var sky = Scene("", "0.5", $$"""
            "background": { "spectrum": "{{spectrum}}", "luminance": 1000 }, "integrator": { "type": "path", "spectral_grid": 1 },
            """);
        var (l, e) = Mean(Render(sky));
        Check($"{spectrum}: sky 1000 cd/m², plane illuminance (lx)", e, Math.PI * 1000);
        Check($"{spectrum}: sky 1000 cd/m², plane of ρ 0.5 luminance (cd/m²)", l, 500);
    }

    [Theory]
    [InlineData("\"emission\": { \"spectrum\": \"D65\", \"luminance\": 3, \"radiance\": 1 }", "both radiance and luminance")]
    [InlineData("\"emission\": { \"spectrum\": 0, \"luminance\": 3 }", "emits no visible light")]
    public void A_bad_luminance_is_one_line_with_exit_2(string emission, string what)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene,
            Scene("", extra: "\"integrator\": \"path\",").Replace("\"diffuse\": 1 }", $"\"diffuse\": 1, {emission} }}"));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains(what, err);
        Assert.Contains("$.materials.diffuser.emission", err);
    }

    [Fact]
    public void Paper_radiometry_is_refused_in_one_line_with_a_hint()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene("""{ "type": "point", "position": [0, 0, 2], "spectrum": "D65", "intensity": 1 }""")
            .Replace("\"radiometry\": \"physical\", \"scaling\": \"absolute\", ", ""));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet", "--formats", "png,photometry");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains("physical radiometry", err);
    }

    [SkippableFact]
    [Trait("Category", "Interop")]
    public void Oiiotool_and_exrheader_read_the_photometry_exr_values_and_units()
    {
        var folder = Render(Scene("""{ "type": "point", "position": [0, 0, 2], "spectrum": "D65", "luminous_intensity": 1000 }"""));
        var file = Path.Combine(folder, "photometry.exr");
        var header = Tool.Find("exrheader");
        Skip.If(header is null, "exrheader is not installed (Debian package openexr)");
        var (exit, stdout, stderr) = Tool.Run(header!, [file]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, stderr);
        Assert.Contains("illuminance, 32-bit floating-point", stdout);
        Assert.Contains("luminance, 32-bit floating-point", stdout);
        Assert.Contains("illuminanceUnits (type string): \"lx\"", stdout);
        Assert.Contains("luminanceUnits (type string): \"cd.m^-2\"", stdout);
        var oiio = Tool.Find("oiiotool");
        Skip.If(oiio is null, "oiiotool is not installed (Debian package openimageio-tools)");
        (exit, stdout, stderr) = Tool.Run(oiio!, ["--info", "-v", "--stats", file]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, stderr);
        var order = Regex.Match(stdout, @"channel list: ([^\n]+)").Groups[1].Value.Trim().Split(", ");
        var avg = Regex.Match(stdout, @"Stats Avg: ([^(\n]+)").Groups[1].Value.Split(' ', StringSplitOptions.RemoveEmptyEntries)
            .Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray();
        Check("oiiotool: illuminance (lx)", avg[Array.IndexOf(order, "illuminance")], 250);
        Check("oiiotool: luminance (cd/m²)", avg[Array.IndexOf(order, "luminance")], 250 / Math.PI);
    }
}
