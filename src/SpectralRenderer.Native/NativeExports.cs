using System.Globalization;
using System.Runtime.InteropServices;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Relighting;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Native;

/// <summary>
/// libspectral's C ABI, version <see cref="AbiVersion"/> (python/spectralrenderer/_native.py is its one caller in the
/// repository; README, "Python"). A render is a handle: <c>spectral_render</c> always returns one (never null), holding
/// either the render or the error — its status (0 success, 1 work failed or interrupted, 2 bad input: the CLI's exit
/// codes) and the one line the CLI prints. Nothing is global: every call works on its handle only, so calls on different
/// handles may run on different threads at once. Memory: every pointer an accessor returns belongs to the handle and
/// stays valid, unmoved (pinned), until <c>spectral_free</c>; strings are UTF-8, NUL-terminated. No exception crosses
/// the boundary.
/// </summary>
public static unsafe partial class NativeExports
{
    /// <summary>
    /// The ABI's major version: raised when a function's signature or meaning changes (a caller built for another major
    /// refuses the library). Functions added beside the existing ones raise <see cref="AbiMinor"/> only, so a caller
    /// checks major == its own and minor ≥ the one that added the functions it calls.
    /// </summary>
    public const int AbiVersion = 1;

    /// <summary>
    /// The ABI's minor version: 0 the first functions; 1 added spectral_abi_minor, spectral_relight, spectral_camera, the
    /// capture accessors and spectral_recover (version 1's functions unchanged; spectral_save writes lights/ when the
    /// render's formats name them, as `spectral render` does); 2 added spectral_noise, spectral_mask_count,
    /// spectral_mask_name and spectral_mask, and spectral_camera's off_axis and psf options; 3 made spectral_render take
    /// every option of `spectral render` (the options table, RenderOptions: band_range, target_error, models, crop, shard,
    /// shards besides the first eleven) and spectral_relight and spectral_save's lights work on path renders.
    /// </summary>
    public const int AbiMinor = 3;

    [UnmanagedCallersOnly(EntryPoint = "spectral_abi_version")]
    public static int Version() => AbiVersion;

    [UnmanagedCallersOnly(EntryPoint = "spectral_abi_minor")]
    public static int Minor() => AbiMinor;

    /// <summary>
    /// Renders a scene given as UTF-8 JSON text. <paramref name="path"/> names it (its relative mesh paths resolve from its
    /// folder; messages name it). A null <paramref name="scene"/> reads the file at <paramref name="path"/> as `spectral render`
    /// does: our JSON, or a Mitsuba 3 XML (another renderer's format, docs/import.md) converted in memory. <paramref name="options"/>: a
    /// JSON object of `spectral render`'s options, each optional, keyed by the option's name with '_' for '-'
    /// (<see cref="RenderOptions.All"/>: width, height, bands, wave, spp, target_error, threads, rgb, integration, formats,
    /// exr_compression, models, crop, shard, …), valued as on the command line (a text or a number; an array for models, or items joined by
    /// ','), checked by the same code with the same messages; no job array variable is read. <paramref name="cancel"/> (may be null): the
    /// render stops soon after the caller sets *cancel to non-zero (status 1, "interrupted …"). <paramref name="progress"/> (may be null)
    /// is called after each tile with (user, tiles done, tiles) on a worker thread.
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_render")]
    public static nint Render(byte* scene, byte* path, byte* options, int* cancel,
        delegate* unmanaged<nint, int, int, void> progress, nint user)
    {
        var handle = new NativeRender();
        try
        {
            string name = Utf8(path) ?? "scene.json";
            // No text: the scene file at path, read (or converted from another renderer's format) as `spectral render` does.
            byte[]? text = scene is null ? null : new ReadOnlySpan<byte>(scene, StrLen(scene)).ToArray();
            var values = RenderOptions.Parse(RenderOptions.FromJson(Options(Utf8(options))), () => text ?? []);
            var request = values.Request(name, ShardRegion.Of(values, jobArray: false)) with
            {
                SceneText = text,
                OutDir = null,   // nothing written: the film stays in memory until spectral_save (RenderJob.WriteTo)
                Run = new ManifestRun { CommandLine = "spectralrenderer (Python, libspectral)" },
            };
            using var stop = new CancellationTokenSource();
            int* flag = cancel;
            // The caller's flag, read after every tile and every 20 ms (before the first tile ends).
            void Poll() { if (flag is not null && Volatile.Read(ref *flag) != 0) stop.Cancel(); }
            using var timer = new Timer(_ => Poll(), null, 20, 20);
            var observer = new RenderObserver(Progress: p =>
            {
                Poll();
                if (progress is not null) progress(user, p.TilesDone, p.Tiles);
            });
            Poll();
            var job = RenderJob.Load(request, observer);
            job.Build();
            stop.Token.ThrowIfCancellationRequested();
            job.Render(observer, stop.Token);
            handle.Set(job);
        }
        catch (Exception e)
        {
            handle.Fail(e);
        }
        return GCHandle.ToIntPtr(GCHandle.Alloc(handle));
    }

