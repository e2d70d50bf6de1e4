using System.Globalization;
using System.Runtime.InteropServices;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;
using SpectralRenderer.Relighting;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Native;

/// <summary>
/// libspectral's camera and recovery (ABI 1.1): `spectral camera` and `spectral recover` on a render held in memory, the
/// same engine calls in the same order as the commands (CameraCommand, CameraCapture.Open, RecoverCommand), nothing written.
/// A capture or a recovery is a handle as a render is (spectral_status, spectral_message, spectral_free); its arrays belong
/// to it until spectral_free.
/// </summary>
public static unsafe partial class NativeExports
{
    /// <summary>
    /// The camera stage on the render held by <paramref name="h"/> (its cube, ids, colours and per-light transfer), as
    /// `spectral camera FOLDER` runs it on the folder the render would write. <paramref name="options"/>: a JSON object,
    /// each key optional — sensor (a preset's name, a sensor file, "scene"), exposure ("auto" or seconds), seed, noise
    /// ("on"/"off"), radiance_scale, demosaic ("malvar"/"bilinear"), signals ("exact"/"bands"), off_axis ("cos4th"/"none"),
    /// psf ("diffraction"/"none") (ABI 1.2), threads.
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_camera")]
    public static nint Camera(nint h, byte* options)
    {
        var handle = new NativeRender();
        try
        {
            var source = Get(h) is { Job.Result: not null } r ? r
                : throw new InputException("spectral_camera", "the handle holds no render", "give the camera a successful render");
            handle.SetCapture(NativeCapture.Run(source, Utf8(options)));
        }
        catch (Exception e)
        {
            handle.Fail(e, "spectral camera: ");
        }
        return GCHandle.ToIntPtr(GCHandle.Alloc(handle));
    }

    /// <summary>Height, width, raw planes and channels of a capture (zeros for another handle).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_capture_shape")]
    public static void CaptureShape(nint h, int* height, int* width, int* planes, int* channels)
    {
        var c = Get(h)?.Capture;
        *height = c?.Raw.Height ?? 0; *width = c?.Raw.Width ?? 0;
        *planes = c?.Raw.Planes ?? 0; *channels = c?.Raw.Sensor.ChannelCount ?? 0;
    }

    /// <summary>The raw digital numbers, H × W (× planes) float32: raw.npy's values.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_capture_raw")]
    public static float* CaptureRaw(nint h) => (float*)CaptureGuard(h, c => c.Pin(c.Raw.Dn));

    /// <summary>The processed image's 8-bit sRGB, H × W × 3 bytes: processed.png's pixels.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_capture_rgb8")]
    public static byte* CaptureRgb8(nint h) => (byte*)CaptureGuard(h, c => c.Pin(c.Image.Srgb8));

    /// <summary>The demosaicked channel signals ė in e⁻/s, H × W × channels float32 (what recovery reads).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_capture_rates")]
    public static float* CaptureRates(nint h) => (float*)CaptureGuard(h, c => c.Pin(c.Image.Rates));

    /// <summary>camera.json's content for the capture (its "files" absent: nothing is written), UTF-8 JSON.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_capture_manifest")]
    public static byte* CaptureManifest(nint h) => (byte*)CaptureGuard(h, c => (nint)c.ManifestUtf8);

    /// <summary>
    /// Recovery of reflectance from the capture held by <paramref name="h"/>, as `spectral recover CAMERADIR` on the folder
    /// the capture would write. <paramref name="options"/>: a JSON object, each key optional — method (a name or a comma
    /// list, "all" the default), training, white_object, white_region ([x0, y0, x1, y1], x1 and y1 exclusive), range ([lo, hi] nm).
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_recover")]
    public static nint Recover(nint h, byte* options)
    {
        var handle = new NativeRender();
        try
        {
            var capture = Get(h)?.Capture
                ?? throw new InputException("spectral_recover", "the handle holds no capture",
                    "recover from what spectral_camera returned");
            handle.SetRecovery(NativeRecovery.Run(capture, Utf8(options)));
        }
        catch (Exception e)
        {
            handle.Fail(e, "spectral recover: ");
        }
        return GCHandle.ToIntPtr(GCHandle.Alloc(handle));
    }

