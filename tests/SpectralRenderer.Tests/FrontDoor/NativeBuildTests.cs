using System.Text.Json.Nodes;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Distributed;

namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// README, "Install": `dotnet publish src/SpectralRenderer.Cli -c Release -p:SpectralNative=true -o DIR` gives the native
/// command DIR/spectral (Native AOT, no JIT). It is the same program compiled by another compiler, so the reference it is
/// checked against is the engine the tests run under the JIT: every file of a render, a relight and a camera simulation
/// must be the same bytes, and bad input must give the same one-line message and exit code.
/// The publish runs with its own --artifacts-path, so it shares no bin/ or obj/ folder with the build the tests run from.
/// </summary>
[Trait("Category", "Slow")]
[Trait("Category", "Interop")]
[Trait("Category", "Publish")]   // a Native AOT publish in the fixture: minutes; .ci/run runs it, the fast core does not
public class NativeBuildTests : IClassFixture<NativeBuildTests.Native>
{
    public sealed class Native
    {
        public string Work { get; } = Reference.TempDir();
        public string? Exe { get; }
        public string? Unavailable { get; }

        public Native()
        {
            var out_ = Path.Combine(Work, "native");
            var env = new Dictionary<string, string?> { ["DOTNET_CLI_TELEMETRY_OPTOUT"] = "1", ["DOTNET_NOLOGO"] = "1" };
            var (code, stdout, stderr) =
                Repo.Run("dotnet", ["publish", Repo.PathOf("src", "SpectralRenderer.Cli", "SpectralRenderer.Cli.csproj"),
                "-c", "Release", "-p:SpectralNative=true", "--artifacts-path", Path.Combine(Work, "artifacts"), "-o", out_], env: env,
                    timeoutMs: 600_000);
            var log = stdout + stderr;
            // Offline (no NuGet for the ILCompiler packs) or without a linker, there is no native build to test: say why.
            if (code != 0 && (log.Contains("NU1101") || log.Contains("NU1301") || log.Contains("NU1102")))
            {
                Unavailable = "the ILCompiler packs could not be restored from NuGet: "
                    + log.Split('\n').First(l => l.Contains("NU1")).Trim();
                return;
            }
            Assert.True(code == 0, $"dotnet publish -p:SpectralNative=true failed:\n{log}");
            Exe = Path.Combine(out_, OperatingSystem.IsWindows() ? "spectral.exe" : "spectral");
        }
    }

    readonly Native native;
    public NativeBuildTests(Native native) => this.native = native;

    string Exe()
    {
        Skip.If(native.Unavailable is not null, native.Unavailable);
        return native.Exe!;
    }

    static string Scene(string name) => Repo.PathOf("scenes", name);

    (int Exit, string Out, string Err) RunNative(params string[] args) => Repo.Run(Exe(), args, workDir: native.Work);

    /// <summary>The folders as <see cref="ShardMergeTests.AssertSameRender"/> compares them, "build" aside (another compilation of the
    /// engine).</summary>
    static void AssertSameFolder(string expected, string actual)
    {
        foreach (var dir in new[] { expected, actual })
        {
            var path = Path.Combine(dir, "render.json");
            var m = JsonNode.Parse(File.ReadAllText(path))!.AsObject();
            m.Remove("build");
            File.WriteAllText(path, m.ToJsonString());
        }
        ShardMergeTests.AssertSameRender(expected, actual);
    }

    [SkippableFact]
    public void The_native_command_is_one_executable_with_its_data_and_no_managed_assembly()
    {
        var exe = Exe();
        var dir = Path.GetDirectoryName(exe)!;
        Assert.False(File.Exists(Path.Combine(dir, "spectral.dll")), "a native build needs no spectral.dll");
        Assert.False(File.Exists(Path.Combine(dir, "SpectralRenderer.dll")), "a native build needs no SpectralRenderer.dll");
        Assert.True(File.Exists(Path.Combine(dir, "data", "cie1931-2deg-cmf.csv")), "the data tables are published beside it");
        var head = new byte[4];
        using (var f = File.OpenRead(exe)) f.ReadExactly(head);
        if (OperatingSystem.IsLinux()) Assert.Equal("\u007fELF"u8.ToArray(), head);
        var (code, stdout, err) = RunNative("--help");
        Assert.True(code == 0, err);
        Assert.Contains("usage: spectral <command>", stdout);
    }