    /// <summary>0 success, 1 work failed or interrupted, 2 bad input (the CLI's exit codes).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_status")]
    public static int Status(nint h) => Get(h)?.Status ?? 2;

    /// <summary>The error's one line as the CLI prints it ("spectral render: …"), or an empty string.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_message")]
    public static byte* Message(nint h) => Get(h) is { } r ? r.MessageUtf8 : null;

    /// <summary>Height, width and band count of the cube (zeros after an error).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_shape")]
    public static void Shape(nint h, int* height, int* width, int* bands)
    {
        var r = Get(h)?.Job?.Result;
        *height = r?.Image.Height ?? 0; *width = r?.Image.Width ?? 0; *bands = r?.Image.Bands ?? 0;
    }

    /// <summary>The cube, H × W × N float32 row-major (spectral.npy's layout and values), owned by the handle.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_cube")]
    public static float* Cube(nint h) => (float*)Guard(h, r => r.Cube);

    /// <summary>The N band centres in nm (float64; wavelengths.csv's centre column).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_wavelengths")]
    public static double* Wavelengths(nint h) => (double*)Guard(h, r => r.Wavelengths);

    /// <summary>The N + 1 band edges in nm (float64).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_band_edges")]
    public static double* BandEdges(nint h) => (double*)Guard(h, r => r.Edges);

    /// <summary>CIE 1931 X, Y, Z per pixel, H × W × 3 float32 (κ included; the colours the preview is encoded from).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_xyz")]
    public static float* Xyz(nint h) => (float*)Guard(h, r => r.Xyz);

    /// <summary>The preview's 8-bit display RGB, H × W × 3 bytes (preview.png's pixels).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_rgb8")]
    public static byte* Rgb8(nint h) => (byte*)Guard(h, r => r.Rgb8);

    /// <summary>Object ids per pixel, H × W int32: 0 background, k the scene's k-th object (object-id.png's values).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_ids")]
    public static int* Ids(nint h) => (int*)Guard(h, r => r.Ids);

    /// <summary>
    /// The standard error of each pixel's mean from its samples, H × W × (N + 1) float32: per band, then of luminance Y
    /// (noise.npy's values, ABI 1.2); null unless the render's formats name noise (spp ≥ 2).
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_noise")]
    public static float* Noise(nint h) => (float*)Guard(h, r => r.Noise);

    /// <summary>The number of analysis masks the render holds (ABI 1.2): a lit mask per light (at most 32), then the highlight.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_mask_count")]
    public static int MaskCount(nint h)
    {
        try { return Get(h) is { Job.Result: not null } r ? r.Masks.Count : 0; }
        catch (Exception) { return 0; }
    }

