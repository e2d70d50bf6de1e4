using System.Globalization;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// Issue 42: an adaptive render's one-line summary printed the sample cap as its spp. It must print the samples the pixels
/// took — the same minimum, mean and maximum render.json's sampling.adaptive records from the per-pixel counts.
/// </summary>
public class RenderSummaryTests
{
    [Fact]
    public void An_adaptive_renders_summary_gives_the_samples_its_pixels_took()
    {
        var dir = Reference.TempDir();
        var scene = Reference.RepoFile("scenes/path-cornell-room.json");
        var (exit, _, err) = CliRunner.Run("render", scene, "-o", dir, "--width", "16", "--height", "12", "--spp", "64",
            "--target-error", "0.05", "--formats", "png");
        Assert.Equal(0, exit);
        var adaptive = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "render.json")))!["sampling"]!["adaptive"]!;
        var m = Regex.Match(err, @"(\d+)–(\d+) spp \(mean ([\d.]+), cap (\d+)\)");
        Assert.True(m.Success, err);
        Assert.Equal(adaptive["spp_min"]!.GetValue<int>(), int.Parse(m.Groups[1].Value, CultureInfo.InvariantCulture));
        Assert.Equal(adaptive["spp_max"]!.GetValue<int>(), int.Parse(m.Groups[2].Value, CultureInfo.InvariantCulture));
        Assert.Equal(adaptive["spp_mean"]!.GetValue<double>(), double.Parse(m.Groups[3].Value, CultureInfo.InvariantCulture), 0.05);
        Assert.Equal(64, int.Parse(m.Groups[4].Value, CultureInfo.InvariantCulture));
        Assert.True(adaptive["spp_min"]!.GetValue<int>() < 64, "the target stops some pixels before the cap");
    }
}
