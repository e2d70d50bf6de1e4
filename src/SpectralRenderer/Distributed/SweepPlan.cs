using System.Globalization;
using System.Security.Cryptography;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Distributed;

/// <summary>One job of a sweep: its number, id (its folder's name), the label of each axis value, and the scene edits.</summary>
public sealed record SweepJob(int Index, string Id, IReadOnlyList<(string Axis, string Label)> Parameters,
    IReadOnlyList<(string Path, JsonNode? Value)> Edits);

/// <summary>
/// A parameter sweep (docs/sweep-format.md): a base scene file and axes of scene edits whose Cartesian product is the
/// job list (first axis slowest), then any extra jobs. An edit puts a JSON value at a path into the scene:
/// <c>materials.patch.diffuse</c>, <c>lights[0].spectrum</c>, <c>objects[name=bunny].file</c>, <c>camera.fov</c>,
/// <c>bands</c> — so an axis can vary lights, the materials of named objects, meshes, cameras or band grids.
/// </summary>
public sealed class SweepPlan
{
    public required string PlanPath { get; init; }
    public required string ScenePath { get; init; }
    public required JsonObject BaseScene { get; init; }
    public required IReadOnlyList<string> AxisNames { get; init; }
    public required IReadOnlyList<SweepJob> Jobs { get; init; }
    /// <summary>The plan's "formats" for every job (null: the scene's own).</summary>
    public string? Formats { get; init; }

    static readonly JsonDocumentOptions Options =
        new() { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true, AllowDuplicateProperties = false };

