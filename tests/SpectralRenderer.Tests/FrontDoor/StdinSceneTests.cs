namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>`spectral render -` reads the scene from standard input; its relative paths resolve from the working folder.</summary>
public class StdinSceneTests
{
    static string Cli => Repo.PathOf("src", "SpectralRenderer.Cli", "bin", Repo.Configuration, "net10.0",
        OperatingSystem.IsWindows() ? "spectral.exe" : "spectral");

    [Fact]
    public void Render_dash_reads_the_scene_from_stdin_and_resolves_paths_from_the_working_folder()
    {
        var work = Reference.TempDir();
        // A reflectance file next to the working folder, named relatively by the scene.
        File.WriteAllText(Path.Combine(work, "card.csv"), "wavelength_nm,grey\n300,0.5\n900,0.5\n");
        const string scene = """
            { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 12 },
              "materials": { "card": { "diffuse": "card.csv:grey" } },
              "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65" } ],
              "objects": [ { "type": "quad", "name": "card", "size": 4, "material": "card" } ] }
            """;
        var (code, _, err) = Repo.Run(Cli, ["render", "-", "-o", "out", "--formats", "npy", "--quiet"], workDir: work, stdin: scene);
        Assert.True(code == 0, err);
        Assert.True(File.Exists(Path.Combine(work, "out", "spectral.npy")));
        Assert.True(File.Exists(Path.Combine(work, "out", "render.json")));

        // Without -o the render goes to out/stdin; a mistake is reported against <stdin> with its line and column.
        (code, _, err) = Repo.Run(Cli, ["render", "-", "--formats", "npy", "--quiet"], workDir: work, stdin: scene);
        Assert.True(code == 0, err);
        Assert.True(File.Exists(Path.Combine(work, "out", "stdin", "spectral.npy")));
        (code, _, err) = Repo.Run(Cli, ["render", "-", "-o", "bad"], workDir: work, stdin: scene.Replace("card.csv:grey", "card.csv:gray"));
        Assert.Equal(2, code);
        Assert.StartsWith("spectral render: <stdin>:2:", err);
        Assert.False(Directory.Exists(Path.Combine(work, "bad")));
    }
}
