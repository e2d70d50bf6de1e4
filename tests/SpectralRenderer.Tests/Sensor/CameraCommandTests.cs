using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Imaging;
using SpectralRenderer.Sensor;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Imaging;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>`spectral camera` end to end: reproducible noise, the ideal colorimetric sensor against 1 nm CIE sums, the DNG in
/// dcraw.</summary>
public class CameraCommandTests
{
    /// <summary>Three flat grey quads (reflectance 0.2, 0.5, 0.9) lit head-on by one light, so each band radiance is R·E_b
    /// exactly.</summary>
    static string GreyChart(string light, string bands, int width = 24, int height = 8, string cameraExtra = "")
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "greys.json");
        File.WriteAllText(scene, $$"""
        {
          "bands": "{{bands}}", "white": "{{light}}",
          "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 30, "width": {{width}}, "height": {{height}}{{cameraExtra}} },
          "materials": { "g2": { "diffuse": 0.2 }, "g5": { "diffuse": 0.5 }, "g9": { "diffuse": 0.9 } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "{{light}}" } ],
          "objects": [
            { "type": "quad", "name": "g2", "center": [-1.8, 0, 0], "size": 1.6, "material": "g2" },
            { "type": "quad", "name": "g5", "center": [0, 0, 0], "size": 1.6, "material": "g5" },
            { "type": "quad", "name": "g9", "center": [1.8, 0, 0], "size": 1.6, "material": "g9" }
          ]
        }
        """);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        Assert.True(code == 0, err);
        return outDir;
    }

    /// <summary>A tiny independent CSV reader for the CIE tables in data/ (not the engine's).</summary>
    static (double[] Wl, double[] V) Column(string file, string column)
    {
        var lines = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, file));
        int col = Array.IndexOf(lines[0].Split(','), column);
        var rows = lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')).ToArray();
        return (rows.Select(r => double.Parse(r[0], CultureInfo.InvariantCulture)).ToArray(),
            rows.Select(r => double.Parse(r[col], CultureInfo.InvariantCulture)).ToArray());
    }

    static double Lerp((double[] Wl, double[] V) t, double x)
    {
        if (x <= t.Wl[0]) return t.V[0];
        if (x >= t.Wl[^1]) return t.V[^1];
        int i = Array.BinarySearch(t.Wl, x);
        if (i >= 0) return t.V[i];
        i = ~i - 1;
        return t.V[i] + (x - t.Wl[i]) / (t.Wl[i + 1] - t.Wl[i]) * (t.V[i + 1] - t.V[i]);
    }

    /// <summary>
    /// Σ cmf·E·R over 380–780 nm, CIE 015's 1 nm sum (trapezoidal form, <see cref="Cie015.Sum"/>) of the tables' linear
    /// interpolants, R constant in each of <paramref name="bandReflectance"/>'s equal bands (one value: a grey).
    /// </summary>
    static double[] ExactXyz((double[] Wl, double[] V) light, double[] bandReflectance)
    {
        var cmf = new[] { "xbar", "ybar", "zbar" }.Select(c => Column("cie1931-2deg-cmf.csv", c)).ToArray();
        int width = 400 / bandReflectance.Length;
        return cmf.Select(t => Enumerable.Range(0, bandReflectance.Length).Sum(b =>
            bandReflectance[b] * Cie015.Sum(x => Lerp(t, x) * Lerp(light, x), 380 + b * width, 380 + (b + 1) * width))).ToArray();
    }

    [Theory]
    [InlineData("led-blue", "leds.csv", "blue_465nm")]
    [InlineData("D65", "illuminants.csv", "D65")]
    public void CieXyzSensor_NoiseOff_RawIsProportionalToExactXyz(string light, string file, string column)
    {
        var render = GreyChart(light, "380:780:20");
        var outDir = Path.Combine(render, "cam");
        var (code, _, err) =
            CliRunner.Run("camera", render, "--sensor", "cie-xyz", "--noise", "off", "-o", outDir, "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);
        var (shape, raw) = NpyReader.Read(File.OpenRead(Path.Combine(outDir, "raw.npy")));
        Assert.Equal([8, 24, 3], shape);
        var scene = CameraScene.Open(render);
        var spd = Column(file, column);
        double? ratio = null;
        foreach (var (name, r) in new[] { ("g2", 0.2), ("g5", 0.5), ("g9", 0.9) })
        {
            int id = scene.Folder.ObjectIndex(name);
            int pixel = Array.FindIndex(scene.Folder.ObjectIds, v => v == id);
            var exact = ExactXyz(spd, [r]);
            for (int c = 0; c < 3; c++)
            {
                double q = raw[pixel * 3 + c] / exact[c];
                ratio ??= q;
                Assert.InRange(q / ratio.Value, 1 - 1e-5, 1 + 1e-5);
            }
        }
    }

    [Fact]
    public void CieXyzSensor_NoiseOff_ColorChecker_IsProportionalToTheExactXyzOfTheCube()
    {
        // Rendered with products of band means (--integration weighted), a 20-band cube holds each patch as its band-mean
        // reflectance R_b times the light: L(λ) = R_b·E(λ) in band b. Its XYZ, Σ CMF·E·R_b at 1 nm, is computed here from the tables.
        var dir = Reference.TempDir();
        var render = Path.Combine(dir, "cc");
        var (code, _, err) = CliRunner.Run("render", Path.Combine(RepoScenes, "paper-3.1-colorchecker-d65.json"), "-o", render,
            "--width", "60", "--height", "40", "--quiet", "--formats", "npy,aov", "--integration", "weighted");
        Assert.True(code == 0, err);
        var outDir = Path.Combine(render, "cam");
        // The band route: the cube's band values as they are (the exact route integrates the patches' full spectra instead).
        (code, _, err) = CliRunner.Run("camera", render, "--sensor", "cie-xyz", "--noise", "off", "-o", outDir, "--signals", "bands",
            "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);
        var (_, raw) = NpyReader.Read(File.OpenRead(Path.Combine(outDir, "raw.npy")));
        var scene = CameraScene.Open(render);
        var d65 = Column("illuminants.csv", "D65");
        var header = File.ReadLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "colorchecker-ohta.csv")).First().Split(',');
        double? ratio = null;
        Assert.Equal(24, scene.Patches.Count);
        foreach (var p in scene.Patches)
        {
            var refl = Column("colorchecker-ohta.csv", header[p.Number]);
            var bandMean = Enumerable.Range(0, 20)
                .Select(b => Enumerable.Range(0, 2000).Average(k => Lerp(refl, 380 + 20 * b + (k + 0.5) * 0.01))).ToArray();
            var exact = ExactXyz(d65, bandMean);
            int pixel = p.Pixels[0];
            for (int c = 0; c < 3; c++)
            {
                double q = raw[pixel * 3 + c] / exact[c];
                ratio ??= q;
                Assert.True(Math.Abs(q / ratio.Value - 1) <= 1e-5,
                    $"patch {p.Number} channel {c}: relative error {q / ratio.Value - 1:E3}");
            }
        }
    }

    static string RepoScenes
    {
        get
        {
            for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
                if (File.Exists(Path.Combine(d.FullName, "scenes", "paper-3.1-colorchecker-d65.json")))
                    return Path.Combine(d.FullName, "scenes");
            throw new DirectoryNotFoundException("scenes/");
        }
    }

    [Fact]
    public void SameSeed_GivesIdenticalRaw_ForOneAndManyThreads()
    {
        var render = GreyChart("D65", "380:780:20");
        byte[] Raw(string threads, string seed, string sensor)
        {
            var o = Path.Combine(render, $"cam-{sensor}-{threads}-{seed}");
            var (code, _, err) = CliRunner.Run("camera", render, "--sensor", sensor, "--threads", threads, "--seed", seed, "-o", o);
            Assert.True(code == 0, err);
            return File.ReadAllBytes(Path.Combine(o, "raw.npy"));
        }
        foreach (var sensor in new[] { "nikon-d5100", "wheel-6" })
        {
            var one = Raw("1", "7", sensor);
            Assert.Equal(one, Raw("3", "7", sensor));
            Assert.NotEqual(one, Raw("1", "8", sensor));
        }
    }

    [SkippableTheory]
    [InlineData("nikon-d5100")]
    [InlineData("sigma-sd-merrill")]   // the Sigma's curves on the Bayer layout issue 12 names
    [InlineData("canon-5d-mark-ii")]
    public void Dng_OpensInDcraw_WithSizeCfaPatternAndLevels(string preset)
    {
        var dcraw = Tool.Find("dcraw");
        Skip.If(dcraw is null, "dcraw is not installed (Debian package dcraw); skipping this interop test");
        var render = GreyChart("D65", "380:780:20", 48, 24);   // dcraw refuses images under 22 pixels a side
        var sensorFile = Path.Combine(render, "bayer-black.json");
        File.WriteAllText(sensorFile, $$"""{ "preset": "{{preset}}", "black_level_dn": 64, "prnu_percent": 0.5 }""");
        var outDir = Path.Combine(render, "cam");
        var (code, _, err) = CliRunner.Run("camera", render, "--sensor", sensorFile, "-o", outDir);
        Assert.True(code == 0, err);
        var dng = Path.Combine(outDir, "raw.dng");

        var info = Tool.Run(dcraw!, ["-i", "-v", dng]);
        Assert.True(info.Exit == 0, info.Err);
        Assert.Contains("Image size:    48 x 24", info.Out);
        Assert.Contains("Filter pattern: RG/GB", info.Out);
        Assert.Contains("Raw colors: 3", info.Out);

        // Totally raw 16-bit PGM: every value equals raw.npy's digital number.
        var rawRun = Tool.Run(dcraw!, ["-D", "-4", "-v", dng]);
        Assert.True(rawRun.Exit == 0, rawRun.Err);
        var pgm = File.ReadAllBytes(Path.Combine(outDir, "raw.pgm"));
        var header = System.Text.Encoding.ASCII.GetString(pgm, 0, 20).Split((char[])['\n', ' '], StringSplitOptions.RemoveEmptyEntries);
        Assert.Equal(["P5", "48", "24", "65535"], header[..4]);
        var (_, raw) = NpyReader.Read(File.OpenRead(Path.Combine(outDir, "raw.npy")));
        int start = pgm.Length - raw.Length * 2;
        for (int i = 0; i < raw.Length; i++)
            Assert.Equal((int)raw[i], pgm[start + 2 * i] << 8 | pgm[start + 2 * i + 1]);

        // Levels: dcraw scales with the DNG's black and white level.
        var scaled = Tool.Run(dcraw!, ["-v", "-d", "-4", "-T", dng]);
        Assert.True(scaled.Exit == 0, scaled.Err);
        Assert.Contains("darkness 64, saturation 4095", scaled.Err);
        Assert.True(File.Exists(Path.Combine(outDir, "raw.tiff")));
    }

    [Fact]
    public void CameraJson_RecordsEveryParameterAndTheWeights()
    {
        var render = GreyChart("D65", "380:780:20");
        var outDir = Path.Combine(render, "cam");
        var (code, _, err) = CliRunner.Run("camera", render, "--sensor", "mosaic-16", "--exposure", "0.002", "-o", outDir);
        Assert.True(code == 0, err);
        var j = JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "camera.json")))!;
        var s = j["sensor"]!;
        Assert.Equal("mosaic", (string)s["arrangement"]!);
        Assert.Equal(16, s["channels"]!.AsArray().Count);
        Assert.Equal(20, s["channels"]![0]!["weights_e_per_s_per_band_unit"]!.AsArray().Count);
        Assert.Equal(10000, (double)s["full_well_e"]!, 6);
        Assert.Equal(0.002, (double)j["simulation"]!["exposure_s"]![0]!, 12);
        Assert.Contains("relative", (string)j["simulation"]!["radiance_scale_source"]!);
        Assert.False(File.Exists(Path.Combine(outDir, "raw.dng")));   // not a Bayer sensor
    }

    [Fact]
    public void BadSensor_IsOneLineWithAHint()
    {
        var render = GreyChart("D65", "380:780:20");
        var (code, _, err) = CliRunner.Run("camera", render, "--sensor", "nikon-d510");
        Assert.Equal(2, code);
        Assert.Contains("did you mean", err);
        var bad = Path.Combine(render, "bad.json");
        File.WriteAllText(bad, """{ "preset": "wheel-6", "fill_factor": 3 }""");
        (code, _, err) = CliRunner.Run("camera", render, "--sensor", bad);
        Assert.Equal(2, code);
        Assert.Contains("$.fill_factor", err);
        Assert.Single(err.Trim().Split('\n'));
    }

    const string MyWheel = """
        { "preset": "wheel-6", "name": "my-wheel", "f_number": 2.8, "read_noise_v": 2e-3,
          "channels": [ { "name": "F450", "gaussian": { "centre_nm": 450, "fwhm_nm": 30 } }, { "name": "F600", "box": [580, 620] } ] }
        """;

    [Fact]
    public void SensorInlineInTheScenesCamera_IsTheSameSensorAsTheFile_AndRecoverReadsItBack()
    {
        // The same sensor object as a file (--sensor FILE) and inline in the scene's camera (no --sensor): identical raw
        // files and the same channel weights in camera.json, and `spectral recover` re-resolves it from the render.
        var inline = GreyChart("D65", "380:780:20", cameraExtra: $", \"sensor\": {MyWheel}");
        var plain = GreyChart("D65", "380:780:20");
        var file = Path.Combine(plain, "my-wheel.json");
        File.WriteAllText(file, MyWheel);
        string Run(string render, params string[] extra)
        {
            var o = Path.Combine(render, "cam");
            var (code, _, err) = CliRunner.Run(["camera", render, "--seed", "3", "-o", o, .. extra]);
            Assert.True(code == 0, err);
            return o;
        }
        var a = Run(inline);
        var b = Run(plain, "--sensor", file);
        Assert.Equal(File.ReadAllBytes(Path.Combine(b, "raw.npy")), File.ReadAllBytes(Path.Combine(a, "raw.npy")));
        var ja = JsonNode.Parse(File.ReadAllText(Path.Combine(a, "camera.json")))!;
        var jb = JsonNode.Parse(File.ReadAllText(Path.Combine(b, "camera.json")))!;
        Assert.Equal("scene", (string)ja["sensor_argument"]!);
        Assert.Equal("my-wheel", (string)ja["sensor"]!["name"]!);
        Assert.Equal(2, ja["sensor"]!["channels"]!.AsArray().Count);
        Assert.Equal(jb["sensor"]!["channels"]!.ToJsonString(), ja["sensor"]!["channels"]!.ToJsonString());   // with the weights
        var (rc, csv, rerr) = CliRunner.Run("recover", a, "--method", "wiener", "--csv");
        Assert.True(rc == 0, rerr);
        Assert.Contains("wiener,", csv);

        // A preset name inline, and an inline error naming the scene file and the JSON path.
        var named = GreyChart("D65", "380:780:20", cameraExtra: ", \"sensor\": \"nikon-d5100\"");
        Assert.Equal("nikon-d5100", (string)JsonNode.Parse(File.ReadAllText(Path.Combine(Run(named), "camera.json")))!["sensor"]!["name"]!);
        var bad = GreyChart("D65", "380:780:20", cameraExtra: ", \"sensor\": { \"preset\": \"wheel-6\", \"fill_factor\": 3 }");
        var (code, _, err) = CliRunner.Run("camera", bad);
        Assert.Equal(2, code);
        Assert.Contains("greys.json: $.camera.sensor.fill_factor", err);
        Assert.Single(err.Trim().Split('\n'));
        // No sensor anywhere: --sensor is required.
        (code, _, err) = CliRunner.Run("camera", plain);
        Assert.Equal(2, code);
        Assert.Contains("--sensor is required", err);
    }
}