    public static SweepPlan Load(string planPath)
    {
        var bytes = InputFile.ReadAllBytes(planPath, "sweep plan");
        // Found by fuzzing (fuzz/run.sh sweep): text that is not UTF-8 fails in the JSON reader's strings, not as bad input.
        if (!System.Text.Unicode.Utf8.IsValid(bytes)) throw new InputException(planPath, "is not valid UTF-8", "save the plan as UTF-8");
        var locator =
            new JsonLocator(bytes, new JsonReaderOptions { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true });
        InputException Bad(string path, string what, string? hint = null) =>
            new(locator.Locate(path) is { } pos ? $"{planPath}:{pos}: {path}" : $"{planPath}: {path}", what,
                hint ?? "see the sweep plan format in README.md");
        // Found by fuzzing (fuzz/run.sh sweep): a key given twice in one object broke the JSON object's enumeration.
        if (locator.Duplicate is { } dup)
            throw new InputException($"{planPath}:{locator.Position(dup.Offset)}: {dup.Path}",
                $"key {MessageText.Quote(dup.Path[(dup.Path.LastIndexOf('.') + 1)..])} appears a second time in this object",
                "each key may appear once: remove or rename one of them");
        JsonObject plan;
        try
        {
            plan = JsonNode.Parse(bytes, documentOptions: Options) as JsonObject
                ?? throw Bad("$", "is not a JSON object", "a plan is { \"scene\": …, \"axes\": [ … ] }");
        }
        catch (JsonException e)
        {
            throw new InputException(planPath, $"is not valid JSON: {e.Message.Split(" LineNumber:")[0]}",
                "check for a missing comma, quote or bracket");
        }
        foreach (var (k, _) in plan)
            if (k is not ("scene" or "axes" or "set" or "extra" or "formats" or "name"))
                throw Bad($"$.{k}", "is not a plan key",
                    InputException.DidYouMean(k, ["scene", "axes", "set", "extra", "formats", "name"])
                        ?? "keys: scene, set, axes, extra, formats");
        if (plan["scene"] is not JsonValue sv || sv.GetValueKind() != JsonValueKind.String)
            throw Bad("$.scene", "is missing or not a file name",
                "\"scene\": \"../scenes/paper-3.2-bunny-19.json\" (relative to the plan)");
        var scenePath = Path.GetFullPath(Path.Combine(Path.GetDirectoryName(Path.GetFullPath(planPath))!, sv.GetValue<string>()));
        var sceneBytes = InputFile.ReadAllBytes(scenePath, "base scene");
        if (!System.Text.Unicode.Utf8.IsValid(sceneBytes))
            throw new InputException(scenePath, "is not valid UTF-8", "save the scene file as UTF-8");
        JsonObject scene;
        try { scene = JsonNode.Parse(sceneBytes, documentOptions: Options) as JsonObject ?? throw new JsonException("not an object"); }
        catch (JsonException e)
        {
            var place = JsonFields.Place(e, Encoding.UTF8.GetString(sceneBytes),
                new JsonReaderOptions { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true });
            throw new InputException($"{scenePath}:{place}", $"is not a valid scene: {e.Message.Split(" LineNumber:")[0]}",
                "check for a missing comma, quote or bracket, or a key given twice");
        }

        var fixedEdits = plan["set"] is JsonObject set ? Edits(set, "$.set", Bad) : [];
        var axes = new List<(string Name, List<(string Label, List<(string, JsonNode?)> Edits)> Values)>();
        if (plan["axes"] is JsonArray axisArray)
            for (int a = 0; a < axisArray.Count; a++)
            {
                string at = $"$.axes[{a}]";
                if (axisArray[a] is not JsonObject axis)
                    throw Bad(at, "is not an object", "{ \"name\": …, \"path\": …, \"values\": [ … ] }");
                foreach (var (k, _) in axis)
                    if (k is not ("name" or "path" or "values" or "labels"))
                        throw Bad($"{at}.{k}", "is not an axis key", "keys: name, path, values, labels");
                string name = axis["name"] is JsonValue n && n.GetValueKind() == JsonValueKind.String
                    ? n.GetValue<string>()
                    : throw Bad($"{at}.name", "is missing", "every axis has a name (a column of index.csv)");
                if (axes.Any(x => x.Name == name) || name is "job" or "status" or "seconds" or "path")
                    throw Bad($"{at}.name", $"'{name}' is taken", "axis names are unique and not job, status, seconds or path");
                if (axis["values"] is not JsonArray values || values.Count == 0)
                    throw Bad($"{at}.values", "is missing or empty", "a list of the values the axis takes");
                var labels = axis["labels"] as JsonArray;
                if (labels is not null && labels.Count != values.Count)
                    throw Bad($"{at}.labels", $"has {labels.Count} labels for {values.Count} values");
                string? path = axis["path"] is JsonValue p && p.GetValueKind() == JsonValueKind.String ? p.GetValue<string>() : null;
                if (path is not null && !PathSyntax.IsMatch(path))
                    throw Bad($"{at}.path", $"'{path}' is not a scene path",
                        "e.g. materials.patch.diffuse, lights[0].spectrum, objects[name=bunny].file");
                var list = new List<(string, List<(string, JsonNode?)>)>();
                for (int v = 0; v < values.Count; v++)
                {
                    var edits = path is not null ? [(path, values[v]?.DeepClone())]
                        : values[v] is JsonObject o ? Edits(o, $"{at}.values[{v}]", Bad)
                        : throw Bad($"{at}.values[{v}]", "is not an object of path: value edits, and the axis has no path",
                            "give the axis a \"path\", or make each value { \"path\": value, … }");
                    list.Add((Label(labels?[v] ?? values[v], v), edits));
                }
                axes.Add((name, list));
            }
        else if (plan["axes"] is not null) throw Bad("$.axes", "is not a list of axes");

        var jobs = new List<SweepJob>();
        // The product of the axes' lengths, saturated (no overflow) once it is past the limit.
        long product = axes.Count == 0 ? 0 : axes.Aggregate(1L, (c, x) => c > MaxJobs ? c : c * x.Values.Count);
        long extras = (plan["extra"] as JsonArray)?.Count ?? 0;
        if (product + extras > MaxJobs)
            throw Bad(product > MaxJobs ? "$.axes" : "$.extra",
                $"makes {(product > MaxJobs ? "more than 100,000" : (product + extras).ToString("N0", CultureInfo.InvariantCulture))} "
                    + $"jobs, more than the limit of 100,000",
                "split the sweep into several plans");
        int total = (int)product;
        int digits = Math.Max(4, (total + extras).ToString(CultureInfo.InvariantCulture).Length);
        string Id(int i) => i.ToString(CultureInfo.InvariantCulture).PadLeft(digits, '0');
        for (int j = 0; j < total; j++)
        {
            var parameters = new List<(string, string)>();
            var edits = new List<(string, JsonNode?)>(fixedEdits);
            int rest = j;
            var picks = new int[axes.Count];
            for (int a = axes.Count - 1; a >= 0; a--) { picks[a] = rest % axes[a].Values.Count; rest /= axes[a].Values.Count; }
            for (int a = 0; a < axes.Count; a++)
            {
                var (label, e) = axes[a].Values[picks[a]];
                parameters.Add((axes[a].Name, label));
                edits.AddRange(e);
            }
            jobs.Add(new SweepJob(j, Id(j), parameters, edits));
        }
        var axisNames = axes.Select(a => a.Name).ToList();
        if (plan["extra"] is JsonArray extra)
        {
            if (extra.Count > 0) axisNames.Add("extra");
            for (int x = 0; x < extra.Count; x++)
            {
                string at = $"$.extra[{x}]";
                if (extra[x] is not JsonObject e || e["set"] is not JsonObject es)
                    throw Bad(at, "is not { \"name\": …, \"set\": { path: value, … } }");
                var parameters = new List<(string, string)> { ("extra", Label(e["name"] ?? JsonValue.Create(x), x)) };
                jobs.Add(new SweepJob(jobs.Count, Id(jobs.Count), parameters, [.. fixedEdits, .. Edits(es, $"{at}.set", Bad)]));
            }
        }
        else if (plan["extra"] is not null) throw Bad("$.extra", "is not a list of jobs");
        if (jobs.Count == 0) throw Bad("$.axes", "makes no jobs", "give at least one axis with values, or extra jobs");

        string? formats = plan["formats"] switch
        {
            null => null,
            JsonArray fa => string.Join(',', fa.Select(f => f?.ToString())),
            JsonValue fv when fv.GetValueKind() == JsonValueKind.String => fv.GetValue<string>(),
            _ => throw Bad("$.formats", "is not a list of formats", "e.g. [\"npy\", \"png\"]"),
        };
        // Checked here, where the plan says it, rather than in every job's scene (which would name --formats).
        if (formats is not null)
            SceneLoader.ParseFormats(formats.Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries),
                locator.Locate("$.formats") is { } fpos ? $"{planPath}:{fpos}: $.formats" : $"{planPath}: $.formats");
        var result = new SweepPlan
        {
            PlanPath = Path.GetFullPath(planPath),
            ScenePath = scenePath,
            BaseScene = scene,
            AxisNames = axisNames,
            Jobs = jobs,
            Formats = formats
        };
        // Every edit must land: check each job's paths now, before any job runs.
        foreach (var job in jobs)
            try { result.SceneFor(job); }
            catch (InputException e) { throw new InputException(planPath, $"job {job.Id}: {e.What}", e.Hint); }
        return result;
    }

    /// <summary>The most jobs a plan may make.</summary>
    public const int MaxJobs = 100_000;

    /// <summary>
    /// Loads every job's scene as the job will (with <paramref name="overrides"/>), before any job runs: its JSON, spectra,
    /// materials, lights, camera and the overrides on it; each distinct set of mesh objects (file, fit, transform) is read
    /// once. A job's bad scene is bad input naming its own scene file, <paramref name="outDir"/>/jobs/ID/scene.json (written
    /// then, so its line:column are true), see <see cref="InJobScene"/>.
    /// </summary>
    public void CheckJobs(IEnumerable<SweepJob> jobs, SceneOverrides overrides, string outDir, CancellationToken cancel = default)
    {
        var meshSets = new HashSet<string>(StringComparer.Ordinal);
        foreach (var job in jobs)
        {
            cancel.ThrowIfCancellationRequested();
            var scene = SceneFor(job);
            var meshes = string.Concat((scene["objects"] as JsonArray ?? []).OfType<JsonObject>()
                .Where(o => o["type"] is JsonValue t && t.GetValueKind() == JsonValueKind.String
                    && t.GetValue<string>().Equals("mesh", StringComparison.OrdinalIgnoreCase))
                .Select(o => o.ToJsonString()));
            var text = SceneBytes(job);
            try { SceneLoader.Parse(text, ScenePath, overrides with { LoadMeshes = meshSets.Add(meshes) }); }
            catch (InputException e) { throw InJobScene(e, job, text, outDir); }
        }
    }

    /// <summary>
    /// An error of a job's scene (parsed as if it were the base scene file, so its relative files resolve alike) as the
    /// job's own: the place named in OUTDIR/jobs/ID/scene.json, which is written with the job's scene text, and the job named.
    /// </summary>
    public InputException InJobScene(InputException e, SweepJob job, byte[] text, string outDir)
    {
        if (!e.Where.StartsWith(ScenePath, StringComparison.Ordinal))
            return new InputException(e.Where, $"sweep job {job.Id}: {e.What}", e.Hint) { Problem = e.Problem };
        var file = Path.Combine(outDir, "jobs", job.Id, "scene.json");
        try
        {
            Directory.CreateDirectory(Path.GetDirectoryName(file)!);
            Imaging.AtomicFile.WriteAllBytes(file, text);
        }
        catch (Exception io) when (io is IOException or UnauthorizedAccessException) { file = $"job {job.Id}'s scene"; }
        return new InputException(file + e.Where[ScenePath.Length..], $"sweep job {job.Id}: {e.What}", e.Hint) { Problem = e.Problem };
    }

    static List<(string, JsonNode?)> Edits(JsonObject o, string at, Func<string, string, string?, InputException> bad)
    {
        var list = new List<(string, JsonNode?)>();
        foreach (var (path, value) in o)
        {
            if (!PathSyntax.IsMatch(path))
                throw bad($"{at}", $"'{path}' is not a scene path",
                    "e.g. materials.patch.diffuse, lights[0].spectrum, objects[name=bunny].file");
            list.Add((path, value?.DeepClone()));
        }
        return list;
    }

    /// <summary>A value's label in the index: a string or number as it is, an object by its "name", else its position.</summary>
    static string Label(JsonNode? v, int position) => v switch
    {
        JsonValue s when s.GetValueKind() == JsonValueKind.String => s.GetValue<string>(),
        JsonValue n => n.ToJsonString(),
        JsonObject o when o["name"] is JsonValue name => name.ToString(),
        _ => position.ToString(CultureInfo.InvariantCulture),
    };

    static readonly Regex PathSyntax =
        new(@"^[A-Za-z_][\w-]*(\[(\d+|[A-Za-z_]\w*=[^\]]+)\])*(\.[A-Za-z_][\w-]*(\[(\d+|[A-Za-z_]\w*=[^\]]+)\])*)*$",
        RegexOptions.CultureInvariant);
    static readonly Regex Segment = new(@"([A-Za-z_][\w-]*)|\[(\d+)\]|\[([A-Za-z_]\w*)=([^\]]+)\]", RegexOptions.CultureInvariant);

    /// <summary>The job's scene: the base scene with the job's edits applied in order.</summary>
    public JsonObject SceneFor(SweepJob job)
    {
        var scene = (JsonObject)BaseScene.DeepClone();
        foreach (var (path, value) in job.Edits) Set(scene, path, value?.DeepClone());
        return scene;
    }

    /// <summary>The job's scene file text (UTF-8), as the job renders it and as its folder keeps it.</summary>
    public byte[] SceneBytes(SweepJob job) =>
        Encoding.UTF8.GetBytes(SceneFor(job).ToJsonString(new JsonSerializerOptions { WriteIndented = true }));

    /// <summary>SHA-256 of what a job computes (its scene text and the formats): a finished job is skipped only when it is
    /// unchanged.</summary>
    public string JobHash(SweepJob job, string? formats) =>
        "sha256:"
            + Convert.ToHexStringLower(SHA256.HashData([.. SceneBytes(job), .. Encoding.UTF8.GetBytes("\nformats=" + (formats ?? ""))]));

    /// <summary>Puts <paramref name="value"/> at <paramref name="path"/>; missing object keys on the way are created, list elements must
    /// exist.</summary>
    static void Set(JsonObject root, string path, JsonNode? value)
    {
        var segments = Segment.Matches(path).ToList();
        JsonNode node = root;
        string walked = "";
        for (int i = 0; i < segments.Count; i++)
        {
            var s = segments[i];
            bool last = i == segments.Count - 1;
            if (s.Groups[1].Success)
            {
                string key = s.Groups[1].Value;
                if (node is not JsonObject o)
                    throw new InputException("", $"'{walked}' is not an object, so it has no '{key}' (path {path})",
                        "check the path against the scene's structure");
                if (last) { o[key] = value; return; }
                node = o[key] ??= segments[i + 1].Groups[1].Success
                    ? new JsonObject()
                    : throw new InputException("", $"the scene has no list '{walked}{(walked.Length > 0 ? "." : "")}{key}' (path {path})",
                        "check the path against the scene's structure");
                walked += (walked.Length > 0 ? "." : "") + key;
            }
            else
            {
                if (node is not JsonArray list)
                    throw new InputException("", $"'{walked}' is not a list (path {path})", "check the path against the scene's structure");
                int index;
                if (s.Groups[2].Success)
                {
                    index = int.Parse(s.Groups[2].Value, CultureInfo.InvariantCulture);
                    if (index >= list.Count)
                        throw new InputException("", $"'{walked}' has {list.Count} elements, so no [{index}] (path {path})",
                            "lists count from 0");
                }
                else
                {
                    string key = s.Groups[3].Value, want = s.Groups[4].Value;
                    index = list.Select((e, k) => (e, k))
                        .FirstOrDefault(t => t.e is JsonObject eo && eo[key]?.ToString() == want, (null, -1)).Item2;
                    if (index < 0)
                        throw new InputException("", $"no element of '{walked}' has {key} '{want}' (path {path})",
                            InputException.DidYouMean(want, list.OfType<JsonObject>().Select(e => e[key]?.ToString() ?? ""))
                                ?? $"name the {walked} in the base scene");
                }
                walked += s.Value;
                if (last) { list[index] = value; return; }
                node = list[index]
                    ?? throw new InputException("", $"'{walked}' is null (path {path})", "check the path against the scene's structure");
            }
        }
    }
}
