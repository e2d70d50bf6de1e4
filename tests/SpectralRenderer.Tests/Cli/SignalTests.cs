using System.Diagnostics;
using System.Globalization;
using System.Runtime.InteropServices;
using System.Text.RegularExpressions;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// SIGINT and SIGTERM in every command that writes, sent to a real child process while its output is staged (the
/// test hook SPECTRAL_TEST_STAGE_DELAY_MS holds it there, in one long step with no cancellation check): it stops
/// within half a second of the signal with one line of what was left, exit 1, the staging removed and the folder
/// as it was; a sweep rebuilds its index.
/// </summary>
[Collection("Alone")]
public class SignalTests
{
    const string Scene = """
    { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 },
      "materials": { "green": { "diffuse": "colorchecker:14" }, "white": { "diffuse": "colorchecker:19" } },
      "lights": [ { "type": "point", "name": "key", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [ { "type": "sphere", "name": "ball", "radius": 1, "material": "green" },
                   { "type": "plane", "name": "board", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "white" } ] }
    """;

    [DllImport("libc", SetLastError = true)]
    static extern int kill(int pid, int sig);

    static void Ok(params string[] args)
    {
        var (code, _, err) = CliRunner.Run(args);
        Assert.True(code == 0, $"{string.Join(' ', args)}: {err}");
    }

    static readonly Lazy<string> Shared = new(() =>
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "s.json"), Scene);
        Ok("render", Path.Combine(dir, "s.json"), "-o", Path.Combine(dir, "r"), "--formats", "png,npy,aov,lights", "--quiet");
        foreach (var i in new[] { "0", "1" })
            Ok("render", Path.Combine(dir, "s.json"), "--height", "64", "--formats", "npy", "--shard", $"{i}/2", "-o", Path.Combine(dir, i == "0" ? "a" : "b"), "--quiet");
        File.WriteAllText(Path.Combine(dir, "plan.json"), """{ "scene": "s.json", "axes": [ { "name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"] } ] }""");
        return dir;
    });

    public static TheoryData<string, int> Cases()
    {
        var d = new TheoryData<string, int>();
        foreach (var c in new[] { "render", "relight", "merge", "camera", "recover", "probe", "reconstruct", "sweep" })
            foreach (var s in new[] { 2, 15 }) d.Add(c, s);
        return d;
    }

    /// <summary>The command and the folder whose staging appears beside it; {t} a fresh folder.</summary>
    static (string[] Args, string Target) Plan(string name, string d, string t) => name switch
    {
        "render" => (["render", $"{d}/s.json", "-o", $"{t}/o", "--quiet"], $"{t}/o"),
        "relight" => (["relight", $"{d}/r", "--light", "key=A", "-o", $"{t}/o", "--quiet"], $"{t}/o"),
        "merge" => (["merge", $"{d}/a", $"{d}/b", "-o", $"{t}/o", "--quiet"], $"{t}/o"),
        "camera" => (["camera", $"{d}/r", "--sensor", "isetcam", "--noise", "off", "-o", $"{t}/o"], $"{t}/o"),
        "recover" => (["recover", $"{t}/o", "--method", "pinv"], $"{t}/o"),
        "probe" => (["probe", $"{d}/r", "--pixel", "1,1", "-o", $"{t}/o/p"], $"{t}/o"),
        "reconstruct" => (["reconstruct", $"{t}/o", "--white-object", "board"], $"{t}/o"),
        "sweep" => (["sweep", $"{d}/plan.json", "-o", $"{t}/o", "--quiet"], $"{t}/o"),
        _ => throw new ArgumentException(name),
    };

    [SkippableFact]
    public void Sigterm_stops_a_camera_run_while_it_writes_within_half_a_second_and_leaves_nothing() => Stops("camera", 15);

    [SkippableTheory]
    [Trait("Category", "Slow")]
    [MemberData(nameof(Cases))]
    public void A_signal_stops_each_command_while_it_writes_within_half_a_second_and_leaves_the_folder_as_it_was(string name, int signal) =>
        Stops(name, signal);

    static void Stops(string name, int signal)
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "POSIX signals");
        var d = Shared.Value;
        var t = Reference.TempDir();
        var (args, target) = Plan(name, d, t);
        if (name == "recover") Ok("camera", $"{d}/r", "--sensor", "isetcam", "--noise", "off", "-o", target);
        if (name == "reconstruct") Ok("render", $"{d}/s.json", "-o", target, "--formats", "npy,aov", "--quiet");
        var before = Directory.Exists(target) ? Directory.GetFiles(target, "*", SearchOption.AllDirectories).Order().ToArray() : [];

        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        psi.ArgumentList.Add(Path.Combine(AppContext.BaseDirectory, "spectral.dll"));
        foreach (var a in args) psi.ArgumentList.Add(a);
        psi.Environment["SPECTRAL_TEST_STAGE_DELAY_MS"] = "20000";
        using var p = Process.Start(psi)!;
        var err = p.StandardError.ReadToEndAsync();
        var staging = $".{Path.GetFileName(target)}.render-";
        var wait = Stopwatch.StartNew();
        while (!Directory.EnumerateDirectories(t).Any(e => Path.GetFileName(e).StartsWith(staging, StringComparison.Ordinal)) && !p.HasExited
               && wait.Elapsed < TimeSpan.FromSeconds(60))
            Thread.Sleep(10);
        Assert.False(p.HasExited, $"{name} ended before the signal: {(p.HasExited ? err.Result : "")}");
        var clock = Stopwatch.StartNew();
        Assert.Equal(0, kill(p.Id, signal));
        Assert.True(p.WaitForExit(5000), $"{name}: signal {signal} did not stop it within 5 s");
        var exited = clock.Elapsed;
        Assert.Equal(1, p.ExitCode);
        var line = err.Result.Trim();
        Assert.DoesNotContain('\n', line);
        Assert.Contains($"spectral {name}: interrupted by {(signal == 2 ? "SIGINT" : "SIGTERM")}", line);
        var m = Regex.Match(line, @"stopped (\d+\.\d+) s after the signal");
        Assert.True(m.Success, line);
        Assert.True(double.Parse(m.Groups[1].Value, CultureInfo.InvariantCulture) < 0.5, line);
        Assert.True(exited < TimeSpan.FromSeconds(2), $"{name}: exited {exited.TotalSeconds:0.00} s after the signal");
        // No staging left, the folder as it was (a sweep's index rebuilt: every job pending).
        Assert.Empty(Directory.GetFileSystemEntries(t, $".{Path.GetFileName(target)}.*"));
        var after = Directory.Exists(target) ? Directory.GetFiles(target, "*", SearchOption.AllDirectories).Order().ToArray() : [];
        if (name == "sweep")
        {
            Assert.Contains("index.csv", line);
            var index = File.ReadAllText(Path.Combine(target, "index.csv"));
            Assert.Equal(2, Regex.Matches(index, ",pending,").Count);
        }
        else
        {
            Assert.Equal(before, after);
            Assert.Matches(name is "recover" or "probe" or "reconstruct" ? "is as it was" : before.Length > 0 ? "unchanged" : "holds no", line);
        }
    }
}