    /// <summary>The number of methods a recovery holds (0 for another handle).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_recovery_count")]
    public static int RecoveryCount(nint h) => Get(h)?.Recovery?.Results.Count ?? 0;

    /// <summary>Method <paramref name="i"/>'s reflectance, H × W × N float32: recovered-&lt;method&gt;.npy's values.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_recovery_reflectance")]
    public static float* RecoveryReflectance(nint h, int i) =>
        (float*)RecoveryGuard(h, r => i >= 0 && i < r.Results.Count ? r.Pin(r.Results[i].Reflectance) : 0);

    /// <summary>
    /// The recovery as JSON: {"methods": [names in order], "shape": [H, W, N], "wavelengths": [...], "metrics_csv":
    /// recovery-metrics.csv's text, …}.
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_recovery_manifest")]
    public static byte* RecoveryManifest(nint h) => (byte*)RecoveryGuard(h, r => (nint)r.ManifestUtf8);

    static nint CaptureGuard(nint h, Func<NativeCapture, nint> value)
    {
        try { return Get(h)?.Capture is { } c ? value(c) : 0; }
        catch (Exception) { return 0; }
    }

    static nint RecoveryGuard(nint h, Func<NativeRecovery, nint> value)
    {
        try { return Get(h)?.Recovery is { } r ? value(r) : 0; }
        catch (Exception) { return 0; }
    }

    /// <summary>Options and changes objects: a key given twice is refused as bad JSON (a JSON object with one throws when read).</summary>
    internal static readonly JsonDocumentOptions StrictJson = new() { AllowDuplicateProperties = false };

    /// <summary>A JSON options object, its keys checked against <paramref name="known"/>.</summary>
    internal static JsonObject OptionsObject(string? json, string what, params string[] known)
    {
        JsonObject o;
        try
        {
            o = json is null
                ? []
                : JsonNode.Parse(json, documentOptions: StrictJson) as JsonObject ?? throw new JsonException("not an object");
        }
        catch (JsonException e)
        {
            throw new InputException(what, $"not a JSON object: {e.Message}", $"known keys: {string.Join(", ", known)}");
        }
        foreach (var (key, _) in o)
            if (Array.IndexOf(known, key) < 0)
                throw new InputException($"{what}.{key}", "unknown option",
                    InputException.DidYouMean(key, known) ?? $"known: {string.Join(", ", known)}");
        return o;
    }

    internal static string? Text(JsonObject o, string key) => o[key] switch
    {
        null => null,
        JsonValue v when v.TryGetValue(out string? s) => s,
        var n => n.ToJsonString(),
    };
}

/// <summary>Pinned arrays and UTF-8 strings handed out by a capture or a recovery, freed with it.</summary>
abstract unsafe class PinnedHolder : IDisposable
{
    readonly List<GCHandle> _pins = [];
    readonly Dictionary<object, nint> _pinned = new(ReferenceEqualityComparer.Instance);
    readonly Lock _lock = new();
    byte* _manifest;

    public nint Pin(Array a)
    {
        lock (_lock)
        {
            if (_pinned.TryGetValue(a, out var p)) return p;
            var g = GCHandle.Alloc(a, GCHandleType.Pinned);
            _pins.Add(g);
            return _pinned[a] = g.AddrOfPinnedObject();
        }
    }

    protected abstract string ManifestText();

    public byte* ManifestUtf8
    {
        get
        {
            lock (_lock)
            {
                if (_manifest is not null) return _manifest;
                var bytes = Encoding.UTF8.GetBytes(ManifestText());
                var p = (byte*)NativeMemory.Alloc((nuint)bytes.Length + 1);
                bytes.CopyTo(new Span<byte>(p, bytes.Length));
                p[bytes.Length] = 0;
                return _manifest = p;
            }
        }
    }

    public void Dispose()
    {
        foreach (var g in _pins) g.Free();
        _pins.Clear();
        _pinned.Clear();
        if (_manifest is not null) NativeMemory.Free(_manifest);
        _manifest = null;
    }
}

