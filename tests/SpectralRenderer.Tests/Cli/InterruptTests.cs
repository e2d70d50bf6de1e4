using System.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Cli;

/// <summary>Ctrl+C (SIGINT) during a render leaves no incomplete file under a final name.</summary>
[Collection("Alone")]
public class InterruptTests
{
    [SkippableFact]
    public void Sigint_stops_the_render_with_exit_1_and_leaves_nothing_half_written()
    {
        Skip.IfNot(OperatingSystem.IsLinux() && File.Exists("/bin/kill"), "needs Linux and /bin/kill to send SIGINT");
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, """
        { "camera": { "position": [0, 1, 6], "look_at": [0, 0.5, 0], "width": 1600, "height": 1200, "spp": 16 },
          "materials": { "m": { "diffuse": "colorchecker:14", "specular": 0.3, "mirror": 0.2 } },
          "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "m" }, { "type": "plane", "material": "m" } ],
          "max_depth": 3 }
        """);
        var outDir = Path.Combine(dir, "out");
        var dll = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        foreach (var a in new[] { dll, "render", scene, "-o", outDir }) psi.ArgumentList.Add(a);
        using var p = Process.Start(psi)!;
        var err = p.StandardError.ReadToEndAsync();
        // Wait until the render's staging folder exists beside OUTDIR (the scene is loaded and rendering has begun), then interrupt.
        var clock = Stopwatch.StartNew();
        while (!Directory.EnumerateDirectories(dir).Any(d => Path.GetFileName(d).StartsWith(".out.render-", StringComparison.Ordinal))
            && clock.Elapsed.TotalSeconds < 30 && !p.HasExited)
            Thread.Sleep(20);
        Thread.Sleep(300);
        Assert.False(p.HasExited, "the render finished before it could be interrupted");
        Process.Start("/bin/kill", ["-INT", p.Id.ToString()])!.WaitForExit();
        Assert.True(p.WaitForExit(60_000), "the process did not stop after SIGINT");
        Assert.Equal(1, p.ExitCode);
        Assert.Contains("interrupted", err.Result);
        Assert.False(Directory.Exists(outDir));   // the render is staged beside OUTDIR and swapped in only when whole
        Assert.Empty(Directory.GetFileSystemEntries(dir, ".out.*"));
        var files = Directory.Exists(outDir) ? Directory.GetFiles(outDir, "*", SearchOption.AllDirectories) : [];
        Assert.DoesNotContain(files, f => f.EndsWith(".tmp", StringComparison.Ordinal));
        Assert.DoesNotContain(files, f => f.EndsWith("render.json", StringComparison.Ordinal));
        foreach (var f in files.Where(f => f.EndsWith(".png", StringComparison.Ordinal))) Assert.True(PngReader.Read(f).Width == 1600);
    }
}
