using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// A `spectral camera` output folder read back: camera.json, raw.npy, the sensor re-resolved with the recorded
/// exposures (so the channel weights are the ones used), the processed signals, and the render it looked at.
/// </summary>
public sealed class CameraCapture
{
    public required string Dir { get; init; }
    public required JsonObject Manifest { get; init; }
    public required CameraScene Scene { get; init; }
    public required RawFrame Raw { get; init; }
    public required ProcessedImage Image { get; init; }
    public required ColourCorrection Colour { get; init; }

    public SensorModel Sensor => Raw.Sensor;

    public static CameraCapture Open(string dir)
    {
        var path = Path.Combine(dir, "camera.json");
        if (!File.Exists(path)) throw new InputException(dir, "has no camera.json", "give the -o folder of a 'spectral camera' run");
        JsonObject m;
        try { m = JsonNode.Parse(File.ReadAllText(path)) as JsonObject ?? throw new InputException(path, "is not a JSON object", "give the camera.json a 'spectral camera' run wrote"); }
        catch (JsonException e) { throw new InputException($"{path}:{(e.LineNumber ?? 0) + 1}", $"broken JSON: {e.Message}", "camera.json is damaged: run 'spectral camera' again"); }
        try
        {
            var renderDir = Path.GetFullPath(Path.Combine(dir, (string)m["render_folder"]!));
            var scene = CameraScene.Open(renderDir);
            var sim = m["simulation"]!;
            var exposures = sim["exposure_s"]!.AsArray().Select(v => (double)v!).ToArray();
            var argument = (string)m["sensor_argument"]!;
            var sensor = argument == SensorFile.SceneArgument
                ? SensorFile.FromScene(scene.Folder.Manifest.ResolvedScene?.ToJson(), scene.Folder.Manifest.Scene)
                  ?? throw new InputException(path, "names the scene's sensor but the render's scene has none", "run 'spectral camera' again")
                : SensorFile.Resolve(argument);
            // The lens as the capture had it (--off-axis, --psf override the sensor's).
            if ((string?)m["sensor"]?["optics"]?["off_axis"] is { } oa) sensor = sensor with { OffAxis = SensorFile.ParseOffAxis(oa, $"{path}: $.sensor.optics.off_axis") };
            if ((string?)m["sensor"]?["optics"]?["psf"] is { } psf) sensor = sensor with { Psf = SensorFile.ParsePsf(psf, $"{path}: $.sensor.optics.psf") };
            var options = new SimulationOptions { Seed = (ulong)sim["seed"]!, Noise = ((string)sim["noise"]!).StartsWith("on", StringComparison.Ordinal) };
            double scale = (double)sim["radiance_scale_w_m2_sr_nm_per_band_unit"]!;
            var weights = ChannelWeights.Compute(sensor, scene.Grid, scene.Light, scale);
            var npy = Path.Combine(dir, "raw.npy");
            if (!File.Exists(npy)) throw new InputException(dir, "has no raw.npy", "run 'spectral camera' again");
            using var f = File.OpenRead(npy);
            var (shape, dn) = NpyReader.Read(f, npy);
            int planes = shape.Length == 2 ? 1 : shape[2];
            if (shape[0] != scene.Height || shape[1] != scene.Width || planes != sensor.Planes)
                throw new InputException(npy, $"is {string.Join("×", shape)} but the render is {scene.Height}×{scene.Width} and the sensor has {sensor.Planes} planes",
                    "the camera folder and its render do not match; run 'spectral camera' again");
            var raw = new RawFrame(scene.Width, scene.Height, planes, dn, exposures, new double[exposures.Length], weights, sensor, options);
            // The route and the white the capture used (camera.json), so the white balance and forward model are its own.
            bool exact = ((string?)sim["signal_route"])?.StartsWith("exact", StringComparison.Ordinal) == true;
            double whiteScale = (double?)sim["white_radiance_scale"] ?? 1;
            var colour = ColourCorrection.Fit(weights, scene.Grid, scene.Light, scene.Observer, exact ? sensor : null, whiteScale);
            var demosaic = (string?)m["processing"]?["demosaic"] == "bilinear" ? DemosaicMethod.Bilinear : DemosaicMethod.Malvar;
            return new CameraCapture { Dir = dir, Manifest = m, Scene = scene, Raw = raw, Image = ImageProcessing.Run(raw, colour, demosaic), Colour = colour };
        }
        catch (Exception e) when (e is NullReferenceException or InvalidOperationException or FormatException)
        {
            throw new InputException(path, $"is missing a field 'spectral camera' writes ({e.Message})", "run 'spectral camera' again with this version");
        }
    }

