using System.Runtime.CompilerServices;
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

    [MethodImpl(MethodImplOptions.NoOptimization)]  // runs once: cheap compilation matters more than speed
    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("merge", argv, ["-o", "--out"], ["--quiet"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        var outDir = a.Value("--out") ?? throw new InputException("", "no output folder given", "usage: spectral merge SHARD_DIR… -o OUTDIR");
        if (a.Positionals.Count == 0) throw new InputException("", "no shard folders given", "usage: spectral merge SHARD_DIR… -o OUTDIR");
        RenderCommand.PrepareOutputFolder(outDir);
        using var cancel = new CancellationTokenSource();
        ConsoleCancelEventHandler onCancel = (_, e) => { e.Cancel = true; cancel.Cancel(); };
        Console.CancelKeyPress += onCancel;
        try
        {
            var clock = System.Diagnostics.Stopwatch.StartNew();
            var files = ShardMerge.Merge(a.Positionals, outDir, "spectral merge " + string.Join(' ', argv), cancel.Token);
            if (!a.Flag("--quiet")) stderr.WriteLine($"merged {a.Positionals.Count} shards into {outDir}: {files.Count} files in {clock.Elapsed.TotalSeconds:0.##} s, peak working set {System.Diagnostics.Process.GetCurrentProcess().PeakWorkingSet64 / 1048576.0:0} MiB");
            return CommandLine.Success;
        }
        finally { Console.CancelKeyPress -= onCancel; }
    }
}
