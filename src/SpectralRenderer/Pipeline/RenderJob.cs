using System.Diagnostics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Pipeline;

/// <summary>What a caller hears while a job runs: the scene's warnings, the render's progress, and how long ago it was stopped.</summary>
/// <param name="StoppedAfter">Appended to an interruption's message (e.g. ", 0.120 s after the signal").</param>
public sealed record RenderObserver(Action<string>? Warning = null, Action<RenderProgress>? Progress = null,
    Func<string>? StoppedAfter = null);

/// <summary>
/// One render, assembled once for every command (render, bench, sweep, experiments, relight): the scene loaded and
/// checked against the request (region, products, memory), its geometry built (from the shared
/// <see cref="GeometryCache"/> where given), the integrator made by name, the film rendered (or recombined from a
/// per-light transfer), the transfer traced when the lights product is asked for, and every product written into a
/// staged <see cref="OutputFolder"/> that is swapped in whole. Cancelled or failed, the staging is removed and the folder
/// holds what it held. <see cref="Run"/> does it all; the steps are public for the callers that interleave their own work.
/// </summary>
public sealed class RenderJob
{
    public RenderRequest Request { get; }
    public Scene Scene { get; }
    /// <summary>The film pixels rendered (null: the whole film) and the shard's description.</summary>
    public PixelRect? Crop { get; }
    public string? Shard { get; }
    public double LoadSeconds { get; }
    public double BuildSeconds { get; private set; }
    public SceneGeometry? Geometry { get; private set; }
    public IIntegrator? Integrator { get; private set; }
    public RenderResult? Result { get; private set; }
    /// <summary>The per-light transfer (the lights product, or the one a relit render was recombined from).</summary>
    public ILightTransfer? Transfer { get; private set; }
    public double? TransferSeconds { get; private set; }
    /// <summary>render.json's "run" as it will be written; a caller may add to it before <see cref="Write"/>.</summary>
    public ManifestRun? RunRecord { get; set; }

    /// <summary>Text files written with the render's own (name → text; a relight's relight-metrics.csv): staged and swapped
    /// in with them, listed in render.json.</summary>
    public IReadOnlyDictionary<string, string>? ExtraFiles { get; set; }

    /// <summary>The load's observer's warning line (an all-black or all-white preview is said there), or null.</summary>
    Action<string>? _warning;
    /// <summary>The files written, relative to the folder (render.json last).</summary>
    public IReadOnlyList<string> Files { get; private set; } = [];
    public double WriteSeconds { get; private set; }
    /// <summary>Triangles of degenerate shape the meshes' BVHs left out.</summary>
    public int DegenerateTriangles => Scene.Objects.Sum(o => o.Mesh?.DegenerateCount ?? 0);
    public int Threads => Request.Threads;
    /// <summary>The products named in the request beyond the scene's formats.</summary>
    public IReadOnlyList<OutputProduct> NamedProducts { get; }
    OutputFolder? _folder;

    RenderJob(RenderRequest request, Scene scene, double loadSeconds)
    {
        Request = request;
        Scene = scene;
        NamedProducts = OutputProductTable.Named(request.Products);
        LoadSeconds = loadSeconds;
        if (request.Region is { } region)
        {
            Crop = region.Rectangle(scene.Camera.Width, scene.Camera.Height);
            Shard = region.Shard;
        }
    }

    /// <summary>Loads, checks and renders the request and writes its products; the job tells what it did.</summary>
    public static RenderJob Run(RenderRequest request, RenderObserver? observer = null, CancellationToken cancel = default)
    {
        var job = Load(request, observer);
        job.Execute(observer, cancel);
        return job;
    }

    /// <summary>The scene loaded and checked: the region and the products agree, the render fits in memory.</summary>
    public static RenderJob Load(RenderRequest request, RenderObserver? observer = null)
    {
        // A name no integrator is registered under is bad input, said before a mesh is read.
        if (request.Integrator is { } named && !Integrators.Has(named))
            throw new InputException("--integrator", $"unknown integrator '{named}'",
                $"known integrators: {string.Join(", ", Integrators.Names)}");
        var clock = Stopwatch.StartNew();
        ImportReport? imported = null;
        var scene = request.Scene ?? SceneLoader.Parse(request.SceneText ?? SceneBytes(request, out imported), request.ScenePath,
            request.Overrides);
        var job = new RenderJob(request, scene, clock.Elapsed.TotalSeconds) { Import = imported, _warning = observer?.Warning };
        if (imported is not null && observer?.Warning is { } say) say($"spectral import: {imported.Summary()}");
        job.Check();
        if (observer?.Warning is { } warn) foreach (var w in scene.Warnings) warn(w);
        // What the render and its writers hold, checked before anything is built.
        if (request.OutDir is not null) RenderMemory.Check(scene, request.Threads, job.NamedProducts, job.IntegratorName);
        return job;
    }

