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

    /// <summary>Whether the capture's signals came by the exact route (camera.json's signal_route; the colour fit follows it).</summary>
    public bool ExactSignals => Colour.ExactSignals;

    public static CameraCapture Open(string dir)
    {
        var path = Path.Combine(dir, "camera.json");
        if (!File.Exists(path)) throw new InputException(dir, "has no camera.json", "give the -o folder of a 'spectral camera' run");
        var m = JsonFields.ParseFile(path, "camera.json", RunAgain);
        var record = Read(m, path);
        var r = new JsonFields(path, RunAgain);
        var renderDir = Path.GetFullPath(Path.Combine(dir, record.RenderFolder));
        if (!Directory.Exists(renderDir))
            throw r.Bad("$.render_folder",
                $"names {MessageText.Quote(record.RenderFolder, 60)}, which is not a folder (the render was moved or removed)");
        var scene = CameraScene.Open(renderDir);
        var sensor = record.SensorArgument == SensorFile.SceneArgument
            ? SensorFile.FromScene(scene.Folder.Manifest.ResolvedScene?.ToJson(), scene.Folder.Manifest.Scene)
              ?? throw r.Bad("$.sensor_argument", "names the scene's sensor but the render's scene has none")
            : SensorFile.Resolve(record.SensorArgument);
        // The lens as the capture had it (--off-axis, --psf override the sensor's).
        if (r.OptObject(m, "sensor", "$") is { } sensorNode && r.OptObject(sensorNode, "optics", "$.sensor") is { } optics)
        {
            if (r.OptString(optics, "off_axis", "$.sensor.optics") is { } oa)
                sensor = sensor with { OffAxis = SensorFile.ParseOffAxis(oa, $"{path}: $.sensor.optics.off_axis") };
            if (r.OptString(optics, "psf", "$.sensor.optics") is { } psf)
                sensor = sensor with { Psf = SensorFile.ParsePsf(psf, $"{path}: $.sensor.optics.psf") };
        }
        var exposures = record.Exposures;
        if (exposures.Length != sensor.Exposures)
            throw r.Bad("$.simulation.exposure_s",
                $"has {exposures.Length} exposures, the sensor {MessageText.Quote(sensor.Name)} takes {sensor.Exposures}");
        var options = new SimulationOptions { Seed = record.Seed, Noise = record.Noise };
        var weights = ChannelWeights.Compute(sensor, scene.Grid, scene.Light, record.RadianceScale);
        var npy = Path.Combine(dir, "raw.npy");
        if (!File.Exists(npy)) throw new InputException(dir, "has no raw.npy", "run 'spectral camera' again");
        int[] shape; float[] dn;
        using (var f = File.OpenRead(npy)) (shape, dn) = NpyReader.Read(f, npy);
        int planes = shape.Length == 2 ? 1 : shape.Length == 3 ? shape[2] : -1;
        if (shape.Length is < 2 or > 3 || shape[0] != scene.Height || shape[1] != scene.Width || planes != sensor.Planes)
            throw new InputException(npy,
                $"is {string.Join("×", shape)} but the render is {scene.Height}×{scene.Width} and the sensor has {sensor.Planes} planes",
                "the camera folder and its render do not match; run 'spectral camera' again");
        var raw = new RawFrame(scene.Width, scene.Height, planes, dn, exposures, new double[exposures.Length], weights, sensor, options);
        // The route and the white the capture used (camera.json), so the white balance and forward model are its own.
        var colour =
            ColourCorrection.Fit(weights, scene.Grid, scene.Light, scene.Observer, record.Exact ? sensor : null, record.WhiteScale);
        return new CameraCapture
        {
            Dir = dir,
            Manifest = m,
            Scene = scene,
            Raw = raw,
            Image = ImageProcessing.Run(raw, colour, record.Demosaic),
            Colour = colour
        };
    }

    const string RunAgain = "camera.json is not as 'spectral camera' writes it: run 'spectral camera' again with this version";

    /// <summary>What camera.json records of a capture, as <see cref="Open"/> uses it.</summary>
    public sealed record CameraRecord(string RenderFolder, string SensorArgument, double[] Exposures, ulong Seed, bool Noise,
        double RadianceScale, bool Exact, double WhiteScale, DemosaicMethod Demosaic);

    /// <summary>
    /// camera.json's fields, checked (<see cref="JsonFields"/>): the render folder and sensor as strings, the exposures and
    /// radiance scales finite and positive, the seed a whole number ≥ 0; <paramref name="path"/> names the file in errors.
    /// </summary>
    public static CameraRecord Read(JsonObject m, string path)
    {
        var r = new JsonFields(path, RunAgain);
        var sim = r.Object(m, "simulation", "$");
        const string at = "$.simulation";
        var exposures = r.Numbers(sim, "exposure_s", at, null, 0);
        for (int i = 0; i < exposures.Length; i++)
            if (!(exposures[i] > 0)) throw r.Bad($"{at}.exposure_s[{i}]", "is 0, not a positive exposure");
        var seedNode = sim["seed"];
        ulong seed = seedNode is JsonValue sv && sv.GetValueKind() == JsonValueKind.Number && sv.TryGetValue(out ulong sd) ? sd
            : throw r.Bad($"{at}.seed", $"is {JsonFields.Kind(seedNode)}, expected a whole number ≥ 0");
        double Positive(string key, double? fallback)
        {
            double v = (fallback is null ? r.Number(sim, key, at, 0) : r.OptNumber(sim, key, at, 0)) ?? fallback!.Value;
            return v > 0 ? v : throw r.Bad($"{at}.{key}", "is 0, not a positive scale");
        }
        var processing = r.OptObject(m, "processing", "$");
        return new CameraRecord(r.String(m, "render_folder", "$"), r.String(m, "sensor_argument", "$"), exposures, seed,
            r.String(sim, "noise", at).StartsWith("on", StringComparison.Ordinal),
                Positive("radiance_scale_w_m2_sr_nm_per_band_unit", null),
            r.OptString(sim, "signal_route", at)?.StartsWith("exact", StringComparison.Ordinal) == true,
                Positive("white_radiance_scale", 1),
            processing is not null && r.OptString(processing, "demosaic", "$.processing") == "bilinear"
                ? DemosaicMethod.Bilinear
                : DemosaicMethod.Malvar);
    }

    /// <summary>The camera run in memory on a render (nothing written): what `spectral camera` would write, read back.</summary>
    /// <param name="display">Whether the processed image gets its XYZ and sRGB too (recovery needs only the rates).</param>
    /// <param name="cube">The camera's input when not the band cube at <paramref name="radianceScale"/> (the exact route's
    /// integrals).</param>
    /// <param name="whiteScale">The render's white diffuser radiance per unit of the light's band values
    /// (<see cref="ColourCorrection.WhiteScale"/>).</param>
    public static CameraCapture Simulate(CameraScene scene, SensorModel sensor, SimulationOptions options, double radianceScale = 1,
        bool display = true,
        RadianceCube? cube = null, double whiteScale = 1)
    {
        cube ??= scene.Cube(radianceScale);
        var raw = SensorSimulation.Run(sensor, cube, scene.Light, options);
        var colour = ColourCorrection.Fit(raw.Weights, scene.Grid, scene.Light, scene.Observer,
            cube.ChannelIntegrals is null ? null : sensor, whiteScale);
        return new CameraCapture
        {
            Dir = scene.Folder.Path,
            Manifest = [],
            Scene = scene,
            Raw = raw,
            Image = ImageProcessing.Run(raw, colour, display: display),
            Colour = colour
        };
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
    /// The recovery's forward model for this capture's signal route (<see cref="Recovery.ForwardModel"/>): on the band route
    /// <see cref="ForwardMatrix"/> on the band means, on the exact route the same white at the training spectra's full
    /// resolution, so the estimators see what the exact route made of the training spectra.
    /// </summary>
    public ForwardModel ForwardModel(TrainingSet training)
    {
        // Kept for the training set last asked (recover builds one estimator per method from it).
        if (model is { } m && ReferenceEquals(m.Training, training)) return m.Model;
        var f = ExactSignals
            ? Recovery.ForwardModel.Exact(Sensor, Raw.Weights.Factor, Colour.WhiteScale, Scene.Light, Scene.Grid, training)
            : Recovery.ForwardModel.Bands(ForwardMatrix(), training);
        model = new ModelFor(training, f);
        return f;
    }

    sealed record ModelFor(TrainingSet Training, ForwardModel Model);
    ModelFor? model;

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
            double dn2 = kk * kk * (e + p * p * e * e + Sensor.DarkCurrentElectronsPerSecond * t
                + Sensor.ReadNoiseElectrons * Sensor.ReadNoiseElectrons)
                + 1.0 / 12;
            v[k] = dn2 / (kk * t * kk * t);
        }
        return v;
    }
}
