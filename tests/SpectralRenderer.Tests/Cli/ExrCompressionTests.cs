using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// --exr-compression (and output.exr_compression): zip stores noisy chunks raw, zip-all deflates every chunk,
/// none writes NO_COMPRESSION; all three carry the very same band values as spectral.npy.
/// </summary>
public class ExrCompressionTests
{
    /// <summary>A lit sphere over a floor: shading varies from pixel to pixel, as in a real render.</summary>
    static string Scene()
    {
        var path = Path.Combine(Reference.TempDir(), "sphere.json");
        File.WriteAllText(path, """
            { "camera": { "position": [0, 1.5, 4], "look_at": [0, 0.5, 0], "fov": 40, "width": 120, "height": 80 },
              "materials": { "m": { "diffuse": "colorchecker:13", "specular": 0.3, "shininess": 30 },
                             "floor": { "diffuse": "colorchecker:22" } },
              "ambient": 0.05,
              "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65", "intensity": 0.5 } ],
              "objects": [ { "type": "sphere", "name": "ball", "center": [0, 0.5, 0], "radius": 1, "material": "m" },
                           { "type": "plane", "name": "floor", "point": [0, -0.5, 0], "material": "floor" } ] }
            """);
        return path;
    }

    [Fact]
    public void Each_choice_writes_its_compression_and_the_same_values()
    {
        var sizes = new Dictionary<string, long>();
        foreach (var (choice, attribute) in new[] { ("zip", 3), ("zip-all", 3), ("none", 0) })
        {
            var dir = Reference.TempDir();
            var (code, _, err) =
                CliRunner.Run("render", Scene(), "-o", dir, "--formats", "exr,npy", "--exr-compression", choice, "--quiet");
            Assert.True(code == 0, err);
            var exr = ExrReader.Read(Path.Combine(dir, "spectral.exr"));
            var npy = NpyReader.ReadImage(Path.Combine(dir, "spectral.npy"), exr.Image.Grid);
            Assert.Equal(attribute, exr.Compression);
            Assert.Equal(npy.Data, exr.Image.Data);
            sizes[choice] = new FileInfo(Path.Combine(dir, "spectral.exr")).Length;
        }
        // Deflating every chunk gives the smallest file; storing noisy chunks raw lies between it and no compression.
        Assert.True(sizes["zip-all"] < sizes["zip"], $"zip-all {sizes["zip-all"]} vs zip {sizes["zip"]}");
        Assert.True(sizes["zip"] < sizes["none"], $"zip {sizes["zip"]} vs none {sizes["none"]}");
    }

    [Fact]
    public void An_unknown_choice_is_one_line_with_a_hint()
    {
        var (code, _, err) = CliRunner.Run("render", Scene(), "-o", Reference.TempDir(), "--exr-compression", "zpi", "--quiet");
        Assert.Equal(2, code);
        Assert.Equal("spectral render: --exr-compression: unknown EXR compression 'zpi' (hint: did you mean 'zip'?)", err.Trim());
    }

    [Fact]
    public void The_scene_file_chooses_it_too_and_a_bad_value_points_at_its_line()
    {
        var path = Scene();
        var text = File.ReadAllText(path).TrimEnd().TrimEnd('}') + ",\n  \"output\": { \"exr_compression\": \"zip-all\" } }";
        File.WriteAllText(path, text);
        Assert.Equal(SpectralRenderer.Scenes.ExrCompressionChoice.ZipAll,
            SpectralRenderer.Scenes.Loading.SceneLoader.Load(path).Output.ExrCompression);
        File.WriteAllText(path, text.Replace("\"zip-all\"", "\"lzw\""));
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => SpectralRenderer.Scenes.Loading.SceneLoader.Load(path));
        int line = text.Split('\n').Length;
        Assert.StartsWith($"{path}:{line}:", e.Message);
        Assert.Contains("$.output.exr_compression: unknown EXR compression 'lzw'", e.Message);
    }
}
