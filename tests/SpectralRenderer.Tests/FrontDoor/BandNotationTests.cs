using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// Band notation: --bands/"bands" give edges start:end:count, --wave/"wave" give centres start:step:end
/// (MATLAB/ISETCam colon notation, width = step). Bands are numbered from 1 in every file and table a
/// person reads. Expected grids are the closed forms of the notation, not the program's output.
/// </summary>
public class BandNotationTests
{
    const string Scene = """
        { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 30, "width": 64, "height": 48 },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65" } ],
          "objects": [ { "type": "quad", "name": "card", "size": 4, "material": "colorchecker:14" } ] }
        """;

    [Theory]
    [InlineData("400:10:700", 31, 395.0, 705.0, 10.0)]
    [InlineData("380:20:760", 20, 370.0, 770.0, 20.0)]
    [InlineData("400:10:705", 31, 395.0, 705.0, 10.0)]   // MATLAB: the last centre not beyond the end
    [InlineData("400:0.5:700", 601, 399.75, 700.25, 0.5)]
    [InlineData("550:5:550", 1, 547.5, 552.5, 5.0)]
    public void Wave_gives_band_centres_step_apart_each_step_wide(string wave, int count, double start, double end, double width)
    {
        var g = BandGrid.ParseWave(wave);
        Assert.Equal(count, g.Count);
        Assert.Equal(start, g.Start, 9);
        Assert.Equal(end, g.End, 9);
        Assert.Equal(width, g.Width, 9);
        double first = double.Parse(wave.Split(':')[0], CultureInfo.InvariantCulture);
        for (int b = 0; b < g.Count; b++) Assert.Equal(first + b * width, g.Centre(b), 6);
    }

    [Theory]
    [InlineData("400:0:700", "positive step")]
    [InlineData("700:10:400", "before it starts")]
    [InlineData("400:10", "not a list of band centres")]
    [InlineData("4:10:700", "at or below 0 nm")]
    public void Bad_wave_is_one_line_with_a_hint(string wave, string what)
    {
        var e = Assert.Throws<InputException>(() => BandGrid.ParseWave(wave));
        Assert.Contains(what, e.Message);
        Assert.Contains("e.g. 400:10:700", e.Message);
    }

    [Fact]
    public void Wave_on_the_command_line_and_in_the_scene_equal_the_same_edges()
    {
        var byWave = SceneText.Load(Scene, new SceneOverrides { Wave = "400:10:700" }).Grid;
        var byEdges = SceneText.Load(Scene, new SceneOverrides { Bands = "395:705:31" }).Grid;
        var byKey = SceneText.Load(Scene.Replace("\"camera\"", "\"wave\": \"400:10:700\", \"camera\"")).Grid;
        Assert.Equal(byEdges, byWave);
        Assert.Equal(byEdges, byKey);
        var both = Assert.Throws<InputException>(() =>
            SceneText.Load(Scene.Replace("\"camera\"", "\"wave\": \"400:10:700\", \"bands\": \"380:780:20\", \"camera\"")));
        Assert.Contains("both", both.Message);
        var (code, _, err) =
            CliRunner.Run("render", WriteScene(Scene), "--wave", "400:10:700", "--bands", "20", "--quiet", "-o", Reference.TempDir());
        Assert.Equal(2, code);
        Assert.Contains("--wave and --bands", err);
    }

    [Fact]
    public void Colors_takes_wave_for_the_same_bands_as_their_edges()
    {
        var (code, byWave, err) = CliRunner.Run("colors", "--wave", "390:20:770", "--csv");
        Assert.True(code == 0, err);
        var (_, byEdges, _) = CliRunner.Run("colors", "--bands", "380:780:20", "--csv");
        Assert.Equal(byEdges, byWave);
        (code, _, err) = CliRunner.Run("colors", "--wave", "390:20:770", "--bands", "380:780:20");
        Assert.Equal(2, code);
        Assert.Contains("--wave and --bands", err);
    }

