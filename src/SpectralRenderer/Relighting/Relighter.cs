using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Relighting;

/// <summary>What to change: per light (by name) a new spectrum and/or intensity, and the reference white.</summary>
/// <summary>A light's new spectrum and/or intensity; <paramref name="Where"/> names where the spectrum was given
/// (a sweep CSV's file:row:column) for messages, null for the command line's --light.</summary>
public sealed record LightChange(string Light, string? Spectrum, double? Intensity, string? Where = null);

/// <summary>
/// Relighting a render folder that has the per-light transfer (lights/): the scene is rebuilt from the
/// resolved scene and the command-line overrides render.json recorded, with the lights' spectra, intensities
/// and the reference white changed as asked (so the band grid, κ, eq. 3 weights and every output option are
/// exactly what a fresh render of the changed scene has), and the image is S + Σ_c F_c · P_c under the new
/// light band values (<see cref="ILightTransfer.Relight"/>). No ray is traced. The result is written as a
/// complete render folder, its render.json saying it was relit and from what.
/// </summary>
public static class Relighter
{
    public sealed record Source(string Dir, RenderManifest Manifest, ManifestScene Scene, string ScenePath, SceneOverrides Overrides,
        string[] LightNames);

    /// <summary>A render folder read through its manifest: the resolved scene and the overrides it was rendered with.</summary>
    public static Source Open(string dir)
    {
        if (!Directory.Exists(dir)) throw new InputException(dir, "no such render folder", "give the -o folder of a 'spectral render' run");
        var manifest = RenderManifest.Read(dir).Whole(dir);
        if (manifest.ResolvedScene is not { } scene)
            throw new InputException(Path.Combine(dir, RenderManifest.FileName), "has no resolved_scene",
                "render again with this version of spectral");
        // No ray is traced: the meshes' triangles are not needed (nor their files present).
        var overrides = Pipeline.RenderJob.Overrides(manifest.Run?.Overrides) with { LoadMeshes = false };
        var names = scene.Lights.Select(l => l.Name).ToArray();
        return new Source(dir, manifest, scene, manifest.Scene.Length > 0 ? manifest.Scene : Path.Combine(dir, "scene.json"), overrides,
            names);
    }

    /// <summary>The scene of <paramref name="src"/> with the changes applied, loaded as a render would load it.</summary>
    /// <paramref name="whiteWhere"/> names where the white was given (default --white).
    public static Scene ChangedScene(Source src, IReadOnlyList<LightChange> changes, string? white, string? whiteWhere = null)
    {
        var edits = new List<(int, string?, double?)>();
        foreach (var c in changes)
        {
            int k = Array.IndexOf(src.LightNames, c.Light);
            if (k < 0 && NotRelightable(src, c.Light) is { } what)
                throw new InputException($"--light {c.Light}",
                    $"'{c.Light}' is {what}: a relight changes the scene's lights (point, spot, directional, goniometric); emitting "
                        + $"surfaces and the sky are kept as rendered",
                    $"change it in the scene file and render again; relightable lights: {string.Join(", ", src.LightNames)}");
            if (k < 0)
                throw new InputException($"--light {c.Light}", $"the render has no light named '{c.Light}'",
                    InputException.DidYouMean(c.Light, src.LightNames) is { } d
                        ? d
                        : $"its lights are: {string.Join(", ", src.LightNames)}");
            if (c.Spectrum is not null) Check(src, c.Spectrum, c.Where ?? $"--light {c.Light}");
            edits.Add((k, c.Spectrum, c.Intensity));
        }
        if (white is not null) Check(src, white, whiteWhere ?? "--white");
        try
        {
            return SceneLoader.Parse(src.Scene.WithLights(edits, white), src.ScenePath, src.Overrides);
        }
        catch (InputException e) when (white is not null && e.Where.EndsWith("$.white", StringComparison.Ordinal))
        {
            // The new white is the user's argument, not the rendered scene's field: name where it was given.
            throw new InputException(whiteWhere ?? "--white", e.What, e.Hint);
        }
    }

    /// <summary>What <paramref name="name"/> is when it is a source of light a relight keeps (an emitting material, the sky), else
    /// null.</summary>
    static string? NotRelightable(Source src, string name)
    {
        var doc = src.Scene.ToJson();
        if (doc["materials"]?[name] is JsonObject m && m["emission"] is not null) return "an emitting material (an area light)";
        return name is "sky" or "background" && (doc["sky"] is not null || doc["background"] is not null)
            ? "the scene's sky (its background)"
            : null;
    }

