using System.Diagnostics;
using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Relighting;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral camera OUTDIR [--sensor NAME|FILE|scene]`: the render seen by a simulated camera (ISETCam's sensor model).</summary>
public static class CameraCommand
{
    const string Help = """
        usage: spectral camera OUTDIR [--sensor NAME|FILE|scene] [--exposure auto|SECONDS] [--seed N] [--noise on|off]
                                      [--radiance-scale S] [--demosaic malvar|bilinear] [--signals exact|bands]
                                      [--off-axis cos4th|none] [--psf diffraction|none] [--threads N]
                                      [-o DIR] [--bench N]

        OUTDIR is the folder a 'spectral render' wrote; --sensor defaults to the scene camera's "sensor" (scene).

        Simulates a camera looking at a render (docs/camera.md): optics (thin lens with cos⁴ fall-off and the
        diffraction-limited Airy blur at the f-number, ISETCam's default optics), pixel, channel quantum
        efficiencies, exposure, photon shot noise, dark current, read noise, PRNU/DSNU, full well, gain, ADC.
        The scene light (render.json's reference white) prefilters the channel weights per band.

          --sensor NAME|FILE   isetcam, nikon-d5100, sigma-sd-merrill (Bayer), sigma-sd-merrill-x3 (Foveon),
                               canon-5d-mark-ii, wheel-6, mosaic-16, cie-xyz, a sensor JSON file, or scene
                               (the default: the "sensor" of the scene's camera object)
          --exposure           auto (default: brightest expected pixel at 0.8 of the full well) or seconds
          --seed N             temporal noise seed (default 1); the same seed gives the same raw file
          --noise off          the expected signal: no noise, no dark current, no quantisation
          --radiance-scale S   W·m⁻²·sr⁻¹·nm⁻¹ per band unit of the render (default 1; the paper's radiometry
                               has no unit, so this states one)
          --demosaic           malvar (Malvar–He–Cutler, Bayer; default) or bilinear (any mosaic)
          --signals            exact (default: each eq. 2 term's ∫ η·λ/(hc)·E·m dλ at full spectral resolution,
                               from the render's lights/ or its transfer traced again) or bands (the band cube)
          --off-axis           cos4th (default: irradiance × cos⁴ of the pixel's field angle, from the render camera's
                               field of view) or none; overrides the sensor's "off_axis"
          --psf                diffraction (default: the Airy pattern of the f-number per band) or none; overrides "psf"
          -o DIR               output folder (default OUTDIR/camera-<sensor>)
          --bench N            time the sensor simulation N times and print the figures (nothing written)

        Writes raw.npy (H×W, or H×W×C for full and wheel sensors, float32 digital numbers), raw.png (16-bit;
        raw-<channel>.png per plane for full and wheel), raw.dng (Bayer sensors: CFA, black/white levels,
        colour matrix), processed.png (demosaicked, white-balanced, colour-corrected sRGB), patches.csv (per
        ColorChecker patch: ΔE00 of the corrected colour against the exact colour, SNR per channel) and
        camera.json (every parameter, per-band channel weights, exposures, the colour matrix).
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("camera", argv,
            ["--sensor", "--exposure", "--seed", "--noise", "--radiance-scale", "--demosaic", "--signals", "--off-axis", "--psf",
                "--threads", "-o", "--bench"],
                [],
            new Dictionary<string, string> { ["--output"] = "-o" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one render folder", "usage: spectral camera OUTDIR --sensor nikon-d5100");
        var dir = a.Positionals[0];
        var scene = CameraScene.Open(dir);
        // --sensor, else the sensor written in the scene's camera object (render.json keeps the resolved scene).
        var sensorName = a.Value("--sensor") ?? SensorFile.SceneArgument;
        var sensor = sensorName == SensorFile.SceneArgument
            ? SensorFile.FromScene(scene.Folder.Manifest.ResolvedScene?.ToJson(), scene.Folder.Manifest.Scene)
              ?? throw new InputException("command line", "--sensor is required: the scene's camera has no \"sensor\"",
                  $"one of {string.Join(", ", SensorPresets.Names)}, a JSON file, or \"sensor\" in the scene's camera object")
            : SensorFile.Resolve(sensorName);
        if (a.Value("--exposure") is { } ex)
        {
            if (ex == "auto") sensor = sensor with { ExposureSeconds = null };
            else
                sensor = sensor with
                {
                    ExposureSeconds = a.Double("--exposure", 1e-10, 1e5, "seconds") is { } t
                    ? t
                    : throw new InputException("command line", $"--exposure '{ex}' must be auto or positive seconds",
                        "e.g. --exposure auto or --exposure 0.01 (seconds)")
                };
        }
        if (a.Value("--off-axis") is { } oa) sensor = sensor with { OffAxis = SensorFile.ParseOffAxis(oa, "--off-axis") };
        if (a.Value("--psf") is { } psf) sensor = sensor with { Psf = SensorFile.ParsePsf(psf, "--psf") };
        bool noise = a.Value("--noise") switch
        {
            null or "on" => true,
            "off" => false,
            var v => throw new InputException("command line", $"--noise '{v}' is not on or off", "use --noise on or --noise off"),
        };
        var demosaic = a.Value("--demosaic") switch
        {
            null or "malvar" => DemosaicMethod.Malvar,
            "bilinear" => DemosaicMethod.Bilinear,
            var v => throw new InputException("command line", $"--demosaic '{v}' is not malvar or bilinear",
                "use --demosaic malvar or --demosaic bilinear"),
        };
        ulong seed = a.Value("--seed") is { } sv
            ? ulong.TryParse(sv, NumberStyles.None, CultureInfo.InvariantCulture, out var s)
            ? s
            : throw new InputException("command line", $"--seed '{sv}' is not a whole number ≥ 0", "give a whole number, e.g. --seed 1")
            : 1;
        double scale = a.Double("--radiance-scale", 1e-20, 1e20, "W·m⁻²·sr⁻¹·nm⁻¹ per band unit") ?? 1;
        if (!(scale > 0)) throw new InputException("command line", "--radiance-scale must be positive", "W·m⁻²·sr⁻¹·nm⁻¹ per band unit");
        int threads = a.Int("--threads", 1, 1024) ?? -1;

        bool wantExact = a.Value("--signals") switch
        {
            null or "exact" => true,
            "bands" => false,
            var v => throw new InputException("command line", $"--signals '{v}' is not exact or bands",
                "use --signals exact (default) or --signals bands"),
        };

        var options = new SimulationOptions { Seed = seed, Noise = noise, Threads = threads };
        var cube = scene.Cube(scale);
        double whiteScale = 1;
        string whiteSource = CameraRun.PaperWhite;
        string? routeNote = null;
        if (wantExact)
        {
            if (ExactChannelSignals.Compute(scene, sensor, threads, out var why) is { } exact)
            {
                cube = cube with { ChannelIntegrals = exact.Integrals, Route = exact.Route, OpticsApplied = exact.OpticsApplied };
                whiteScale = exact.WhiteScale;
                whiteSource = exact.WhiteScaleSource;
            }
            else routeNote = $"note: channel signals from the band cube (not exact): {why}";
        }
        if (cube.ChannelIntegrals is null && ExactChannelSignals.BandRouteWhite(scene, threads) is { } white)
        {   // The band route sees the render's radiometry too: its white as the exact route would take it (1 for a cube from elsewhere).
            whiteScale = white.Scale;
            whiteSource = white.Source;
        }

        if (a.Int("--bench", 1, 1000) is int repeat)
        {
            SensorSimulation.Run(sensor, cube, scene.Light, options);   // warm-up (JIT)
            var times = new List<double>();
            var cpu = new List<double>();
            var process = Process.GetCurrentProcess();
            for (int i = 0; i < repeat; i++)
            {
                process.Refresh();
                var cpu0 = process.TotalProcessorTime;
                var sw = Stopwatch.StartNew();
                SensorSimulation.Run(sensor, cube, scene.Light, options);
                times.Add(sw.Elapsed.TotalSeconds);
                process.Refresh();
                cpu.Add((process.TotalProcessorTime - cpu0).TotalSeconds);
            }
            times.Sort();
            cpu.Sort();
            // CPU seconds (all threads of the process) tell the work apart from waiting for a core another program holds.
            stdout.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"camera {sensor.Name}: {cube.Width}×{cube.Height}×{cube.Bands} bands, noise {(noise ? "on" : "off")}, "
                    + $"{Environment.ProcessorCount} CPUs; sensor simulation min {times[0]:F3} s, median {times[times.Count / 2]:F3} s "
                    + $"over {repeat} runs (CPU time median {cpu[cpu.Count / 2]:F3} s)"));
            return CommandLine.Success;
        }

        var outDir = a.Value("-o") ?? Path.Combine(dir, $"camera-{sensor.Name}");
        if (OutputFolder.SameFolder(dir, outDir))
            throw new InputException("-o", $"{outDir} is the render folder itself",
                "write the camera's files to a folder of their own (default OUTDIR/camera-<sensor>)");
        var (raw, colour, image, patches, manifest) = CameraRun.Run(scene, sensor, cube, options, demosaic, whiteScale, whiteSource,
            a.Value("--radiance-scale") is not null ? "--radiance-scale" : null,
            sensorName != SensorFile.SceneArgument && File.Exists(sensorName) ? Path.GetFullPath(sensorName) : sensorName,
            Path.GetRelativePath(Path.GetFullPath(outDir), Path.GetFullPath(dir)));
        // One folder transaction (OutputFolder): the files are staged, swapped in whole with camera.json last, and
        // replace only what the previous camera.json lists; a signal, error or refusal leaves the folder as it was.
        using var folder = OutputFolder.Begin(outDir, "camera.json", "camera run");
        var final = outDir;
        outDir = folder.Staging;
        var written = new List<string>();
        void Done(string f) { written.Add(f); Signals.Token.ThrowIfCancellationRequested(); }

        int[] shape = raw.Planes == 1 ? [raw.Height, raw.Width] : [raw.Height, raw.Width, raw.Planes];
        AtomicFile.Write(Path.Combine(outDir, "raw.npy"), st => NpyWriter.Write(st, shape, raw.Dn)); Done("raw.npy");
        if (raw.Planes == 1)
        {
            PngWriter.WriteGray16(Path.Combine(outDir, "raw.png"), raw.Width, raw.Height, Plane(raw, 0));
            Done("raw.png");
        }
        else
            for (int c = 0; c < raw.Planes; c++)
            {
                var name = $"raw-{sensor.Channels[c].Name}.png";
                PngWriter.WriteGray16(Path.Combine(outDir, name), raw.Width, raw.Height, Plane(raw, c)); Done(name);
            }
        if (sensor.IsBayer)
        {
            var (matrix, neutral) = DngColour(colour);
            DngWriter.Write(Path.Combine(outDir, "raw.dng"), raw, matrix, neutral, DngWriter.IlluminantCode(scene.LightName),
                $"SpectralRenderer {CommandLine.Version}");
            Done("raw.dng");
        }
        PngWriter.WriteRgb8(Path.Combine(outDir, "processed.png"), raw.Width, raw.Height, image.Srgb8); Done("processed.png");
        AtomicFile.WriteAllText(Path.Combine(outDir, "patches.csv"), PatchesCsv(sensor, patches)); Done("patches.csv");

        manifest["files"] = new JsonArray(written.Append("camera.json").Select(f => (JsonNode)f).ToArray());
        AtomicFile.WriteAllText(Path.Combine(outDir, "camera.json"),
            manifest.ToJsonString(new JsonSerializerOptions { WriteIndented = true }) + "\n");
        folder.Commit([.. written, "camera.json"], Signals.Token);
        outDir = final;

        var inv = CultureInfo.InvariantCulture;
        if (routeNote is not null) stderr.WriteLine(routeNote);
        if (raw.ClippingWarning() is { } warning) stderr.WriteLine(warning);
        stdout.WriteLine(string.Create(inv,
            $"camera {sensor.Name} ({sensor.Arrangement.ToString().ToLowerInvariant()}, {sensor.ChannelCount} channels) on {dir}: exposure "
                + $"{string.Join(", ", raw.ExposureSeconds.Select(t => t.ToString("G4", inv)))} s, noise {(noise ? "on" : "off")}, K "
                + $"= {sensor.SystemGain:G4} DN/e⁻"));
        if (patches.Count > 0)
        {
            stdout.WriteLine($"{"patch",5} {"object",-12} {"ΔE00",7}  SNR dB per channel (20 log10 mean/σ of DN − black; "
                + "— no signal above black)");
            foreach (var p in patches)
                stdout.WriteLine(string.Create(inv,
                    $"{p.Patch,5} {p.Object,-12} {p.DeltaE00,7:F3}  {string.Join(" ", p.SnrDb.Select(SnrText))}"));
            stdout.WriteLine(string.Create(inv,
                $"mean ΔE00 {patches.Average(p => p.DeltaE00):F3}, max {patches.Max(p => p.DeltaE00):F3} (corrected colour vs 1 nm "
                    + $"CIE XYZ under {scene.LightName})"));
        }
        stdout.WriteLine($"wrote {string.Join(", ", written)}, camera.json in {outDir}");
        return CommandLine.Success;
    }

    /// <summary>A patch's SNR in dB on the console: "—" without signal above black (−∞ dB), "n/a" with under two unclipped sites.</summary>
    static string SnrText(double db) =>
        double.IsFinite(db) ? db.ToString("F1", CultureInfo.InvariantCulture)
            : double.IsNaN(db) ? "n/a" : db > 0 ? "inf" : "—";

    static ushort[] Plane(RawFrame raw, int plane)
    {
        var v = new ushort[raw.Width * raw.Height];
        for (int i = 0; i < v.Length; i++) v[i] = (ushort)Math.Clamp(Math.Round(raw.Dn[i * raw.Planes + plane]), 0, 65535);
        return v;
    }

    /// <summary>ColorMatrix1 = (M·diag(1/ė_white))⁻¹, XYZ → camera, scaled so the white's largest camera value is 1; AsShotNeutral =
    /// ė_white / max.</summary>
    static (double[,] Matrix, double[] Neutral) DngColour(ColourCorrection colour)
    {
        var m = (double[,])colour.Matrix.Clone();
        for (int c = 0; c < 3; c++) for (int i = 0; i < 3; i++) m[i, c] /= colour.WhiteRate[c];
        var inv = Dense.Inverse(m);
        var w = Dense.Multiply(inv, [colour.White.X, colour.White.Y, colour.White.Z]);
        double max = w.Max();
        for (int i = 0; i < 3; i++) for (int j = 0; j < 3; j++) inv[i, j] /= max;
        double wmax = colour.WhiteRate.Max();
        return (inv, colour.WhiteRate.Select(v => v / wmax).ToArray());
    }

    static string PatchesCsv(SensorModel sensor, List<PatchMetrics> patches)
    {
        var inv = CultureInfo.InvariantCulture;
        var sb = new StringBuilder("patch,object,pixels,camera_X,camera_Y,camera_Z,exact_X,exact_Y,exact_Z,dE00");
        foreach (var c in sensor.Channels) sb.Append(",snr_db_").Append(c.Name);
        sb.Append('\n');
        foreach (var p in patches)
        {
            sb.Append(inv,
                $"{p.Patch},{p.Object},{p.Pixels},{p.Camera.X:R},{p.Camera.Y:R},{p.Camera.Z:R},{p.Exact.X:R},"
                    + $"{p.Exact.Y:R},{p.Exact.Z:R},{p.DeltaE00:R}");
            foreach (var v in p.SnrDb)
                sb.Append(',').Append(double.IsFinite(v) ? v.ToString("R", inv) : double.IsNaN(v) ? "" : v > 0 ? "inf" : "-inf");
            sb.Append('\n');
        }
        return sb.ToString();
    }
}