    /// <summary>Mask <paramref name="i"/>'s name, UTF-8: "lit-K" (mask-lit-K.png, render.json's K-th light) or "highlight".</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_mask_name")]
    public static byte* MaskName(nint h, int i) => (byte*)Guard(h, r => i >= 0 && i < r.Masks.Count ? r.Masks[i].Name : 0);

    /// <summary>Mask <paramref name="i"/>, H × W uint8: mask-&lt;name&gt;.png's pixels (the aov product's: 255 or 0).</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_mask")]
    public static byte* Mask(nint h, int i) => (byte*)Guard(h, r => i >= 0 && i < r.Masks.Count ? r.Masks[i].Pixels : 0);

    /// <summary>render.json's content for the render held (its "files" empty and "run" absent until saved), UTF-8 JSON.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_manifest")]
    public static byte* Manifest(nint h) => (byte*)Guard(h, r => (nint)r.ManifestUtf8);

    /// <summary>
    /// Writes the render folder `spectral render -o FOLDER` writes (the same files, byte for byte, but render.json's
    /// run-describing fields). Returns the status; on failure <paramref name="error"/> (if not null) receives a new handle
    /// holding the message, to be freed.
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_save")]
    public static int Save(nint h, byte* folder, nint* error)
    {
        var r = Get(h);
        var failure = new NativeRender();
        try
        {
            if (r?.Job is null) throw new InputException("spectral_save", "the handle holds no render", "save a successful render");
            var dir = Utf8(folder);
            if (string.IsNullOrWhiteSpace(dir)) throw new InputException("-o", "the output folder name is empty", "give a folder name");
            r.Save(dir);
            return 0;
        }
        catch (Exception e)
        {
            failure.Fail(e);
            if (error is not null) *error = GCHandle.ToIntPtr(GCHandle.Alloc(failure));
            return failure.Status;
        }
    }

    /// <summary>
    /// Relights the render held by <paramref name="h"/> as `spectral relight` does (no ray traced into the picture): a new
    /// handle, as <c>spectral_render</c> returns, holding the render under the changed lights or the error.
    /// <paramref name="changes"/>: a JSON object {"lights": {"NAME": {"spectrum": S, "intensity": F}, …}, "white": S}
    /// (every key optional; S a spectrum value of the scene format: a name, blackbody:T, …, or inline [[nm, value], …]).
    /// The per-light transfer is traced once per source handle (the render's own camera rays) and kept with it; a
    /// relit handle relights again from the same transfer. <paramref name="cancel"/> as for spectral_render.
    /// </summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_relight")]
    public static nint Relight(nint h, byte* changes, int* cancel)
    {
        var handle = new NativeRender();
        try
        {
            var source = Get(h) is { Job.Result: not null } r ? r
                : throw new InputException("spectral_relight", "the handle holds no render", "relight a successful render");
            using var stop = new CancellationTokenSource();
            int* flag = cancel;
            using var timer = new Timer(_ => { if (flag is not null && Volatile.Read(ref *flag) != 0) stop.Cancel(); }, null, 20, 20);
            handle.Set(source.Relit(Utf8(changes), stop.Token));
        }
        catch (Exception e)
        {
            handle.Fail(e, "spectral relight: ");
        }
        return GCHandle.ToIntPtr(GCHandle.Alloc(handle));
    }

    /// <summary>Frees the handle and every buffer it owns; null is ignored.</summary>
    [UnmanagedCallersOnly(EntryPoint = "spectral_free")]
    public static void Free(nint h)
    {
        if (h == 0) return;
        var g = GCHandle.FromIntPtr(h);
        (g.Target as NativeRender)?.Dispose();
        g.Free();
    }

    /// <summary>An accessor's pointer, or null when the handle holds no render or the value cannot be made (never a throw).</summary>
    static nint Guard(nint h, Func<NativeRender, nint> value)
    {
        try { return Get(h) is { Job.Result: not null } r ? value(r) : 0; }
        catch (Exception) { return 0; }
    }

