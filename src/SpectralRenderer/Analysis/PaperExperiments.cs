using System.Diagnostics;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Analysis;

/// <summary>One scene of the paper rendered: where its outputs are, what it cost, or why it was skipped.</summary>
public sealed record ExperimentRun(string Section, string Name, string Title, string OutDir, int Width, int Height, int Bands,
    double LoadSeconds, double RenderSeconds, double WriteSeconds, long Rays, int Triangles, string? Skipped)
{
    public bool Done => Skipped is null;
}

/// <summary>
/// Renders every scene of the paper (§3.1 chart, §3.2 four bunnies, §3.3 the statue under four lights,
/// §3.4 the analysis bunny) into one folder each, for <see cref="PaperReport"/>.
/// </summary>
public static class PaperExperiments
{
    public static readonly (string Section, string File, string Title)[] Scenes =
    [
        ("3.1", "paper-3.1-colorchecker-d65", "ColorChecker under D65"),
        ("3.2", "paper-3.2-bunny-19", "bunny, patch #19 (white)"),
        ("3.2", "paper-3.2-bunny-14", "bunny, patch #14 (green)"),
        ("3.2", "paper-3.2-bunny-07", "bunny, patch #7 (orange)"),
        ("3.2", "paper-3.2-bunny-05", "bunny, patch #5 (blue flower)"),
        ("3.3", "paper-3.3-statue-A", "statue under CIE A"),
        ("3.3", "paper-3.3-statue-D65", "statue under D65"),
        ("3.3", "paper-3.3-statue-led-blue", "statue under the blue LED"),
        ("3.3", "paper-3.3-statue-led-green", "statue under the green LED"),
        ("3.4", "paper-3.4-bunny-analysis", "bunny #14 on a white board"),
    ];

    /// <summary>Renders each scene from <paramref name="sceneDir"/> into <paramref name="outDir"/>/NAME, at <paramref name="scale"/> × its resolution.</summary>
    public static List<ExperimentRun> Run(string sceneDir, string outDir, double scale, IReadOnlyList<string> models, int threads, Action<string>? log = null)
    {
        var runs = new List<ExperimentRun>();
        foreach (var (section, file, title) in Scenes)
        {
            var path = Path.Combine(sceneDir, file + ".json");
            var dir = Path.Combine(outDir, file);
            var clock = Stopwatch.StartNew();
            Scene scene;
            try
            {
                scene = SceneLoader.Load(path, new SceneOverrides { ModelDirectories = models, ResolutionScale = scale, Formats = "png,bands,npy,aov" });
            }
            catch (InputException e) when (e.What.Contains("not found", StringComparison.Ordinal))
            {
                runs.Add(new ExperimentRun(section, file, title, dir, 0, 0, 0, 0, 0, 0, 0, 0, e.Message));
                log?.Invoke($"{file}: skipped — {e.Message}");
                continue;
            }
            double load = clock.Elapsed.TotalSeconds;
            var geometry = new SceneGeometry(scene);
            var result = Renderer.Render(scene, Integrators.Create(scene, geometry), threads);
            clock.Restart();
            RenderOutputWriter.Write(scene, result, dir);
            if (file.StartsWith("paper-3.1", StringComparison.Ordinal))
            {   // Fig. 3 also in the paper's own eq. 4.
                var eq4 = RenderOutputWriter.Preview(result.Image, new DisplayEncoder(scene.Colorimeter, RgbSpace.Paper, scene.Output.Exposure));
                AtomicFile.Write(Path.Combine(dir, "preview-eq4.png"), s => PngWriter.WriteRgb8(s, result.Image.Width, result.Image.Height, eq4));
            }
            double write = clock.Elapsed.TotalSeconds;
            runs.Add(new ExperimentRun(section, file, title, dir, result.Image.Width, result.Image.Height, scene.Bands,
                load, result.Elapsed.TotalSeconds, write, result.Rays.Total, geometry.TriangleCount, null));
            log?.Invoke($"{file}: {result.Image.Width}×{result.Image.Height} in {result.Elapsed.TotalSeconds:0.00} s");
        }
        return runs;
    }
}
