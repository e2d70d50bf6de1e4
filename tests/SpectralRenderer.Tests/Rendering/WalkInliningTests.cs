using System.Diagnostics;
using System.Text.RegularExpressions;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path walk keeps its small helpers inlined. The JIT stops inlining into a method once the method's inlining budget
/// is spent, and what it then leaves as calls is arbitrary: on main 20512a2 the walk (2,230 bytes of IL, ~400 inlinees)
/// called the Sobol sampler's hash steps, Vector3.Dot and its band loops out of line, ~10 % of the path Cornell room's
/// time (BENCHMARKS.md, "The path walk's inlining"). The walk's rarer steps are therefore methods of their own; this test
/// reads the machine code the JIT makes for the walk and its next-event estimation (DOTNET_JitDisasm of the release
/// runtime, as scripts/jit-calls.sh prints it) and fails when a helper that must be inlined is called.
/// </summary>
[Trait("Category", "Slow")]   // one CLI process with the JIT's disassembly: ~5 s
public class WalkInliningTests
{
    /// <summary>Call targets that mean the walk's budget ran out: the sampler's draws and their hash steps, the band
    /// arithmetic, the vector maths.</summary>
    static readonly string[] MustInline =
    [
        "Sampler:At1D", "Sampler:At2D", "OwenSobol:", "Renderer:Hash", "PathIntegrator:Multiply(", "PathIntegrator:Max(",
        "PathIntegrator:Scale(", "MemoryMarshal:Cast", "Vector3:Dot", "Vector2:.ctor", "Vector2:Create", "Vector`1[float]:.ctor",
        "SceneGeometry:get_Epsilon", "BsdfSample:get_", "PathVertex:.ctor", "Visibility:Leaving", "Visibility:ShadowRay",
    ];

    [SkippableFact]
    public void The_path_walk_calls_none_of_its_inlined_helpers()
    {
        var dll = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        var listing = Path.Combine(Reference.TempDir(), "walk.asm");
        var psi = new ProcessStartInfo("dotnet") { RedirectStandardError = true, RedirectStandardOutput = true, UseShellExecute = false };
        foreach (var a in new[] { dll, "bench", Reference.RepoFile("scenes/path-cornell-room.json"), "--width", "32", "--height", "24",
            "--spp", "2", "--repeat", "1", "--threads", "1" })
            psi.ArgumentList.Add(a);
        psi.Environment["DOTNET_JitDisasm"] = "*PathIntegrator:Walk *PathIntegrator:NextEvent";
        psi.Environment["DOTNET_JitStdOutFile"] = listing;
        using var p = Process.Start(psi)!;
        var stderr = p.StandardError.ReadToEndAsync();
        p.StandardOutput.ReadToEnd();
        Assert.True(p.WaitForExit(120_000), "bench did not finish");
        Assert.True(p.ExitCode == 0, stderr.Result);
        Skip.IfNot(File.Exists(listing), "this runtime does not write the JIT's disassembly (DOTNET_JitDisasm)");

        // Each method's listing, and the targets of its call instructions.
        var methods = new List<(string Name, List<string> Calls)>();
        foreach (var line in File.ReadLines(listing))
        {
            if (line.StartsWith("; Assembly listing for method ", StringComparison.Ordinal))
                methods.Add((line["; Assembly listing for method ".Length..], []));
            else if (methods.Count > 0 && Regex.Match(line, @"^\s+call\s+(.*)$") is { Success: true } m)
                methods[^1].Calls.Add(m.Groups[1].Value);
        }
        // The walk over a camera sample, the walk from a ray, and next-event estimation, for the film's sink.
        Assert.Contains(methods, x => x.Name.Contains("PathIntegrator:Walk", StringComparison.Ordinal) && x.Calls.Count > 0);
        Assert.Contains(methods, x => x.Name.Contains("PathIntegrator:NextEvent", StringComparison.Ordinal));
        var outOfLine = methods
            .SelectMany(x => x.Calls.Where(c => MustInline.Any(h => c.Contains(h, StringComparison.Ordinal)))
                .Select(c => $"{x.Name.Split('[', '(')[0]} calls {c}"))
            .Distinct().ToList();
        Assert.True(outOfLine.Count == 0, "the path walk's inlining budget is spent (move a rare step into a method of its own, "
            + "as PathIntegrator.Escaped, Seen and DeltaLobes are):\n" + string.Join("\n", outOfLine));
    }
}