    static NativeRender? Get(nint h) => h == 0 ? null : GCHandle.FromIntPtr(h).Target as NativeRender;

    static int StrLen(byte* s) { int n = 0; while (s[n] != 0) n++; return n; }

    static string? Utf8(byte* s) => s is null ? null : Encoding.UTF8.GetString(s, StrLen(s));

    /// <summary>The options object (keys and values: <see cref="RenderOptions.FromJson"/>); null is none.</summary>
    static JsonObject Options(string? json)
    {
        try
        {
            return json is null ? [] : JsonNode.Parse(json, documentOptions: StrictJson) as JsonObject
                ?? throw new JsonException("not an object");
        }
        catch (JsonException e) { throw new InputException("options", $"not a JSON object: {e.Message}", "pass {\"width\": 64, …}"); }
    }
}

/// <summary>One handle's render (or error) and the pinned buffers handed out for it.</summary>
sealed unsafe class NativeRender : IDisposable
{
    public RenderJob? Job { get; private set; }
    public int Status { get; private set; }
    public byte* MessageUtf8 { get; private set; }
    readonly List<GCHandle> _pins = [];
    readonly List<nint> _strings = [];
    nint _cube, _wavelengths, _edges, _xyz, _rgb8, _ids, _noise;
    List<(nint Name, nint Pixels)>? _masks;
    byte* _manifest;

    public void Set(RenderJob job) { Job = job; MessageUtf8 = String(""); }

    /// <summary>A relit render: its job (the transfer recombined) and what its save records of the relight.</summary>
    public void Set(Relight relit) { Set(relit.Job); _relit = relit; }

    /// <summary>What a relight made: the job, and the source's scene name and overrides (to relight it again), its changes.</summary>
    public sealed record Relight(RenderJob Job, string ScenePath, SceneOverrides Overrides, ManifestRelit Record);

    Relight? _relit;
    ILightTransfer? _transfer;
    readonly Lock _transferLock = new();

    /// <summary>The scene's name and the overrides it was loaded with (a relit render: its source's).</summary>
    string ScenePath => _relit?.ScenePath ?? Job!.Request.ScenePath;
    SceneOverrides Overrides => _relit?.Overrides ?? Job!.Request.Overrides;

    /// <summary>
    /// The per-light transfer of this render: a relit render's own, the one its save traced (the lights format), else its
    /// camera samples traced again once, each light's contribution kept apart (as `spectral render --formats …,lights`
    /// does), and kept. Refused where the command line refuses the lights format (RenderJob.CheckTransferRecordable).
    /// </summary>
    ILightTransfer Transfer(CancellationToken cancel)
    {
        var job = Job!;
        if (job.Transfer is { } own) return own;
        lock (_transferLock)
        {
            if (_transfer is not null) return _transfer;
            job.CheckTransferRecordable();   // the lights format's rule: an integrator that records one, no refusal, no crop
            var recorder = job.Integrator as ITransferIntegrator
                ?? throw new InvalidOperationException($"integrator '{job.IntegratorName}' has a transfer format but records none");
            return _transfer = recorder.TraceTransfer(job.Scene, job.Threads, cancel, job.Crop);
        }
    }