    [SkippableFact]
    public void A_native_render_writes_the_same_files_as_the_engine_under_the_jit()
    {
        var exe = Exe();
        string jit = Path.Combine(native.Work, "chart-jit"), aot = Path.Combine(native.Work, "chart-native");
        string[] args = ["render", Scene("paper-3.1-colorchecker-d65.json"), "--width", "120", "--height", "80", "--spp", "2", "--formats",
            "all,lights", "--quiet"];
        var (code, _, err) = CliRunner.Run([.. args, "-o", jit]);
        Assert.True(code == 0, err);
        (code, _, err) = Repo.Run(exe, [.. args, "-o", aot], workDir: native.Work);
        Assert.True(code == 0, err);
        AssertSameFolder(jit, aot);

        // Whitted glass and mirrors (refraction, dispersion, Fresnel) down the same code.
        string gj = Path.Combine(native.Work, "glass-jit"), ga = Path.Combine(native.Work, "glass-native");
        string[] glass = ["render", Scene("glass-mirror.json"), "--width", "96", "--height", "72", "--quiet"];
        (code, _, err) = CliRunner.Run([.. glass, "-o", gj]);
        Assert.True(code == 0, err);
        (code, _, err) = Repo.Run(exe, [.. glass, "-o", ga], workDir: native.Work);
        Assert.True(code == 0, err);
        AssertSameFolder(gj, ga);
    }

    [SkippableFact]
    public void A_native_relight_and_camera_simulation_write_the_same_files_as_the_jit()
    {
        var exe = Exe();
        var source = Path.Combine(native.Work, "source");
        var (code, _, err) = Repo.Run(exe,
            ["render", Scene("paper-3.1-colorchecker-d65.json"), "-o", source, "--width", "96", "--height", "64", "--formats", "all,lights",
                "--quiet"],
            workDir: native.Work);
        Assert.True(code == 0, err);

        string rj = Path.Combine(native.Work, "relit-jit"), ra = Path.Combine(native.Work, "relit-native");
        (code, _, err) = CliRunner.Run("relight", source, "--light", "D65=blackbody:3000", "-o", rj, "--quiet");
        Assert.True(code == 0, err);
        (code, _, err) = Repo.Run(exe, ["relight", source, "--light", "D65=blackbody:3000", "-o", ra, "--quiet"], workDir: native.Work);
        Assert.True(code == 0, err);
        // The native relight of its own render reuses the light-independent files (same build), as the JIT's cannot.
        var copied = JsonNode.Parse(File.ReadAllText(Path.Combine(ra, "render.json")))!["run"]!["relit"]!["copied_files"]!.AsArray();
        Assert.Contains(copied, f => (string?)f == "object-id.png");
        AssertSameFolder(rj, ra);

        string cj = Path.Combine(native.Work, "camera-jit"), ca = Path.Combine(native.Work, "camera-native");
        (code, _, err) = CliRunner.Run("camera", source, "--sensor", "nikon-d5100", "--seed", "7", "-o", cj);
        Assert.True(code == 0, err);
        (code, _, err) = Repo.Run(exe, ["camera", source, "--sensor", "nikon-d5100", "--seed", "7", "-o", ca], workDir: native.Work);
        Assert.True(code == 0, err);
        foreach (var f in new[] { "raw.npy", "raw.png", "raw.dng", "processed.png", "patches.csv", "camera.json" })
            Assert.True(File.ReadAllBytes(Path.Combine(cj, f)).AsSpan().SequenceEqual(File.ReadAllBytes(Path.Combine(ca, f))),
                $"camera {f} differs");
    }

    [SkippableFact]
    public void Bad_input_gives_the_native_command_the_same_one_line_message_and_exit_code()
    {
        Exe();
        var scene = Path.Combine(native.Work, "bad.json");
        File.WriteAllText(scene, "{ \"camera\": { \"width\": -4 } }");
        var (jitCode, _, jitErr) = CliRunner.Run("render", scene, "-o", Path.Combine(native.Work, "bad-jit"));
        var (code, _, err) = RunNative("render", scene, "-o", Path.Combine(native.Work, "bad-native"));
        Assert.Equal(2, jitCode);
        Assert.Equal(jitCode, code);
        Assert.Equal(jitErr, err);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.False(Directory.Exists(Path.Combine(native.Work, "bad-native")));
    }
}
