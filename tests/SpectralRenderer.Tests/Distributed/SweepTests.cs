using System.Diagnostics;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Distributed;

/// <summary>Sweep plans: the job list is the product of the axes; runs resume; slices and reruns render each job once.</summary>
public class SweepTests
{
    const string BaseScene = """
        { "camera": { "position": [0, 1, 5], "look_at": [0, 0.6, 0], "width": 24, "height": 16, "spp": 1 },
          "materials": { "ball": { "diffuse": "colorchecker:14" }, "floor": { "diffuse": "colorchecker:neutral-6.5" } },
          "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "name": "sphere", "center": [0, 0.7, 0], "radius": 0.7, "material": "ball" },
                       { "type": "plane", "name": "floor", "material": "floor" } ] }
        """;

    /// <summary>A folder with scene.json and plan.json: 3 patches × 2 lights + one extra job (7 jobs).</summary>
    public static string Plan(string dir, string formats = "[\"npy\", \"png\"]", string extraAxes = "")
    {
        File.WriteAllText(Path.Combine(dir, "scene.json"), BaseScene);
        File.WriteAllText(Path.Combine(dir, "plan.json"), $$"""
            // a test plan
            { "scene": "scene.json",
              "formats": {{formats}},
              "axes": [
                { "name": "patch", "path": "objects[name=sphere].material", "values": ["ball", "floor", "ball"], "labels": ["ball", "floor",
                  "ball-again"] },
                { "name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"] }, {{extraAxes}}
              ],
              "extra": [ { "name": "wide", "set": { "camera.fov": 60, "bands": "400:700:31" } } ],
            }
            """);
        return Path.Combine(dir, "plan.json");
    }

    [Fact]
    public void The_job_list_is_the_product_of_the_axes_first_axis_slowest_then_the_extra_jobs()
    {
        var plan = SweepPlan.Load(Plan(Reference.TempDir()));
        Assert.Equal(7, plan.Jobs.Count);
        Assert.Equal(["0000", "0001", "0002", "0003", "0004", "0005", "0006"], plan.Jobs.Select(j => j.Id));
        Assert.Equal([("patch", "floor"), ("light", "A")], plan.Jobs[3].Parameters);
        Assert.Equal([("extra", "wide")], plan.Jobs[6].Parameters);
        var scene = plan.SceneFor(plan.Jobs[3]);
        Assert.Equal("floor", scene["objects"]![0]!["material"]!.GetValue<string>());
        Assert.Equal("A", scene["lights"]![0]!["spectrum"]!.GetValue<string>());
        var wide = plan.SceneFor(plan.Jobs[6]);
        Assert.Equal(60, wide["camera"]!["fov"]!.GetValue<int>());
        Assert.Equal("400:700:31", wide["bands"]!.GetValue<string>());
        Assert.Equal("ball", wide["objects"]![0]!["material"]!.GetValue<string>());   // the base scene's
    }

