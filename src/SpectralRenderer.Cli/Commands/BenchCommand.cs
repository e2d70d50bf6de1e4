using System.Diagnostics;
using System.Globalization;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral bench`: load, BVH build and render times, rays and Mrays/s, peak working set.</summary>
public static class BenchCommand
{
    const string Help = """
        usage: spectral bench [SCENE] [--width W] [--height H] [--repeat N] [--threads N] [--bands N|S:E:N | --wave S:STEP:E]
                              [--band-range S:E:N] [--spp N] [--rgb MODE] [--integration S] [--formats LIST]
                              [--models DIR] [--integrator NAME]

        Measures a scene (default: scenes/paper-3.2-bunny-14.json at 1024 × 1024): scene and mesh load,
        BVH build, and the render itself (median of N repeats, after one warm-up), with the rays traced
        (primary, shadow, secondary), Mrays/s and the process's peak working set. Writes no files.
        Prints a table and one machine-readable line starting with "bench:".
        """;

    /// <summary>The render options bench takes (RenderOptions' table): what shapes the scene and the integrator.</summary>
    static readonly RenderOption[] Shared = [.. RenderOptions.All.Where(o => o.Name is "width" or "height" or "threads" or "bands"
        or "band-range" or "wave" or "spp" or "models" or "rgb" or "integration" or "formats" or "integrator")];

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("bench", argv, ["--repeat", .. Shared.Select(o => o.Flag)], []);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count > 1)
            throw new InputException("command line", $"unexpected argument {MessageText.Quote(a.Positionals[1])}",
                "usage: spectral bench [SCENE]");
        var scenePath = a.Positionals.Count == 1 ? a.Positionals[0] : DefaultScene();
        int repeat = a.Int("--repeat", 1, 1000) ?? 5;
        int threads = a.Int("--threads", 1, 1024) ?? Environment.ProcessorCount;
        var options = RenderOptions.Parse(a.Given(Shared), () => InputFile.ReadAllBytes(scenePath, "scene file"));
        var overrides = options.Overrides with
        {
            Width = a.Int("--width", 1, SceneLoader.MaxResolution) ?? (a.Positionals.Count == 0 ? 1024 : null),
            Height = a.Int("--height", 1, SceneLoader.MaxResolution) ?? (a.Positionals.Count == 0 ? 1024 : null),
        };

        var job = RenderJob.Load(new RenderRequest
        {
            ScenePath = scenePath,
            Overrides = overrides,
            Integrator = options.Integrator,
            Threads = threads,
        });
        var scene = job.Scene;
        double load = job.LoadSeconds;
        job.Build();   // as `render` does: the loader's garbage returned
        double build = job.BuildSeconds;

        job.Render();   // warm-up: JIT and caches
        var times = new List<double>();
        RenderResult? last = null;
        for (int i = 0; i < repeat; i++)
        {
            job.ReleaseResult();
            GC.Collect();
            last = job.Render();
            times.Add(last.Elapsed.TotalSeconds);
        }
        times.Sort();
        double median = times.Count % 2 == 1 ? times[times.Count / 2] : 0.5 * (times[times.Count / 2 - 1] + times[times.Count / 2]);
        var rays = last!.Rays;
        double mrays = rays.Total / median / 1e6;
        long peak = Process.GetCurrentProcess().PeakWorkingSet64;
        var inv = CultureInfo.InvariantCulture;
        int tris = job.Geometry!.TriangleCount;
        double bytesPerTriangle = job.Geometry.TriangleBytesPerTriangle;

        stdout.WriteLine($"scene            {scenePath}");
        stdout.WriteLine(string.Create(inv,
            $"image            {scene.Camera.Width} × {scene.Camera.Height}, {scene.Bands} bands ({scene.Grid}), "
                + $"{scene.Camera.SamplesPerPixel} spp, {threads} threads"));
        stdout.WriteLine(string.Create(inv, $"triangles        {tris:N0}"));
        stdout.WriteLine(string.Create(inv, $"load (+meshes)   {load:0.000} s"));
        stdout.WriteLine(string.Create(inv, $"BVH build        {build:0.000} s"));
        stdout.WriteLine(
            string.Create(inv, $"triangle memory  {bytesPerTriangle:0.0} bytes/triangle (corners, binary and wide BVH, indices)"));
        stdout.WriteLine(
            string.Create(inv, $"render median    {median:0.0000} s  (min {times[0]:0.0000}, max {times[^1]:0.0000}, {repeat} runs)"));
        stdout.WriteLine(string.Create(inv,
            $"rays             {rays.Total:N0} (primary {rays.Primary:N0}, shadow {rays.Shadow:N0}, secondary {rays.Secondary:N0})"));
        stdout.WriteLine(string.Create(inv, $"throughput       {mrays:0.00} Mrays/s"));
        stdout.WriteLine(string.Create(inv,
            $"peak working set {peak / 1048576.0:0.0} MB (framebuffer "
                + $"{(long)scene.Camera.Width * scene.Camera.Height * scene.Bands * 4 / 1048576.0:0.0} MB)"));
        stdout.WriteLine(string.Create(inv,
            $"bench: scene={Path.GetFileName(scenePath)} width={scene.Camera.Width} height={scene.Camera.Height} bands={scene.Bands} "
                + $"spp={scene.Camera.SamplesPerPixel} threads={threads} triangles={tris} load_s={load:0.0000} build_s={build:0.0000} "
                + $"render_s={median:0.0000} rays={rays.Total} primary={rays.Primary} shadow={rays.Shadow} secondary={rays.Secondary} "
                + $"mrays_per_s={mrays:0.00} peak_ws_mb={peak / 1048576.0:0.0} bytes_per_triangle={bytesPerTriangle:0.0}"));
        return CommandLine.Success;
    }

    static string DefaultScene()
    {
        foreach (var root in new[] { Directory.GetCurrentDirectory(), AppContext.BaseDirectory })
            for (var d = new DirectoryInfo(root); d is not null; d = d.Parent)
            {
                var p = Path.Combine(d.FullName, "scenes", "paper-3.2-bunny-14.json");
                if (File.Exists(p)) return p;
            }
        throw new InputException("bench", "the default scene scenes/paper-3.2-bunny-14.json was not found", "name a scene file");
    }
}