    static string WriteScene(string json)
    {
        var path = Path.Combine(Reference.TempDir(), "scene.json");
        File.WriteAllText(path, json);
        return path;
    }

    [Fact]
    public void Bands_are_numbered_from_1_in_png_names_wavelengths_csv_and_probe()
    {
        var outDir = Path.Combine(Reference.TempDir(), "out");
        var (code, _, err) =
            CliRunner.Run("render", WriteScene(Scene), "--wave", "400:10:700", "--formats", "bands,npy", "--quiet", "-o", outDir);
        Assert.True(code == 0, err);

        // wavelengths.csv: band k (1…31) is centred on 400 + 10·(k − 1) nm, 10 nm wide.
        var rows = File.ReadAllLines(Path.Combine(outDir, "wavelengths.csv")).Skip(1).Where(l => l.Length > 0)
            .Select(l => l.Split(',').Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray()).ToArray();
        Assert.Equal(31, rows.Length);
        for (int k = 1; k <= 31; k++)
        {
            var r = rows[k - 1];
            Assert.Equal(k, r[0]);
            Assert.Equal(395 + 10 * (k - 1), r[1], 9);
            Assert.Equal(400 + 10 * (k - 1), r[2], 9);
            Assert.Equal(405 + 10 * (k - 1), r[3], 9);
        }
        // The band PNG numbered k covers the same range as row k.
        var pngs = Directory.GetFiles(Path.Combine(outDir, "bands"), "band-*.png").Select(Path.GetFileName).Order().ToArray();
        Assert.Equal(31, pngs.Length);
        Assert.Equal("band-01-395-405nm.png", pngs[0]);
        Assert.Equal("band-31-695-705nm.png", pngs[^1]);

        // probe: the band column of the CSV and of the table counts 1…31 too.
        (code, var stdout, err) = CliRunner.Run("probe", outDir, "--pixel", "32,24", "--csv", "-o", Path.Combine(outDir, "probe"));
        Assert.True(code == 0, err);
        var probeBands = stdout.Trim().Split('\n').Skip(1).Select(l => int.Parse(l.Split(',')[0], CultureInfo.InvariantCulture)).ToArray();
        Assert.Equal(Enumerable.Range(1, 31), probeBands);
        (code, stdout, err) = CliRunner.Run("probe", outDir, "--pixel", "32,24", "-o", Path.Combine(outDir, "probe"));
        Assert.True(code == 0, err);
        var table = stdout.Split('\n').Where(l => l.Contains('–')).Select(l => l.Trim().Split(' ')[0]).ToArray();
        Assert.Equal("1", table[0]);
        Assert.Equal("31", table[^1]);
    }

    [Theory]
    [InlineData("--width", "64", 64, 48)]     // the scene's camera is 640 × 480 below
    [InlineData("--height", "30", 40, 30)]
    [InlineData("--width", "101", 101, 76)]   // 75.75 rounds to 76
    public void Width_or_height_alone_keeps_the_cameras_aspect_ratio(string option, string value, int width, int height)
    {
        var scene = WriteScene(Scene.Replace("\"width\": 64, \"height\": 48", "\"width\": 640, \"height\": 480"));
        var outDir = Path.Combine(Reference.TempDir(), "out");
        var (code, _, err) = CliRunner.Run("render", scene, option, value, "--formats", "png", "--quiet", "-o", outDir);
        Assert.True(code == 0, err);
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "render.json")))!;
        Assert.Equal(width * height, (long)json["rays"]!["primary"]!);
        var png = File.ReadAllBytes(Path.Combine(outDir, "preview.png"));   // IHDR: width and height, big-endian, at 16 and 20
        Assert.Equal(width, System.Buffers.Binary.BinaryPrimitives.ReadInt32BigEndian(png.AsSpan(16)));
        Assert.Equal(height, System.Buffers.Binary.BinaryPrimitives.ReadInt32BigEndian(png.AsSpan(20)));
    }
}
