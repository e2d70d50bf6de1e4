using System.Collections.Concurrent;
using System.Diagnostics;
using System.Runtime.InteropServices;
using SpectralRenderer.Output;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Output;

/// <summary>
/// One folder transaction for every command that writes (OutputFolder): killed at each step of its swap, the next
/// writer finishes the swap and the folder holds one whole result, equal to an uninterrupted run's; a second writer
/// meanwhile is refused naming the folder; a refused write leaves no staging; source and target are compared by
/// identity, not spelling.
/// </summary>
public class FolderTransactionTests
{
    const string Scene = """
    { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 },
      "materials": { "green": { "diffuse": "colorchecker:14" }, "white": { "diffuse": "colorchecker:19" } },
      "lights": [ { "type": "point", "name": "key", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [ { "type": "sphere", "name": "ball", "radius": 1, "material": "green" },
                   { "type": "plane", "name": "board", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "white" } ] }
    """;

    sealed class SimulatedKill() : Exception("killed (simulated) during the swap");

    /// <summary>The swap step at which a folder's writer "dies": the exception unwinds like a kill, leaving the disk as it was.</summary>
    static readonly ConcurrentDictionary<string, int> KillAt = new(StringComparer.Ordinal);

    static FolderTransactionTests()
    {
        OutputFolder.SwapStep = (final, step) =>
        {
            if (KillAt.TryGetValue(final, out int k) && k == step) throw new SimulatedKill();
        };
    }

    static void Ok(params string[] args)
    {
        var (code, _, err) = CliRunner.Run(args);
        Assert.True(code == 0, $"{string.Join(' ', args)}: {err}");
    }

    /// <summary>A scene, its render r (lights, AOVs, cube) and two shards a and b, made once and only read.</summary>
    static readonly Lazy<string> Shared = new(() =>
    {
        var dir = Reference.TempDir();
        var s = Path.Combine(dir, "s.json");
        File.WriteAllText(s, Scene);
        Ok("render", s, "-o", Path.Combine(dir, "r"), "--formats", "png,npy,aov,lights", "--quiet");
        foreach (var i in new[] { "0", "1" })
            Ok("render", s, "--width", "8", "--height", "64", "--formats", "npy,aov", "--shard", $"{i}/2", "-o",
                Path.Combine(dir, i == "0" ? "a" : "b"), "--quiet");
        return dir;
    });

    static string Base() => Shared.Value;

    /// <summary>(the run that leaves an old result, the command, the folder it writes) for each command; {d} = the base folder, {t} = the
    /// target.</summary>
    public static TheoryData<string> Commands() => ["render", "relight", "merge", "camera", "recover", "probe", "reconstruct"];

    static (string[] Before, string[] Command, string Target) Plan(string name, string d, string t) => name switch
    {
        "render" => (["render", $"{d}/s.json", "-o", t, "--formats", "png,npy", "--quiet"],
                     ["render", $"{d}/s.json", "-o", t, "--formats", "png,envi,aov", "--quiet"], t),
        "relight" => (["relight", $"{d}/r", "--light", "key=A", "-o", t, "--quiet"],
                      ["relight", $"{d}/r", "--light", "key=blackbody:3000", "-o", t, "--quiet"], t),
        "merge" =>
            (["render", $"{d}/s.json", "-o", t, "--formats", "png", "--quiet"], ["merge", $"{d}/a", $"{d}/b", "-o", t, "--quiet"], t),
        "camera" => (["camera", $"{d}/r", "--sensor", "isetcam", "--noise", "off", "-o", t],
                     ["camera", $"{d}/r", "--sensor", "nikon-d5100", "--noise", "off", "-o", t], t),
        "recover" => (["recover", t, "--method", "pinv"], ["recover", t, "--method", "pinv,wiener"], t),
        "probe" => (["probe", $"{d}/r", "--pixel", "1,1", "-o", $"{t}/p"], ["probe", $"{d}/r", "--pixel", "2,2", "-o", $"{t}/p"], t),
        "reconstruct" => (["reconstruct", t, "--white-object", "board", "--pixel", "1,1"],
            ["reconstruct", t, "--white-object", "board", "--pixel", "2,2"], t),
        _ => throw new ArgumentException(name),
    };

    /// <summary>What a target needs before the command's first run: shards, a camera folder, a render to reconstruct.</summary>
    static void Prepare(string name, string d, string t)
    {
        switch (name)
        {
            case "recover": Ok("camera", $"{d}/r", "--sensor", "isetcam", "--noise", "off", "-o", t); break;
            case "reconstruct": Ok("render", $"{d}/s.json", "-o", t, "--formats", "npy,aov", "--quiet"); break;
        }
    }

