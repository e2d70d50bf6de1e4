namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// README, "Install": the CLI packs as a .NET tool whose command is `spectral`. This packs the already-built CLI
/// (dotnet pack --no-build), installs the package into a temporary --tool-path from that folder alone (a
/// nuget.config that clears every other source, so nothing is fetched), and runs the installed command.
/// </summary>
public class ToolInstallTests
{
    [Fact]
    [Trait("Category", "Slow")]
    [Trait("Category", "Interop")]
    [Trait("Category", "Publish")]   // dotnet pack and tool install: .ci/run runs it, the fast core does not
    public void The_packed_tool_installs_into_a_tool_path_and_runs_as_spectral()
    {
        var work = Reference.TempDir();
        string feed = Path.Combine(work, "feed"), tools = Path.Combine(work, "tools"), config = Path.Combine(work, "nuget.config");
        File.WriteAllText(config, $"""
            <?xml version="1.0" encoding="utf-8"?>
            <configuration>
              <packageSources><clear /><add key="local" value="{feed}" /></packageSources>
            </configuration>
            """);
        var env = new Dictionary<string, string?> { ["DOTNET_CLI_TELEMETRY_OPTOUT"] = "1", ["DOTNET_NOLOGO"] = "1" };
        List<string> pack = ["pack", Repo.PathOf("src", "SpectralRenderer.Cli", "SpectralRenderer.Cli.csproj"), "-c", Repo.Configuration,
            "--no-build", "-o", feed];
#if NO_READY_TO_RUN
        pack.Add("-p:SpectralReadyToRun=false");
#endif
        var (code, stdout, stderr) = Repo.Run("dotnet", pack, env: env);
        Assert.True(code == 0, $"dotnet pack failed:\n{stdout}\n{stderr}");
        Assert.Single(Directory.GetFiles(feed, "SpectralRenderer.Cli.*.nupkg"));

        (code, stdout, stderr) = Repo.Run("dotnet",
            ["tool", "install", "SpectralRenderer.Cli", "--tool-path", tools, "--configfile", config], workDir: work, env: env);
        Assert.True(code == 0, $"dotnet tool install failed:\n{stdout}\n{stderr}");

        var spectral = Path.Combine(tools, OperatingSystem.IsWindows() ? "spectral.exe" : "spectral");
        Assert.True(File.Exists(spectral), $"no {spectral} after install");
        (code, stdout, stderr) = Repo.Run(spectral, ["--help"], workDir: work);
        Assert.True(code == 0, stderr);
        Assert.Contains("usage: spectral <command>", stdout);
        Assert.Contains("render", stdout);
        // The installed tool carries its data tables: the ColorChecker under D65 against the 1 nm reference.
        (code, stdout, stderr) = Repo.Run(spectral, ["colors", "--illuminant", "D65", "--csv"], workDir: work);
        Assert.True(code == 0, stderr);
        Assert.Equal(25, stdout.Trim().Split('\n').Length);
    }
}
