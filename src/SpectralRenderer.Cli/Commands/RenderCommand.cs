using System.Globalization;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Output;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral render SCENE.json -o OUTDIR`: load, render in tiles on all cores, write the outputs.</summary>
public static class RenderCommand
{
    /// <summary>`spectral render --help`: the command's own options, then the render options' table (RenderOptions).</summary>
    public static string Help => Usage() + "\n\n" + """
        Renders a scene file (docs/scene-format.md) with the paper's eq. 2 in every band and writes:
          preview.png        8-bit sRGB (or eq. 4 with --rgb paper)
          bands/             one 16-bit greyscale PNG per band on a common scale, and bands.png (Fig. 2)
          spectral.exr       all bands, spectral OpenEXR layout (S0.<λ>nm channels) + R G B + X Y Z
          spectral.hdr/.img  ENVI cube, BSQ float32, wavelengths in nm
          spectral.npy       H × W × N float32 NumPy array, with wavelengths.csv
          object-id.png      16-bit id of the object seen at each pixel (0 = background; ids in render.json)
          render.json        resolved scene, band edges, κ, white point, timings, ray counts, version

          SCENE.json            the scene; - reads it from standard input (relative paths then resolve
                                from the working folder)
          -o, --out DIR         output folder (default: out/<scene file name>, out/stdin for -)
          --quiet               no progress or summary on stderr

        Bands are numbered from 1 (the first band is band 1) in every file and table a person reads.

        Render options (the same in libspectral's options JSON and as Python's render(scene, **options) keywords, with
        '_' for '-': target_error, exr_compression, …):

        """ + RenderOptions.HelpLines(RenderOptions.All).TrimEnd('\n');

    /// <summary>The usage line: the command's own options, then every render option, wrapped under the first.</summary>
    static string Usage()
    {
        const string head = "usage: spectral render SCENE.json|- [-o OUTDIR] [--quiet]";
        var lines = new List<string> { head };
        foreach (var o in RenderOptions.All)
        {
            string item = $" [{o.Flag} {o.Value}]";
            if (lines[^1].Length + item.Length > 116) lines.Add(new string(' ', "usage: spectral render".Length));
            lines[^1] += item;
        }
        return string.Join('\n', lines);
    }

    /// <summary>The command's own options (-o, --quiet) and the render options' flags.</summary>
    static string[] Values => ["-o", "--out", .. RenderOptions.All.Select(o => o.Flag)];

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("render", argv, Values, ["--quiet"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        JitWarmup.Start(JitWarmup.Render);   // the hot loops compile on the other core while the scene loads
        if (a.Positionals.Count != 1)
            throw new InputException("command line",
                a.Positionals.Count == 0 ? "no scene file given" : $"unexpected argument {MessageText.Quote(a.Positionals[1])}",
                "usage: spectral render SCENE.json -o OUTDIR");
        var scenePath = a.Positionals[0];
        bool fromStdin = scenePath == SceneLoader.StandardInput;
        var outDir = a.Value("--out") ?? Path.Combine("out", fromStdin ? "stdin" : Path.GetFileNameWithoutExtension(scenePath));
        if (string.IsNullOrWhiteSpace(outDir))
            throw new InputException("-o", "the output folder name is empty", "give a folder name, e.g. -o out/scene");
        bool quiet = a.Flag("--quiet");

        byte[]? text = null;
        byte[] Text() => text ??=
            fromStdin ? SceneLoader.ReadAll(Console.OpenStandardInput()) : InputFile.ReadAllBytes(scenePath, "scene file");
        var options = RenderOptions.Parse(a.Given(RenderOptions.All), Text);   // options are checked before the scene is read
        var request = options.Request(scenePath, ShardRegion.Of(options, jobArray: true)) with
        {
            OutDir = outDir,
            Run = new ManifestRun { CommandLine = "spectral render " + string.Join(' ', argv) },
        };
        request = request with { SceneText = text ?? (fromStdin ? Text() : null) };
        var job = RenderJob.Load(request, new RenderObserver(Warning: stderr.WriteLine));
        if (Integrators.Entry(job.IntegratorName)?.WarmedUp != true) JitWarmup.Stop();   // its hot loops are not the ones warmed up

        // SIGINT and SIGTERM (Signals, answered from the command's start) stop the render at the next pixel (and the
        // writers at the next file): the staged files are removed, the output folder keeps what it held, and the message says so.
        var progress = quiet ? null : ProgressBar.For(stderr);
        job.Execute(new RenderObserver(Progress: progress is null ? null : progress.Report, StoppedAfter: Signals.StoppedAfter),
            Signals.Token);
        progress?.Finish();
        var result = job.Result!;
        var scene = job.Scene;
        if (result.Rays.OverBudgetRays > 0)
            stderr.WriteLine(MessageText.Line($"spectral render: warning: {result.Rays.OverBudgetRays} camera rays reached the ray budget "
                + $"of {scene.RayBudget} rays; their deepest reflections and refractions are missing",
                " (hint: raise \"ray_budget\", or lower \"max_depth\" or raise \"min_ray_weight\" in the scene)"));
        if (!quiet)
        {
            double secs = result.Elapsed.TotalSeconds;
            int triangles = job.Geometry?.TriangleCount ?? 0;
            string shard = job.Shard is null ? "" : $", shard {job.Shard}";
            string crop = job.Crop is { } c ? $" (film {scene.Camera.Width}×{scene.Camera.Height}, crop {c}{shard})" : "";
            string mesh = triangles > 0 ? $", {triangles:N0} triangles ({job.DegenerateTriangles} degenerate skipped)" : "";
            // Adaptive sampling: the samples each pixel took, not the cap.
            string spp = result.SamplesUsed is { Length: > 0 } used
                ? string.Create(CultureInfo.InvariantCulture,
                    $"{used.Min()}–{used.Max()} spp (mean {used.Average(u => (double)u):0.#}, cap {scene.Camera.SamplesPerPixel})")
                : $"{scene.Camera.SamplesPerPixel} spp";
            stderr.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"rendered {result.Image.Width}×{result.Image.Height}{crop}, {scene.Grid.Count} bands ({scene.Grid}), "
                    + $"{spp}{mesh} in {secs:0.###} s "
                    + $"({result.Rays.Total / Math.Max(secs, 1e-9) / 1e6:0.##} Mrays/s, {result.Threads} threads); "
                    + $"wrote {job.Files.Count} files to {outDir} in {job.WriteSeconds:0.##} s"));
        }
        return CommandLine.Success;
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
            string reason = e is PathTooLongException
                ? "the path is too long"
                : e.Message.Replace(Path.GetFullPath(outDir), "it").Replace(outDir, "it");
            throw new InputException(outDir, $"cannot be written: {reason}", "choose a folder you can write to");
        }
    }
}