    /// <summary>
    /// This render under changed lights, as `spectral relight` computes it from the folder's lights/: the scene rebuilt from
    /// render.json's resolved scene and recorded overrides with the changes (<see cref="Relighter.ChangedScene"/>: the same
    /// checks and messages), the transfer recombined. Inline spectra ([[nm, value], …]) join the scene's named spectra.
    /// </summary>
    public Relight Relit(string? json, CancellationToken cancel)
    {
        var clock = System.Diagnostics.Stopwatch.StartNew();
        // render.json's text parsed back, as relight reads it from the folder.
        var manifest = RenderManifest.Parse(JsonNode.Parse(Marshal.PtrToStringUTF8((nint)ManifestUtf8)!)!.AsObject(), ScenePath);
        var resolved = manifest.ResolvedScene
            ?? throw new InputException("spectral_relight", "the render has no resolved scene",
                "render again with this version of spectral");
        var document = resolved.ToJson();
        var (changes, white) = Changes(json, document);
        var overrides = RenderJob.Overrides(RenderJob.Recorded(Overrides)) with { LoadMeshes = false };
        var names = resolved.Lights.Select(l => l.Name).ToArray();
        var src = new Relighter.Source("", manifest, new ManifestScene(document), ScenePath, overrides, names);
        var scene = Relighter.ChangedScene(src, changes, white);
        scene.Output.Products &= ~OutputProducts.Noise;   // as `spectral relight`: measured from samples, which a relit render has none of
        // Whichever integrator rendered it: its transfer recombined, as `spectral relight` does from lights/.
        var transfer = Transfer(cancel);
        foreach (var c in changes)
            if (c.Spectrum is not null
                && transfer.Format.RefusesNewSpectrum(scene.Lights[Array.IndexOf(src.LightNames, c.Light)]) is { } why)
                throw new InputException($"changes.lights.{c.Light}", $"light '{c.Light}' {why}",
                    "give it a new intensity only, or render the scene again with the new spectrum");
        cancel.ThrowIfCancellationRequested();
        var job = RenderJob.Load(new RenderRequest
        {
            Scene = scene,
            ScenePath = ScenePath,
            Integrator = transfer.Format.Integrator,
            FromTransfer = new TransferSource(transfer, null),
            Detail = RunDetail.None,
        });
        job.Render(cancel: cancel);
        var record = new ManifestRelit
        {
            From = "a render in memory (spectralrenderer, libspectral)",
            FromCreatedUtc = manifest.CreatedUtc,
            Method = transfer.RelightMethod,
            Changes = changes.Select(c => new ManifestLightChange(c.Light, c.Spectrum, c.Intensity)).ToArray(),
            White = white,
            ComputeSeconds = clock.Elapsed.TotalSeconds,
        };
        return new Relight(job, ScenePath, Overrides, record);
    }

    /// <summary>The changes object: per light a spectrum and/or intensity, and the white; inline spectra named into the scene.</summary>
    static (List<LightChange>, string? White) Changes(string? json, JsonObject document)
    {
        JsonObject o;
        try
        {
            o = json is null
                ? []
                : JsonNode.Parse(json, documentOptions: NativeExports.StrictJson) as JsonObject ?? throw new JsonException("not an object");
        }
        catch (JsonException e)
        {
            throw new InputException("changes", $"not a JSON object: {e.Message}", "pass {\"lights\": {\"NAME\": {\"spectrum\": \"A\"}}}");
        }
        string? Spectrum(JsonNode? node, string where, string name)
        {
            switch (node)
            {
                case null: return null;
                case JsonValue v when v.TryGetValue(out string? text): return text;
                case JsonArray or JsonObject or JsonValue:
                    // An inline spectrum: one of the scene's named spectra, under a name no other spectrum has.
                    var named = document["spectra"] as JsonObject ?? (JsonObject)(document["spectra"] = new JsonObject());
                    string key = name;
                    for (int i = 2; named.ContainsKey(key); i++) key = string.Create(CultureInfo.InvariantCulture, $"{name}-{i}");
                    named[key] = node.DeepClone();
                    return key;
                default:
                    throw new InputException(where, $"{MessageText.Quote(node.ToJsonString())} is not a spectrum",
                        "a name (e.g. \"A\", \"blackbody:3000\") or [[nm, value], …]");
            }
        }
        var changes = new List<LightChange>();
        foreach (var (key, value) in o)
        {
            if (key == "white" || key == "lights") continue;
            throw new InputException($"changes.{key}", "unknown key", "known: lights, white");
        }
        if (o["lights"] is JsonObject lights)
            foreach (var (name, value) in lights)
            {
                string where = $"--light {name}";
                if (value is JsonObject c && (c.ContainsKey("spectrum") || c.ContainsKey("intensity")))
                {
                    foreach (var (k, _) in c)
                        if (k is not ("spectrum" or "intensity"))
                            throw new InputException($"{where}: {k}", "unknown key", "known: spectrum, intensity");
                    double? intensity = null;
                    if (c["intensity"] is { } f)
                        intensity = f is JsonValue fv && fv.TryGetValue(out double d) && double.IsFinite(d) && d >= 0 ? d
                            : throw new InputException("--intensity", $"{MessageText.Quote(f.ToJsonString())} is not a non-negative number",
                                "e.g. intensity 0.5");
                    changes.Add(new LightChange(name, Spectrum(c["spectrum"], where, $"relight-{name}"), intensity));
                }
                else changes.Add(new LightChange(name, Spectrum(value, where, $"relight-{name}"), null));
            }
        else if (o["lights"] is { } bad)
            throw new InputException("changes.lights", "not an object",
                "{\"NAME\": \"SPECTRUM\"} or {\"NAME\": {\"spectrum\": …, \"intensity\": …}}");
        return (changes, Spectrum(o["white"], "--white", "relight-white"));
    }

