using System.Diagnostics;
using SpectralRenderer.Analysis;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Paper;

/// <summary>One scene of the paper rendered: where its outputs are, what it cost, or why it was skipped.</summary>
public sealed record ExperimentRun(string Section, string Name, string Title, string OutDir, int Width, int Height, int Bands,
    double LoadSeconds, double RenderSeconds, double WriteSeconds, long Rays, int Triangles, string? Skipped)
{
    public bool Done => Skipped is null;
}

/// <summary>
/// Renders every scene of the paper (§3.1 the chart, §3.2 one mesh in four materials, §3.3 one material under
/// four lights, §3.4 the reconstruction scene) into one folder each, for <see cref="PaperReport"/>.
/// </summary>
public static class PaperExperiments
{
    /// <summary>The paper's scene files by section; each image's title is taken from its scene (<see cref="Describe"/>).</summary>
    public static readonly (string Section, string File)[] Scenes =
    [
        ("3.1", "paper-3.1-colorchecker-d65"),
        ("3.2", "paper-3.2-bunny-19"), ("3.2", "paper-3.2-bunny-14"), ("3.2", "paper-3.2-bunny-07"), ("3.2", "paper-3.2-bunny-05"),
        ("3.3", "paper-3.3-statue-A"), ("3.3", "paper-3.3-statue-D65"), ("3.3", "paper-3.3-statue-led-blue"),
            ("3.3", "paper-3.3-statue-led-green"),
        ("3.4", "paper-3.4-bunny-analysis"),
    ];

    /// <summary>
    /// A title from what the scene holds: its meshes (or, without meshes, how many objects) with their diffuse
    /// reflectances, and its lights' spectra.
    /// </summary>
    public static string Describe(Scene scene)
    {
        var meshes = scene.Objects.Where(o => o.Mesh is not null).ToList();
        string what = meshes.Count > 0
            ? string.Join(", ",
                meshes.Select(o => $"{o.Name} in {scene.Materials[o.Material].DiffuseSpectrum?.Name ?? scene.Materials[o.Material].Name}"))
            : $"{scene.Objects.Count} objects";
        var lights = scene.Lights.Select(l => l.Spectrum?.Name ?? l.Name).Distinct().ToList();
        return lights.Count == 0 ? what : $"{what} under {string.Join(" and ", lights)}";
    }

    /// <summary>
    /// Renders each scene from <paramref name="sceneDir"/> into <paramref name="outDir"/>/NAME, at <paramref name="scale"/> × its
    /// resolution and with <paramref name="samplesPerPixel"/> samples per pixel (null: the scene's own).
    /// </summary>
    /// <remarks>
    /// The scenes whose report sections take longest to compute (the §3.1 chart: the camera comparison; §3.4: the
    /// analysis) are rendered first, so <paramref name="written"/> can start those sections while the other scenes
    /// render; the runs are returned in the order of <see cref="Scenes"/>.
    /// </remarks>
    public static List<ExperimentRun> Run(string sceneDir, string outDir, double scale, IReadOnlyList<string> models, int threads,
        Action<string>? log = null, int? samplesPerPixel = null,
        Action<ExperimentRun>? written = null)
    {
        var runs = new List<ExperimentRun>();
        var geometries = new GeometryCache();   // the statue under four lights, the bunny in five scenes: one BVH each
        foreach (var (section, file) in Scenes.OrderBy(s => s.Section is "3.1" or "3.4" ? 0 : 1))
        {
            var path = Path.Combine(sceneDir, file + ".json");
            var dir = Path.Combine(outDir, file);
            RenderJob render;
            try
            {
                render = RenderJob.Load(new RenderRequest
                {
                    ScenePath = path,
                    Overrides = new SceneOverrides
                    {
                        ModelDirectories = models,
                        ResolutionScale = scale,
                        SamplesPerPixel = samplesPerPixel,
                        Formats = "png,bands,npy,aov"
                    },
                    Threads = threads,
                    OutDir = dir,
                    Geometries = geometries,
                    Detail = RunDetail.None,
                });
            }
            catch (InputException e) when (e.Problem == InputProblem.MissingFile)
            {
                runs.Add(new ExperimentRun(section, file, file, dir, 0, 0, 0, 0, 0, 0, 0, 0, e.Message));
                log?.Invoke($"{file}: skipped — {e.Message}");
                continue;
            }
            double load = render.LoadSeconds;
            render.Execute();
            var (scene, result, geometry) = (render.Scene, render.Result!, render.Geometry!);
            var clock = Stopwatch.StartNew();
            if (file.StartsWith("paper-3.1", StringComparison.Ordinal))
            {   // Fig. 3 also in the paper's own eq. 4.
                // The pixels' own colours (exact on the tables by default), as preview.png uses them.
                var eq4 = RenderOutputWriter.Preview(result.Image.Width, result.Image.Height, XyzPlanes.FromPixels(result.Xyz!),
                    new DisplayEncoder(scene.Colorimeter, RgbSpace.Paper, scene.Output.Exposure));
                AtomicFile.Write(Path.Combine(dir, "preview-eq4.png"),
                    s => PngWriter.WriteRgb8(s, result.Image.Width, result.Image.Height, eq4));
            }
            double write = render.WriteSeconds + clock.Elapsed.TotalSeconds;
            var run = new ExperimentRun(section, file, Describe(scene), dir, result.Image.Width, result.Image.Height, scene.Bands,
                load, result.Elapsed.TotalSeconds, write, result.Rays.Total, geometry.TriangleCount, null);
            runs.Add(run);
            log?.Invoke($"{file}: {result.Image.Width}×{result.Image.Height} in {result.Elapsed.TotalSeconds:0.00} s");
            written?.Invoke(run);
        }
        return runs.OrderBy(r => Array.FindIndex(Scenes, s => s.File == r.Name)).ToList();
    }
}