/// <summary>A camera capture of a render in memory: what `spectral camera` computes (raw, processed image, camera.json).</summary>
sealed class NativeCapture : PinnedHolder
{
    public required CameraScene Scene { get; init; }
    public required RawFrame Raw { get; init; }
    public required ProcessedImage Image { get; init; }
    public required ColourCorrection Colour { get; init; }
    public required JsonObject Manifest { get; init; }
    public required string SensorArgument { get; init; }
    public required double RadianceScale { get; init; }
    public required DemosaicMethod Demosaic { get; init; }
    public required double WhiteScale { get; init; }

    protected override string ManifestText() => Manifest.ToJsonString(new JsonSerializerOptions { WriteIndented = true }) + "\n";

    /// <summary>CameraCommand.Run's options and its <see cref="CameraRun"/>, the render in memory for its folder.</summary>
    public static NativeCapture Run(NativeRender render, string? json)
    {
        var o = NativeExports.OptionsObject(json, "options", "sensor", "exposure", "seed", "noise", "radiance_scale", "demosaic",
            "signals", "off_axis", "psf", "threads");
        var (scene, renderScene, transfer) = render.CameraInput();
        var sensorName = NativeExports.Text(o, "sensor") ?? SensorFile.SceneArgument;
        var sensor = sensorName == SensorFile.SceneArgument
            ? SensorFile.FromScene(scene.Folder.Manifest.ResolvedScene?.ToJson(), scene.Folder.Manifest.Scene)
              ?? throw new InputException("options.sensor", "the scene's camera has no \"sensor\"",
                  $"give sensor=: one of {string.Join(", ", SensorPresets.Names)}, or a JSON file")
            : SensorFile.Resolve(sensorName);
        if (o["exposure"] is { } ex)
        {
            if (NativeExports.Text(o, "exposure") == "auto") sensor = sensor with { ExposureSeconds = null };
            else sensor = sensor with
            {
                ExposureSeconds = ex is JsonValue v && v.TryGetValue(out double t) && t > 0 && double.IsFinite(t) ? t
                    : throw new InputException("options.exposure",
                        $"{MessageText.Quote(ex.ToJsonString())} must be auto or positive seconds",
                        "e.g. exposure=\"auto\" or exposure=0.01 (seconds)"),
            };
        }
        // The lens, as `spectral camera --off-axis/--psf`: overrides the sensor's "off_axis" and "psf".
        if (NativeExports.Text(o, "off_axis") is { } oa)
            sensor = sensor with { OffAxis = SensorFile.ParseOffAxis(oa, "options.off_axis") };
        if (NativeExports.Text(o, "psf") is { } psf) sensor = sensor with { Psf = SensorFile.ParsePsf(psf, "options.psf") };
        bool noise = NativeExports.Text(o, "noise") switch
        {
            null or "on" or "true" => true,
            "off" or "false" => false,
            var v => throw new InputException("options.noise", $"'{v}' is not on or off", "noise=True or noise=False"),
        };
        var demosaic = NativeExports.Text(o, "demosaic") switch
        {
            null or "malvar" => DemosaicMethod.Malvar,
            "bilinear" => DemosaicMethod.Bilinear,
            var v => throw new InputException("options.demosaic", $"'{v}' is not malvar or bilinear",
                "demosaic=\"malvar\" or \"bilinear\""),
        };
        ulong seed = o["seed"] is null ? 1 : o["seed"] is JsonValue sv && sv.TryGetValue(out ulong s) ? s
            : throw new InputException("options.seed", $"{MessageText.Quote(o["seed"]!.ToJsonString())} is not a whole number ≥ 0",
                "e.g. seed=1");
        double scale = 1;
        if (o["radiance_scale"] is { } rs && !(rs is JsonValue rv && rv.TryGetValue(out scale) && scale > 0 && double.IsFinite(scale)))
            throw new InputException("options.radiance_scale", "must be positive", "W·m⁻²·sr⁻¹·nm⁻¹ per band unit");
        int threads = -1;
        if (o["threads"] is { } th && !(th is JsonValue tv && tv.TryGetValue(out threads) && threads >= 1 && threads <= 1024))
            throw new InputException("options.threads", $"{MessageText.Quote(th.ToJsonString())} is not an integer from 1 to 1024",
                "e.g. threads=2");
        bool wantExact = NativeExports.Text(o, "signals") switch
        {
            null or "exact" => true,
            "bands" => false,
            var v => throw new InputException("options.signals", $"'{v}' is not exact or bands",
                "signals=\"exact\" (default) or \"bands\""),
        };

        var options = new SimulationOptions { Seed = seed, Noise = noise, Threads = threads };
        var cube = scene.Cube(scale);
        double whiteScale = 1;
        string whiteSource = CameraRun.PaperWhite;
        if (wantExact && transfer is { } traced
            && ExactChannelSignals.Compute(scene, sensor, renderScene, traced,
                "the render's per-light transfer (traced in memory: the render's rays)",
                threads, out _) is { } exact)
        {
            cube = cube with { ChannelIntegrals = exact.Integrals, Route = exact.Route, OpticsApplied = exact.OpticsApplied };
            whiteScale = exact.WhiteScale;
            whiteSource = exact.WhiteScaleSource;
        }
        else if (wantExact && render.PathFilm(threads) is { } film
            && ExactChannelSignals.Compute(scene, sensor, renderScene, film.Film, film.From, threads, out _) is { } pathExact)
        {
            cube = cube with { ChannelIntegrals = pathExact.Integrals, Route = pathExact.Route, OpticsApplied = pathExact.OpticsApplied };
            whiteScale = pathExact.WhiteScale;
            whiteSource = pathExact.WhiteScaleSource;
        }
        if (cube.ChannelIntegrals is null && ExactChannelSignals.BandRouteWhite(scene, renderScene, transfer, render.IsPath) is { } white)
        {   // The band route sees the render's radiometry too, as `spectral camera --signals bands` does.
            whiteScale = white.Scale;
            whiteSource = white.Source;
        }
        var (raw, colour, image, _, manifest) = CameraRun.Run(scene, sensor, cube, options, demosaic, whiteScale, whiteSource,
            o["radiance_scale"] is not null ? "radiance_scale" : null, sensorName, null);
        if (raw.ClippingWarning() is { } warning) manifest["warning"] = warning;
        return new NativeCapture
        {
            Scene = scene,
            Raw = raw,
            Image = image,
            Colour = colour,
            Manifest = manifest,
            SensorArgument = sensorName,
            RadianceScale = scale,
            Demosaic = demosaic,
            WhiteScale = whiteScale,
        };
    }