    /// <summary>Every file under <paramref name="dir"/> (relative name → bytes); manifests by name only (they hold times).</summary>
    static Dictionary<string, byte[]> Snapshot(string dir) =>
        Directory.GetFiles(dir, "*", SearchOption.AllDirectories).ToDictionary(f => Path.GetRelativePath(dir, f),
            f => f.EndsWith(".json", StringComparison.Ordinal) || f.EndsWith(".svg", StringComparison.Ordinal) ? [] : File.ReadAllBytes(f));

    static void AssertSame(Dictionary<string, byte[]> expected, Dictionary<string, byte[]> actual, string what)
    {
        Assert.True(expected.Keys.Order().SequenceEqual(actual.Keys.Order()),
            $"{what}: files {string.Join(",", actual.Keys.Order())} ≠ {string.Join(",", expected.Keys.Order())}");
        foreach (var (f, bytes) in expected) Assert.True(bytes.AsSpan().SequenceEqual(actual[f]), $"{what}: {f} differs");
    }

    static void AssertNothingBeside(string target)
    {
        var parent = Path.GetDirectoryName(target)!;
        Assert.Empty(Directory.GetFileSystemEntries(parent, $".{Path.GetFileName(target)}.*"));
    }

    /// <summary>Steps 1 (journal written), 5 and 9 (files moving, or the clean-up of a small swap): fast; every step under Slow.</summary>
    [Theory]
    [MemberData(nameof(Commands))]
    public void Killed_at_steps_of_its_swap_the_next_writer_finishes_it_and_the_folder_is_one_whole_result(string name) =>
        KilledAt(name, [1, 5, 9]);

    [Theory]
    [Trait("Category", "Slow")]
    [MemberData(nameof(Commands))]
    public void Killed_at_each_step_of_its_swap_the_next_writer_finishes_it_and_the_folder_is_one_whole_result(string name) =>
        KilledAt(name, [.. Enumerable.Range(1, 199)]);

    static void KilledAt(string name, int[] kills)
    {
        var d = Base();
        var w = Reference.TempDir();
        // The result an uninterrupted run writes, in a twin folder.
        var twin = Path.Combine(w, "twin");
        Prepare(name, d, twin);
        var (_, command, _) = Plan(name, d, twin);
        Ok(command);
        var expected = Snapshot(twin);

        var t = Path.Combine(w, "t");
        Prepare(name, d, t);
        var (before, run, target) = Plan(name, d, t);
        Ok(before);
        var real = OutputFolder.RealPath(Path.GetFullPath(target));
        int steps = 0, journals = 0;
        foreach (int k in kills)
        {
            KillAt[real] = k;
            int code;
            try { code = CliRunner.Run(run).Exit; }
            finally { KillAt.TryRemove(real, out _); }
            if (code == 0) break;   // the swap has fewer steps than k: every step was tried
            steps = k;
            if (File.Exists(Path.Combine(w, ".t.journal"))) journals++;   // none only after the swap's last step
            // The next writer on the folder finishes the killed swap before anything else: one whole result, the new one.
            using (OutputFolder.BeginFiles(target, [], "check")) { }
            AssertSame(expected, Snapshot(target), $"{name}, killed at step {k}");
            AssertNothingBeside(target);
            // The same command again ends whole too.
            Ok(run);
            AssertSame(expected, Snapshot(target), $"{name}, rerun after step {k}");
            Ok(before);
        }
        Assert.True(journals >= Math.Min(2, kills.Length - 1), $"{name}: only {journals} kills left a journal");
        AssertNothingBeside(target);
    }

    [Theory]
    [MemberData(nameof(Commands))]
    public void A_second_writer_of_the_folder_exits_2_naming_it_and_the_first_goes_on(string name)
    {
        var d = Base();
        var w = Reference.TempDir();
        var t = Path.Combine(w, "t");
        Prepare(name, d, t);
        var (before, run, target) = Plan(name, d, t);
        Ok(before);
        var old = Snapshot(target);
        string[] second;
        using (var first = OutputFolder.BeginFiles(target, [], "first writer"))
        {
            var (code, _, err) = CliRunner.Run(run);
            Assert.True(code == 2, err);
            Assert.Contains("is being written by another spectral process", err);
            Assert.Contains(Path.GetFileName(target), err);
            Assert.Contains("(hint: ", err);
            second = Directory.GetFileSystemEntries(w, ".t.*").Where(e => e != first.Staging).Select(Path.GetFileName).ToArray()!;
        }
        Assert.Equal([".t.lock"], second);   // the first writer's lock, and no staging of the refused one
        AssertSame(old, Snapshot(target), $"{name}: the refused writer changed the folder");
        Ok(run);
        AssertNothingBeside(target);
    }

