using System.Text.Json.Nodes;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Output;

/// <summary>
/// Issue 42: a photometric scene (absolute κ: Y in cd/m²; or relative κ under a lamp of a few lux) at the default
/// exposure 1 rendered a preview that was all white or all black, silently. Now such a preview says so in one line
/// with a hint (auto exposure, which does give a picture); the viewer opens at the render's own exposure, and a path
/// render's lights/ are named as per-light outputs, not "no per-light outputs".
/// </summary>
public class PhotometricExposureTests
{
    /// <summary>A white diffuser (ρ = 0.9) lit head-on by a 1000 cd lamp at 2 m (250 lx: L ≈ 72 cd/m²; relative κ puts the white at
    /// D65 as tabulated, ~7 Mlx, so Y ≈ 3e-5), a dark floor around it.</summary>
    static string Scene(string scaling, string exposure, string lamp = "\"luminous_intensity\": 1000") => $$"""
        { "radiometry": "physical", "scaling": "{{scaling}}", "white": "D65", "bands": "380:780:20",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 30, "width": 24, "height": 64, "spp": 1 },
          "materials": { "white": { "diffuse": 0.9 }, "grey": { "diffuse": 0.2 } },
          "lights": [ { "type": "point", "name": "lamp", "position": [0, 0, 2], "spectrum": "D65", {{lamp}} } ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 1, "material": "white" },
                       { "type": "quad", "center": [0, 0, -0.01], "size": 6, "material": "grey" } ]{{exposure}} }
        """;

    static (string Dir, string Err) Render(string scene, string formats = "png,npy")
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "s.json"), scene);
        var (code, _, err) = CliRunner.Run("render", Path.Combine(dir, "s.json"), "-o", Path.Combine(dir, "r"), "--formats", formats,
            "--quiet");
        Assert.True(code == 0, err);
        return (Path.Combine(dir, "r"), err);
    }

    /// <summary>"black", "white" or "" for the preview as read back from its PNG (every code 0, every code 255, else).</summary>
    static string Blank(string dir)
    {
        var png = PngReader.Read(Path.Combine(dir, "preview.png"));
        var s = png.Samples;
        return s.All(v => v == 0) ? "black" : s.All(v => v == (1 << png.BitDepth) - 1) ? "white" : "";
    }

    static JsonNode Colour(string dir) => JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "render.json")))!["colour"]!;

    [Theory]
    [InlineData("absolute", "\"luminous_intensity\": 1000", "white")]
    [InlineData("relative", "\"luminous_intensity\": 1000", "black")]
    public void A_photometric_scenes_blank_preview_at_exposure_1_is_said_in_one_line_and_auto_exposure_gives_a_picture(
        string scaling, string lamp, string blankAt1)
    {
        var (auto, err) = Render(Scene(scaling, ", \"output\": { \"exposure\": \"auto\" }", lamp));
        Assert.Equal("", Blank(auto));
        Assert.DoesNotContain("warning", err);
        Assert.StartsWith("auto", (string)Colour(auto)["exposure_mode"]!);
        Assert.NotEqual(1.0, (double)Colour(auto)["exposure"]!);

        // The default exposure 1: the preview is blank, and the render says so once.
        var (fixedOne, warning) = Render(Scene(scaling, "", lamp));
        Assert.Equal(blankAt1, Blank(fixedOne));
        Assert.Equal("fixed", (string)Colour(fixedOne)["exposure_mode"]!);
        var line = warning.Trim();
        Assert.DoesNotContain('\n', line);
        Assert.Contains($"preview.png is all {blankAt1} at exposure 1", line);
        Assert.Contains("(hint: ", line);
        Assert.Contains(blankAt1 == "black" ? "larger" : "smaller", line);
    }

    static JsonObject ViewerData(string dir)
    {
        var (code, _, err) = CliRunner.Run("view", dir);
        Assert.True(code == 0, err);
        var line = File.ReadLines(Path.Combine(dir, "viewer-data.js"))
            .First(l => l.StartsWith("window.SPECTRAL_VIEWER = ", StringComparison.Ordinal));
        return JsonNode.Parse(line["window.SPECTRAL_VIEWER = ".Length..].TrimEnd(';'))!.AsObject();
    }

    [Fact]
    public void The_viewer_opens_at_the_renders_own_exposure()
    {
        var (dir, _) = Render(Scene("absolute", ", \"output\": { \"exposure\": \"auto\" }"));
        Assert.Equal((double)Colour(dir)["exposure"]!, (double)ViewerData(dir)["exposure"]!);
        Assert.NotEqual(1.0, (double)ViewerData(dir)["exposure"]!);
        var (given, _) = Render(Scene("absolute", ", \"output\": { \"exposure\": 0.004 }"));
        Assert.Equal(0.004, (double)ViewerData(given)["exposure"]!);
    }

    [Fact]
    public void The_viewer_of_a_path_render_with_lights_names_its_per_light_outputs()
    {
        var scene = Scene("absolute", ", \"integrator\": \"path\"");
        var (path, _) = Render(scene, "png,npy,lights");
        Assert.True(Directory.Exists(Path.Combine(path, "lights")));
        Assert.True((bool)ViewerData(path)["other_transfer"]!);
        var (none, _) = Render(scene, "png,npy");
        Assert.False((bool)ViewerData(none)["other_transfer"]!);
        // The page says which, from that flag: never "no per-light outputs" when there are some.
        var page = File.ReadAllText(Path.Combine(path, "viewer.html"));
        Assert.Contains("D.other_transfer ? \"per-light outputs (lights/) of a path render", page);
    }
}
