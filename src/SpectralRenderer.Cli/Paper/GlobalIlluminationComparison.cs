using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Cli.Paper;

/// <summary>
/// Direct light (the paper's model: Whitted, eq. 2's light terms and its mirror chains) against global illumination (the
/// path integrator: every bounce) for one scene of each of §3.1–3.4, both in physical radiometry and without the scenes'
/// constant ambient term (the paper's stand-in for the light between surfaces, which the path render computes, and whose
/// paper units are no radiance), so that the report can say how much the shadows and the §3.4 white-board reconstruction
/// change. Each scene is rendered twice into
/// gi/NAME/direct and gi/NAME/path; the regions are the direct render's (its lit masks: lit = every light reaches the
/// centre ray's point, shadow = none), so both renders are measured on the same pixels; luminance is Y = Σ_b W_y,b·L_b
/// of each render's band cube (render.json's weights). gi/comparison.csv holds every number.
/// </summary>
public static class GlobalIlluminationComparison
{
    /// <summary>One scene per section of the paper.</summary>
    public static readonly (string Section, string File)[] Scenes =
    [
        ("3.1", "paper-3.1-colorchecker-d65"), ("3.2", "paper-3.2-bunny-19"), ("3.3", "paper-3.3-statue-D65"),
        ("3.4", "paper-3.4-bunny-analysis"),
    ];

    /// <summary>
    /// One number of the comparison: a quantity (mean luminance "Y", or the §3.4 reconstruction's mean "rmse" / "gfc")
    /// over a region's pixels, in the direct and the path render.
    /// </summary>
    public sealed record Row(string Section, string Scene, string Quantity, string Region, int Pixels, double Direct, double Path)
    {
        public double Ratio => Direct != 0 ? Path / Direct : double.NaN;
    }

    public sealed record Result(List<Row> Rows, List<(string Scene, string Why)> Skipped, string Folder, double Seconds);

    const string SubjectScene = "paper-3.4-bunny-analysis";

    /// <summary>
    /// Renders each of <paramref name="only"/> (null: <see cref="Scenes"/>) from <paramref name="sceneDir"/> directly and
    /// with the path integrator, both with <paramref name="spp"/> samples per pixel (the same pixel footprint), into
    /// <paramref name="outDir"/>/gi, and compares.
    /// </summary>
    public static Result Run(string sceneDir, string outDir, double scale, IReadOnlyList<string> models, int threads, int spp,
        IReadOnlyCollection<string>? only = null, GeometryCache? geometries = null, Action<string>? log = null)
    {
        var clock = System.Diagnostics.Stopwatch.StartNew();
        var folder = Path.Combine(outDir, "gi");
        Directory.CreateDirectory(folder);
        geometries ??= new GeometryCache();
        var rows = new List<Row>();
        var skipped = new List<(string, string)>();
        foreach (var (section, file) in Scenes.Where(s => only is null || only.Contains(s.Section)))
        {
            var path = Path.Combine(sceneDir, file + ".json");
            var dir = Path.Combine(folder, file);
            var doc = JsonNode.Parse(File.ReadAllBytes(path), null,
                new JsonDocumentOptions { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true })!.AsObject();
            doc["radiometry"] = "physical";
            doc.Remove("ambient");   // the paper's constant stand-in for the light between surfaces, which the path render computes
            var overrides = new SceneOverrides
            {
                ModelDirectories = models,
                ResolutionScale = scale,
                SamplesPerPixel = spp,
                Formats = "npy,aov",
            };
            try
            {
                Render(path, doc, Path.Combine(dir, "direct"), overrides, threads, geometries);
                doc["integrator"] = new JsonObject { ["type"] = "path" };
                Render(path, doc, Path.Combine(dir, "path"), overrides, threads, geometries);
            }
            catch (InputException e) when (e.Problem == InputProblem.MissingFile)
            {
                skipped.Add((file, e.Message));
                log?.Invoke($"gi {file}: skipped — {e.Message}");
                continue;
            }
            rows.AddRange(Compare(section, file, Path.Combine(dir, "direct"), Path.Combine(dir, "path")));
            log?.Invoke($"gi {file}: direct and path rendered");
        }
        AtomicFile.WriteAllText(Path.Combine(folder, "comparison.csv"), Csv(rows));
        return new Result(rows, skipped, folder, clock.Elapsed.TotalSeconds);
    }

