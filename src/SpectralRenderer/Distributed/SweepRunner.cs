using System.Diagnostics;
using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Distributed;

/// <summary>Progress of a sweep: after each job of this slice (done, failed or skipped as finished before).</summary>
public readonly record struct SweepProgress(int Finished, int Jobs, SweepJob Job, string Status, double Seconds, TimeSpan Elapsed);

/// <summary>What a run of a sweep did.</summary>
public sealed record SweepSummary(int Jobs, int InSlice, int Rendered, int Skipped, int Failed, int DoneInIndex);

/// <summary>
/// Runs the jobs of a <see cref="SweepPlan"/> into OUT/jobs/ID/ (a render folder with the job's scene.json and, last,
/// job.json), one after the other, each render on all cores. A job whose job.json says done with the same job hash is
/// skipped, so a rerun resumes where an interrupted or failed run stopped and no finished job is rendered twice; an
/// interrupted job left no job.json and is rendered again. After the run (finished, failed or interrupted) the index
/// is rebuilt from every job's job.json: OUT/index.csv and OUT/index.jsonl, one row per job of the plan, in job order.
/// Slices (<see cref="Shard"/>: job mod N = I) running at once share nothing but the index, which each rewrites whole
/// (atomically) from the job folders.
/// </summary>
public static class SweepRunner
{
    /// <summary>Dataset layouts: "folders" (jobs/ID/ only) or "pairs" (also cube/ID.npy and rgb/ID.png, the spectral-recovery
    /// layout).</summary>
    public static readonly string[] Layouts = ["folders", "pairs"];

    public static SweepSummary Run(SweepPlan plan, string outDir, Shard slice, SceneOverrides overrides, string layout, int threads,
        Action<SweepProgress>? progress, CancellationToken cancel)
    {
        string? formats = overrides.Formats ?? plan.Formats;
        if (layout == "pairs") formats = PairsFormats(formats);
        overrides = overrides with { Formats = formats };
        var mine = plan.Jobs.Where(j => slice.Owns(j.Index)).ToList();
        // Every job of the slice checked before the first runs: a plan with a bad job renders nothing.
        plan.CheckJobs(mine, overrides, outDir, cancel);
        Directory.CreateDirectory(Path.Combine(outDir, "jobs"));
        int rendered = 0, skipped = 0, failed = 0, finished = 0;
        var clock = Stopwatch.StartNew();
        var geometries = new GeometryCache();   // jobs that vary lights or materials, not the mesh, share its BVH
        try
        {
            foreach (var job in mine)
            {
                cancel.ThrowIfCancellationRequested();
                var dir = Path.Combine(outDir, "jobs", job.Id);
                string hash = plan.JobHash(job, formats);
                if (IsDone(dir, hash))
                {
                    skipped++;
                    progress?.Invoke(new SweepProgress(++finished, mine.Count, job, "skipped", 0, clock.Elapsed));
                    continue;
                }
                var started = Stopwatch.StartNew();
                string status = "done";
                string? error = null;
                try
                {
                    RenderJob(plan, job, dir, overrides, threads, geometries, cancel);
                    if (layout == "pairs") Pair(outDir, dir, job.Id);
                    rendered++;
                }
                catch (InputException e) { status = "failed"; error = e.Message; failed++; }
                catch (IOException e) { status = "failed"; error = e.Message; failed++; }
                // job.json last: its "done" is the mark that everything before it is complete.
                WriteJobRecord(dir, job, status, started.Elapsed.TotalSeconds, hash, error);
                progress?.Invoke(new SweepProgress(++finished, mine.Count, job, status, started.Elapsed.TotalSeconds, clock.Elapsed));
            }
        }
        finally
        {
            WriteIndex(plan, outDir, layout);
        }
        int doneInIndex = plan.Jobs.Count(j => ReadRecord(Path.Combine(outDir, "jobs", j.Id))?.Status == "done");
        return new SweepSummary(plan.Jobs.Count, mine.Count, rendered, skipped, failed, doneInIndex);
    }

