using System.Reflection.PortableExecutable;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// The CLI's build output is precompiled ReadyToRun (the start-up figures in BENCHMARKS.md depend on it): its
/// assemblies carry a ReadyToRun header (the CLI header's ManagedNativeHeader directory, ECMA-335 §II.25.3.3),
/// which plain IL assemblies (the engine as the tests load it) do not.
/// </summary>
public class ReadyToRunTests
{
#if DEBUG
    const string Configuration = "Debug";
#else
    const string Configuration = "Release";
#endif

    static bool IsReadyToRun(string path)
    {
        using var pe = new PEReader(File.OpenRead(path));
        return pe.PEHeaders.CorHeader is { ManagedNativeHeaderDirectory.Size: > 0 };
    }

    [SkippableTheory]
    [InlineData("spectral.dll")]
    [InlineData("SpectralRenderer.dll")]
    public void The_cli_build_output_is_ready_to_run(string assembly)
    {
#if NO_READY_TO_RUN
        Skip.If(true, "built with -p:SpectralReadyToRun=false: the CLI is JIT-compiled");
#endif
        var root = new DirectoryInfo(AppContext.BaseDirectory);
        while (root is not null && !File.Exists(Path.Combine(root.FullName, "SpectralRenderer.sln"))) root = root.Parent;
        Assert.NotNull(root);
        var cliOutput = Path.Combine(root!.FullName, "src", "SpectralRenderer.Cli", "bin", Configuration, "net10.0");
        Assert.True(IsReadyToRun(Path.Combine(cliOutput, assembly)), $"{assembly} in {cliOutput} has no ReadyToRun header");
        // The same check on the engine as the test host loads it (IL only) tells the two apart.
        Assert.False(IsReadyToRun(typeof(SpectralRenderer.Spectra.BandGrid).Assembly.Location));
    }
}