    /// <summary>A spectrum named on the command line resolves (or is one of the scene's own named spectra).</summary>
    static void Check(Source src, string spectrum, string where)
    {
        if (src.Scene.NamesSpectrum(spectrum)) return;
        Spectra.SpectrumLibrary.Resolve(spectrum, Path.GetDirectoryName(Path.GetFullPath(src.ScenePath)), where);
    }

    /// <summary>Relights <paramref name="src"/> into <paramref name="outDir"/>: every file a render writes.</summary>
    public static (Scene Scene, List<string> Files, TimeSpan Compute) Write(Source src, IReadOnlyList<LightChange> changes, string? white,
        string outDir,
        string commandLine, CancellationToken cancel = default, bool metrics = false)
    {
        var scene = ChangedScene(src, changes, white);
        scene.Output.Products &= ~OutputProducts.Noise;   // measured from a render's samples: a relit render has none to write
        // By identity, not spelling: "r/", "./r" or a link to r is the folder being relit too.
        if (OutputFolder.SameFolder(src.Dir, outDir))
            throw new InputException(outDir, "is the folder being relit", "write the relit render to another folder with -o");
        var format = TransferFiles.FormatOf(src.Dir);
        foreach (var c in changes)
            if (c.Spectrum is not null && format?.RefusesNewSpectrum(scene.Lights[Array.IndexOf(src.LightNames, c.Light)]) is { } why)
                throw new InputException($"--light {c.Light}", $"light '{c.Light}' {why}",
                    "give it a new --intensity only, or render the scene again with the new spectrum");
        var clock = System.Diagnostics.Stopwatch.StartNew();
        // The transfer of whichever integrator rendered the folder (lights.json's kind), checked against the rebuilt scene.
        var transfer = TransferFiles.Read(src.Dir, scene);
        if (transfer.Mismatch(scene) is { } mismatch)
            throw new InputException(src.Dir, mismatch, "the scene file changed since the render; render again");
        var reuse = Reusable(src, scene, transfer.Region);
        var job = Pipeline.RenderJob.Load(new Pipeline.RenderRequest
        {
            Scene = scene,
            ScenePath = src.ScenePath,
            OutDir = outDir,
            Integrator = transfer.Format.Integrator,
            FromTransfer = new Pipeline.TransferSource(transfer, reuse),
            Detail = Pipeline.RunDetail.None,
        });
        var result = job.Render(cancel: cancel);
        var compute = clock.Elapsed;
        var copied = (reuse?.Names ?? Enumerable.Empty<string>()).Concat(transfer.StoredFiles);
        string? metricsCsv = null;
        RelightMetrics? metricsRecord = null;
        if (metrics)
        {
            var unchanged = transfer.Relight(ChangedScene(src, [], null)).Xyz!;
            (metricsRecord, metricsCsv) = Metrics(src, scene, transfer.ObjectIds, unchanged, result.Xyz!);
        }
        return Finish(job, src, scene, changes, white, commandLine, compute, metricsRecord, metricsCsv, copied, transfer.RelightMethod,
            cancel);
    }

    /// <summary>The relit render's run record (what changed, how, which files were copied from the source: no light changes
    /// them, see <see cref="Reusable"/>) and its files, with relight-metrics.csv when asked for.</summary>
    static (Scene Scene, List<string> Files, TimeSpan Compute) Finish(Pipeline.RenderJob job, Source src, Scene scene,
        IReadOnlyList<LightChange> changes, string? white, string commandLine, TimeSpan compute, RelightMetrics? metricsRecord,
        string? metricsCsv, IEnumerable<string> copied, string method, CancellationToken cancel)
    {
        job.RunRecord = new ManifestRun
        {
            CommandLine = commandLine,
            HasOverrides = true,
            Overrides = src.Manifest.Run?.Overrides,
            Relit = new ManifestRelit
            {
                From = Path.GetFullPath(src.Dir),
                FromCreatedUtc = src.Manifest.CreatedUtc,
                Method = method,
                Changes = changes.Select(c => new ManifestLightChange(c.Light, c.Spectrum, c.Intensity)).ToArray(),
                White = white,
                ComputeSeconds = compute.TotalSeconds,
                Metrics = metricsRecord,
                CopiedFiles = copied.Order(StringComparer.Ordinal).ToArray(),
            },
        };
        // relight-metrics.csv is staged and swapped in with the render's files (never written beside them afterwards).
        if (metricsCsv is not null) job.ExtraFiles = new Dictionary<string, string> { ["relight-metrics.csv"] = metricsCsv };
        var files = job.Write(cancel).ToList();
        return (scene, files, compute);
    }

