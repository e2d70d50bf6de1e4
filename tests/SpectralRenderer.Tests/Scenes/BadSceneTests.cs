using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>Bad scene input: one line naming file:line:column and the JSON path, a hint, exit code 2, nothing in OUTDIR.</summary>
public class BadSceneTests
{
    const string Good = """
    {
      "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 },
      "materials": { "green": { "diffuse": "colorchecker:14" } },
      "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [ { "type": "sphere", "radius": 1, "material": "green" } ]
    }
    """;

    static (int, string, string) RenderText(string json, out string outDir)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, json);
        outDir = Path.Combine(dir, "out");
        return CliRunner.Run("render", scene, "-o", outDir, "--quiet");
    }

    [Fact]
    public void The_good_scene_renders()
    {
        var (code, _, err) = RenderText(Good, out var outDir);
        Assert.Equal(0, code);
        Assert.Equal("", err);
        Assert.True(File.Exists(Path.Combine(outDir, "preview.png")));
        Assert.True(File.Exists(Path.Combine(outDir, "render.json")));
        Assert.Empty(Directory.GetFiles(outDir, "*.tmp", SearchOption.AllDirectories));
    }

    [Theory]
    [InlineData("\"width\": 8,", "\"width\": 8", "scene.json:2:", "JSON syntax error")]
    [InlineData("\"colorchecker:14\"", "\"colorchecker:gren\"", "scene.json:3:40: $.materials.green.diffuse",
        "unknown ColorChecker patch 'gren' (hint: did you mean 'green'?)")]
    [InlineData("\"material\": \"green\"", "\"material\": \"gren\"", "scene.json:5:61: $.objects[0].material", "did you mean 'green'?")]
    [InlineData("\"radius\": 1", "\"radius\": \"one\"", "scene.json:5:46: $.objects[0].radius", "expected a number, found a string")]
    [InlineData("\"position\": [0, 0, 5], ", "", "$.camera.position", "missing required field 'position'")]
    [InlineData("\"width\": 8", "\"width\": 0", "scene.json:2:69: $.camera.width", "resolution 0×6 is not positive")]
    [InlineData("\"height\": 6", "\"height\": -6", "$.camera.height", "is not positive")]
    [InlineData("\"type\": \"sphere\"", "\"type\": \"sphre\"", "scene.json:5:26: $.objects[0].type", "did you mean 'sphere'?")]
    [InlineData("\"type\": \"point\"", "\"type\": \"pointy\"", "$.lights[0].type", "unknown light type 'pointy'")]
    [InlineData("\"width\": 8, \"height\": 6", "\"width\": 30000, \"height\": 30000", "$.camera", "framebuffer of 20 bands needs 67.1 GiB")]
    [InlineData("\"spectrum\": \"D65\"", "\"spectrum\": [[400, 1], [700, 1]]", "$.lights[0].spectrum",
        "covers 400–700 nm but the bands need 380–780 nm")]
    [InlineData("\"spectrum\": \"D65\"", "\"spectrum\": [[400, 1], [700, -1]]", "$.lights[0].spectrum[1][1]", "negative value -1")]
    [InlineData("\"radius\": 1", "\"radius\": 1, \"radiu\": 2", "$.objects[0].radiu", "did you mean 'radius'?")]
    [InlineData("\"spectrum\": \"D65\"", "\"spectrum\": 0", "$.lights[0].spectrum", "has no luminance over the bands")]
    [InlineData("\"type\": \"point\", \"position\": [0, 3, 3]", "\"type\": \"spot\", \"position\": [0, 3, 3], \"look_at\": [0, 3, 3]",
        "$.lights[0].look_at", "look_at equals position")]
    public void Broken_scenes_give_one_located_line_exit_2_and_write_nothing(string find, string replace, string where, string what)
    {
        Assert.Contains(find, Good);
        var (code, _, err) = RenderText(Good.Replace(find, replace), out var outDir);
        Assert.Equal(2, code);
        var lines = err.TrimEnd('\n').Split('\n');
        Assert.Single(lines);
        Assert.Contains(where, err);
        Assert.Contains(what, err);
        Assert.False(Directory.Exists(outDir), "the output folder must not be created for bad input");
    }

    [Fact]
    public void A_missing_scene_file_and_bad_options_are_exit_2()
    {
        var (code, _, err) = CliRunner.Run("render", "/nonexistent/scene.json");
        Assert.Equal(2, code);
        Assert.Contains("/nonexistent/scene.json: scene file not found", err);
        (code, _, err) = CliRunner.Run("render", "x.json", "--spp", "zero");
        Assert.Equal(2, code);
        Assert.Contains("--spp: 'zero' is not a whole number", err);
        (code, _, err) = CliRunner.Run("rendr");
        Assert.Equal(2, code);
        Assert.Contains("did you mean 'render'?", err);
    }

    [Fact]
    public void An_output_path_that_is_a_file_is_exit_2()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Good);
        var blocker = Path.Combine(dir, "taken");
        File.WriteAllText(blocker, "x");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", blocker, "--quiet");
        Assert.Equal(2, code);
        Assert.Contains("exists and is a file", err);
    }

    [Fact]
    public void An_output_folder_that_cannot_be_created_is_exit_2()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Good);
        File.WriteAllText(Path.Combine(dir, "file"), "x");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "file", "sub"), "--quiet");
        Assert.Equal(2, code);
        Assert.Contains("cannot be written", err);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
    }

    [Fact]
    public void A_file_where_the_bands_folder_goes_is_bad_input_exit_2_and_leaves_it_alone()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Good);
        var outDir = Path.Combine(dir, "out");
        Directory.CreateDirectory(outDir);
        File.WriteAllText(Path.Combine(outDir, "bands"), "a file where the bands folder goes");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains("(hint: ", err);
        Assert.False(File.Exists(Path.Combine(outDir, "render.json")));
        Assert.Equal("a file where the bands folder goes", File.ReadAllText(Path.Combine(outDir, "bands")));
        Assert.Empty(Directory.GetFileSystemEntries(dir, ".out.*"));
    }

    [Fact]
    public void Rendering_again_into_a_folder_replaces_the_previous_render_whole()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Good);
        var outDir = Path.Combine(dir, "out");
        Assert.Equal(0, CliRunner.Run("render", scene, "-o", outDir, "--quiet").Exit);
        File.WriteAllText(Path.Combine(outDir, "notes.txt"), "mine");
        Assert.Equal(0, CliRunner.Run("render", scene, "-o", outDir, "--bands", "5", "--formats", "png,bands,npy,aov", "--quiet").Exit);
        Assert.Equal(5, Directory.GetFiles(Path.Combine(outDir, "bands"), "band-*.png").Length);
        Assert.False(File.Exists(Path.Combine(outDir, "spectral.exr")));
        Assert.True(File.Exists(Path.Combine(outDir, "notes.txt")));
        var (code, stdout, _) = CliRunner.Run("probe", outDir, "--pixel", "4,3", "--csv");
        Assert.Equal(0, code);
        Assert.Equal(1 + 5, stdout.Trim().Split('\n').Length);   // header + 5 bands
    }
}
