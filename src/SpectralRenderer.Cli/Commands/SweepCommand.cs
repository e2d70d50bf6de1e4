using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral sweep PLAN.json`: a plan's jobs rendered into a dataset with an index, locally or as a job array.</summary>
public static class SweepCommand
{
    public const string Help = """
        usage: spectral sweep PLAN.json [-o OUTDIR] [--shard I/N | --shards N] [--layout folders|pairs]
                                        [--formats LIST] [--threads N] [--models DIR] [--quiet]
               spectral sweep PLAN.json --emit slurm|k8s [-o OUTDIR] [--shards N] [--image IMAGE]

        Renders every job of a sweep plan (docs/sweep-format.md: a base scene and axes of scene edits whose product
        is the job list, plus extra jobs) into OUTDIR/jobs/ID/ — a render folder with the job's scene.json and job.json
        (status, seconds, parameters) — and writes the dataset index OUTDIR/index.csv and OUTDIR/index.jsonl (job id,
        status done/failed/pending, seconds, path, one column per axis). Jobs run one after another, each on all cores.
        A rerun skips finished jobs (same scene and formats), so an interrupted or pre-empted run resumes; a job
        interrupted midway left no job.json and runs again.

          -o, --out DIR      the dataset folder (default: out/<plan name>)
          --shard I/N        run slice I (from 0) of N: the jobs whose number mod N is I. Without it, a job array task
                             takes I and N from SLURM_ARRAY_TASK_ID/_MIN/_MAX/_STEP (or _COUNT), JOB_COMPLETION_INDEX
                             (Kubernetes, with --shards N) or AWS_BATCH_JOB_ARRAY_INDEX/_SIZE; --shard none runs all
          --shards N         the slice count where the scheduler gives none; with --emit, the array's task count
                             (default: one task per job)
          --layout pairs     also OUTDIR/cube/ID.npy and OUTDIR/rgb/ID.png for each job (cube + RGB pairs, as the
                             spectral-recovery challenges use; adds npy and png to the formats)
          --formats LIST     the render formats of every job (default: the plan's "formats", else the scene's)
          --threads N        worker threads of each render (default: all cores)
          --models DIR       a folder to search for mesh files
          --emit slurm       write OUTDIR/sweep.sbatch, an sbatch array script running this plan (sbatch it)
          --emit k8s         write OUTDIR/sweep-job.yaml, a Kubernetes Indexed Job running it (--image: the image
                             with spectral on its PATH; the plan and OUTDIR on a shared volume at the same paths)
          --quiet            no progress or summary on stderr
        """;

    static readonly string[] Values =
        ["-o", "--out", "--shard", "--shards", "--layout", "--formats", "--threads", "--models", "--emit", "--image"];

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("sweep", argv, Values, ["--quiet"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("", a.Positionals.Count == 0 ? "no sweep plan given" : $"unexpected argument '{a.Positionals[1]}'",
                "usage: spectral sweep PLAN.json -o OUTDIR");
        var planPath = a.Positionals[0];
        var outDir = a.Value("--out") ?? Path.Combine("out", Path.GetFileNameWithoutExtension(planPath));
        string layout = a.Value("--layout") ?? "folders";
        if (!SweepRunner.Layouts.Contains(layout))
            throw new InputException("--layout", $"'{layout}' is not a layout", "folders (default) or pairs");
        int? shards = a.Int("--shards", 1, 1 << 20);
        bool quiet = a.Flag("--quiet");
        var models = a.Values("--models").Select(Path.GetFullPath).ToList();
        foreach (var m in models)
            if (!Directory.Exists(m))
                throw new InputException("--models", $"folder '{m}' does not exist", "pass the folder that holds the mesh files");
        var plan = SweepPlan.Load(planPath);

        if (a.Value("--emit") is { } emit)
        {
            int tasks = shards ?? plan.Jobs.Count;
            RenderCommand.PrepareOutputFolder(outDir);
            // The array runs every job: each one's scene is checked now, before anything is submitted.
            plan.CheckJobs(plan.Jobs, new SceneOverrides { Formats = a.Value("--formats"), ModelDirectories = models }, outDir);
            var file = emit switch
            {
                "slurm" => EmitSlurm(plan, outDir, tasks, layout, a, models),
                "k8s" => EmitKubernetes(plan, outDir, tasks, layout, a, models),
                _ => throw new InputException("--emit", $"'{emit}' is not a scheduler", "slurm or k8s"),
            };
            if (!quiet) stderr.WriteLine($"wrote {file}: {plan.Jobs.Count} jobs in {tasks} array tasks");
            return CommandLine.Success;
        }

        Shard slice;
        string? sliceText = a.Value("--shard");
        if (sliceText == "none") slice = new Shard(0, 1);
        else if (sliceText is not null) slice = Shard.Parse(sliceText);
        else slice = SchedulerEnvironment.Resolve(shards)?.Shard ?? (shards is null ? new Shard(0, 1)
            : throw new InputException("--shards", "is given but no job array variable is set", "use --shard I/N outside a job array"));

        RenderCommand.PrepareOutputFolder(outDir);
        var overrides = new SceneOverrides { Formats = a.Value("--formats"), ModelDirectories = models };
        // SIGINT/SIGTERM (Signals; SIGTERM is what Slurm sends on pre-emption) stop the running job's render at its next
        // pixel; the index is rebuilt from the job records whichever way the run ends, a forced stop included.
        var cancel = Signals.Token;
        Signals.ExpectCommits(int.MaxValue);   // finished only when its index says so
        Signals.OnForcedStop(() => SweepRunner.WriteIndex(plan, outDir, layout == "pairs" ? "pairs" : "folders"));
        Signals.DescribeLeft(() => $"finished jobs are kept and listed in {Path.Combine(outDir, "index.csv")} (rebuilt); the running job "
            + $"left nothing under a final name; run the same command again to resume");
        // One sweep at a time on a dataset: a second one exits 2 naming the folder (the jobs' folders are locked each too).
        // The slices of one job array share it by design (disjoint jobs; the index rebuilt one slice at a time).
        using var dataset = slice.Count > 1 ? null : OutputFolder.BeginFiles(outDir, ["index.csv", "index.jsonl"], "sweep index");
        {
            bool terminal = ReferenceEquals(stderr, Console.Error) && !Console.IsErrorRedirected;
            Action<SweepProgress>? progress = quiet ? null : p =>
            {
                double f = (double)p.Finished / p.Jobs, secs = p.Elapsed.TotalSeconds;
                int filled = (int)(f * 30);
                string line = string.Create(CultureInfo.InvariantCulture,
                    $"[{new string('#', filled)}{new string('.', 30 - filled)}] {p.Finished}/{p.Jobs} jobs  job {p.Job.Id} {p.Status} "
                        + $"{p.Seconds:0.0} s  "
                        + $"({string.Join(", ", p.Job.Parameters.Where(x => x.Label.Length > 0).Select(x => $"{x.Axis}={x.Label}"))})  ETA "
                        + $"{(f > 0 ? secs / f - secs : 0):0} s");
                if (terminal) stderr.Write("\r" + line.PadRight(110)[..Math.Max(110, line.Length)]);
                else stderr.WriteLine(line);
            };
            SweepSummary s;
            try { s = SweepRunner.Run(plan, outDir, slice, overrides, layout, a.Int("--threads", 1, 1024) ?? 0, progress, cancel); }
            catch (OperationCanceledException)
            {
                if (terminal && !quiet) stderr.WriteLine();
                stderr.WriteLine($"spectral sweep: "
                    + $"interrupted{(Signals.Signal.Length > 0 ? $" by {Signals.Signal}" : "")}{Signals.StoppedAfter()}; finished jobs are "
                    + $"kept and listed in {Path.Combine(outDir, "index.csv")} (rebuilt); run the same command again to resume");
                return CommandLine.Failure;
            }
            if (terminal && !quiet) stderr.WriteLine();
            if (!quiet)
                stderr.WriteLine($"sweep {Path.GetFileName(planPath)}{(slice.Count > 1 ? $" slice {slice}" : "")}: {s.InSlice} of {s.Jobs} "
                    + $"jobs here — {s.Rendered} rendered, {s.Skipped} already done, {s.Failed} failed; {s.DoneInIndex}/{s.Jobs} done in "
                    + $"{Path.Combine(outDir, "index.csv")}");
            if (s.Failed > 0)
            {
                stderr.WriteLine($"spectral sweep: {s.Failed} jobs failed (their errors are in index.jsonl and jobs/ID/job.json)");
                return CommandLine.Failure;
            }
            return CommandLine.Success;
        }
    }

    /// <summary>How this process was started (the same spectral binary, or `dotnet spectral.dll`), for the emitted scripts.</summary>
    [System.Diagnostics.CodeAnalysis.UnconditionalSuppressMessage("SingleFile", "IL3000",
        Justification = "The assembly's path is read only when the process is `dotnet`; the native spectral is its own ProcessPath.")]
    static string SpectralCommand()
    {
        var exe = Environment.ProcessPath ?? "spectral";
        var dll = typeof(SweepCommand).Assembly.Location;
        return Path.GetFileNameWithoutExtension(exe) == "dotnet" && dll.Length > 0 ? $"{Quote(exe)} {Quote(dll)}" : Quote(exe);
    }

    static string Quote(string s) =>
        s.Length > 0 && s.All(c => char.IsLetterOrDigit(c) || "/._-+=:,".Contains(c)) ? s : "'" + s.Replace("'", "'\\''") + "'";

    /// <summary>The arguments a job array's task runs (after the spectral command), one string per argument.</summary>
    static List<string> Common(SweepPlan plan, string outDir, string layout, Arguments a, List<string> models)
    {
        List<string> args = ["sweep", plan.PlanPath, "-o", Path.GetFullPath(outDir)];
        if (layout != "folders") args.AddRange(["--layout", layout]);
        if (a.Value("--formats") is { } f) args.AddRange(["--formats", f]);
        if (a.Value("--threads") is { } t) args.AddRange(["--threads", t]);
        foreach (var m in models) args.AddRange(["--models", m]);
        return args;
    }

    static string EmitSlurm(SweepPlan plan, string outDir, int tasks, string layout, Arguments a, List<string> models)
    {
        var logs = Path.Combine(Path.GetFullPath(outDir), "logs");
        Directory.CreateDirectory(logs);
        var sbatch = Path.Combine(Path.GetFullPath(outDir), "sweep.sbatch");
        var threads = a.Value("--threads") is null ? " --threads \"${SLURM_CPUS_PER_TASK:-1}\"" : "";
        var script = $"""
            #!/bin/bash
            # {plan.Jobs.Count} jobs of {Path.GetFileName(plan.PlanPath)} as a Slurm job array of {tasks} tasks: task I runs the
            # jobs whose number mod {tasks} is I (spectral reads SLURM_ARRAY_TASK_ID/_MIN/_MAX/_STEP). Finished jobs are
            # skipped, so resubmitting after a failure or pre-emption resumes. Submit with: sbatch {sbatch}
            #SBATCH --job-name=spectral-sweep
            #SBATCH --array=0-{tasks - 1}
            #SBATCH --output={logs}/%A_%a.out
            #SBATCH --cpus-per-task=1
            set -euo pipefail
            exec {SpectralCommand()} {string.Join(' ', Common(plan, outDir, layout, a, models).Select(Quote))}{threads}

            """;
        var path = Path.Combine(outDir, "sweep.sbatch");
        AtomicFile.WriteAllText(path, script);
        if (!OperatingSystem.IsWindows()) File.SetUnixFileMode(path, (UnixFileMode)0b111_101_101);
        return path;
    }

    /// <summary>A YAML double-quoted scalar (YAML 1.2 §7.3.1): any path or name, spaces, colons and quotes included.</summary>
    static string YamlString(string s) => "\"" + string.Concat(s.Select(c => c switch
    {
        '\\' => "\\\\",
        '"' => "\\\"",
        < ' ' or '\x7f' => $"\\x{(int)c:x2}",
        _ => c.ToString(),
    })) + "\"";

    static string EmitKubernetes(SweepPlan plan, string outDir, int tasks, string layout, Arguments a, List<string> models)
    {
        string image = a.Value("--image") ?? "spectral:latest";
        // An exec-form command: each argument its own YAML string, never split on spaces (a path may hold them).
        List<string> args = ["spectral", .. Common(plan, outDir, layout, a, models), "--shards", $"{tasks}", "--quiet"];
        string name = "spectral-sweep-"
            + new string(Path.GetFileNameWithoutExtension(plan.PlanPath).ToLowerInvariant()
                .Select(c => char.IsAsciiLetterOrDigit(c) ? c : '-').ToArray())
                .Trim('-');
        if (name.Length > 52) name = name[..52].TrimEnd('-');
        var command = string.Join(", ", args.Select(YamlString));
        string shared = Path.GetDirectoryName(plan.PlanPath)!;
        var yaml = $"""
            # {plan.Jobs.Count} jobs of {Path.GetFileName(plan.PlanPath)} as a Kubernetes Indexed Job of {tasks} completions: pod I runs
            # the jobs whose number mod {tasks} is I (spectral reads JOB_COMPLETION_INDEX; the count is --shards {tasks}).
            # The plan, its scene and the output folder must be at the same paths in the pod: mount the shared volume there
            # (the persistentVolumeClaim below is an example). Apply with: kubectl apply -f sweep-job.yaml
            apiVersion: batch/v1
            kind: Job
            metadata:
              name: {name}
            spec:
              completionMode: Indexed
              completions: {tasks}
              parallelism: {Math.Min(tasks, 16)}
              backoffLimitPerIndex: 2
              maxFailedIndexes: {tasks}
              template:
                spec:
                  restartPolicy: Never
                  containers:
                    - name: spectral
                      image: {YamlString(image)}
                      command: [{command}]
                      volumeMounts:
                        - name: data
                          mountPath: {YamlString(shared)}
                        - name: out
                          mountPath: {YamlString(Path.GetFullPath(outDir))}
                  volumes:
                    - name: data
                      persistentVolumeClaim:
                        claimName: spectral-data
                    - name: out
                      persistentVolumeClaim:
                        claimName: spectral-out

            """;
        var path = Path.Combine(outDir, "sweep-job.yaml");
        AtomicFile.WriteAllText(path, yaml);
        return path;
    }
}