    /// <summary>A capture (spectral_camera) or a recovery (spectral_recover) this handle holds instead of a render.</summary>
    public NativeCapture? Capture { get; private set; }
    public NativeRecovery? Recovery { get; private set; }
    public void SetCapture(NativeCapture c) { Capture = c; MessageUtf8 = String(""); }
    public void SetRecovery(NativeRecovery r) { Recovery = r; MessageUtf8 = String(""); }

    /// <summary>
    /// What `spectral camera` reads from the folder this render would write (CameraScene.Open: render.json, the cube, the
    /// ids, the colours, the masks, the ground-truth reflectance), taken from memory; the render's scene and its per-light
    /// transfer for the exact channel signals (null for an integrator that records none: the band cube's route).
    /// </summary>
    public (CameraScene Scene, Scene RenderScene, ITermRoute? Transfer) CameraInput()
    {
        var job = Job!;
        var result = Result;
        var image = result.Image;
        var manifest = RenderManifest.Parse(JsonNode.Parse(Marshal.PtrToStringUTF8((nint)ManifestUtf8)!)!.AsObject(), ScenePath);
        int n = image.Width * image.Height;
        float[] x = new float[n], y = new float[n], z = new float[n];
        if (result.Xyz is { } px)
            for (int i = 0; i < n; i++) { x[i] = px[3 * i]; y[i] = px[3 * i + 1]; z[i] = px[3 * i + 2]; }
        else
        {
            var p = Planes;
            for (int i = 0; i < n; i++) { x[i] = (float)p.X[i]; y[i] = (float)p.Y[i]; z[i] = (float)p.Z[i]; }
        }
        var folder = new RenderFolder
        {
            Path = ScenePath,
            Manifest = manifest,
            Image = image,
            ObjectIds = result.ObjectIds,
            PixelXyz = (x, y, z),
        };
        int lights = job.Scene.Lights.Count;
        var planes = AnalysisImages.GroundTruthBands(job.Scene, result);
        var truth = new SpectralImage(image.Width, image.Height, image.Grid);
        for (int b = 0; b < image.Bands; b++)
            for (int i = 0; i < n; i++) truth.Data[i * image.Bands + b] = planes[b * n + i];
        var aovs = new RenderAovs
        {
            Lit = lights <= LitMasks.MaxLights
                ? Enumerable.Range(0, lights)
                    .Select(k => Enumerable.Range(0, n).Select(i => result.LitMasks.IsLit(i, k)).ToArray()).ToArray()
                : null,
            LightNames = manifest.Lights.Select(l => l.Name).ToArray(),
            Highlight = result.Highlights.Select(v => v * 2 > 255).ToArray(),
            HighlightFraction = manifest.HighlightFraction,
            Reflectance = truth,
        };
        // A cropped render has no whole-film transfer to trace (as PathFilm): its camera takes the band route.
        bool traced = job.Transfer is ITermRoute
            || job.Transfer is null && job.Crop is null
                && job.Integrator is ITransferIntegrator { TransferFormat.Route: CameraRoute.Terms };
        return (CameraScene.Of(folder, aovs), job.Scene, traced ? Transfer(default) as ITermRoute : null);
    }

