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
            Ok("render", Path.Combine(dir, "s.json"), "--height", "64", "--formats", "npy", "--shard", $"{i}/2", "-o",
                Path.Combine(dir, i == "0" ? "a" : "b"), "--quiet");
        File.WriteAllText(Path.Combine(dir, "plan.json"),
            """{ "scene": "s.json", "axes": [ { "name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"] } ] }""");
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

    static Process Start(IDictionary<string, string>? env, params string[] args)
    {
        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        psi.ArgumentList.Add(Path.Combine(AppContext.BaseDirectory, "spectral.dll"));
        foreach (var a in args) psi.ArgumentList.Add(a);
        foreach (var (k, v) in env ?? new Dictionary<string, string>()) psi.Environment[k] = v;
        return Process.Start(psi)!;
    }

    static double SecondsAfterSignal(string line)
    {
        var m = Regex.Match(line, @"(\d+\.\d+) s after the signal");
        Assert.True(m.Success, line);
        return double.Parse(m.Groups[1].Value, CultureInfo.InvariantCulture);
    }

    /// <summary>
    /// The bar: a 2×2 image whose every camera ray branches (a glass ball inside a mirror sphere, no weight threshold,
    /// depth 64) until the documented ray budget of 20 000 rays ends its tree — first shown by the 1-spp render's
    /// warning — with 200 samples a pixel (seconds of work on four pixels): SIGINT stops the render by itself, within
    /// 0.5 s, with its own line (the render's, not the watchdog's), exit 1 and nothing left.
    /// </summary>
    [SkippableFact]
    public void Sigint_stops_a_2x2_render_whose_rays_branch_to_the_ray_budget_within_half_a_second()
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "POSIX signals");
        var d = Reference.TempDir();
        var lights = string.Join(", ", Enumerable.Range(0, 40).Select(i => string.Create(CultureInfo.InvariantCulture,
            $$"""{ "type": "point", "position": [{{0.1 * i - 2}}, 0.5, {{0.3 * (i % 5) - 0.5}}], "spectrum": "D65" }""")));
        string Scene(int spp) => $$"""
            { "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 2, "height": 2, "spp": {{spp}} },
              "materials": { "m": { "diffuse": 0.1, "mirror": 0.9 }, "g": { "diffuse": 0, "transmit": 0.9, "mirror": 0.1, "ior": 1.5 } },
              "lights": [ {{lights}} ],
              "objects": [ { "type": "sphere", "radius": 10, "material": "m" }, { "type": "sphere", "radius": 1, "material": "g" },
                           { "type": "sphere", "center": [1.5, 0, 0], "radius": 0.4, "material": "g" } ],
              "max_depth": 64, "min_ray_weight": 0 }
            """;
        File.WriteAllText(Path.Combine(d, "one.json"), Scene(1));
        File.WriteAllText(Path.Combine(d, "many.json"), Scene(200));
        var (code, _, warning) =
            CliRunner.Run("render", Path.Combine(d, "one.json"), "-o", Path.Combine(d, "one"), "--formats", "npy", "--quiet");
        Assert.True(code == 0, warning);
        Assert.Contains("4 camera rays reached the ray budget of 20000 rays", warning);

        var o = Path.Combine(d, "o");
        using var p = Start(null, "render", Path.Combine(d, "many.json"), "-o", o, "--formats", "npy", "--quiet");
        var err = p.StandardError.ReadToEndAsync();
        var wait = Stopwatch.StartNew();
        while (!Directory.EnumerateDirectories(d).Any(e => Path.GetFileName(e).StartsWith(".o.render-", StringComparison.Ordinal))
            && !p.HasExited
               && wait.Elapsed < TimeSpan.FromSeconds(60))
            Thread.Sleep(10);
        Thread.Sleep(500);   // inside the camera rays' trees
        Assert.False(p.HasExited, $"the render ended before the signal: {(p.HasExited ? err.Result : "")}");
        var clock = Stopwatch.StartNew();
        Assert.Equal(0, kill(p.Id, 2));
        Assert.True(p.WaitForExit(5000), "SIGINT did not stop it within 5 s");
        Assert.True(clock.Elapsed < TimeSpan.FromSeconds(2), $"exited {clock.Elapsed.TotalSeconds:0.00} s after the signal");
        Assert.Equal(1, p.ExitCode);
        var line = err.Result.Trim();
        Assert.DoesNotContain('\n', line);
        Assert.Contains("spectral render: interrupted while rendering", line);
        Assert.True(SecondsAfterSignal(line) < 0.5, line);
        Assert.False(Directory.Exists(o));
        Assert.Empty(Directory.GetFileSystemEntries(d, ".o.*"));
    }

    /// <summary>`view --serve` (until Ctrl+C, as its help says) stops serving on SIGINT and SIGTERM within 0.5 s, its files kept.</summary>
    [SkippableTheory]
    [InlineData(2)]
    [InlineData(15)]
    public void A_signal_stops_the_viewer_within_half_a_second(int signal)
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "POSIX signals");
        var r = Path.Combine(Reference.TempDir(), "r");
        Ok("render", Path.Combine(Shared.Value, "s.json"), "-o", r, "--formats", "npy", "--quiet");
        using var p = Start(null, "view", r, "--serve");
        var serving = p.StandardOutput.ReadLineAsync();
        Assert.True(serving.Wait(TimeSpan.FromSeconds(60)), "the viewer did not start serving");
        Assert.Contains("serving ", serving.Result);
        var err = p.StandardError.ReadToEndAsync();
        var clock = Stopwatch.StartNew();
        Assert.Equal(0, kill(p.Id, signal));
        Assert.True(p.WaitForExit(5000), "the signal did not stop it within 5 s");
        Assert.True(clock.Elapsed < TimeSpan.FromSeconds(2), $"exited {clock.Elapsed.TotalSeconds:0.00} s after the signal");
        var line = err.Result.Trim();
        Assert.Contains($"spectral view: stopped serving on {(signal == 2 ? "SIGINT" : "SIGTERM")}", line);
        Assert.True(SecondsAfterSignal(line) < 0.5, line);
        Assert.True(File.Exists(Path.Combine(r, "viewer.html")));
    }

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
        while (!Directory.EnumerateDirectories(t).Any(e => Path.GetFileName(e).StartsWith(staging, StringComparison.Ordinal))
            && !p.HasExited
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
            Assert.Matches(name is "recover" or "probe" or "reconstruct" ? "is as it was" : before.Length > 0 ? "unchanged" : "holds no",
                line);
        }
    }
}