    /// <summary>
    /// The scene file's bytes: our JSON as it is, or a scene of another format (Mitsuba XML, pbrt, glTF: <see cref="SceneFormats"/>)
    /// converted in memory to our JSON with its meshes inline, parsed from the source file's folder; <paramref name="report"/>
    /// then says what the conversion approximated.
    /// </summary>
    static byte[] SceneBytes(RenderRequest request, out ImportReport? report)
    {
        report = null;
        if (SceneFormats.Find(request.ScenePath) is not { } format)
            return InputFile.ReadAllBytes(request.ScenePath, "scene file");
        var imported = format.Convert(request.ScenePath, new ImportOptions(ModelDirectories: request.Overrides.ModelDirectories));
        report = imported.Report;
        return ImportWriter.InlineJson(imported);
    }

    /// <summary>What the conversion of a scene file of another format did (null for our JSON).</summary>
    public ImportReport? Import { get; private init; }

    /// <summary>The integrator's name: the command line's, else the scene's "integrator", else whitted.</summary>
    public string IntegratorName => Request.Integrator ?? Scene.Integrator?.Name ?? Integrators.Default;

    /// <summary>What a crop or shard cannot hold; an integrator the scene names that is not registered.</summary>
    void Check()
    {
        if (Request.Integrator is null && Scene.Integrator is { } chosen && !Integrators.Has(chosen.Name))
            throw new InputException($"{Scene.SourcePath}: $.integrator", $"unknown integrator '{chosen.Name}'",
                $"known integrators: {string.Join(", ", Integrators.Names)}");
        if (Scene.Integrator is { } given && Integrators.Entry(given.Name) is { } entry)
            foreach (var (key, where) in given.Keys)
                if (!entry.Keys.Contains(key))
                    throw new InputException(where, $"the {given.Name} integrator takes no {MessageText.Quote(key)}",
                        entry.Keys.Count == 0 ? $"give just \"integrator\": \"{given.Name}\""
                            : $"{given.Name} takes: {string.Join(", ", entry.Keys)}");
        bool lights = (Scene.Output.Products & OutputProducts.Lights) != 0;
        var products = Scene.Output.Products;
        if (Shard is not null && (products & OutputProducts.Bands) != 0 && (products & (OutputProducts.Envi | OutputProducts.Npy)) == 0)
            throw new InputException("--shard",
                "band images need a float cube in each shard: merge rescales them to the whole image's brightest value",
                    "add envi or npy to --formats");
        if (lights) CheckTransferRecordable();
        if ((products & OutputProducts.Noise) != 0 && Scene.Camera.SamplesPerPixel < 2)
            throw new InputException("--formats",
                $"noise is each pixel's standard error from its samples and needs at least 2 samples per pixel, found spp "
                    + $"{Scene.Camera.SamplesPerPixel}",
                "give --spp 2 or more (or the scene's camera.spp), or leave noise out of the formats");
        if ((products & OutputProducts.Noise) != 0 && Request.FromTransfer is not null)
            throw new InputException("--formats",
                "noise is measured from a render's samples; a relit render is recombined from the per-light transfer and has none",
                "leave noise out of the formats of the relit render");
        if (Crop is not null && Scene.Output.ExposureAuto)
            throw new InputException(Request.ScenePath.Length > 0 ? Request.ScenePath : Scene.SourcePath,
                "output.exposure \"auto\" is chosen from the whole image, which a shard or crop does not see",
                "give every shard one fixed exposure: --exposure E (or the scene's \"exposure\"), e.g. the one a small whole render "
                    + "chose, its render.json's $.colour.exposure");
    }