    /// <summary>The camera run in memory on a render (nothing written): what `spectral camera` would write, read back.</summary>
    /// <param name="display">Whether the processed image gets its XYZ and sRGB too (recovery needs only the rates).</param>
    /// <param name="cube">The camera's input when not the band cube at <paramref name="radianceScale"/> (the exact route's integrals).</param>
    /// <param name="whiteScale">The render's white diffuser radiance per unit of the light's band values (<see cref="ColourCorrection.WhiteScale"/>).</param>
    public static CameraCapture Simulate(CameraScene scene, SensorModel sensor, SimulationOptions options, double radianceScale = 1, bool display = true,
        RadianceCube? cube = null, double whiteScale = 1)
    {
        cube ??= scene.Cube(radianceScale);
        var raw = SensorSimulation.Run(sensor, cube, scene.Light, options);
        var colour = ColourCorrection.Fit(raw.Weights, scene.Grid, scene.Light, scene.Observer, cube.ChannelIntegrals is null ? null : sensor, whiteScale);
        return new CameraCapture { Dir = scene.Folder.Path, Manifest = [], Scene = scene, Raw = raw, Image = ImageProcessing.Run(raw, colour, display: display), Colour = colour };
    }

    /// <summary>
    /// A (C × N): expected e⁻/s per unit reflectance in band b, for a surface lit like the white diffuser (its radiance is
    /// the light's band values × the render's white scale: intensity, and 1/π in physical radiometry). w_c,b·E_b =
    /// s·∫_b η_c·λ·E dλ/(hc), so A is also the exact route's forward model of a reflectance constant in each band.
    /// </summary>
    public double[,] ForwardMatrix()
    {
        var e = Spectra.BandProjection.Means(Scene.Light, Scene.Grid);
        for (int b = 0; b < e.Length; b++) e[b] *= Colour.WhiteScale;
        int c = Sensor.ChannelCount, n = e.Length;
        var a = new double[c, n];
        for (int i = 0; i < c; i++) for (int b = 0; b < n; b++) a[i, b] = Raw.Weights[i, b] * e[b];
        return a;
    }

    /// <summary>
    /// Per channel, the temporal noise variance of ė = (DN − black)/(K t) at the mean signal ė̄ of the surface pixels:
    /// [K²(ė̄t + (p ė̄ t)² + dark·t + σ_read²) + 1/12] / (K t)² — shot, PRNU, dark, read and quantisation. With noise
    /// off only the quantisation step's 1/12 DN² remains: the resolution a real raw file has, and the floor that keeps the
    /// estimators from amplifying model errors (demosaicking, highlights) without bound.
    /// </summary>
    public double[] NoiseVariance()
    {
        int c = Sensor.ChannelCount;
        var v = new double[c];
        double kq = Sensor.SystemGain;
        if (!Raw.Options.Noise)
        {
            for (int k = 0; k < c; k++) { double t = Raw.ExposureOf(k); v[k] = 1.0 / 12 / (kq * t * kq * t); }
            return v;
        }
        var mean = new double[c];
        int count = 0;
        for (int i = 0; i < Scene.Width * Scene.Height; i++)
        {
            if (Scene.Folder.ObjectIds[i] < 0) continue;
            for (int k = 0; k < c; k++) mean[k] += Image.Rates[i * c + k];
            count++;
        }
        double kk = Sensor.SystemGain, p = Sensor.PrnuPercent / 100;
        for (int k = 0; k < c; k++)
        {
            double t = Raw.ExposureOf(k), e = Math.Max(0, count > 0 ? mean[k] / count : 0) * t;
            double dn2 = kk * kk * (e + p * p * e * e + Sensor.DarkCurrentElectronsPerSecond * t + Sensor.ReadNoiseElectrons * Sensor.ReadNoiseElectrons) + 1.0 / 12;
            v[k] = dn2 / (kk * t * kk * t);
        }
        return v;
    }
}
