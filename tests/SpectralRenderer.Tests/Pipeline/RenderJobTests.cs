using SpectralRenderer.Output;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Pipeline;

/// <summary>The one render job: the integrator chosen by name on the command line, and render.json's typed "run".</summary>
public class RenderJobTests
{
    const string Scene = """
    {
      "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 12, "height": 8 },
      "materials": { "green": { "diffuse": "colorchecker:14" } },
      "lights": [ { "type": "point", "name": "key", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [ { "type": "sphere", "radius": 1, "material": "green" } ]
    }
    """;

    static string WriteScene(string dir)
    {
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene);
        return path;
    }

    [Fact]
    public void An_unknown_integrator_is_bad_input_naming_the_known_ones_and_writes_nothing()
    {
        var dir = Reference.TempDir();
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", WriteScene(dir), "-o", outDir, "--quiet", "--integrator", "pathh");
        Assert.Equal(2, code);
        var line = Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.StartsWith("spectral render: --integrator: unknown integrator 'pathh'", line);
        Assert.Contains("(hint: known integrators: whitted", line);
        Assert.False(File.Exists(Path.Combine(outDir, "render.json")));
        Assert.Empty(Directory.GetDirectories(dir, ".out.render-*"));
    }

    [Fact]
    public void Bench_takes_the_integrator_by_name_too()
    {
        var dir = Reference.TempDir();
        var (code, _, err) = CliRunner.Run("bench", WriteScene(dir), "--repeat", "1", "--integrator", "nope");
        Assert.Equal(2, code);
        Assert.Contains("--integrator: unknown integrator 'nope'", err);
    }

    [Fact]
    public void The_integrator_named_on_the_command_line_is_the_one_rendered()
    {
        // The default's own name gives the default's files, byte for byte.
        var dir = Reference.TempDir();
        var scene = WriteScene(dir);
        Assert.Equal(0, CliRunner.Run("render", scene, "-o", Path.Combine(dir, "a"), "--quiet").Exit);
        Assert.Equal(0, CliRunner.Run("render", scene, "-o", Path.Combine(dir, "b"), "--quiet", "--integrator", "whitted").Exit);
        foreach (var f in new[] { "preview.png", "spectral.npy", "object-id.png" })
            Assert.Equal(File.ReadAllBytes(Path.Combine(dir, "a", f)), File.ReadAllBytes(Path.Combine(dir, "b", f)));
    }

    [Fact]
    public void The_job_records_its_run_as_a_type_that_reads_back_to_the_same_json()
    {
        var dir = Reference.TempDir();
        var scene = WriteScene(dir);
        var outDir = Path.Combine(dir, "out");
        var job = RenderJob.Run(new RenderRequest
        {
            ScenePath = scene,
            Overrides = new SceneOverrides { Width = 10, Formats = "png,npy,lights" },
            Threads = 1,
            OutDir = outDir,
            Run = new ManifestRun { CommandLine = "test" },
        });
        Assert.Equal(10, job.Result!.Image.Width);
        Assert.NotNull(job.Transfer);   // the lights product asks for the per-light transfer
        Assert.Contains("lights/lights.json", job.Files);

        var text = File.ReadAllText(Path.Combine(outDir, RenderManifest.FileName));
        var manifest = RenderManifest.Read(outDir);
        var run = manifest.Run!;
        Assert.Equal("test", run.CommandLine);
        Assert.Equal(0, run.Triangles);
        Assert.Equal(10, run.Overrides!.Width);
        Assert.Null(run.Overrides.Height);
        Assert.Equal("png,npy,lights", run.Overrides.Formats);
        Assert.NotNull(run.LightTransferSeconds);
        Assert.NotNull(run.WriteSeconds);
        Assert.Null(run.Relit);
        // The one writer and the one reader agree: the manifest read back writes the file's text again.
        Assert.Equal(text, manifest.ToJsonText());
    }

    [Fact]
    public void A_relit_render_records_its_source_and_changes_and_reads_back_the_same()
    {
        var dir = Reference.TempDir();
        var scene = WriteScene(dir);
        Assert.Equal(0, CliRunner.Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "png,lights").Exit);
        var (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--light", "key=A", "-o", Path.Combine(dir, "A"),
            "--quiet", "--metrics");
        Assert.True(code == 0, err);
        var relitDir = Path.Combine(dir, "A");
        var manifest = RenderManifest.Read(relitDir);
        var relit = manifest.Run!.Relit!;
        Assert.Equal(Path.GetFullPath(Path.Combine(dir, "r")), relit.From);
        var change = Assert.Single(relit.Changes);
        Assert.Equal(("key", "A", (double?)null), (change.Light, change.Spectrum, change.Intensity));
        Assert.Equal("sphere-0", Assert.Single(relit.Metrics!.Objects).Object);
        Assert.Equal(File.ReadAllText(Path.Combine(relitDir, RenderManifest.FileName)), manifest.ToJsonText());
    }
}