    /// <summary>
    /// The source's files that a render of the relit scene writes byte for byte the same, when the source was written by
    /// this very build (render.json "build"): object-id.png and mask-lit-K.png (which object each centre ray sees and
    /// which lights reach it: geometry, whatever the lights' spectra and intensities), and reflectance.exr when the
    /// materials' band values are the source's (lights/lights.json) and its header is (κ and the colorimetry follow the
    /// reference white). Null when the source is another build's.
    /// </summary>
    public static ReusedFiles? Reusable(Source src, Scene scene, PixelRect crop)
    {
        if (src.Manifest.Build != RenderOutputWriter.EngineBuild || src.Manifest.Files is not { } listed) return null;
        // What the products say a relight may copy: files of the geometry alone; the ground truth when the materials and its header are the
        // source's.
        var names = new List<string>();
        foreach (var file in listed)
        {
            switch (Output.Products.OutputProductTable.Owner(file)?.Reuse(file) ?? Output.Products.RelightReuse.Never)
            {
                case Output.Products.RelightReuse.Geometry: names.Add(file); break;
                case Output.Products.RelightReuse.SameMaterials when SameMaterials(src, scene)
                    && SameHeader(src, file, AnalysisImages.ReflectanceFileStart(scene, crop)):
                    names.Add(file); break;
            }
        }
        return new ReusedFiles(Path.GetFullPath(src.Dir), names.Where(n => File.Exists(Path.Combine(src.Dir, n))));
    }

    /// <summary>Whether the source's <paramref name="file"/> starts with <paramref name="start"/> (and holds more).</summary>
    static bool SameHeader(Source src, string file, byte[] start)
    {
        var path = Path.Combine(src.Dir, file);
        if (!File.Exists(path) || new FileInfo(path).Length <= start.Length) return false;
        var head = new byte[start.Length];
        using (var f = File.OpenRead(path)) f.ReadExactly(head);
        return head.AsSpan().SequenceEqual(start);
    }

    /// <summary>Whether the scene's materials are the source's, name for name and band value for band value (lights/lights.json).</summary>
    static bool SameMaterials(Source src, Scene scene)
    {
        try
        {
            var lightsJson = Path.Combine(src.Dir, TransferFormat.Folder, TransferFormat.Description);
            var json = JsonNode.Parse(File.ReadAllText(lightsJson))?["materials"] as JsonArray;
            if (json is null || json.Count != scene.Materials.Count) return false;
            for (int m = 0; m < json.Count; m++)
            {
                var values = json[m]?["diffuse_band_values"] as JsonArray;
                if ((string?)json[m]?["name"] != scene.Materials[m].Name || values is null || values.Count != scene.Bands) return false;
                for (int b = 0; b < scene.Bands; b++)
                    if ((float)(double)values[b]! != scene.Materials[m].Diffuse[b]) return false;
            }
            return true;
        }
        catch (Exception e) when (e is JsonException or InvalidOperationException or FormatException or IOException) { return false; }
    }

    /// <summary>
    /// The lighting designer's view of a relight: per light of the relit scene its CIE 13.3 Ra and CIE 224:2017 Rf, and per
    /// object the ΔE00 (CIEDE2000, Lab on the relit scene's white) between each pixel's colour in the source render and
    /// in the relit one (mean and maximum over the pixels whose centre ray sees the object).
    /// </summary>
    public static (RelightMetrics Record, string Csv) Metrics(Source src, Scene relit, int[] objectIds, float[] xyz0, float[] relitXyz)
    {
        var white = relit.Colorimeter.White;
        int objects = relit.Objects.Count;
        var sum = new double[objects]; var max = new double[objects]; var count = new int[objects];
        for (int i = 0; i < objectIds.Length; i++)
        {
            int o = objectIds[i];
            if (o < 0) continue;
            var a = Color.Lab.FromXyz(new Color.Xyz(xyz0[3 * i], xyz0[3 * i + 1], xyz0[3 * i + 2]), white);
            var b = Color.Lab.FromXyz(new Color.Xyz(relitXyz[3 * i], relitXyz[3 * i + 1], relitXyz[3 * i + 2]), white);
            double d = Color.DeltaE2000.Between(a, b);
            sum[o] += d; count[o]++; max[o] = Math.Max(max[o], d);
        }
        var csv = new StringBuilder("kind,name,pixels,mean_dE00,max_dE00,Ra_CIE13.3,Rf_CIE224_2017,CCT_K\n");
        var lights = new List<RelightLightMetrics>();
        foreach (var l in relit.Lights)
        {
            double? ra = null, rf = null, cct = null;
            if (l.Spectrum is { } sp)
                try { var r = Color.ColorRenderingIndex.Of(sp); ra = r.Ra; cct = r.Cct; rf = Color.ColorFidelityIndex.Of(sp).Rf; }
                catch (Exception e) when (e is ArgumentException or InvalidOperationException) { }
            lights.Add(new RelightLightMetrics(l.Name, l.Spectrum?.Name, ra, rf, cct));
            csv.Append(CultureInfo.InvariantCulture, $"light,{l.Name},,,,{ra:0.00},{rf:0.00},{cct:0}\n");
        }
        var objs = new List<RelightObjectMetrics>();
        for (int o = 0; o < objects; o++)
        {
            if (count[o] == 0) continue;
            objs.Add(new RelightObjectMetrics(relit.Objects[o].Name, count[o], sum[o] / count[o], max[o]));
            csv.Append(CultureInfo.InvariantCulture,
                $"object,{relit.Objects[o].Name},{count[o]},{sum[o] / count[o]:0.0000},{max[o]:0.0000},,,\n");
        }
        return (new RelightMetrics(relit.ReferenceWhite.Name, lights, objs), csv.ToString());
    }