    /// <summary>
    /// Refuses (bad input) a per-light transfer this render cannot record: its integrator records none, its transfer's format
    /// refuses the scene (e.g. a path render's adaptive sampling), or a crop that is not a shard of a format shards write.
    /// The lights product and the C ABI's relight ask it.
    /// </summary>
    public void CheckTransferRecordable()
    {
        var transfer = Integrators.Entry(IntegratorName)?.Transfer
            ?? throw new InputException("--formats", $"the per-light outputs (lights) are recorded by the {Recording()} integrators; " +
                $"the {IntegratorName} integrator does not record one",
                $"leave lights out of the formats, or render with --integrator {Recording(" or ")}");
        if (transfer.Refuses(Scene) is { } refused) throw new InputException(refused.Option, refused.What, refused.Hint);
        if (Crop is not null && !(Shard is not null && transfer.Shards))
            throw new InputException("--formats", transfer.Shards
                    ? $"a {IntegratorName} render's per-light outputs (lights) are written for whole renders and shards, not for a crop"
                    : "the per-light outputs (lights) are written for whole renders only, not for a crop or shard",
                "render lights without --crop" + (transfer.Shards ? "" : "/--shard"));
    }

    /// <summary>The integrators that record a per-light transfer, named as a sentence lists them ("whitted and path").</summary>
    static string Recording(string and = " and ")
    {
        var names = Integrators.Names.Where(n => Integrators.Entry(n)?.Transfer is not null).ToList();
        return names.Count <= 1 ? string.Concat(names) : string.Join(", ", names[..^1]) + and + names[^1];
    }

    /// <summary>
    /// Begins the output folder, builds, renders, traces the transfer when asked and writes; the folder is left as it was on failure.
    /// </summary>
    public void Execute(RenderObserver? observer = null, CancellationToken cancel = default)
    {
        Begin();
        try
        {
            if (Request.FromTransfer is null) Build();
            Render(observer, cancel);
            Write(cancel, observer?.Progress);
        }
        catch (Exception e) when (e is not InterruptedException)
        {
            _folder?.Abandon();
            throw;
        }
    }

    void Begin()
    {
        if (Request.OutDir is { } dir && _folder is null) _folder = OutputFolder.Begin(dir);
    }

    /// <summary>
    /// The scene's ray queries and the integrator; the loader's garbage returned when no BVH is shared with later renders.
    /// </summary>
    public void Build()
    {
        if (Integrator is not null) return;
        var clock = Stopwatch.StartNew();
        Geometry = new SceneGeometry(Scene, Request.Geometries);
        Integrator = Integrators.Create(Scene, Geometry, IntegratorName);   // its name checked in Load
        if (Request.Geometries is null) Renderer.ReturnLoadGarbage();
        BuildSeconds = clock.Elapsed.TotalSeconds;
    }

    /// <summary>Lets the last film go (bench, before it collects and renders again: one framebuffer held at a time).</summary>
    public void ReleaseResult() => Result = null;

    /// <summary>Renders the film (or recombines it from the request's transfer); may be called again (bench repeats).</summary>
    public RenderResult Render(RenderObserver? observer = null, CancellationToken cancel = default)
    {
        if (Request.FromTransfer is { Transfer: { } source })
        {
            Transfer = source;
            return Result = source.Relight(Scene);
        }
        Build();
        Result = null;   // a repeated render lets the previous film go first
        int done = 0, total = 0;
        try
        {
            Result = Renderer.Render(Scene, Integrator!, Request.Threads, p =>
            {
                done = p.TilesDone; total = p.Tiles;
                observer?.Progress?.Invoke(p);
            }, cancel, Crop, Request.Packets, noise: (Scene.Output.Products & OutputProducts.Noise) != 0);
        }
        catch (OperationCanceledException e)
        {
            _folder?.Abandon();
            string where = _folder is null ? ""
                : $"; {_folder.Final} {(_folder.HoldsRender ? "still holds the previous render, unchanged" : "holds no render")}";
            string tiles = $"{done} of {(total > 0 ? total : "all")} tiles done{observer?.StoppedAfter?.Invoke()}";
            throw new InterruptedException($"interrupted while rendering ({tiles}): nothing was written{where}", e.CancellationToken);
        }
        return Result;
    }

