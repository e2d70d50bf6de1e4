using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral merge SHARD_DIR… -o OUTDIR`: the shards of a render assembled into the whole render's folder.</summary>
public static class MergeCommand
{
    public const string Help = """
        usage: spectral merge SHARD_DIR… -o OUTDIR [--quiet]

        Assembles the folders of `spectral render SCENE --shard I/N` (any order) into the folder one process would
        have written: every file byte for byte; render.json too but for created_utc, timings_s, rays.mrays_per_s, threads and
        run, which describe the runs. The cubes are streamed (ENVI by offset, NPY by rows, OpenEXR chunk by chunk);
        the band images are rescaled to the whole image's brightest band value. Refuses, naming the folder: shards of
        different scenes or settings (scene_hash), missing or overlapping rows, half-written shards (no render.json,
        listed files missing or short).

          -o, --out DIR      the merged render folder (created; a previous render's files in it are replaced)
          --quiet            no summary on stderr
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("merge", argv, ["-o", "--out"], ["--quiet"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        var outDir =
            a.Value("--out") ?? throw new InputException("", "no output folder given", "usage: spectral merge SHARD_DIR… -o OUTDIR");
        if (a.Positionals.Count == 0) throw new InputException("", "no shard folders given", "usage: spectral merge SHARD_DIR… -o OUTDIR");
        RenderCommand.PrepareOutputFolder(outDir);
        var clock = System.Diagnostics.Stopwatch.StartNew();
        List<string> files;
        // SIGINT/SIGTERM (Signals) stop the merge at the next file or chunk; its staging is removed, OUTDIR keeps what it held.
        try { files = ShardMerge.Merge(a.Positionals, outDir, "spectral merge " + string.Join(' ', argv), Signals.Token); }
        catch (OperationCanceledException e) when (e is not InterruptedException)
        {
            throw new InterruptedException($"interrupted by {Signals.Signal} while merging{Signals.StoppedAfter()}: the merged files were "
                + $"not swapped in; {outDir} holds what it held",
                e.CancellationToken);
        }
        if (!a.Flag("--quiet"))
            stderr.WriteLine($"merged {a.Positionals.Count} shards into {outDir}: {files.Count} files in {clock.Elapsed.TotalSeconds:0.##} "
                + $"s, peak working set {System.Diagnostics.Process.GetCurrentProcess().PeakWorkingSet64 / 1048576.0:0} MiB");
        return CommandLine.Success;
    }
}