    /// <summary>
    /// The capture as `spectral recover` reads it back from the camera folder (CameraCapture.Open): raw.npy's values, the
    /// sensor re-resolved with the recorded exposures, the channel weights and colour fit again, the image processed again.
    /// </summary>
    public CameraCapture ReadBack()
    {
        var sensor = SensorArgument == SensorFile.SceneArgument
            ? SensorFile.FromScene(Scene.Folder.Manifest.ResolvedScene?.ToJson(), Scene.Folder.Manifest.Scene)!
            : SensorFile.Resolve(SensorArgument);
        var options = new SimulationOptions { Seed = Raw.Options.Seed, Noise = Raw.Options.Noise };
        var weights = ChannelWeights.Compute(sensor, Scene.Grid, Scene.Light, RadianceScale);
        var exposures = Raw.ExposureSeconds.ToArray();
        var raw = new RawFrame(Raw.Width, Raw.Height, Raw.Planes, Raw.Dn, exposures, new double[exposures.Length], weights, sensor,
            options);
        bool exact = Manifest["simulation"]?["signal_route"]?.GetValue<string>().StartsWith("exact", StringComparison.Ordinal) == true;
        var colour = ColourCorrection.Fit(weights, Scene.Grid, Scene.Light, Scene.Observer, exact ? sensor : null, WhiteScale);
        var image = ImageProcessing.Run(raw, colour, Demosaic);
        return new CameraCapture { Dir = "", Manifest = Manifest, Scene = Scene, Raw = raw, Image = image, Colour = colour };
    }
}

/// <summary>Reflectance recovered from a capture: what `spectral recover` computes (per method the cube, and the metrics).</summary>
sealed class NativeRecovery : PinnedHolder
{
    public required List<RecoveryResult> Results { get; init; }
    public required string Csv { get; init; }
    public required CameraScene Scene { get; init; }
    public required string Training { get; init; }