    /// <summary>
    /// A path render's film on its sub-band grid for the camera's exact signals (ExactChannelSignals.Path.cs): from its per-light
    /// transfer when it holds one (a relight's, or the lights output), else its camera samples traced again (the same paths);
    /// null for a render of another integrator, an adaptive or cropped one.
    /// </summary>
    public (SubBandFilm Film, string From)? PathFilm(int threads)
    {
        var job = Job!;
        if (job.Transfer is ISubBandFilmRoute t)
            return (t.Film(job.Scene), "the render's path transfer in memory (L_f = F_f + sum_k T_k,f * E_k,f, no rays traced)");
        if (job.Integrator is not ISubBandFilmIntegrator path || job.Scene.TargetError > 0
            || Result.Crop != PixelRect.Whole(job.Scene.Camera.Width, job.Scene.Camera.Height)) return null;
        return (path.TraceSubBandFilm(job.Scene, threads < 0 ? 0 : threads),
            "the render's camera samples traced again in memory (the same paths)");
    }

    /// <summary>Whether the render held is a path render (its integrator, or the path transfer it was relit from).</summary>
    public bool IsPath => Job is { } job && (job.Integrator is ISubBandFilmIntegrator || job.Transfer is ISubBandFilmRoute);

    /// <summary>The error as the CLI ends `spectral render` with it (CommandLine.Describe: code and one line).</summary>
    public void Fail(Exception e, string prefix = "spectral render: ")
    {
        if (e is AggregateException agg && agg.Flatten().InnerExceptions.Count > 0) e = agg.Flatten().InnerExceptions[0];
        var (code, message) = e switch
        {
            InputException => (2, e.Message),
            WorkFailedException or InterruptedException => (1, e.Message),
            OperationCanceledException => (1, "interrupted; no output was left under a final name"),
            OutOfMemoryException or InsufficientExecutionStackException =>
                (1, $"out of memory ({e.GetType().Name}) (hint: lower the resolution, band count or mesh size)"),
            IOException => (1, e.Message),
            UnauthorizedAccessException => (2, $"{e.Message} (hint: choose files and folders you can read and write)"),
            _ => (1, $"internal error {e.GetType().Name}: {e.Message} "
                + "(hint: this is a defect of spectral; please report it with the input)"),
        };
        Status = code;
        MessageUtf8 = String(prefix + (e is InputException ? MessageText.Escape(message) : MessageText.Line(message)));
    }

    RenderResult Result => Job?.Result ?? throw new InvalidOperationException("no render");

    public nint Cube => _cube != 0 ? _cube : _cube = Pin(Result.Image.Data);
    public nint Wavelengths => _wavelengths != 0 ? _wavelengths
        : _wavelengths = Pin(Enumerable.Range(0, Result.Image.Bands).Select(Result.Image.Grid.Centre).ToArray());
    public nint Edges => _edges != 0 ? _edges : _edges = Pin(Result.Image.Grid.Edges());
    public nint Ids => _ids != 0 ? _ids : _ids = Pin(Result.ObjectIds.Select(i => i + 1).ToArray());

    public nint Noise => _noise != 0 ? _noise : Result.Noise is { } noise ? _noise = Pin(noise) : 0;

