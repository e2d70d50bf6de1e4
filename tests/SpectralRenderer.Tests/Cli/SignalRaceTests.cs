using System.Diagnostics;
using System.Runtime.InteropServices;
using System.Text.Json.Nodes;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// Issue 42's race: `render`, `relight`, `camera` and `probe` re-run into a folder that holds an earlier result, sent
/// SIGINT or SIGTERM at 50 instants spread over the last second of an uninterrupted run (timed first), as a child
/// process. Every time the folder must be the old result whole (byte for byte the copy it started from) with a non-zero
/// exit, or the new result whole (the files of an uninterrupted run into a twin folder) with exit 0 — never a mix,
/// never a staging folder, journal or lock beside it.
/// </summary>
[Collection("Alone")]
public class SignalRaceTests
{
    const string Scene = """
    { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 160, "height": 120 },
      "materials": { "green": { "diffuse": "colorchecker:14" }, "white": { "diffuse": "colorchecker:19" } },
      "lights": [ { "type": "point", "name": "key", "position": [0, 3, 3], "spectrum": "LIGHT" } ],
      "objects": [ { "type": "sphere", "name": "ball", "radius": 1, "material": "green" },
                   { "type": "plane", "name": "board", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "white" } ] }
    """;

    const string Formats = "png,npy,aov,lights,exr";

    [DllImport("libc", SetLastError = true)]
    static extern int kill(int pid, int sig);

    static void Ok(params string[] args)
    {
        var (code, _, err) = CliRunner.Run(args);
        Assert.True(code == 0, $"{string.Join(' ', args)}: {err}");
    }