    protected override string ManifestText()
    {
        var g = Scene.Grid;
        return new JsonObject
        {
            ["methods"] = new JsonArray(Results.Select(r => (JsonNode)SpectralEstimator.Name(r.Method)).ToArray()),
            ["shape"] = new JsonArray(Scene.Height, Scene.Width, g.Count),
            ["wavelengths"] = new JsonArray(Enumerable.Range(0, g.Count).Select(b => (JsonNode)g.Centre(b)).ToArray()),
            ["training"] = Training,
            ["forward_model"] = Results.FirstOrDefault()?.Estimator.Model.Route,
            ["white"] = Results.FirstOrDefault()?.WhiteDescription,
            ["metrics_csv"] = Csv,
        }.ToJsonString();
    }

    /// <summary>RecoverCommand.Run's steps on the capture read back as the command reads its folder.</summary>
    public static NativeRecovery Run(NativeCapture native, string? json)
    {
        var o = NativeExports.OptionsObject(json, "options", "method", "training", "white_object", "white_region", "range");
        var methodText = NativeExports.Text(o, "method") ?? "all";
        var methods = methodText == "all" ? Enum.GetValues<RecoveryMethod>().ToList()
            : methodText.Split(',').Select(m => SpectralEstimator.Parse(m.Trim())).Distinct().ToList();
        string? obj = NativeExports.Text(o, "white_object");
        if (obj is not null && o["white_region"] is not null)
            throw new InputException("options", "give at most one of white_object and white_region", "one white reference");
        var capture = native.ReadBack();
        var scene = capture.Scene;
        var training = TrainingSet.Load(NativeExports.Text(o, "training") ?? "rawtoaces-190", scene.Grid);
        WhiteReference? white = obj is not null ? Reconstruction.WhiteObject(scene.Folder, obj, scene.Aovs)
            : o["white_region"] is { } wr ? Region(scene, wr) : null;
        (double, double)? range = null;
        if (o["range"] is { } rn)
        {
            range = rn is JsonArray { Count: 2 } a && a[0] is JsonValue l && l.TryGetValue(out double lo)
                && a[1] is JsonValue h && h.TryGetValue(out double hi) && hi > lo ? (lo, hi)
                : throw new InputException("options.range", $"{MessageText.Quote(rn.ToJsonString())} is not [lo, hi] in nm",
                    "e.g. range=(400, 700)");
        }
        var (firstBand, bandCount) = RecoveryEvaluation.BandsInside(scene.Grid, range);
        string rangeText = string.Create(CultureInfo.InvariantCulture,
            $"{scene.Grid.Lower(firstBand):0.##}-{scene.Grid.Upper(firstBand + bandCount - 1):0.##}");
        var results = methods.Select(m => RecoveryEvaluation.Run(capture, m, training, white?.Mask, white?.Description, range)).ToList();
        var inv = CultureInfo.InvariantCulture;
        var csv = new StringBuilder("method,region,count,rmse,gfc,dE00_D65,dE00_A,metric_range_nm\n");
        foreach (var r in results.SelectMany(r => r.Rows))
            csv.Append(inv, $"{r.Method},{r.Region},{r.Count},{r.Rmse:R},{r.Gfc:R},{r.DeltaE00D65:R},{r.DeltaE00A:R},{rangeText}\n");
        return new NativeRecovery { Results = results, Csv = csv.ToString(), Scene = scene, Training = training.Name };
    }

    static WhiteReference Region(CameraScene scene, JsonNode node)
    {
        var v = node is JsonArray { Count: 4 } a ? a.Select(x => x is JsonValue n && n.TryGetValue(out int i) ? i : (int?)null).ToArray()
            : [];
        if (v.Length != 4 || v.Any(n => n is null))
            throw new InputException("options.white_region", $"{MessageText.Quote(node.ToJsonString())} is not [x0, y0, x1, y1]",
                "four whole pixel numbers, x1 and y1 exclusive (as --crop), e.g. (0, 0, 16, 10)");
        return Reconstruction.WhiteRegion(scene.Folder, v[0]!.Value, v[1]!.Value, v[2]!.Value, v[3]!.Value, "options.white_region");
    }
}