    /// <summary>The analysis masks as the aov product writes them (AnalysisImages): mask-lit-K.png's, mask-highlight.png's.</summary>
    public List<(nint Name, nint Pixels)> Masks
    {
        get
        {
            lock (_transferLock)
            {
                if (_masks is not null) return _masks;
                var result = Result;
                var masks = new List<(nint, nint)>();
                for (int k = 0; k < AnalysisImages.LitMaskCount(Job!.Scene); k++)
                {
                    var mask = new byte[result.ObjectIds.Length];
                    AnalysisImages.LitMask(result, k, mask);
                    masks.Add(((nint)String(string.Create(CultureInfo.InvariantCulture, $"lit-{k}")), Pin(mask)));
                }
                masks.Add(((nint)String("highlight"), Pin(result.Highlights)));
                return _masks = masks;
            }
        }
    }

    XyzPlanes Planes => Result.Xyz is { } px ? XyzPlanes.FromPixels(px) : XyzPlanes.Compute(Job!.Scene.Colorimeter, Result.Image);

    public nint Xyz
    {
        get
        {
            if (_xyz != 0) return _xyz;
            if (Result.Xyz is { } px) return _xyz = Pin(px);
            var p = Planes;
            var xyz = new float[3 * p.X.Length];
            for (int i = 0; i < p.X.Length; i++)
            {
                xyz[3 * i] = (float)p.X[i]; xyz[3 * i + 1] = (float)p.Y[i]; xyz[3 * i + 2] = (float)p.Z[i];
            }
            return _xyz = Pin(xyz);
        }
    }

    public nint Rgb8
    {
        get
        {
            if (_rgb8 != 0) return _rgb8;
            var xyz = Planes;
            var image = Result.Image;
            var encoder = RenderOutputWriter.PreviewEncoder(Job!.Scene, xyz);
            return _rgb8 = Pin(RenderOutputWriter.Preview(image.Width, image.Height, xyz, encoder));
        }
    }

    public byte* ManifestUtf8
    {
        get
        {
            if (_manifest is not null) return _manifest;
            var scene = Job!.Scene;
            var xyz = Planes;
            var m = RenderOutputWriter.Describe(scene, Result, Result.Image.Max(), null, RenderOutputWriter.PreviewEncoder(scene, xyz));
            return _manifest = String(m.ToJsonText());
        }
    }

    /// <summary>
    /// The render folder through <see cref="RenderJob.WriteTo"/>, as `spectral render` writes it: render.json's "run" as
    /// RenderJob records it, the per-light transfer traced when the formats name lights (Whitted or path). A relit render's
    /// run records its source's overrides and the relight, as `spectral relight` does.
    /// </summary>
    public void Save(string dir)
    {
        var job = Job!;
        if (_relit is { } relit)
            job.RunRecord = new ManifestRun
            {
                CommandLine = "spectralrenderer.relight (Python, libspectral)",
                HasOverrides = true,
                Overrides = RenderJob.Recorded(relit.Overrides),
                Relit = relit.Record,
            };
        job.WriteTo(dir);
    }

    nint Pin(Array a)
    {
        var g = GCHandle.Alloc(a, GCHandleType.Pinned);
        _pins.Add(g);
        return g.AddrOfPinnedObject();
    }

    byte* String(string s)
    {
        var bytes = Encoding.UTF8.GetBytes(s);
        var p = (byte*)NativeMemory.Alloc((nuint)bytes.Length + 1);
        bytes.CopyTo(new Span<byte>(p, bytes.Length));
        p[bytes.Length] = 0;
        _strings.Add((nint)p);
        return p;
    }

    public void Dispose()
    {
        Capture?.Dispose();
        Recovery?.Dispose();
        foreach (var g in _pins) g.Free();
        _pins.Clear();
        foreach (var p in _strings) NativeMemory.Free((void*)p);
        _strings.Clear();
        _masks = null;
        Job = null;
    }
}