    /// <summary>One row of a sweep file: its changes, its white (and the white's file:row:column) and its line.</summary>
    public sealed record SweepRow(List<LightChange> Changes, string? White, string? WhiteWhere, int Line);

    /// <summary>
    /// A sweep file: a CSV whose header names columns <c>LIGHT</c> (its spectrum), <c>LIGHT.intensity</c> and
    /// optionally <c>white</c>; every row is one relit render (an empty cell keeps the render's value). Blank lines are
    /// skipped; every message names the file's own row (line) and column (1-based cell).
    /// </summary>
    public static List<SweepRow> ReadSweep(string path, string[] lightNames)
    {
        var lines = InputFile.ReadAllText(path).Replace("\r\n", "\n").Split('\n').Select((l, i) => (Text: l, Row: i + 1))
            .Where(l => l.Text.Trim().Length > 0).ToArray();
        if (lines.Length < 2)
            throw new InputException($"{path}:{(lines.Length == 0 ? 1 : lines[0].Row + 1)}:1",
                "a sweep needs a header and at least one row", "e.g. header 'D65,D65.intensity' then 'A,1'");
        var header = lines[0].Text.Split(',').Select(h => h.Trim()).ToArray();
        int headerRow = lines[0].Row;
        for (int c = 0; c < header.Length; c++)
        {
            var h = header[c];
            var light = h.EndsWith(".intensity", StringComparison.Ordinal) ? h[..^".intensity".Length] : h;
            if (h != "white" && Array.IndexOf(lightNames, light) < 0)
                throw new InputException($"{path}:{headerRow}:{c + 1}", $"column {MessageText.Quote(h)} names no light of the render",
                    $"columns: white, a light's name (its spectrum) or NAME.intensity; lights: {string.Join(", ", lightNames)}");
            if (Array.IndexOf(header, h) < c)
                throw new InputException($"{path}:{headerRow}:{c + 1}", $"column {MessageText.Quote(h)} appears twice",
                    "give every column once");
        }
        var rows = new List<SweepRow>();
        foreach (var (text, row) in lines.Skip(1))
        {
            var cells = text.Split(',').Select(x => x.Trim()).ToArray();
            if (cells.Length != header.Length)
                throw new InputException($"{path}:{row}:{Math.Min(cells.Length, header.Length) + 1}",
                    $"{cells.Length} cells, the header names {header.Length}", "every row needs one cell per header column");
            var changes = new Dictionary<string, LightChange>();
            string? white = null, whiteWhere = null;
            for (int c = 0; c < cells.Length; c++)
            {
                if (cells[c].Length == 0) continue;
                var h = header[c];
                string where = $"{path}:{row}:{c + 1}";
                if (h == "white") { (white, whiteWhere) = (cells[c], where); continue; }
                if (h.EndsWith(".intensity", StringComparison.Ordinal))
                {
                    var name = h[..^".intensity".Length];
                    // The range a scene's "intensity" takes (as --intensity), so the scene file is never blamed for it.
                    if (!double.TryParse(cells[c], NumberStyles.Float, CultureInfo.InvariantCulture, out double f) || !double.IsFinite(f)
                        || f < 0 || f > 1e30)
                        throw new InputException(where, $"{MessageText.Quote(cells[c])} is not a non-negative intensity ≤ 1e30",
                            "intensities are plain non-negative numbers, e.g. 0.5");
                    changes[name] = (changes.GetValueOrDefault(name) ?? new LightChange(name, null, null)) with { Intensity = f };
                }
                else
                    changes[h] =
                        (changes.GetValueOrDefault(h) ?? new LightChange(h, null, null)) with { Spectrum = cells[c], Where = where };
            }
            rows.Add(new SweepRow(changes.Values.ToList(), white, whiteWhere, row));
        }
        return rows;
    }
}
