using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// Relight = re-render: a scene rendered under CIE A with the per-light outputs, relit to other lights, against
/// direct renders of the same scene with those lights (an independent computation: the renderer traces the
/// scene again; relight traces nothing). Bars (issue 15): ≤ 1e-5 relative in every band of every pixel, and
/// ΔE00 ≤ 0.01 between the X Y Z channels of the two spectral.exr files.
/// </summary>
public class RelightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>Two lights (a point light with fall-off and a spot), diffuse + Blinn–Phong, a tinted mirror, Fresnel glass with
    /// total internal reflection, global and per-light ambient, a background, 2 spp.</summary>
    public static string TwoLightScene(string first, string second, double secondIntensity = 1) => $$"""
        {
          "name": "two-lights", "bands": "380:780:20", "white": "D65",
          "camera": { "position": [0, 1.2, 5], "look_at": [0, 0.6, 0], "fov": 40, "width": 48, "height": 36, "spp": 2 },
          "materials": {
            "green": { "diffuse": "colorchecker:14", "specular": 0.4, "shininess": 30 },
            "mirror": { "diffuse": "colorchecker:7", "mirror": "colorchecker:19", "specular": 0.2 },
            "glass": { "diffuse": 0, "mirror": 1, "transmit": 1, "ior": 1.5, "fresnel": true },
            "floor": { "diffuse": "colorchecker:neutral-6.5" }
          },
          "ambient": { "name": "D65", "scale": 0.05 },
          "background": 0.02,
          "lights": [
            { "type": "point", "name": "key", "position": [2, 4, 3], "spectrum": "{{first}}", "intensity": 1, "attenuation": [0.5, 0.05,
              0.02] },
            { "type": "spot", "name": "blue", "position": [-2, 3, 2], "look_at": [0, 0.5, 0], "cutoff": 35, "exponent": 4,
              "spectrum": "{{second}}", "intensity": {{secondIntensity.ToString(System.Globalization.CultureInfo.InvariantCulture)}},
                "ambient": { "name": "D65", "scale": 0.02 } }
          ],
          "objects": [
            { "type": "sphere", "name": "ball", "center": [-0.9, 0.5, 0], "radius": 0.5, "material": "green" },
            { "type": "sphere", "name": "chrome", "center": [0.3, 0.5, -0.6], "radius": 0.5, "material": "mirror" },
            { "type": "box", "name": "cube", "min": [0.7, 0, 0.5], "max": [1.3, 0.6, 1.1], "material": "glass" },
            { "type": "plane", "name": "floor", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" }
          ],
          "max_depth": 4
        }
        """;

    static string Write(string dir, string name, string json)
    {
        var p = Path.Combine(dir, name);
        File.WriteAllText(p, json);
        return p;
    }

    static void Render(string scene, string outDir, params string[] extra)
    {
        var (code, _, err) = CliRunner.Run(["render", scene, "-o", outDir, "--quiet", .. extra]);
        Assert.True(code == 0, err);
    }

    static void Relight(string from, string to, params string[] args)
    {
        var (code, _, err) = CliRunner.Run(["relight", from, "-o", to, "--quiet", .. args]);
        Assert.True(code == 0, err);
    }

    /// <summary>Every band of every pixel (spectral.npy) within 1e-5 relative, and ΔE00 of the EXR's X Y Z within 0.01.</summary>
    void AssertSameRender(string direct, string relit)
    {
        double worstRel = 0;
        using (var a = File.OpenRead(Path.Combine(direct, "spectral.npy")))
        using (var b = File.OpenRead(Path.Combine(relit, "spectral.npy")))
        {
            var (sa, da) = NpyReader.Read(a);
            var (sb, db) = NpyReader.Read(b);
            Assert.Equal(sa, sb);
            int nonzero = 0;
            for (int i = 0; i < da.Length; i++)
            {
                double tol = 1e-5 * Math.Abs(da[i]) + 1e-30;
                if (Math.Abs(da[i] - db[i]) > tol)
                    Assert.Fail($"value {i} (pixel {i / sa[2]}, band {i % sa[2]}): direct {da[i]:R}, relit {db[i]:R}, relative "
                        + $"{Math.Abs(da[i] - db[i]) / Math.Abs(da[i]):0.###e0}");
                if (da[i] != 0) { nonzero++; worstRel = Math.Max(worstRel, Math.Abs(da[i] - db[i]) / Math.Abs(da[i])); }
            }
            Assert.True(nonzero > da.Length / 2, "the images are mostly black: the comparison would prove nothing");
        }
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(direct, "render.json")))!;
        var w = json["colour"]!["white_xyz"]!.AsArray().Select(v => (double)v!).ToArray();
        var white = new Xyz(w[0], w[1], w[2]);
        var ea = ExrReader.Read(Path.Combine(direct, "spectral.exr"));
        var eb = ExrReader.Read(Path.Combine(relit, "spectral.exr"));
        double worst = 0;
        for (int i = 0; i < ea.OtherChannels["X"].Length; i++)
        {
            var xa = new Xyz(ea.OtherChannels["X"][i], ea.OtherChannels["Y"][i], ea.OtherChannels["Z"][i]);
            var xb = new Xyz(eb.OtherChannels["X"][i], eb.OtherChannels["Y"][i], eb.OtherChannels["Z"][i]);
            worst = Math.Max(worst, DeltaE2000.Between(Lab.FromXyz(xa, white), Lab.FromXyz(xb, white)));
        }
        Assert.True(worst <= 0.01, $"worst ΔE00 {worst}");
        output.WriteLine(
            $"relit vs direct: worst relative band difference {worstRel:0.###e0}, worst ΔE00 of the EXR's XYZ {worst:0.###e0}");
        // Every file the render wrote, the relit folder has too (and render.json says it was relit).
        var files = (JsonArray)json["files"]!;
        foreach (var f in files) Assert.True(File.Exists(Path.Combine(relit, (string)f!)), $"relit folder misses {f}");
        var relitJson = JsonNode.Parse(File.ReadAllText(Path.Combine(relit, "render.json")))!;
        Assert.NotNull(relitJson["run"]!["relit"]);
    }

    [Theory]
    [InlineData("D65", "led-blue", 1.0)]
    [InlineData("led-green", "led-green", 1.0)]
    [InlineData("blackbody:3000", "blackbody:3000", 2.5)]
    public void Two_light_scene_rendered_under_A_relit_equals_a_direct_render(string first, string second, double intensity)
    {
        var dir = Reference.TempDir();
        var underA = Write(dir, "a.json", TwoLightScene("A", "A"));
        Render(underA, Path.Combine(dir, "A"), "--formats", "npy,exr,lights");
        var target = Write(dir, "t.json", TwoLightScene(first, second, intensity));
        Render(target, Path.Combine(dir, "direct"), "--formats", "npy,exr,lights");
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "relit"), "--light", $"key={first}", "--light", $"blue={second}",
            "--intensity", $"blue={intensity.ToString(System.Globalization.CultureInfo.InvariantCulture)}");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    /// <summary>
    /// Dispersive Fresnel glass (Cauchy index): each band refracts along its own path and reflects with its own F, so
    /// the transfer holds one-band components there; the relit render still equals the direct one in every band.
    /// </summary>
    [Theory]
    [InlineData("D65", "led-blue")]
    [InlineData("blackbody:3000", "led-green")]
    public void Dispersive_glass_relit_equals_a_direct_render(string first, string second)
    {
        var dir = Reference.TempDir();
        string Dispersive(string a, string b) => TwoLightScene(a, b).Replace("\"ior\": 1.5", "\"ior\": { \"cauchy\": [1.5, 4200] }");
        Assert.Contains("cauchy", Dispersive("A", "A"));
        Render(Write(dir, "a.json", Dispersive("A", "A")), Path.Combine(dir, "A"), "--formats", "npy,exr,lights");
        Render(Write(dir, "t.json", Dispersive(first, second)), Path.Combine(dir, "direct"), "--formats", "npy,exr");
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "relit"), "--light", $"key={first}", "--light", $"blue={second}");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
        // The glass's one-band components are there, each naming its band.
        var comps = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "A", "lights", "lights.json")))!["components"]!.AsArray();
        var bands = comps.Where(c => c!["band"] is not null).Select(c => (int)c!["band"]!).Distinct().Order().ToArray();
        Assert.Equal(Enumerable.Range(1, 20), bands);
    }

    [Fact]
    public void Physical_radiometry_scene_relit_equals_a_direct_render()
    {
        var dir = Reference.TempDir();
        string Physical(string a, string b) =>
            TwoLightScene(a, b).Replace("\"bands\": \"380:780:20\",", "\"bands\": \"380:780:20\", \"radiometry\": \"physical\",");
        var underA = Write(dir, "a.json", Physical("A", "A"));
        Render(underA, Path.Combine(dir, "A"), "--formats", "npy,exr,lights");
        Render(Write(dir, "t.json", Physical("FL11", "led-blue")), Path.Combine(dir, "direct"), "--formats", "npy,exr,lights");
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "relit"), "--light", "key=FL11", "--light", "blue=led-blue");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    [Fact]
    public void Metrics_give_each_light_its_Ra_and_Rf_and_each_object_its_colour_shift()
    {
        var dir = Reference.TempDir();
        Render(Write(dir, "s.json", TwoLightScene("A", "A")), Path.Combine(dir, "r"), "--formats", "npy,lights");
        // Relit to the same lights: no object's colour moves.
        var (code, stdout, err) =
            CliRunner.Run("relight", Path.Combine(dir, "r"), "--light", "key=A", "-o", Path.Combine(dir, "same"), "--metrics", "--quiet");
        Assert.True(code == 0, err);
        var same = File.ReadAllLines(Path.Combine(dir, "same", "relight-metrics.csv")).Skip(1).Select(l => l.Split(',')).ToArray();
        foreach (var o in same.Where(r => r[0] == "object"))
            Assert.Equal(0, double.Parse(o[4], System.Globalization.CultureInfo.InvariantCulture));
        // To FL11 and the blue LED: Ra and Rf of FL11 as in the reference table, the objects' colours shift.
        (code, stdout, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--light", "key=FL11", "--light", "blue=led-blue", "-o",
            Path.Combine(dir, "fl"), "--metrics", "--quiet");
        Assert.True(code == 0, err);
        var rows = File.ReadAllLines(Path.Combine(dir, "fl", "relight-metrics.csv")).Skip(1).Select(l => l.Split(',')).ToArray();
        var key = rows.Single(r => r[0] == "light" && r[1] == "key");
        var refRow = Reference.Rows("colour-rendering.csv").Single(r => r["column"] == "FL11");
        Assert.Equal(refRow.D("Ra_CIE13.3"), double.Parse(key[5], System.Globalization.CultureInfo.InvariantCulture), 0.1);
        Assert.Equal(refRow.D("Rf_CIE224_2017"), double.Parse(key[6], System.Globalization.CultureInfo.InvariantCulture), 0.1);
        Assert.Contains(rows,
            r => r[0] == "object" && r[1] == "ball" && double.Parse(r[3], System.Globalization.CultureInfo.InvariantCulture) > 1);
        Assert.Contains("relight-metrics.csv", stdout.Length > 0 ? "relight-metrics.csv" : "");
        Assert.NotNull(JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "fl", "render.json")))!["run"]!["relit"]!["metrics"]);
    }

    [Fact]
    public void Light_transfer_is_the_same_for_any_thread_count()
    {
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("A", "led-blue"));
        Render(s, Path.Combine(dir, "t1"), "--formats", "lights", "--threads", "1");
        Render(s, Path.Combine(dir, "t2"), "--formats", "lights", "--threads", "3");
        foreach (var f in new[] { "factors.npy", "pixels.npy", "centre.npy", "ids.npy" })
            Assert.Equal(File.ReadAllBytes(Path.Combine(dir, "t1", "lights", f)), File.ReadAllBytes(Path.Combine(dir, "t2", "lights", f)));
    }

    [SkippableTheory]
    [InlineData("D65")]
    [InlineData("led-green")]
    [InlineData("blackbody:3000")]
    public void Bunny_of_section_3_2_rendered_under_A_relit_equals_a_direct_render(string light)
    {
        ModelFiles.Require("stanford-bunny.obj");
        var dir = Reference.TempDir();
        var scene = File.ReadAllText(Path.Combine(Repo(), "scenes", "paper-3.2-bunny-14.json"));
        var underA = Write(dir, "a.json", scene.Replace("\"spectrum\": \"D65\"", "\"spectrum\": \"A\""));
        string[] size = ["--width", "96", "--height", "72", "--models", Path.GetDirectoryName(ModelFiles.Require("stanford-bunny.obj"))!];
        Render(underA, Path.Combine(dir, "A"), [.. size, "--formats", "all,lights"]);
        var target = Write(dir, "t.json", scene.Replace("\"spectrum\": \"D65\"", $"\"spectrum\": \"{light}\""));
        Render(target, Path.Combine(dir, "direct"), [.. size, "--formats", "all,lights"]);
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "relit"), "--light", $"D65={light}");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    [Fact]
    public void Relit_light_arrays_are_the_sources_whether_copied_or_encoded_again()
    {
        var dir = Reference.TempDir();
        Render(Write(dir, "s.json", TwoLightScene("A", "led-blue")), Path.Combine(dir, "r"), "--formats", "npy,lights");
        string[] arrays = ["factors.npy", "pixels.npy", "centre.npy", "ids.npy"];
        var source = arrays.ToDictionary(f => f, f => File.ReadAllBytes(Path.Combine(dir, "r", "lights", f)));
        // Files as the writer encodes them are copied: the same bytes.
        Relight(Path.Combine(dir, "r"), Path.Combine(dir, "copied"), "--light", "key=D65");
        foreach (var f in arrays) Assert.Equal(source[f], File.ReadAllBytes(Path.Combine(dir, "copied", "lights", f)));
        // factors.npy saved another way (float64, as numpy.save of a float64 array writes it): read, then encoded again
        // by the writer, which gives the bytes of the original float32 file.
        var factors = source["factors.npy"];
        int headerLength = 10 + BitConverter.ToUInt16(factors, 8);
        int count = (factors.Length - headerLength) / 4;
        string dict = $"{{'descr': '<f8', 'fortran_order': False, 'shape': ({count},), }}";
        var header = dict.PadRight((10 + dict.Length + 1 + 63) / 64 * 64 - 10 - 1) + "\n";
        using (var f8 = File.Create(Path.Combine(dir, "r", "lights", "factors.npy")))
        {
            f8.Write([0x93, (byte)'N', (byte)'U', (byte)'M', (byte)'P', (byte)'Y', 1, 0]);
            f8.Write(BitConverter.GetBytes((ushort)header.Length));
            f8.Write(System.Text.Encoding.ASCII.GetBytes(header));
            for (int i = 0; i < count; i++) f8.Write(BitConverter.GetBytes((double)BitConverter.ToSingle(factors, headerLength + 4 * i)));
        }
        Relight(Path.Combine(dir, "r"), Path.Combine(dir, "encoded"), "--light", "key=D65");
        foreach (var f in arrays) Assert.Equal(source[f], File.ReadAllBytes(Path.Combine(dir, "encoded", "lights", f)));
        Assert.Equal(File.ReadAllBytes(Path.Combine(dir, "copied", "spectral.npy")),
            File.ReadAllBytes(Path.Combine(dir, "encoded", "spectral.npy")));
    }

    [Fact]
    public void Light_independent_files_are_the_direct_renders_byte_for_byte_copied_or_encoded()
    {
        // object-id.png, mask-lit-K.png, reflectance.exr and lights/*.npy do not depend on the lights' spectra: from a folder of
        // this build they are copied, from another build's (render.json "build" differs) encoded again; both are the direct
        // render's bytes. A new reference white changes reflectance.exr's header (κ), so it is encoded again then too.
        var dir = Reference.TempDir();
        string[] formats = ["--formats", "npy,exr,aov,lights"];
        Render(Write(dir, "a.json", TwoLightScene("A", "A")), Path.Combine(dir, "A"), formats);
        Render(Write(dir, "t.json", TwoLightScene("FL11", "led-blue")), Path.Combine(dir, "direct"), formats);
        Render(Write(dir, "w.json", TwoLightScene("FL11", "led-blue").Replace("\"white\": \"D65\"", "\"white\": \"A\"")),
            Path.Combine(dir, "direct-white"), formats);
        string[] same = ["object-id.png", "mask-lit-0.png", "mask-lit-1.png", "reflectance.exr", "lights/factors.npy", "lights/pixels.npy",
            "lights/centre.npy", "lights/ids.npy"];
        void Check(string direct, string relit)
        {
            foreach (var f in same)
                Assert.True(File.ReadAllBytes(Path.Combine(direct, f)).AsSpan().SequenceEqual(File.ReadAllBytes(Path.Combine(relit, f))),
                    $"{relit}/{f} differs from {direct}/{f}");
            AssertSameRender(direct, relit);
        }
        string[] Copied(string relit) =>
            JsonNode.Parse(File.ReadAllText(Path.Combine(relit, "render.json")))!["run"]!["relit"]!["copied_files"]!.AsArray()
            .Select(f => (string)f!).ToArray();
        string[] lights = ["--light", "key=FL11", "--light", "blue=led-blue"];
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "copied"), lights);
        Check(Path.Combine(dir, "direct"), Path.Combine(dir, "copied"));
        Assert.Equal(same.Order(StringComparer.Ordinal), Copied(Path.Combine(dir, "copied")));
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "white"), [.. lights, "--white", "A"]);
        Check(Path.Combine(dir, "direct-white"), Path.Combine(dir, "white"));
        Assert.Equal(same.Where(f => f != "reflectance.exr").Order(StringComparer.Ordinal), Copied(Path.Combine(dir, "white")));
        var manifest = Path.Combine(dir, "A", "render.json");
        var json = JsonNode.Parse(File.ReadAllText(manifest))!;
        Assert.Equal(32, ((string)json["build"]!).Length);
        json["build"] = "another build";
        File.WriteAllText(manifest, json.ToJsonString());
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "encoded"), lights);
        Check(Path.Combine(dir, "direct"), Path.Combine(dir, "encoded"));
        Assert.Equal(same.Where(f => f.StartsWith("lights/", StringComparison.Ordinal)).Order(StringComparer.Ordinal),
            Copied(Path.Combine(dir, "encoded")));
    }

    [Fact]
    public void Relight_reads_no_mesh_file()
    {
        // Nothing is traced, so a mesh's triangles are not needed: the relight works after the mesh file is gone.
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "tetra.obj"),
            "v -0.6 0 -0.4\nv 0.6 0 -0.4\nv 0 0 0.7\nv 0 1 0\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 3 2\n");
        string Scene(string spectrum, double intensity) => TwoLightScene(spectrum, "led-blue", intensity).Replace(
            "{ \"type\": \"sphere\", \"name\": \"ball\", \"center\": [-0.9, 0.5, 0], \"radius\": 0.5, \"material\": \"green\" }",
            "{ \"type\": \"mesh\", \"name\": \"ball\", \"file\": \"tetra.obj\", \"fit\": { \"min\": [-1.4, 0, -0.5], \"max\": [-0.4, 1, "
                + "0.5] }, \"material\": \"green\" }");
        Assert.Contains("tetra.obj", Scene("A", 1));
        Render(Write(dir, "a.json", Scene("A", 1)), Path.Combine(dir, "A"), "--formats", "npy,exr,lights");
        Render(Write(dir, "t.json", Scene("FL11", 0.5)), Path.Combine(dir, "direct"), "--formats", "npy,exr,lights");
        File.Delete(Path.Combine(dir, "tetra.obj"));
        Relight(Path.Combine(dir, "A"), Path.Combine(dir, "relit"), "--light", "key=FL11", "--intensity", "blue=0.5");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    static string Repo()
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
            if (File.Exists(Path.Combine(d.FullName, "scenes", "paper-3.2-bunny-14.json"))) return d.FullName;
        throw new DirectoryNotFoundException("scenes/");
    }

    [Fact]
    public void Relighting_without_change_reproduces_the_render_and_the_white_follows()
    {
        // A new reference white changes κ and the colour weights as a render with that white does.
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("D65", "led-blue"));
        Render(s, Path.Combine(dir, "r"), "--formats", "npy,exr,lights");
        var withA = Write(dir, "w.json", TwoLightScene("D65", "led-blue").Replace("\"white\": \"D65\"", "\"white\": \"A\""));
        Render(withA, Path.Combine(dir, "direct"), "--formats", "npy,exr,lights");
        Relight(Path.Combine(dir, "r"), Path.Combine(dir, "relit"), "--white", "A");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    [Fact]
    public void Sweep_writes_one_folder_per_row_and_an_index()
    {
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("A", "A"));
        Render(s, Path.Combine(dir, "r"), "--formats", "npy,exr,lights");
        var sweep = Write(dir, "sweep.csv", "key,blue,blue.intensity\nD65,led-blue,1\nled-green,led-green,1\n");
        var (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--sweep", sweep, "-o", Path.Combine(dir, "sw"), "--quiet");
        Assert.True(code == 0, err);
        Assert.Equal(3, File.ReadAllLines(Path.Combine(dir, "sw", "index.csv")).Length);
        var direct = Write(dir, "d.json", TwoLightScene("led-green", "led-green"));
        Render(direct, Path.Combine(dir, "direct"), "--formats", "npy,exr,lights");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "sw", "0002"));
    }

    /// <summary>
    /// A sweep CSV's defects are named by the sweep file's own row (its line, blank lines counted) and column, found
    /// before the first row is written (no folder of an earlier row is left), never blamed on the scene or --light.
    /// </summary>
    [Theory]
    [InlineData("key,blue\nD65,led-blue\n\nA,D66\n", ":4:2", "unknown spectrum")]
    [InlineData("key,blue.intensity\nD65,1\nA,-1\n", ":3:2", "is not a non-negative intensity")]
    [InlineData("key,blue.intensity\nD65,1\nA,1e31\n", ":3:2", "≤ 1e30")]
    [InlineData("key,white\nD65,A\nA,nope-white\n", ":3:2", "unknown spectrum")]
    [InlineData("key,blue\nD65,led-blue\nA\n", ":3:2", "1 cells, the header names 2")]
    [InlineData("\nkey,bleu\nD65,A\n", ":2:2", "column 'bleu' names no light")]
    [InlineData("key,key\nD65,A\n", ":1:2", "column 'key' appears twice")]
    [InlineData("key\n", ":2:1", "a sweep needs a header and at least one row")]
    public void A_bad_sweep_cell_is_named_by_its_row_and_column_before_anything_is_written(string csv, string place, string says)
    {
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("A", "A"));
        Render(s, Path.Combine(dir, "r"), "--formats", "npy,lights");
        var sweep = Write(dir, "sweep.csv", csv);
        var (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--sweep", sweep, "-o", Path.Combine(dir, "sw"), "--quiet");
        Assert.True(code == 2, err);
        Assert.StartsWith($"spectral relight: {sweep}{place}: ", err);
        Assert.Contains(says, err);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.False(Directory.Exists(Path.Combine(dir, "sw")) && Directory.EnumerateFileSystemEntries(Path.Combine(dir, "sw")).Any());
    }

    [Theory]
    [InlineData(new[] { "--light", "nope=D65" }, "no light named 'nope'")]
    [InlineData(new[] { "--light", "key=D66" }, "unknown spectrum")]
    [InlineData(new[] { "--light", "key" }, "is not NAME=VALUE")]
    [InlineData(new[] { "--intensity", "key=-1" }, "non-negative")]
    [InlineData(new string[0], "nothing to change")]
    public void Bad_arguments_are_one_line_errors_with_exit_2(string[] args, string says)
    {
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("A", "A"));
        Render(s, Path.Combine(dir, "r"), "--formats", "npy,lights");
        var (code, _, err) = CliRunner.Run(["relight", Path.Combine(dir, "r"), "-o", Path.Combine(dir, "x"), .. args]);
        Assert.Equal(2, code);
        Assert.Contains(says, err);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.False(Directory.Exists(Path.Combine(dir, "x")) && Directory.EnumerateFileSystemEntries(Path.Combine(dir, "x")).Any());
    }

    [Fact]
    public void A_render_without_the_lights_output_is_refused()
    {
        var dir = Reference.TempDir();
        var s = Write(dir, "s.json", TwoLightScene("A", "A"));
        Render(s, Path.Combine(dir, "r"), "--formats", "npy");
        var (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--light", "key=D65", "-o", Path.Combine(dir, "x"));
        Assert.Equal(2, code);
        Assert.Contains("lights", err);
    }
}