    [Fact]
    public void A_camera_run_that_would_replace_a_users_file_is_refused_and_leaves_no_staging()
    {
        var d = Base();
        var c = Path.Combine(Reference.TempDir(), "c");
        Directory.CreateDirectory(c);
        File.WriteAllText(Path.Combine(c, "patches.csv"), "mine");
        var (code, _, err) = CliRunner.Run("camera", $"{d}/r", "--sensor", "isetcam", "--noise", "off", "-o", c);
        Assert.True(code == 2, err);
        Assert.Contains("was not written by the previous camera run", err);
        Assert.Equal("mine", File.ReadAllText(Path.Combine(c, "patches.csv")));
        Assert.Single(Directory.GetFileSystemEntries(c));
        AssertNothingBeside(c);
        // A second sensor's run replaces the first one's files whole: nothing of the first stays.
        File.Delete(Path.Combine(c, "patches.csv"));
        Ok("camera", $"{d}/r", "--sensor", "nikon-d5100", "--noise", "off", "-o", c);
        Assert.True(File.Exists(Path.Combine(c, "raw.dng")));
        Ok("camera", $"{d}/r", "--sensor", "wheel-6", "--noise", "off", "-o", c);
        Assert.False(File.Exists(Path.Combine(c, "raw.dng")));
        Assert.False(File.Exists(Path.Combine(c, "raw.png")));
    }

    [SkippableFact]
    public void The_folder_being_relit_is_recognised_by_identity_whatever_its_spelling()
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "symbolic links");
        var d = Reference.TempDir();
        var r = Path.Combine(d, "r");
        Ok("render", Path.Combine(Base(), "s.json"), "-o", r, "--formats", "png,lights", "--quiet");
        var before = Snapshot(r);
        var link = Path.Combine(d, "link");
        Directory.CreateSymbolicLink(link, r);
        foreach (var spelling in new[] { r + "/", r + "/.", link, Path.Combine(d, "r", "..", "r") })
        {
            var (code, _, err) = CliRunner.Run("relight", r, "--light", "key=A", "-o", spelling, "--quiet");
            Assert.True(code == 2, $"{spelling}: {err}");
            Assert.Contains("is the folder being relit", err);
        }
        AssertSame(before, Snapshot(r), "the relit render");
        Assert.Empty(Directory.GetFileSystemEntries(d, ".r.*"));
        Assert.Empty(Directory.GetFileSystemEntries(d, ".link.*"));
    }

    [DllImport("libc", SetLastError = true)]
    static extern int kill(int pid, int sig);

    static Process Start(string dir, IDictionary<string, string>? env, params string[] args)
    {
        var psi = new ProcessStartInfo("dotnet")
        {
            RedirectStandardError = true,
            RedirectStandardOutput = true,
            UseShellExecute = false,
            WorkingDirectory = dir
        };
        psi.ArgumentList.Add(Path.Combine(AppContext.BaseDirectory, "spectral.dll"));
        foreach (var a in args) psi.ArgumentList.Add(a);
        foreach (var (k, v) in env ?? new Dictionary<string, string>()) psi.Environment[k] = v;
        return Process.Start(psi)!;
    }

    /// <summary>The bar: a real kill -9 (SIGKILL, from the process itself at the step) at each step of a render's swap, then the same
    /// command.</summary>
    [SkippableFact]
    [Trait("Category", "Slow")]
    public void A_render_killed_9_at_each_step_of_its_swap_then_run_again_is_one_whole_render()
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "SIGKILL");
        var d = Base();
        var w = Reference.TempDir();
        var (_, command, _) = Plan("render", d, Path.Combine(w, "twin"));
        Ok(command);
        var expected = Snapshot(Path.Combine(w, "twin"));
        var t = Path.Combine(w, "t");
        var (before, run, _) = Plan("render", d, t);
        int killed = 0;
        for (int k = 1; k < 100; k++)
        {
            Ok(before);
            using var p = Start(w,
                new Dictionary<string, string>
                {
                    ["SPECTRAL_TEST_KILL_AT_SWAP_STEP"] = k.ToString(
                    System.Globalization.CultureInfo.InvariantCulture)
                },
                run);
            Assert.True(p.WaitForExit(60_000));
            if (p.ExitCode == 0) break;
            Assert.Equal(137, p.ExitCode);   // 128 + SIGKILL
            killed++;
            Ok(run);   // the same command: finishes the killed swap, then renders and swaps again
            AssertSame(expected, Snapshot(t), $"killed -9 at step {k}, then run again");
            AssertNothingBeside(t);
        }
        Assert.True(killed >= 10, $"only {killed} steps");
    }
}
