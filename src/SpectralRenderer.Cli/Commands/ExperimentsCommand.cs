using System.Diagnostics;
using System.Globalization;
using SpectralRenderer.Analysis;
using SpectralRenderer.Cli.Paper;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral experiments`: every scene of the paper rendered, analysed and reported in report.html.</summary>
public static class ExperimentsCommand
{
    const string Help = """
        usage: spectral experiments [--out DIR] [--scale F] [--spp N] [--scenes DIR] [--models DIR] [--threads N]
                                    [--gi-spp N] [--no-gi] [--quiet]

        Renders every scene of the paper — §3.1 the ColorChecker, §3.2 four bunnies, §3.3 the statue under
        A, D65, blue and green LEDs, §3.4 the analysis bunny — and writes DIR/report.html: one self-contained
        page reproducing Figs. 2–7 with the ΔE00 table, the probed spectra, the white-board reconstruction
        and its per-region metrics, and the run's timings. Each scene's outputs go to DIR/<scene>/.
        Scenes whose mesh is not found are reported as skipped.

          --out DIR      output folder (default: out/experiments)
          --scale F      multiply every scene's resolution (default 1; e.g. 0.5 for a quick run)
          --spp N        samples per pixel for every scene (default: each scene's own, 4 for §3.2–3.4, anti-aliased)
          --scenes DIR   where the paper-*.json scenes are (default: the repository's scenes/)
          --models DIR   a folder to search for the meshes (also $SPECTRAL_MODELS)
          --gi-spp N     samples per pixel of the direct and path renders that compare direct light with global
                         illumination for one scene per section (DIR/gi/, default 16)
          --no-gi        leave that comparison out
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("experiments", argv, ["--out", "-o", "--scale", "--spp", "--scenes", "--models", "--threads", "--gi-spp"],
            ["--quiet", "--no-gi"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count > 0)
            throw new InputException("command line", $"unexpected argument {MessageText.Quote(a.Positionals[0])}",
                "see 'spectral experiments --help'");
        var outDir = a.Value("--out") ?? Path.Combine("out", "experiments");
        double scale = a.Double("--scale") ?? 1;
        if (scale <= 0 || scale > 8)
            throw new InputException("--scale", $"{scale.ToString(CultureInfo.InvariantCulture)} is outside (0, 8]",
                "e.g. --scale 0.5 for half the paper's resolution");
        var sceneDir = a.Value("--scenes") ?? FindScenes();
        if (!Directory.Exists(sceneDir))
            throw new InputException("--scenes", $"folder {MessageText.Quote(sceneDir, 120)} does not exist",
                "pass the repository's scenes/ folder");
        var models = a.Values("--models").ToList();
        foreach (var m in models)
            if (!Directory.Exists(m))
                throw new InputException("--models", $"folder {MessageText.Quote(m, 120)} does not exist",
                    "pass the folder that holds the mesh files");
        int threads = a.Int("--threads", 1, 1024) ?? Environment.ProcessorCount;
        int? spp = a.Int("--spp", 1, 65536);
        bool quiet = a.Flag("--quiet");
        RenderCommand.PrepareOutputFolder(outDir);

        var clock = Stopwatch.StartNew();
        // The report's slow sections start as soon as their scene is written, while the other scenes render.
        var prepared = new Dictionary<string, Task<string>>();
        var runs = PaperExperiments.Run(sceneDir, outDir, scale, models, threads, quiet ? null : stderr.WriteLine, spp,
            written: r => { if (PaperReport.Prepare(r) is { } section) prepared[r.Name] = section; });
        // Direct light against global illumination, one scene per section (gi/), at the same scale.
        var gi = a.Flag("--no-gi") ? null
            : GlobalIlluminationComparison.Run(sceneDir, outDir, scale, models, threads, a.Int("--gi-spp", 1, 65536) ?? 16,
                log: quiet ? null : stderr.WriteLine);
        var report = PaperReport.Write(outDir, runs, clock.Elapsed.TotalSeconds, prepared, gi);
        int skipped = runs.Count(r => !r.Done);
        stdout.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"{runs.Count - skipped} of {runs.Count} scenes rendered in {clock.Elapsed.TotalSeconds:0.0} "
                + $"s{(skipped > 0 ? $" ({skipped} skipped: mesh not found)" : "")}; report: {report}"));
        return CommandLine.Success;
    }

    static string FindScenes()
    {
        foreach (var root in new[] { Directory.GetCurrentDirectory(), AppContext.BaseDirectory })
            for (var d = new DirectoryInfo(root); d is not null; d = d.Parent)
            {
                var p = Path.Combine(d.FullName, "scenes");
                if (File.Exists(Path.Combine(p, "paper-3.1-colorchecker-d65.json"))) return p;
            }
        throw new InputException("experiments", "the paper's scenes were not found", "run from the repository or pass --scenes DIR");
    }
}