    [Theory]
    [InlineData("{ \"name\": \"x\", \"path\": \"objects[name=cube].material\", \"values\": [\"ball\"] }",
        "no element of 'objects' has name 'cube'")]
    [InlineData("{ \"name\": \"x\", \"path\": \"lights[3].spectrum\", \"values\": [\"A\"] }", "has 1 elements, so no [3]")]
    [InlineData("{ \"name\": \"light\", \"path\": \"bands\", \"values\": [\"400:700:31\"] }", "'light' is taken")]
    [InlineData("{ \"name\": \"x\", \"path\": \"bad path!\", \"values\": [1] }", "")]
    public void A_plan_edit_that_cannot_land_is_one_line_naming_the_plan(string axis, string what)
    {
        var dir = Reference.TempDir();
        var e = Assert.Throws<InputException>(() => SweepPlan.Load(Plan(dir, extraAxes: axis)));
        Assert.Contains("plan.json", e.Message);
        Assert.Contains(what, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }

    [Fact]
    public void A_plan_whose_last_job_has_a_bad_scene_renders_nothing_and_names_the_line_of_that_jobs_own_scene()
    {
        var dir = Reference.TempDir();
        // Job 0006 (the extra job) gets both "bands" and "wave", which a scene may not have together.
        var plan = Plan(dir);
        File.WriteAllText(plan,
            File.ReadAllText(plan).Replace("\"bands\": \"400:700:31\"", "\"bands\": \"400:700:31\", \"wave\": \"400:10:700\""));
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("sweep", plan, "-o", outDir, "--quiet");
        Assert.Equal(2, code);
        var scene = Path.Combine(outDir, "jobs", "0006", "scene.json");
        Assert.StartsWith($"spectral sweep: {scene}:", err);
        Assert.Contains("sweep job 0006", err);
        // The line:column the message names is where the job's own scene (written beside it) says "bands" or "wave".
        var at = System.Text.RegularExpressions.Regex.Match(err, @"scene\.json:(\d+):(\d+): \$\.(bands|wave)");
        Assert.True(at.Success, err);
        var line = File.ReadAllLines(scene)[int.Parse(at.Groups[1].Value) - 1];
        Assert.Contains($"\"{at.Groups[3].Value}\"", line);
        // No job rendered, none recorded, no index: the plan was refused before its first job.
        Assert.Empty(Directory.EnumerateFiles(outDir, "render.json", SearchOption.AllDirectories));
        Assert.Empty(Directory.EnumerateFiles(outDir, "job.json", SearchOption.AllDirectories));
        Assert.False(File.Exists(Path.Combine(outDir, "index.csv")));
    }

    static List<JsonObject> Index(string outDir) =>
        File.ReadAllLines(Path.Combine(outDir, "index.jsonl")).Select(l => JsonNode.Parse(l)!.AsObject()).ToList();

    static Dictionary<string, string> Finished(string outDir) =>
        Directory.GetDirectories(Path.Combine(outDir, "jobs")).Where(d => File.Exists(Path.Combine(d, "job.json")))
            .ToDictionary(d => Path.GetFileName(d),
                d => JsonNode.Parse(File.ReadAllText(Path.Combine(d, "job.json")))!["finished_utc"]!.GetValue<string>());

    [Fact]
    public void Slices_render_every_job_once_and_a_rerun_renders_nothing_again()
    {
        var dir = Reference.TempDir();
        var plan = Plan(dir);
        var outDir = Path.Combine(dir, "out");
        var first = CliRunner.Run("sweep", plan, "-o", outDir, "--shard", "0/3", "--quiet");
        Assert.True(first.Exit == 0, first.Err);
        var index = Index(outDir);
        Assert.Equal(7, index.Count);
        Assert.Equal(["done", "pending", "pending", "done", "pending", "pending", "done"],
            index.Select(r => r["status"]!.GetValue<string>()));
        foreach (var s in new[] { "1/3", "2/3" }) Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--shard", s, "--quiet").Exit);
        var finished = Finished(outDir);
        Assert.Equal(7, finished.Count);
        Assert.All(Index(outDir), r => Assert.Equal("done", r["status"]!.GetValue<string>()));
        Assert.Equal(Enumerable.Range(0, 7).Select(i => $"{i:0000}"), Index(outDir).Select(r => r["job"]!.GetValue<string>()));

        var again = CliRunner.Run("sweep", plan, "-o", outDir);
        Assert.Equal(0, again.Exit);
        Assert.Contains("0 rendered, 7 already done", again.Err);
        Assert.Equal(finished, Finished(outDir));   // no job rendered twice

        // The CSV has the same rows: header + 7, axis columns, the extra job's name.
        var csv = File.ReadAllLines(Path.Combine(outDir, "index.csv"));
        Assert.Equal("job,status,seconds,path,patch,light,extra", csv[0]);
        Assert.Equal(8, csv.Length);
        Assert.StartsWith("0003,done,", csv[4]);
        Assert.EndsWith(",jobs/0003,floor,A,", csv[4]);
        Assert.EndsWith(",jobs/0006,,,wide", csv[7]);
        // Each job is a render folder of its own scene: the extra job has 31 bands.
        Assert.Equal(31,
            JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "jobs", "0006", "render.json")))!["bands"]!["count"]!.GetValue<int>());
    }

    [Fact]
    public void A_job_whose_plan_entry_changed_is_rendered_again_and_only_that_one()
    {
        var dir = Reference.TempDir();
        var plan = Plan(dir);
        var outDir = Path.Combine(dir, "out");
        Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--quiet").Exit);
        var before = Finished(outDir);
        File.WriteAllText(plan, File.ReadAllText(plan).Replace("\"camera.fov\": 60", "\"camera.fov\": 50"));
        var r = CliRunner.Run("sweep", plan, "-o", outDir);
        Assert.Contains("1 rendered, 6 already done", r.Err);
        var after = Finished(outDir);
        Assert.Equal(before.Where(kv => kv.Key != "0006"), after.Where(kv => kv.Key != "0006"));
        Assert.NotEqual(before["0006"], after["0006"]);
    }

    [Fact]
    public void Layout_pairs_puts_each_jobs_cube_and_rgb_side_by_side()
    {
        var dir = Reference.TempDir();
        var outDir = Path.Combine(dir, "out");
        Assert.Equal(0, CliRunner.Run("sweep", Plan(dir, formats: "[\"exr\"]"), "-o", outDir, "--layout", "pairs", "--quiet").Exit);
        foreach (var row in Index(outDir))
        {
            string id = row["job"]!.GetValue<string>();
            Assert.Equal(File.ReadAllBytes(Path.Combine(outDir, "jobs", id, "spectral.npy")),
                File.ReadAllBytes(Path.Combine(outDir, row["cube"]!.GetValue<string>())));
            Assert.Equal(File.ReadAllBytes(Path.Combine(outDir, "jobs", id, "preview.png")),
                File.ReadAllBytes(Path.Combine(outDir, row["rgb"]!.GetValue<string>())));
        }
    }

    [Fact]
    public void Emitted_Slurm_and_Kubernetes_jobs_run_the_same_plan_as_arrays()
    {
        var dir = Reference.TempDir();
        var plan = Plan(dir);
        var outDir = Path.Combine(dir, "out");
        Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--emit", "slurm", "--shards", "3", "--quiet").Exit);
        var sbatch = File.ReadAllText(Path.Combine(outDir, "sweep.sbatch"));
        Assert.StartsWith("#!/bin/bash", sbatch);
        Assert.Contains("#SBATCH --array=0-2\n", sbatch);
        Assert.Contains($"sweep {plan} -o {outDir}", sbatch);
        Assert.DoesNotContain("--shard ", sbatch);   // the slice comes from SLURM_ARRAY_TASK_ID
        Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--emit", "k8s", "--quiet").Exit);
        var yaml = File.ReadAllText(Path.Combine(outDir, "sweep-job.yaml"));
        Assert.Contains("completionMode: Indexed", yaml);
        Assert.Contains("completions: 7", yaml);   // one task per job by default
        Assert.Contains("\"--shards\", \"7\"", yaml);
        if (File.Exists("/bin/bash"))
        {
            using var syntax = Process.Start("/bin/bash", ["-n", Path.Combine(outDir, "sweep.sbatch")])!;   // parses, runs nothing
            syntax.WaitForExit();
            Assert.Equal(0, syntax.ExitCode);
        }
    }

    /// <summary>
    /// Issue 42: an output folder with a space was split into two arguments of the Job's command ("'/x/sw", "dir'"). The
    /// exec-form command is a YAML flow sequence of double-quoted strings, which is also JSON: read back, it is the
    /// arguments as given; the sbatch script runs them through bash, which must give the same words.
    /// </summary>
    [Fact]
    public void An_output_folder_with_spaces_and_quotes_stays_one_argument_of_the_emitted_jobs()
    {
        var dir = Reference.TempDir();
        var plan = Plan(dir);
        var outDir = Path.Combine(dir, "sweep out \"it's\" here");
        Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--emit", "k8s", "--quiet").Exit);
        var yaml = File.ReadAllLines(Path.Combine(outDir, "sweep-job.yaml"));
        var command = yaml.Single(l => l.TrimStart().StartsWith("command: ", StringComparison.Ordinal)).Trim()["command: ".Length..];
        var args = System.Text.Json.Nodes.JsonNode.Parse(command)!.AsArray().Select(x => x!.GetValue<string>()).ToList();
        Assert.Equal(["spectral", "sweep", plan, "-o", outDir, "--shards", "7", "--quiet"], args);
        var relaxed = new System.Text.Json.JsonSerializerOptions
        {
            Encoder = System.Text.Encodings.Web.JavaScriptEncoder.UnsafeRelaxedJsonEscaping,
        };
        Assert.Contains(yaml, l => l.Trim() == "mountPath: " + System.Text.Json.JsonSerializer.Serialize(outDir, relaxed));
        Assert.Equal(0, CliRunner.Run("sweep", plan, "-o", outDir, "--emit", "slurm", "--quiet").Exit);
        if (!File.Exists("/bin/bash")) return;
        var exec = File.ReadAllLines(Path.Combine(outDir, "sweep.sbatch")).Single(l => l.StartsWith("exec ", StringComparison.Ordinal));
        // bash prints the words of the exec line, one per line, instead of running it.
        var words = exec["exec ".Length..].Replace("\"${SLURM_CPUS_PER_TASK:-1}\"", "1");
        using var p =
            Process.Start(new ProcessStartInfo("/bin/bash", ["-c", "printf '%s\\n' " + words]) { RedirectStandardOutput = true })!;
        var printed = p.StandardOutput.ReadToEnd().Split('\n', StringSplitOptions.RemoveEmptyEntries);
        p.WaitForExit();
        Assert.Contains(outDir, printed);
        Assert.Equal("-o", printed[Array.IndexOf(printed, outDir) - 1]);
    }
}