    /// <summary>
    /// The transfer when the lights product is asked for, then every product and render.json into the folder, swapped in whole.
    /// </summary>
    /// <param name="progress">Where the products that trace rays of their own (photometry, grids) report progress, or null.</param>
    public IReadOnlyList<string> Write(CancellationToken cancel = default, Action<RenderProgress>? progress = null)
    {
        var result = Result ?? throw new InvalidOperationException("render before writing");
        if (Request.OutDir is null && _folder is null) return Files;
        Begin();
        if (Transfer is null && (Scene.Output.Products & OutputProducts.Lights) != 0 && Integrator is ITransferIntegrator recorder)
        {
            // The per-light transfer (opt-in): the render's camera samples traced once more, each light's share kept apart.
            var clock = Stopwatch.StartNew();
            try { Transfer = recorder.TraceTransfer(Scene, Request.Threads, cancel, Crop); }
            catch { _folder?.Abandon(); throw; }
            TransferSeconds = clock.Elapsed.TotalSeconds;
        }
        RunRecord ??= Record(result);
        var writeClock = Stopwatch.StartNew();
        Files = RenderOutputWriter.Write(Scene, result, _folder!, RunRecord, cancel, Transfer, Request.FromTransfer?.Reuse, NamedProducts,
            Geometry is not null && Integrator is not null ? new RenderTracer(Geometry, Integrator, Request.Threads) : null, ExtraFiles,
            _warning, progress);
        WriteSeconds = writeClock.Elapsed.TotalSeconds;
        return Files;
    }

    /// <summary>
    /// Writes the render (made without an output folder: the C ABI's spectral_save) into <paramref name="dir"/> as
    /// <see cref="Write"/> does for the request's folder: the transfer traced when the lights product is asked for, the
    /// same run record, swapped in whole. May be called again for another folder.
    /// </summary>
    public IReadOnlyList<string> WriteTo(string dir, CancellationToken cancel = default)
    {
        if (Request.OutDir is not null) throw new InvalidOperationException("the request names its folder: call Write");
        var folder = _folder = OutputFolder.Begin(dir);
        try { return Write(cancel); }
        catch (Exception e) when (e is not InterruptedException)
        {
            folder.Abandon();   // as Execute: the staging removed, the folder holds what it held
            throw;
        }
        finally { _folder = null; }
    }

    /// <summary>render.json's "run": the request's, with what <see cref="RenderRequest.Detail"/> adds.</summary>
    ManifestRun? Record(RenderResult result) => Import is null ? Detailed(result) : (Detailed(result) ?? new ManifestRun()) with
    {
        Imported = Import.ToJson(),
    };

    ManifestRun? Detailed(RenderResult result) => Request.Detail switch
    {
        RunDetail.None => Request.Run,
        RunDetail.Geometry => (Request.Run ?? new ManifestRun()) with { Triangles = Geometry?.TriangleCount },
        _ => (Request.Run ?? new ManifestRun()) with
        {
            LoadSeconds = LoadSeconds,
            BuildSeconds = BuildSeconds,
            Triangles = Geometry?.TriangleCount,
            DegenerateTrianglesSkipped = DegenerateTriangles,
            MinRayWeight = Scene.MinRayWeight,
            RayBudget = Scene.RayBudget,
            RaysPrunedByWeight = result.Rays.PrunedRays,
            CameraRaysOverBudget = result.Rays.OverBudgetRays,
            Shard = Shard,
            LightTransferSeconds = TransferSeconds,
            HasOverrides = true,
            Overrides = Recorded(Request.Overrides),
            Integrator = Request.Integrator,   // what the camera's exact route needs to know (issue 24)
        },
    };

    /// <summary>The command-line overrides as render.json records them (model folders as full paths).</summary>
    public static ManifestOverrides Recorded(SceneOverrides o) => new(o.Width, o.Height, o.Bands, o.Wave, o.SamplesPerPixel, o.Rgb,
        o.Integration, o.Formats, o.ExrCompression, o.ModelDirectories.Select(Path.GetFullPath).ToArray(), o.Exposure);

    /// <summary>The overrides render.json recorded, to load the same scene again (relight).</summary>
    public static SceneOverrides Overrides(ManifestOverrides? o) => new()
    {
        Width = o?.Width,
        Height = o?.Height,
        Bands = o?.Bands,
        Wave = o?.Wave,
        SamplesPerPixel = o?.SamplesPerPixel,
        Rgb = o?.Rgb,
        Integration = o?.Integration,
        Formats = o?.Formats,
        ExrCompression = o?.ExrCompression,
        Exposure = o?.Exposure,
        ModelDirectories = o?.Models.Where(Directory.Exists).ToList() ?? [],
    };
}