    /// <summary>Two renders of the scene (key light D65: old; A: new), made once and only read.</summary>
    static readonly Lazy<string> Shared = new(() =>
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "old.json"), Scene.Replace("LIGHT", "D65"));
        File.WriteAllText(Path.Combine(dir, "new.json"), Scene.Replace("LIGHT", "A"));
        Ok("render", Path.Combine(dir, "old.json"), "-o", Path.Combine(dir, "old"), "--formats", Formats, "--quiet");
        Ok("render", Path.Combine(dir, "new.json"), "-o", Path.Combine(dir, "new"), "--formats", Formats, "--quiet");
        return dir;
    });

    /// <summary>The run that leaves the old result in <paramref name="t"/>, and the command that replaces it.</summary>
    static (string[] Before, string[] Command) Plan(string name, string d, string t) => name switch
    {
        "render" => (["render", $"{d}/old.json", "-o", t, "--formats", Formats, "--quiet"],
                     ["render", $"{d}/new.json", "-o", t, "--formats", Formats, "--quiet"]),
        "relight" => (["relight", $"{d}/old", "--light", "key=FL11", "-o", t, "--quiet"],
                      ["relight", $"{d}/old", "--light", "key=A", "-o", t, "--metrics", "--quiet"]),
        "camera" => (["camera", $"{d}/old", "--sensor", "isetcam", "--noise", "off", "-o", t],
                     ["camera", $"{d}/new", "--sensor", "isetcam", "--noise", "off", "-o", t]),
        "probe" => (["probe", $"{d}/old", "--pixel", "3,3", "-o", $"{t}/p"],
                    ["probe", $"{d}/old", "--pixel", "80,60", "--pixel", "40,30", "-o", $"{t}/p"]),
        _ => throw new ArgumentException(name),
    };

    public static TheoryData<string, int> Cases()
    {
        var d = new TheoryData<string, int>();
        foreach (var c in new[] { "render", "relight", "camera", "probe" })
            foreach (var s in new[] { 2, 15 }) d.Add(c, s);
        return d;
    }

    [SkippableTheory]
    [Trait("Category", "Slow")]
    [MemberData(nameof(Cases))]
    public void A_signal_in_the_last_second_leaves_the_old_folder_whole_or_the_new_one_and_says_which_by_its_exit(string name,
        int signal)
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "POSIX signals");
        var d = Shared.Value;
        var w = Reference.TempDir();
        var t = Path.Combine(w, "t");
        var twin = Path.Combine(w, "twin");   // the same depth as t: a camera run names its render folder relative to itself
        var pristine = Path.Combine(Reference.TempDir(), "t");
        var (before, _) = Plan(name, d, pristine);
        Ok(before);
        var old = Snapshot(pristine);
        var (_, command) = Plan(name, d, t);
        var (_, twinCommand) = Plan(name, d, twin);
        Reset(pristine, twin);
        Ok(twinCommand);
        var fresh = Snapshot(twin);

        // The uninterrupted run, timed (the quickest of three: the first reads its files cold): the signals go into its last
        // second.
        double seconds = double.MaxValue;
        for (int run = 0; run < 3; run++)
        {
            Reset(pristine, t);
            var clock = Stopwatch.StartNew();
            using (var first = Start(command))
            {
                var firstErr = first.StandardError.ReadToEndAsync();
                _ = first.StandardOutput.ReadToEndAsync();
                first.WaitForExit();
                Assert.True(first.ExitCode == 0, firstErr.Result);
            }
            seconds = Math.Min(seconds, clock.Elapsed.TotalSeconds);
            AssertWhole(fresh, Snapshot(t), $"{name}, uninterrupted");
        }

        int interrupted = 0, finished = 0;
        for (int i = 0; i < 50; i++)
        {
            Reset(pristine, t);
            var at = TimeSpan.FromSeconds(Math.Max(0, seconds - 1 + i / 49.0));
            using var p = Start(command);
            var err = p.StandardError.ReadToEndAsync();
            _ = p.StandardOutput.ReadToEndAsync();
            var since = Stopwatch.StartNew();
            while (since.Elapsed < at && !p.HasExited) Thread.Sleep(1);
            bool ranOut = p.HasExited;
            if (!ranOut) Assert.Equal(0, kill(p.Id, signal));
            Assert.True(p.WaitForExit(30_000), $"{name}: still running 30 s after signal {signal} at {at.TotalSeconds:0.000} s");
            p.WaitForExit();
            var what =
                $"{name}, signal {signal} at {at.TotalSeconds:0.000} s of {seconds:0.000} s (exit {p.ExitCode}): {err.Result.Trim()}";
            var now = Snapshot(t);
            Assert.Empty(Directory.GetFileSystemEntries(w, ".t.*"));
            if (Same(old, now))
            {
                Assert.True(p.ExitCode != 0, $"the old folder whole, but exit 0 — {what}");
                interrupted++;
            }
            else
            {
                AssertWhole(fresh, now, what);
                Assert.True(p.ExitCode == 0, $"the new folder whole, but a non-zero exit — {what}");
                finished++;
            }
        }
        Assert.True(interrupted > 0, $"{name}: no signal came before the end ({finished} runs finished)");
    }

    static Process Start(string[] args)
    {
        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        psi.ArgumentList.Add(Path.Combine(AppContext.BaseDirectory, "spectral.dll"));
        foreach (var a in args) psi.ArgumentList.Add(a);
        return Process.Start(psi)!;
    }

    /// <summary>The target replaced by a copy of <paramref name="pristine"/> (the old result), nothing beside it.</summary>
    static void Reset(string pristine, string target)
    {
        if (Directory.Exists(target)) Directory.Delete(target, recursive: true);
        var parent = Path.GetDirectoryName(target)!;
        foreach (var e in Directory.GetFileSystemEntries(parent, $".{Path.GetFileName(target)}.*"))
            if (Directory.Exists(e)) Directory.Delete(e, recursive: true); else File.Delete(e);
        Copy(pristine, target);
    }

    static void Copy(string from, string to)
    {
        Directory.CreateDirectory(to);
        foreach (var f in Directory.GetFiles(from)) File.Copy(f, Path.Combine(to, Path.GetFileName(f)));
        foreach (var d in Directory.GetDirectories(from)) Copy(d, Path.Combine(to, Path.GetFileName(d)));
    }

    static Dictionary<string, byte[]> Snapshot(string dir) => Directory.Exists(dir)
        ? Directory.GetFiles(dir, "*", SearchOption.AllDirectories).ToDictionary(f => Path.GetRelativePath(dir, f), File.ReadAllBytes)
        : [];

    static bool Same(Dictionary<string, byte[]> a, Dictionary<string, byte[]> b) =>
        a.Count == b.Count && a.All(kv => b.TryGetValue(kv.Key, out var v) && kv.Value.AsSpan().SequenceEqual(v));

    /// <summary>The same files as <paramref name="expected"/>; each byte for byte, a manifest (render.json, camera.json) but for
    /// what differs between two runs of one command (times, the command line).</summary>
    static void AssertWhole(Dictionary<string, byte[]> expected, Dictionary<string, byte[]> actual, string what)
    {
        Assert.True(expected.Keys.Order().SequenceEqual(actual.Keys.Order()),
            $"neither folder whole: files {string.Join(",", actual.Keys.Order())} — {what}");
        foreach (var (f, bytes) in expected)
        {
            bool same = f.EndsWith(".json", StringComparison.Ordinal) && !f.Contains('/')
                ? Stable(bytes) == Stable(actual[f])
                : bytes.AsSpan().SequenceEqual(actual[f]);
            Assert.True(same, $"neither folder whole: {f} is not the new run's — {what}");
        }
    }

    static string Stable(byte[] json)
    {
        static JsonNode? Strip(JsonNode? n)
        {
            if (n is JsonObject o)
                foreach (var k in o.Select(kv => kv.Key).ToList())
                {
                    if (k is "created_utc" or "command_line" || k.EndsWith("_s", StringComparison.Ordinal)
                        || k.Contains("seconds", StringComparison.Ordinal))
                        o.Remove(k);
                    else Strip(o[k]);
                }
            else if (n is JsonArray a) foreach (var e in a) Strip(e);
            return n;
        }
        return Strip(JsonNode.Parse(json))!.ToJsonString();
    }
}