    static void Render(string path, JsonObject doc, string outDir, SceneOverrides overrides, int threads, GeometryCache geometries)
    {
        var job = RenderJob.Load(new RenderRequest
        {
            ScenePath = path,
            SceneText = Encoding.UTF8.GetBytes(doc.ToJsonString()),
            Overrides = overrides,
            Threads = threads,
            OutDir = outDir,
            Geometries = geometries,
            Detail = RunDetail.None,
        });
        job.Execute();
    }

    /// <summary>The region means of two render folders of one scene, regions from the direct render's lit masks.</summary>
    public static List<Row> Compare(string section, string scene, string directDir, string pathDir)
    {
        var direct = RenderFolder.Open(directDir);
        var path = RenderFolder.Open(pathDir);
        var aovs = RenderAovs.Open(direct);
        var regions = Regions(direct, aovs);
        var yd = Luminance(direct);
        var yp = Luminance(path);
        var rows = new List<Row>();
        foreach (var (name, mask) in regions)
        {
            int n = 0;
            double sd = 0, sp = 0;
            for (int i = 0; i < mask.Length; i++)
                if (mask[i]) { n++; sd += yd[i]; sp += yp[i]; }
            if (n > 0) rows.Add(new Row(section, scene, "Y", name, n, sd / n, sp / n));
        }
        if (scene == SubjectScene && aovs.Reflectance is not null)
        {   // §3.4: reflectance = pixel ÷ the white board's mean radiance, scored against the ground truth, per region.
            List<RegionSummary> Scored(RenderFolder f) =>
                Reconstruction.Summarise(Reconstruction.Compute(f, aovs, Reconstruction.WhiteObject(f, "board", aovs)).SurfacePixels());
            var sumD = Scored(direct);
            var sumP = Scored(path);
            foreach (var d in sumD)
                if (sumP.FirstOrDefault(p => p.Region == d.Region) is { } p)
                {
                    rows.Add(new Row(section, scene, "rmse", d.Region, d.Count, d.MeanRmse, p.MeanRmse));
                    rows.Add(new Row(section, scene, "gfc", d.Region, d.Count, d.MeanGfc, p.MeanGfc));
                }
        }
        return rows;
    }

    /// <summary>
    /// Surface pixels (the centre ray hits an object), lit (every light reaches it), shadow (none does), from the direct
    /// render's object ids and lit masks.
    /// </summary>
    public static List<(string Name, bool[] Mask)> Regions(RenderFolder direct, RenderAovs aovs)
    {
        int n = direct.ObjectIds.Length;
        var surface = new bool[n];
        var lit = new bool[n];
        var shadow = new bool[n];
        for (int i = 0; i < n; i++)
        {
            if (direct.ObjectIds[i] < 0) continue;
            surface[i] = true;
            int reach = aovs.Lit?.Count(m => m[i]) ?? 0, lights = aovs.Lit?.Length ?? 0;
            lit[i] = lights > 0 && reach == lights;
            shadow[i] = lights > 0 && reach == 0;
        }
        return [("surface", surface), ("lit", lit), ("shadow", shadow)];
    }

    /// <summary>Y per pixel from the band cube with render.json's colour weights.</summary>
    static double[] Luminance(RenderFolder f)
    {
        var img = f.Image;
        var y = new double[img.Width * img.Height];
        var wy = f.Wy;
        for (int i = 0; i < y.Length; i++)
        {
            double s = 0;
            for (int b = 0; b < img.Bands; b++) s += wy[b] * img.Data[i * img.Bands + b];
            y[i] = s;
        }
        return y;
    }

    static string Csv(List<Row> rows)
    {
        var sb = new StringBuilder("section,scene,quantity,region,pixels,direct,path,path_over_direct\n");
        foreach (var r in rows)
            sb.Append(CultureInfo.InvariantCulture,
                $"{r.Section},{r.Scene},{r.Quantity},{r.Region},{r.Pixels},{r.Direct:R},{r.Path:R},{r.Ratio:R}\n");
        return sb.ToString();
    }
}