/// <summary>SIGINT during a sweep, then a rerun: every job done once, none lost (a subprocess, as a user would run it).</summary>
[Collection("Alone")]
public class SweepInterruptTests
{
    [SkippableFact]
    public void A_sweep_interrupted_by_SIGINT_resumes_with_no_job_done_twice_or_lost()
    {
        Skip.IfNot(OperatingSystem.IsLinux() && File.Exists("/bin/kill"), "needs Linux and /bin/kill to send SIGINT");
        var dir = Reference.TempDir();
        // 3 × 2 + 1 jobs, each big enough (~0.2–1 s) to be caught midway.
        var plan = SweepTests.Plan(dir);
        File.WriteAllText(plan,
            File.ReadAllText(plan)
                .Replace("\"scene\": \"scene.json\",",
                    "\"scene\": \"scene.json\", \"set\": { \"camera.width\": 400, \"camera.height\": 300, \"camera.spp\": 4 },"));
        var outDir = Path.Combine(dir, "out");
        var dll = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        foreach (var a in new[] { dll, "sweep", plan, "-o", outDir, "--threads", "1" }) psi.ArgumentList.Add(a);
        using var p = Process.Start(psi)!;
        var err = p.StandardError.ReadToEndAsync();
        var clock = Stopwatch.StartNew();
        int Done() => Directory.Exists(Path.Combine(outDir, "jobs"))
            ? Directory.GetFiles(Path.Combine(outDir, "jobs"), "job.json", SearchOption.AllDirectories).Length
            : 0;
        while (Done() < 2 && clock.Elapsed.TotalSeconds < 60 && !p.HasExited) Thread.Sleep(10);
        Thread.Sleep(100);
        Assert.False(p.HasExited, "the sweep finished before it could be interrupted");
        Process.Start("/bin/kill", ["-INT", p.Id.ToString()])!.WaitForExit();
        Assert.True(p.WaitForExit(60_000), "the sweep did not stop after SIGINT");
        Assert.Equal(1, p.ExitCode);
        Assert.Contains("interrupted", err.Result);
        var before = Directory.GetFiles(Path.Combine(outDir, "jobs"), "job.json", SearchOption.AllDirectories)
            .ToDictionary(f => f, File.ReadAllText);
        Assert.InRange(before.Count, 2, 6);
        Assert.Contains("pending", File.ReadAllText(Path.Combine(outDir, "index.csv")));   // the index was written on the way out

        var resumed = CliRunner.Run("sweep", plan, "-o", outDir, "--threads", "1");
        Assert.True(resumed.Exit == 0, resumed.Err);
        Assert.Contains($"{7 - before.Count} rendered, {before.Count} already done", resumed.Err);
        foreach (var (f, text) in before) Assert.Equal(text, File.ReadAllText(f));   // the finished jobs were not redone
        var rows = File.ReadAllLines(Path.Combine(outDir, "index.jsonl")).Select(l => JsonNode.Parse(l)!).ToList();
        Assert.Equal(Enumerable.Range(0, 7).Select(i => $"{i:0000}"), rows.Select(r => r!["job"]!.GetValue<string>()));
        Assert.All(rows, r => Assert.Equal("done", r!["status"]!.GetValue<string>()));
        Assert.DoesNotContain(Directory.GetFiles(outDir, "*", SearchOption.AllDirectories),
            f => f.EndsWith(".tmp", StringComparison.Ordinal));
    }
}