    static string PairsFormats(string? formats)
    {
        var set = formats is null
            ? new List<string>(OutputNames.ProductNames)
            : formats.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries).ToList();
        if (set.Contains("all")) return "all";
        foreach (var f in new[] { "npy", "png" }) if (!set.Contains(f)) set.Add(f);
        return string.Join(',', set);
    }

    static bool IsDone(string dir, string hash) =>
        ReadRecord(dir) is { Status: "done" } record && record.JobHash == hash && File.Exists(Path.Combine(dir, "render.json"));

    /// <summary>A job's job.json as the index uses it: status (done or failed), seconds, job hash, error.</summary>
    sealed record JobRecord(string Status, double? Seconds, string? JobHash, string? Error);

    /// <summary>
    /// A job's job.json, checked (<see cref="JsonFields"/>): status done or failed, seconds a finite number ≥ 0, the hash
    /// and error strings. A missing, unreadable or damaged record is no record: the job counts as pending and runs again.
    /// </summary>
    static JobRecord? ReadRecord(string dir)
    {
        var path = Path.Combine(dir, "job.json");
        if (!File.Exists(path)) return null;
        try
        {
            var json = JsonFields.ParseFile(path, "job.json", "");
            var r = new JsonFields(path, "");
            string status = r.String(json, "status", "$");
            if (status is not ("done" or "failed")) return null;
            return new JobRecord(status, r.OptNumber(json, "seconds", "$", 0, 1e9), r.OptString(json, "job_hash", "$"),
                r.OptString(json, "error", "$"));
        }
        catch (InputException) { return null; }   // unreadable or damaged: the job counts as not done and runs again
    }

    static void RenderJob(SweepPlan plan, SweepJob job, string dir, SceneOverrides overrides, int threads, GeometryCache geometries,
        CancellationToken cancel)
    {
        Directory.CreateDirectory(dir);
        File.Delete(Path.Combine(dir, "job.json"));
        var text = plan.SceneBytes(job);
        // Parsed as if it were the base scene file, so its relative mesh and spectrum files resolve as the base scene's do;
        // its errors name the job's own scene.json.
        Pipeline.RenderJob render;
        try
        {
            render = Pipeline.RenderJob.Load(new Pipeline.RenderRequest
            {
                ScenePath = plan.ScenePath,
                SceneText = text,
                Overrides = overrides,
                Threads = threads,
                OutDir = dir,
                Geometries = geometries,
                Run = new ManifestRun { CommandLine = $"spectral sweep {plan.PlanPath}", SweepJob = job.Id },
                Detail = Pipeline.RunDetail.Geometry,
            });
        }
        catch (InputException e) { throw plan.InJobScene(e, job, text, Path.GetDirectoryName(Path.GetDirectoryName(dir))!); }
        AtomicFile.WriteAllBytes(Path.Combine(dir, "scene.json"), text);
        render.Execute(cancel: cancel);
    }

    /// <summary>--layout pairs: the job's cube and its RGB image side by side under OUT/cube and OUT/rgb, named by job id.</summary>
    static void Pair(string outDir, string dir, string id)
    {
        foreach (var (sub, file, ext) in new[] { ("cube", "spectral.npy", ".npy"), ("rgb", "preview.png", ".png") })
        {
            Directory.CreateDirectory(Path.Combine(outDir, sub));
            var bytes = File.ReadAllBytes(Path.Combine(dir, file));
            AtomicFile.WriteAllBytes(Path.Combine(outDir, sub, id + ext), bytes);
        }
    }

    static void WriteJobRecord(string dir, SweepJob job, string status, double seconds, string hash, string? error)
    {
        Directory.CreateDirectory(dir);
        var record = new JsonObject
        {
            ["job"] = job.Id,
            ["status"] = status,
            ["seconds"] = Math.Round(seconds, 3),
            ["parameters"] = Parameters(job),
            ["job_hash"] = hash,
            ["finished_utc"] = DateTime.UtcNow.ToString("yyyy-MM-ddTHH:mm:ss.fffZ", CultureInfo.InvariantCulture),
        };
        if (error is not null) record["error"] = error;
        AtomicFile.WriteAllText(Path.Combine(dir, "job.json"), record.ToJsonString(new JsonSerializerOptions { WriteIndented = true }));
    }

    static JsonObject Parameters(SweepJob job)
    {
        var p = new JsonObject();
        foreach (var (axis, label) in job.Parameters) p[axis] = label;
        return p;
    }

    /// <summary>
    /// index.jsonl (one JSON object a line) and index.csv (RFC 4180), one row per job of the plan in job order: job id,
    /// status (done, failed or pending), seconds the render and its files took, the job's folder (relative to OUT), each
    /// axis's value label, and with --layout pairs the cube and rgb files.
    /// </summary>
    public static void WriteIndex(SweepPlan plan, string outDir, string layout)
    {
        // The slices of a job array rebuild the index at the same time: one at a time, so the last to finish reads every
        // job record and writes last.
        using var serial = IndexLock(outDir);
        var jsonl = new StringBuilder();
        var csv = new StringBuilder();
        var header = new List<string> { "job", "status", "seconds", "path" };
        header.AddRange(plan.AxisNames);
        if (layout == "pairs") header.AddRange(["cube", "rgb"]);
        csv.Append(string.Join(',', header.Select(Csv))).Append("\r\n");
        foreach (var job in plan.Jobs)
        {
            var record = ReadRecord(Path.Combine(outDir, "jobs", job.Id));
            string status = record?.Status ?? "pending";
            double? seconds = record?.Seconds;
            string path = $"jobs/{job.Id}";
            var row = new JsonObject
            {
                ["job"] = job.Id,
                ["status"] = status,
                ["seconds"] = seconds,
                ["path"] = path,
                ["parameters"] = Parameters(job)
            };
            var cells = new List<string> { job.Id, status, seconds?.ToString("0.###", CultureInfo.InvariantCulture) ?? "", path };
            foreach (var axis in plan.AxisNames) cells.Add(job.Parameters.FirstOrDefault(p => p.Axis == axis).Label ?? "");
            if (layout == "pairs")
            {
                row["cube"] = $"cube/{job.Id}.npy";
                row["rgb"] = $"rgb/{job.Id}.png";
                cells.AddRange([$"cube/{job.Id}.npy", $"rgb/{job.Id}.png"]);
            }
            if (record?.Error is { } e) row["error"] = e;
            jsonl.Append(row.ToJsonString()).Append('\n');
            csv.Append(string.Join(',', cells.Select(Csv))).Append("\r\n");
        }
        AtomicFile.WriteAllText(Path.Combine(outDir, "index.jsonl"), jsonl.ToString());
        AtomicFile.WriteAllText(Path.Combine(outDir, "index.csv"), csv.ToString());
    }

    /// <summary>OUT/jobs/.index.lock held exclusively (an OS file lock) while the index is rebuilt; waits up to 30 s for another
    /// slice, then goes on without it (a stuck holder: the next rebuild repairs the index).</summary>
    static FileStream? IndexLock(string outDir)
    {
        var path = Path.Combine(outDir, "jobs", ".index.lock");
        long until = Environment.TickCount64 + 30_000;
        while (true)
        {
            try
            {
                Directory.CreateDirectory(Path.GetDirectoryName(path)!);
                return new FileStream(path, FileMode.OpenOrCreate, FileAccess.ReadWrite, FileShare.None, 1);
            }
            catch (IOException) when (Environment.TickCount64 < until) { Thread.Sleep(20); }
            catch (Exception e) when (e is IOException or UnauthorizedAccessException) { return null; }
        }
    }

    static string Csv(string s) => s.IndexOfAny([',', '"', '\r', '\n']) >= 0 ? "\"" + s.Replace("\"", "\"\"") + "\"" : s;
}
