using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

/// <summary>
/// A Mitsuba 3 scene converted to our scene JSON (docs/import.md "Mitsuba 3"): the sensor, film and sampler to the camera,
/// the integrator, shapes to objects, BSDFs to materials, emitters to lights, emitting materials and the background; what
/// has no exact counterpart is approximated, ignored or refused, each in the report with its file:line.
/// </summary>
public sealed partial class MitsubaConverter
{
    /// <summary>Our bands for an imported scene: 380–780 nm in 5 nm bands (Mitsuba's spectral variants sample 360–830 nm).</summary>
    public const string Bands = "380:780:80";

    readonly string _path;
    readonly string _dir;
    readonly ImportOptions _options;
    readonly ImportReport _report;
    readonly Dictionary<string, MitsubaElement> _ids = new(StringComparer.Ordinal);
    readonly HashSet<MitsubaElement> _used = [];
    readonly JsonObject _materials = [];
    readonly JsonArray _lights = [];
    readonly JsonArray _objects = [];
    readonly List<ImportedMesh> _meshes = [];
    readonly Dictionary<MitsubaElement, string> _materialNames = [];
    readonly HashSet<string> _names = new(StringComparer.Ordinal);
    JsonObject? _camera;
    JsonNode? _integrator;
    JsonNode? _background;
    JsonObject? _sky;
    int _seed;

    public MitsubaConverter(string path, ImportOptions options)
    {
        _path = path;
        _dir = Path.GetDirectoryName(Path.GetFullPath(path))!;
        _options = options;
        _report = new ImportReport(path, "mitsuba");
    }

    public ImportedScene Convert()
    {
        var root = MitsubaXml.Read(_path);
        CollectIds(root);
        foreach (var e in root.Children)
        {
            switch (e.Tag)
            {
                case "default": break;
                case "sensor": Sensor(e); break;
                case "integrator": Integrator(e); break;
                case "shape": Shape(e); break;
                case "emitter": Emitter(e); break;
                case "bsdf" or "texture" or "spectrum" or "rgb" or "float" or "integer" or "string" or "boolean" or "point" or "vector"
                    or "transform":
                    break;   // declared by id, converted where referred to
                case "medium": Refuse(e, "a participating medium has no counterpart yet (issue 41)"); break;
                default: Refuse(e, $"<{e.Tag}> is not a scene element this importer knows"); break;
            }
        }
        if (_camera is null)
            throw new InputException($"{Path.GetFileName(_path)}", "the scene has no <sensor>", "add a <sensor type=\"perspective\">");
        if (_objects.Count == 0)
            throw new InputException($"{Path.GetFileName(_path)}", "the scene has no shapes we could convert",
                "add a <shape>, or see the report");
        var scene = new JsonObject
        {
            ["name"] = Path.GetFileName(_path),
            ["description"] = $"imported from Mitsuba 3 XML by spectral import ({Path.GetFileName(_path)})",
            ["bands"] = Bands,
            ["radiometry"] = "physical",
            ["integrator"] = _seed == 0 ? _integrator ?? "path" : WithSeed(_integrator, _seed),
            ["camera"] = _camera,
        };
        ImportDisplay.Native(scene, 1 / ImportDisplay.YBarIntegral);   // Mitsuba's Y: ∫ȳ·L dλ / ∫ȳ dλ
        if (_background is not null) scene["background"] = _background;
        if (_sky is not null) scene["sky"] = _sky;
        scene["materials"] = _materials;
        scene["lights"] = _lights;
        if (_prototypes.Count > 0) scene["prototypes"] = _prototypes;
        scene["objects"] = _objects;
        return new ImportedScene(scene, _report, _meshes);
    }

    static JsonObject WithSeed(JsonNode? integrator, int seed)
    {
        var o = integrator as JsonObject ?? new JsonObject { ["type"] = "path" };
        o["seed"] = seed;
        return o;
    }

    void CollectIds(MitsubaElement e)
    {
        foreach (var c in e.Children)
        {
            if (c.Tag != "ref" && c.Attr("id") is { } id && !_ids.TryAdd(id, c))
                throw new InputException(c.Where, $"id {MessageText.Quote(id)} is given twice (first at {_ids[id].Where})",
                    "give each element its own id");
            CollectIds(c);
        }
    }

    // ---- report ----

    void Note(string kind, MitsubaElement e, string action) => _report.Add(kind, e.Place, e.Label, action);

    /// <summary>An element with no counterpart that changes the picture: an error, unless --lenient (then reported and skipped).</summary>
    void Refuse(MitsubaElement e, string why)
    {
        if (!_options.Lenient)
            throw new InputException(e.Where, $"{e.Label}: {why}", "spectral import --lenient skips it and says so in import-report.json");
        Note("error", e, $"skipped: {why}");
    }

