using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Relight;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// The shipped media scenes (scenes/media-*.json: a glass of water and of red wine on the §3.4 board, the ColorChecker
/// through haze, a foggy Cornell-like room with a spot's beam) load and render at a small size to a finite, non-negative,
/// lit picture; and the red wine, whose absorbance falls by ~50× from 520 to 700 nm, looks red where the camera sees it.
/// </summary>
public class MediaSceneTests
{
    [Theory]
    [InlineData("media-glass-of-water")]
    [InlineData("media-glass-of-red-wine")]
    [InlineData("media-colorchecker-haze")]
    [InlineData("media-cornell-fog-spot")]
    public void A_media_scene_loads_and_renders_small(string name)
    {
        var file = Path.Combine(Repo.Root, "scenes", name + ".json");
        Assert.NotEmpty(SceneLoader.Load(file).Media);
        var dir = Reference.TempDir();
        var (code, _, err) = CliRunner.Run(["render", file, "-o", dir, "--width", "24", "--height", "18", "--spp", "2",
            "--formats", "npy", "--quiet"]);
        Assert.True(code == 0, err);
        var data = PathRelightTests.Npy(dir, "spectral.npy");
        Assert.All(data, v => Assert.True(float.IsFinite(v) && v >= 0, $"{v}"));
        double mean = data.Average(v => (double)v);
        Assert.True(mean > 0, $"mean {mean}");
    }

    [Fact]
    public void The_red_wine_passes_the_red_and_absorbs_the_green()
    {
        var scene = SceneLoader.Load(Path.Combine(Repo.Root, "scenes", "media-glass-of-red-wine.json"),
            new SceneOverrides { Width = 32, Height = 24, SamplesPerPixel = 4 });
        var result = Integrators.Render(scene);
        int wine = scene.Objects.FindIndex(o => o.Name == "wine");
        var grid = scene.Grid;
        var bands = Enumerable.Range(0, grid.Count).Select(grid.Centre).ToArray();
        int board = scene.Objects.FindIndex(o => o.Name == "board");
        // Σ over the object's pixels of the 660–740 nm and 500–560 nm bands.
        (double Red, double Green, int Pixels) Sums(int o)
        {
            double red = 0, green = 0;
            int pixels = 0;
            for (int p = 0; p < result.ObjectIds.Length; p++)
            {
                if (result.ObjectIds[p] != o) continue;
                pixels++;
                for (int b = 0; b < bands.Length; b++)
                {
                    if (bands[b] >= 660 && bands[b] <= 740) red += result.Image.Data[p * bands.Length + b];
                    if (bands[b] >= 500 && bands[b] <= 560) green += result.Image.Data[p * bands.Length + b];
                }
            }
            return (red, green, pixels);
        }
        var (r, g, n) = Sums(wine);
        var (rb, gb, _) = Sums(board);
        Assert.True(n > 20, $"{n} wine pixels");
        // The white board under D65 is greener than red (D65 falls from 520 to 700 nm); the wine, twice as red as it at least.
        Assert.True(r / g > 2 * (rb / gb), $"wine red/green {r / g} vs the board's {rb / gb}");
    }
}
