using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>Physically impossible input: refused (exit 2, one line, a hint) or reported on stderr, never silently rendered.</summary>
public class ImpossibleInputTests
{
    static string Scene(string diffuse, string lights = """[ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ]""",
        string extra = "") =>
        $$"""
    {
      "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 },
      "materials": { "m": { "diffuse": {{diffuse}} } },
      "lights": {{lights}},
      "objects": [ { "type": "sphere", "radius": 1, "material": "m" } ]{{extra}}
    }
    """;

    static (int Exit, string Out, string Err, string OutDir) Render(string json)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, json);
        var outDir = Path.Combine(dir, "out");
        var (code, o, e) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        return (code, o, e, outDir);
    }

    [Fact]
    public void A_reflectance_in_percent_exits_2_with_the_scale_hint_and_writes_nothing()
    {
        var (code, _, err, outDir) = Render(Scene("""[[380, 5], [500, 45.5], [780, 80]]"""));
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains("scene.json:3:", err);
        Assert.Contains("$.materials.m.diffuse", err);
        Assert.Contains("reaches 80", err);
        Assert.Contains("\"scale\": 0.01", err);
        Assert.False(File.Exists(Path.Combine(outDir, "render.json")));
    }

    [Fact]
    public void A_reflectance_of_exactly_2_is_refused_too()
    {
        var (code, _, err, _) = Render(Scene("""{ "constant": 2 }"""));
        Assert.Equal(2, code);
        Assert.Contains("reaches 2", err);
    }

    [Fact]
    public void A_negative_reflectance_beyond_rounding_exits_2()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "r.csv"), "wavelength,r\n380,0.2\n500,-0.01\n780,0.3\n");
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene("""{ "csv": "r.csv", "column": "r" }"""));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        // The CSV reader names the row; the scene's own check (< −1e-9 after scaling) backs it for every other source.
        Assert.Contains("r.csv:3:2", err);
        Assert.Contains("negative value -0.01", err);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
    }

    [Fact]
    public void A_reflectance_factor_between_1_and_2_renders_with_a_one_line_warning()
    {
        var (code, _, err, _) = Render(Scene("""[[380, 0.5], [600, 1.3], [780, 0.9]]"""));
        Assert.Equal(0, code);
        var lines = err.TrimEnd('\n').Split('\n');
        Assert.Single(lines);
        Assert.Contains("warning: reflectance", lines[0]);
        Assert.Contains("1.3 > 1", lines[0]);
        Assert.Contains("$.materials.m.diffuse", lines[0]);
    }

    [Fact]
    public void A_scene_without_light_ambient_or_background_is_reported_as_black()
    {
        var (code, _, err, _) = Render(Scene("0.5", lights: "[]"));
        Assert.Equal(0, code);
        Assert.Contains("can only render black", err);
        Assert.Contains("no light", err);
    }

    [Fact]
    public void A_scene_whose_lights_are_dark_is_reported_as_black_and_one_with_a_background_is_not()
    {
        var dark = Render(Scene("0.5", lights: """[ { "type": "point", "position": [0, 3, 3], "spectrum": "D65", "intensity": 0 } ]"""));
        Assert.Contains("can only render black", dark.Err);
        var bg = Render(Scene("0.5", lights: "[]", extra: ", \"background\": 0.2"));
        Assert.Equal("", bg.Err);
    }
}