    /// <summary>The named properties of <paramref name="e"/> the conversion did not read: reported as ignored.</summary>
    void ReportUnused(MitsubaElement e)
    {
        foreach (var c in e.Children)
            if (!_used.Contains(c) && c.Attr("name") is { } name)
                _report.Add("ignored", c.Place, $"{e.Label} {name}", $"the property '{name}' has no counterpart and was not converted");
    }

    // ---- properties ----

    MitsubaElement? Prop(MitsubaElement e, string name)
    {
        foreach (var c in e.Children)
            if (c.Attr("name") == name)
            {
                _used.Add(c);
                return c;
            }
        return null;
    }

    static string Value(MitsubaElement p) =>
        p.Attr("value") ?? throw new InputException(p.Where, $"<{p.Tag} name=\"{p.Attr("name")}\"> has no value", "give value=\"…\"");

    double Float(MitsubaElement e, string name, double fallback)
    {
        if (Prop(e, name) is not { } p) return fallback;
        if (p.Tag is not ("float" or "integer"))
            throw new InputException(p.Where, $"'{name}' is a <{p.Tag}>, expected a number", $"write <float name=\"{name}\" value=\"…\"/>");
        return Number(Value(p), p.Where, name);
    }

    static double Number(string text, string where, string what)
    {
        if (!double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out var v) || !double.IsFinite(v))
            throw new InputException(where, $"{what}: {MessageText.Quote(text, 30)} is not a number", "write numbers like 0.5 or 1e-3");
        return v;
    }

    string? String(MitsubaElement e, string name) => Prop(e, name) is { } p ? Value(p) : null;

    bool Boolean(MitsubaElement e, string name, bool fallback)
    {
        if (Prop(e, name) is not { } p) return fallback;
        return Value(p).ToLowerInvariant() switch
        {
            "true" or "1" => true,
            "false" or "0" => false,
            var v => throw new InputException(p.Where, $"'{name}': {MessageText.Quote(v)} is not a boolean", "write true or false"),
        };
    }

    /// <summary>A point or vector property: x, y, z attributes or value="x, y, z".</summary>
    double[]? Point(MitsubaElement e, string name)
    {
        if (Prop(e, name) is not { } p) return null;
        return Vector3(p, 0);
    }

    static double[] Vector3(MitsubaElement p, double fallback)
    {
        if (p.Attr("value") is { } v)
        {
            var n = MitsubaXml.Numbers(v, p.Where, p.Tag);
            if (n.Length == 1) return [n[0], n[0], n[0]];
            if (n.Length != 3)
                throw new InputException(p.Where, $"<{p.Tag}> value has {n.Length} numbers, expected 3", "e.g. value=\"0, 1, 0\"");
            return n;
        }
        return
        [
            p.Attr("x") is { } x ? Number(x, p.Where, "x") : fallback,
            p.Attr("y") is { } y ? Number(y, p.Where, "y") : fallback,
            p.Attr("z") is { } z ? Number(z, p.Where, "z") : fallback,
        ];
    }

    /// <summary>A child object element (bsdf, emitter, texture, …) given inline or by &lt;ref id="…"/&gt;.</summary>
    MitsubaElement Resolve(MitsubaElement e)
    {
        if (e.Tag != "ref") return e;
        var id = e.Attr("id") ?? throw new InputException(e.Where, "<ref> without an id", "e.g. <ref id=\"red\"/>");
        return _ids.TryGetValue(id, out var target) ? target
            : throw new InputException(e.Where, $"no element has id {MessageText.Quote(id)}",
                InputException.DidYouMean(id, _ids.Keys) ?? "give the referenced element an id=\"…\"");
    }

    /// <summary>A unique, file-safe name from <paramref name="wanted"/>.</summary>
    string UniqueName(string wanted)
    {
        var clean = new string(wanted.Select(c => char.IsAsciiLetterOrDigit(c) || c is '-' or '_' ? c : '-').ToArray()).Trim('-');
        if (clean.Length == 0) clean = "object";
        var name = clean;
        for (int i = 2; !_names.Add(name); i++) name = $"{clean}-{i}";
        return name;
    }

    // new JsonArray(params JsonNode[]), not a collection expression: that calls JsonArray.Add<T>, which trimming (the native
    // command's AOT build) refuses.
    static JsonArray Array3(double[] v) => new(Round(v[0]), Round(v[1]), Round(v[2]));

    /// <summary>
    /// A number as written in our JSON: rounded to 12 significant digits and below 1e-12 in magnitude to 0 (sin π of a
    /// composed rotation), so composed transforms read cleanly.
    /// </summary>
    static double Round(double v)
    {
        if (Math.Abs(v) < 1e-12) return 0;
        var r = double.Parse(v.ToString("G12", CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
        return r == 0 ? 0 : r;   // no negative zero
    }
}
