using System.Globalization;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral render SCENE.json -o OUTDIR`: load, render in tiles on all cores, write the outputs.</summary>
public static class RenderCommand
{
    public const string Help = """
        usage: spectral render SCENE.json|- [-o OUTDIR] [--width W] [--height H] [--bands N | S:E:N] [--wave S:STEP:E]
                               [--spp N] [--target-error E] [--threads N] [--rgb srgb|paper] [--integration exact|weighted|paper]
                               [--formats LIST] [--exr-compression zip|zip-all|none] [--models DIR] [--quiet]
                               [--crop X0,Y0,X1,Y1 | --shard I/N|none] [--shards N] [--integrator NAME]

        Renders a scene file (docs/scene-format.md) with the paper's eq. 2 in every band and writes:
          preview.png        8-bit sRGB (or eq. 4 with --rgb paper)
          bands/             one 16-bit greyscale PNG per band on a common scale, and bands.png (Fig. 2)
          spectral.exr       all bands, spectral OpenEXR layout (S0.<λ>nm channels) + R G B + X Y Z
          spectral.hdr/.img  ENVI cube, BSQ float32, wavelengths in nm
          spectral.npy       H × W × N float32 NumPy array, with wavelengths.csv
          object-id.png      16-bit id of the object seen at each pixel (0 = background; ids in render.json)
          render.json        resolved scene, band edges, κ, white point, timings, ray counts, version

          SCENE.json         the scene; - reads it from standard input (relative paths then resolve
                             from the working folder)
          -o, --out DIR      output folder (default: out/<scene file name>, out/stdin for -)
          --width, --height  image size in pixels (override the scene's camera); one alone keeps its aspect ratio
          --bands N|S:E:N    band count over the scene's range, or band edges start:end:count: 395:705:31 is
                             31 bands of 10 nm from 395 to 705 nm
          --wave S:STEP:E    band centres in MATLAB/ISETCam colon notation, each STEP wide: 400:10:700 is
                             the same 31 bands, centred on 400, 410, …, 700 nm
          Bands are numbered from 1 (the first band is band 1) in every file and table a person reads.
          --spp N            samples per pixel (1 = pixel centre; more = stratified jitter)
          --target-error E   adaptive sampling: each pixel stops once the relative standard error of its mean
                             luminance is at most E (e.g. 0.01), taking at most --spp samples (render.json: sampling)
          --threads N        worker threads (default: all cores); output is identical for any N
          --rgb MODE         srgb (default) or paper (the paper's eq. 4, linear, clipped)
          --integration S    exact (default: band values and colour integrated on the full tables),
                             weighted (band products, prefiltered colour weights) or paper (eq. 3)
          --formats LIST     comma-separated from png,bands,exr,envi,npy,aov,lights,photometry,noise, or all (every one
                             but lights, photometry and noise, the default); lights = the per-light transfer in lights/ for
                             'relight' and 'view'; photometry = luminance (cd/m²) and illuminance (lx) maps (physical
                             radiometry); noise = each pixel's standard error per band and of luminance (noise.npy,
                             noise.img/.hdr, stderr.* channels in spectral.exr; needs spp >= 2)
          --exr-compression  zip (default: deflate the chunks whose samples repeat, store noisy ones),
                             zip-all (deflate every chunk: smallest file, slower) or none
          --models DIR       a folder to search for mesh files (after the scene's folder, before $SPECTRAL_MODELS)
          --quiet            no progress or summary on stderr
          --crop X0,Y0,X1,Y1 render only film columns X0…X1−1 and rows Y0…Y1−1: every file holds the crop
                             (EXR data window inside the full display window; "crop" in render.json)
          --shard I/N        render strip I (from 0) of N: whole 32-row tile strips, full width; `spectral merge`
                             assembles the N folders into the whole render, byte for byte. Without --shard, a job
                             array task takes I and N from SLURM_ARRAY_TASK_ID/_MIN/_MAX/_STEP (or _COUNT),
                             JOB_COMPLETION_INDEX (Kubernetes, with --shards N) or AWS_BATCH_JOB_ARRAY_INDEX/_SIZE;
                             --shard none renders the whole film even there
          --shards N         the shard count where the scheduler gives none (Kubernetes Indexed Jobs)
          --integrator NAME  the integrator by its registered name (default: whitted, the paper's eq. 2 with
                             Whitted recursion)
        """;

    static readonly string[] Values = ["-o", "--out", "--width", "--height", "--bands", "--band-range", "--wave", "--spp", "--target-error", "--threads", "--rgb", "--integration", "--formats", "--exr-compression", "--models", "--crop", "--shard", "--shards", "--integrator"];

    [MethodImpl(MethodImplOptions.NoOptimization)]  // runs once: cheap compilation matters more than speed
    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("render", argv, Values, ["--quiet"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        JitWarmup.Start(JitWarmup.Render);   // the hot loops compile on the other core while the scene loads
        if (a.Positionals.Count != 1) throw new InputException("command line", a.Positionals.Count == 0 ? "no scene file given" : $"unexpected argument {MessageText.Quote(a.Positionals[1])}", "usage: spectral render SCENE.json -o OUTDIR");
        var scenePath = a.Positionals[0];
        bool fromStdin = scenePath == SceneLoader.StandardInput;
        var outDir = a.Value("--out") ?? Path.Combine("out", fromStdin ? "stdin" : Path.GetFileNameWithoutExtension(scenePath));
        if (string.IsNullOrWhiteSpace(outDir)) throw new InputException("-o", "the output folder name is empty", "give a folder name, e.g. -o out/scene");
        int? threads = a.Int("--threads", 1, 1024);
        bool quiet = a.Flag("--quiet");

        byte[]? text = null;
        byte[] Text() => text ??= fromStdin ? SceneLoader.ReadAll(Console.OpenStandardInput()) : InputFile.ReadAllBytes(scenePath, "scene file");
        var overrides = Overrides(a, Text);   // options are checked before the scene is read
        // --formats may also name registered products beyond the scene's (OutputProductTable.Register): those go to the request.
        var registered = SplitFormats(a.Value("--formats")).Registered;
        var request = new RenderRequest
        {
            ScenePath = scenePath,
            Overrides = overrides,
            Products = registered,
            Integrator = a.Value("--integrator"),
            Region = Region(a),
            Threads = threads ?? 0,
            OutDir = outDir,
            Run = new ManifestRun { CommandLine = "spectral render " + string.Join(' ', argv) },
        };
        request = request with { SceneText = text ?? (fromStdin ? Text() : null) };
        var job = RenderJob.Load(request, new RenderObserver(Warning: stderr.WriteLine));
        if (Integrators.Entry(job.IntegratorName)?.WarmedUp != true) JitWarmup.Stop();   // its hot loops are not the ones warmed up

        // SIGINT and SIGTERM (Signals, answered from the command's start) stop the render at the next pixel (and the
        // writers at the next file): the staged files are removed, the output folder keeps what it held, and the message says so.
        var progress = quiet ? null : ProgressBar.For(stderr);
        job.Execute(new RenderObserver(Progress: progress is null ? null : progress.Report, StoppedAfter: Signals.StoppedAfter), Signals.Token);
        progress?.Finish();
        var result = job.Result!;
        var scene = job.Scene;
        if (result.Rays.OverBudgetRays > 0)
            stderr.WriteLine(MessageText.Line($"spectral render: warning: {result.Rays.OverBudgetRays} camera rays reached the ray budget of {scene.RayBudget} rays; their deepest reflections and refractions are missing",
                " (hint: raise \"ray_budget\", or lower \"max_depth\" or raise \"min_ray_weight\" in the scene)"));
        if (!quiet)
        {
            double secs = result.Elapsed.TotalSeconds;
            int triangles = job.Geometry?.TriangleCount ?? 0;
            stderr.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"rendered {result.Image.Width}×{result.Image.Height}{(job.Crop is { } c ? $" (film {scene.Camera.Width}×{scene.Camera.Height}, crop {c}{(job.Shard is null ? "" : $", shard {job.Shard}")})" : "")}, {scene.Grid.Count} bands ({scene.Grid}), {scene.Camera.SamplesPerPixel} spp{(triangles > 0 ? $", {triangles:N0} triangles ({job.DegenerateTriangles} degenerate skipped)" : "")} in {secs:0.###} s ({result.Rays.Total / Math.Max(secs, 1e-9) / 1e6:0.##} Mrays/s, {result.Threads} threads); wrote {job.Files.Count} files to {outDir} in {job.WriteSeconds:0.##} s"));
        }
        return CommandLine.Success;
    }

    /// <summary>The film pixels to render (null: all) from --crop, --shard or a job array's variables, and the shard's description.</summary>
    static RenderRegion? Region(Arguments a)
    {
        string? crop = a.Value("--crop"), shard = a.Value("--shard");
        int? shards = a.Int("--shards", 1, 1 << 20);
        if (crop is not null && shard is not null) throw new InputException("--crop", "cannot be combined with --shard", "a shard is a crop: give one of them");
        if (crop is not null) return RenderRegion.Crop(crop);
        if (shard == "none") return null;
        if (shard is not null)
        {
            var s = Distributed.Shard.Parse(shard);
            if (shards is { } n && n != s.Count) throw new InputException("--shards", $"{n} disagrees with --shard {shard}", "give --shard I/N alone, or --shards N equal to its N");
            return new RenderRegion(s.Strip, $"{s} (--shard)");
        }
        if (Distributed.SchedulerEnvironment.Resolve(shards) is { } env)
            return new RenderRegion(env.Shard.Strip, $"{env.Shard} ({env.Source})");
        if (shards is not null) throw new InputException("--shards", "is given but no job array variable is set", "use --shard I/N outside a job array");
        return null;
    }

    [MethodImpl(MethodImplOptions.NoOptimization)]  // runs once: cheap compilation matters more than speed
    public static SceneOverrides Overrides(Arguments a, string scenePath) => Overrides(a, () => InputFile.ReadAllBytes(scenePath, "scene file"));

    /// <summary>The command-line overrides; <paramref name="sceneText"/> is read only for a bare band count (which keeps the scene's range).</summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]  // runs once: cheap compilation matters more than speed
    public static SceneOverrides Overrides(Arguments a, Func<byte[]> sceneText)
    {
        string? bands = a.Value("--band-range") ?? a.Value("--bands");
        string? wave = a.Value("--wave");
        if (bands is not null && wave is not null)
            throw new InputException("--wave", "--wave and --bands both give the bands", "use one: --wave 400:10:700 (centres) or --bands 395:705:31 (edges)");
        if (bands is not null && !bands.Contains(':'))
        {
            if (!int.TryParse(bands, NumberStyles.Integer, CultureInfo.InvariantCulture, out int n) || n < 1 || n > Spectra.BandGrid.MaxBands)
                throw new InputException("--bands", $"'{bands}' is neither a band count nor a grid start:end:count", "e.g. --bands 40, --bands 395:705:31 (edges) or --wave 400:10:700 (centres)");
            // A count keeps the scene's range: peek at it without loading the scene twice.
            var range = SceneRange(sceneText());
            bands = string.Create(CultureInfo.InvariantCulture, $"{range.Start}:{range.End}:{n}");
        }
        if (bands is not null) Spectra.BandGrid.Parse(bands, a.Value("--band-range") is not null ? "--band-range" : "--bands");  // reported under the option given
        var models = a.Values("--models").ToList();
        foreach (var m in models)
            if (!Directory.Exists(m)) throw new InputException("--models", $"folder {MessageText.Quote(m, 120)} does not exist", "pass the folder that holds the mesh files");
        return new SceneOverrides
        {
            Width = a.Int("--width", int.MinValue, int.MaxValue),
            Height = a.Int("--height", int.MinValue, int.MaxValue),
            Bands = bands,
            Wave = wave,
            SamplesPerPixel = a.Int("--spp", 1, 65536),
            TargetError = TargetError(a),
            Rgb = a.Value("--rgb"),
            Integration = a.Value("--integration"),
            Formats = SplitFormats(a.Value("--formats")).Formats,
            ExrCompression = a.Value("--exr-compression"),
            ModelDirectories = models,
        };
    }

    /// <summary>--target-error: a relative standard error in (0, 1).</summary>
    static double? TargetError(Arguments a)
    {
        var e = a.Double("--target-error");
        if (e is { } v && !(v > 0 && v < 1))
            throw new InputException("--target-error", $"{v.ToString(CultureInfo.InvariantCulture)} is not a relative error between 0 and 1",
                "e.g. --target-error 0.01 (1 % standard error of each pixel's luminance)");
        return e;
    }

    /// <summary>
    /// The --formats list parted into the scene's own product names (null: none given, or only registered ones — the
    /// scene's formats then apply) and the names of products registered without a scene flag.
    /// </summary>
    static (string? Formats, string[] Registered) SplitFormats(string? formats)
    {
        if (formats is null) return (null, []);
        var extra = OutputProductTable.All.Where(p => p.Flag == OutputProducts.None).Select(p => p.Name).ToHashSet(StringComparer.Ordinal);
        var names = formats.Split(',', StringSplitOptions.TrimEntries);
        string[] registered = [.. names.Where(extra.Contains)];
        if (registered.Length == 0) return (formats, []);
        var own = names.Where(n => !extra.Contains(n)).ToArray();
        return (own.Length == 0 ? null : string.Join(',', own), registered);
    }

    static Spectra.BandGrid SceneRange(byte[] sceneText)
    {
        try
        {
            var node = JsonNode.Parse(sceneText, documentOptions: new System.Text.Json.JsonDocumentOptions
            {
                CommentHandling = System.Text.Json.JsonCommentHandling.Skip,
                AllowTrailingCommas = true,
                AllowDuplicateProperties = false,   // a key twice: the loader reports it with its place (an object with one broke here)
            });
            if (node?["wave"]?.GetValue<string>() is { } w) return Spectra.BandGrid.ParseWave(w);
            if (node?["bands"]?.GetValue<string>() is { } g) return Spectra.BandGrid.Parse(g);
        }
        catch (Exception e) when (e is System.Text.Json.JsonException or InvalidOperationException or InputException) { /* the loader reports it */ }
        return Spectra.BandGrid.Default;
    }

    /// <summary>Creates the output folder, or says in one line why it cannot be used.</summary>
    public static void PrepareOutputFolder(string outDir)
    {
        if (File.Exists(outDir)) throw new InputException(outDir, "exists and is a file, not a folder", "choose another -o");
        try
        {
            Directory.CreateDirectory(outDir);
            var probe = Path.Combine(outDir, $".write-test-{Environment.ProcessId}");
            File.WriteAllBytes(probe, []);
            File.Delete(probe);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            string reason = e is PathTooLongException ? "the path is too long" : e.Message.Replace(Path.GetFullPath(outDir), "it").Replace(outDir, "it");
            throw new InputException(outDir, $"cannot be written: {reason}", "choose a folder you can write to");
        }
    }
}
