using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>
/// A pbrt-v4 scene converted to our scene JSON (docs/import.md "pbrt-v4"): the camera, film, sampler and integrator, shapes
/// to objects (triangle and bilinear meshes inline, PLY meshes by path, spheres, disks), materials, textures, lights and
/// area lights with pbrt's photometric normalisation, and pbrt's named spectra from data/pbrt-v4; what has no exact
/// counterpart is approximated, ignored or refused, each in the report with its file:line.
/// </summary>
public sealed partial class PbrtConverter
{
    /// <summary>Our bands for an imported scene, as the other importers use: 380–780 nm in 5 nm bands.</summary>
    public const string Bands = "380:780:80";

    readonly string _path;
    readonly string _dir;
    readonly ImportOptions _options;
    readonly ImportReport _report;
    readonly JsonObject _spectra = [];
    readonly JsonObject _materials = [];
    readonly JsonArray _lights = [];
    readonly JsonArray _objects = [];
    readonly List<ImportedMesh> _meshes = [];
    readonly HashSet<string> _names = new(StringComparer.Ordinal);
    PbrtDocument _doc = null!;

    /// <summary>Our world from pbrt's: the identity, or a mirror in x when pbrt's camera frame is left-handed.</summary>
    PbrtTransform _world = PbrtTransform.Identity;

    JsonNode? _background;
    double _imagingRatio = 1;   // pbrt's PixelSensor: exposure time (shutterclose − shutteropen) × Film "iso"/100
    JsonObject? _sky;   // an image infinite light: our envmap sky

    public PbrtConverter(string path, ImportOptions options)
    {
        _path = path;
        _dir = Path.GetDirectoryName(Path.GetFullPath(path))!;
        _options = options;
        _report = new ImportReport(path, "pbrt");
    }

    public ImportedScene Convert() => Convert(PbrtParser.Parse(_path, Note));

    /// <summary>Converts pbrt text held in memory (tests, the fuzz target), its relative paths from <c>path</c>'s folder.</summary>
    public ImportedScene ConvertText(string text) => Convert(PbrtParser.ParseText(text, _path, Note));

    ImportedScene Convert(PbrtDocument doc)
    {
        _doc = doc;
        string file = Path.GetFileName(_path);
        var camera = Camera();
        var integrator = Integrator();
        foreach (var light in doc.Lights) Light(light);
        foreach (var shape in doc.Shapes) Shape(shape);
        foreach (var name in doc.InstancedObjects.Order(StringComparer.Ordinal))
            _report.Add("converted", file, $"ObjectInstance \"{name}\"",
                "instanced: each mesh of the object is a prototype, each ObjectInstance an instance of it under the instance's "
                + "transformation (not copied); spheres, disks and cylinders in it are copied");
        if (_objects.Count == 0)
            throw new InputException(file, "the scene has no shapes we could convert", "add a Shape after WorldBegin, or see the report");
        var scene = new JsonObject
        {
            ["name"] = file,
            ["description"] = $"imported from pbrt-v4 by spectral import ({file})",
            ["bands"] = Bands,
            ["radiometry"] = "physical",
            ["integrator"] = integrator,
            ["camera"] = camera,
        };
        ImportDisplay.Native(scene, _imagingRatio);   // pbrt's "cie1931" sensor: Y = imagingRatio·∫ȳ·L dλ
        if (_background is not null) scene["background"] = _background;
        if (_sky is not null) scene["sky"] = _sky;
        if (_spectra.Count > 0) scene["spectra"] = _spectra;
        scene["materials"] = _materials;
        scene["lights"] = _lights;
        if (_prototypes.Count > 0) scene["prototypes"] = _prototypes;
        scene["objects"] = _objects;
        return new ImportedScene(scene, _report, _meshes);
    }

    // ---- report ----

    /// <summary>The report's place of a token: file:line.</summary>
    static string Place(PbrtToken t) => $"{t.File}:{t.Line}";

    static string Place(string where)
    {
        int last = where.LastIndexOf(':');
        return last > 0 && where.IndexOf(':') < last ? where[..last] : where;
    }

    void Note(string kind, string where, string element, string action)
    {
        if (kind == "error") Refuse(where, element, action);
        else _report.Add(kind, Place(where), element, action);
    }

    void Note(string kind, PbrtEntity e, string element, string action) => _report.Add(kind, Place(e.Token), element, action);

    /// <summary>An element with no counterpart that changes the picture: an error, unless --lenient (then reported and skipped).</summary>
    void Refuse(string where, string element, string why)
    {
        if (!_options.Lenient)
            throw new InputException(where, $"{element}: {why}", "spectral import --lenient skips it and says so in import-report.json");
        _report.Add("error", Place(where), element, $"skipped: {why}");
    }

    /// <summary>The parameters of <paramref name="e"/> the conversion did not read: reported as ignored.</summary>
    void ReportUnused(PbrtEntity e, string label)
    {
        foreach (var p in e.Parameters.All)
            if (!p.Used)
            {
                p.Used = true;
                _report.Add("ignored", Place(p.Token), $"{label} \"{p.Type} {p.Name}\"",
                    $"the parameter '{p.Name}' has no counterpart here");
            }
    }

    /// <summary>A name not yet used in the scene (objects, materials and lights share the space).</summary>
    string UniqueName(string wanted)
    {
        var clean = new string(wanted.Select(c => char.IsAsciiLetterOrDigit(c) || c is '-' or '_' or '.' ? c : '-').ToArray()).Trim('-');
        if (clean.Length == 0) clean = "object";
        if (clean.Length > 64) clean = clean[..64];
        string name = clean;
        for (int i = 2; !_names.Add(name); i++) name = $"{clean}-{i}";
        return name;
    }

    /// <summary>A number as written to the scene: 9 significant digits (our scenes are single precision).</summary>
    static double Round(double v) => double.IsFinite(v)
        ? double.Parse(v.ToString("G9", CultureInfo.InvariantCulture), CultureInfo.InvariantCulture)
        : throw new InputException("pbrt", "a converted number overflows (not finite)",
            "check the magnitudes of the transformations and values");

    // new JsonArray(params JsonNode[]): a collection expression calls JsonArray.Add<T>, which the AOT build refuses.
    static JsonArray Array3(double[] v) => new(Round(v[0]), Round(v[1]), Round(v[2]));

    // ---- camera, film, sampler, integrator ----

    JsonObject Camera()
    {
        var file = Path.GetFileName(_path);
        var film = _doc.Film;
        int width = 1280, height = 720;
        if (film is not null)
        {
            width = film.Parameters.Integer("xresolution", 1280);
            height = film.Parameters.Integer("yresolution", 720);
            if (width < 1 || height < 1 || width > 65536 || height > 65536)
                throw new InputException(film.Where, $"the film is {width} × {height} pixels",
                    "give xresolution and yresolution of 1 to 65536");
            foreach (var name in new[] { "filename", "savefp16", "diagonal" }) film.Parameters.Find(name);
            double iso = film.Parameters.Float("iso", 100);
            if (!(iso > 0)) throw new InputException(film.Where, $"iso {iso}", "give an ISO above 0 (pbrt's default is 100)");
            _imagingRatio *= iso / 100;
            if (film.Parameters.Find("sensor") is { } sensor && film.Parameters.String("sensor") != "cie1931")
                _report.Add("approximated", Place(sensor.Token), $"Film \"{film.Type}\" \"sensor\"",
                    "the preview is exposed as pbrt's cie1931 sensor (colour from the CIE 1931 observer, no camera response)");
            ReportUnused(film, $"Film \"{film.Type}\"");
        }
        int spp = 16;
        if (_doc.Sampler is { } sampler)
        {
            spp = sampler.Parameters.Integer("pixelsamples", 16);
            if (spp < 1 || spp > 1 << 20)
                throw new InputException(sampler.Where, $"pixelsamples {spp}", "give a sample count of at least 1");
            Note("converted", sampler, $"Sampler \"{sampler.Type}\"",
                $"{spp} samples per pixel with our sampler (Owen-scrambled Sobol for the path tracer), not pbrt's {sampler.Type}");
            sampler.Parameters.Find("seed");
            ReportUnused(sampler, $"Sampler \"{sampler.Type}\"");
        }

        double fov = 90;
        var camera = _doc.Camera;
        if (camera is null)
            Note("converted", file, "Camera", "the file has no Camera: pbrt's default, a perspective camera at the origin looking down +z");
        else
        {
            if (camera.Type != "perspective")
                Refuse(camera.Where, $"Camera \"{camera.Type}\"",
                    "only the perspective (pinhole) camera has a counterpart; rendered as one");
            fov = camera.Parameters.Float("fov", 90);
            if (!(fov > 0 && fov < 180))
                throw new InputException(camera.Where, $"fov {fov}", "give a field of view between 0 and 180 degrees");
            if (camera.Parameters.Has("lensradius") && camera.Parameters.Float("lensradius", 0) > 0)
                Note("approximated", camera, "Camera \"float lensradius\"", "depth of field is not rendered: a pinhole camera");
            camera.Parameters.Find("focaldistance");
            double open = camera.Parameters.Float("shutteropen", 0), close = camera.Parameters.Float("shutterclose", 1);
            _imagingRatio *= Math.Abs(close - open) > 0 ? Math.Abs(close - open) : 1;
            ReportUnused(camera, $"Camera \"{camera.Type}\"");
        }
        // pbrt's fov spans the shorter image axis; ours is vertical.
        double vertical = width >= height ? fov : 2 * Math.Atan(Math.Tan(fov * Math.PI / 360) * height / width) * 180 / Math.PI;

        var worldFromCamera = _doc.CameraFromWorld.Inverse()
            ?? throw new InputException(camera?.Where ?? file, "the camera's transformation is singular",
                "check the transformations before Camera");
        double[] eye = worldFromCamera.Point(0, 0, 0);
        double[] forward = PbrtTransform.Normalize(worldFromCamera.Vector(0, 0, 1));
        double[] up = PbrtTransform.Normalize(worldFromCamera.Vector(0, 1, 0));
        double[] right = PbrtTransform.Normalize(worldFromCamera.Vector(1, 0, 0));
        if (forward.Length == 0 || up.Length == 0 || right.Length == 0)
            throw new InputException(camera?.Where ?? file, "the camera's transformation flattens an axis",
                "check the Scale before Camera");
        // Our camera's right is forward × up; pbrt's image right is the camera's +x. When they disagree (pbrt's LookAt, a
        // left-handed frame) the world is mirrored in x so that the picture is the same.
        if (PbrtTransform.Dot(right, PbrtTransform.Cross(forward, up)) < 0)
        {
            _world = PbrtTransform.Scale(-1, 1, 1);
            Note("converted", camera?.Where ?? file, "Camera",
                "pbrt's camera frame is left-handed (image right = up × forward): the scene is mirrored in x, as 'Scale -1 1 1' before "
                    + "LookAt would, so the picture is the same");
            eye = _world.Point(eye[0], eye[1], eye[2]);
            forward = _world.Vector(forward[0], forward[1], forward[2]);
            up = _world.Vector(up[0], up[1], up[2]);
        }
        return new JsonObject
        {
            ["position"] = Array3(eye),
            ["look_at"] = Array3([eye[0] + forward[0], eye[1] + forward[1], eye[2] + forward[2]]),
            ["up"] = Array3(up),
            ["fov"] = Round(vertical),
            ["width"] = width,
            ["height"] = height,
            ["spp"] = spp,
        };
    }

    JsonNode Integrator()
    {
        var e = _doc.Integrator;
        if (e is null) return new JsonObject { ["type"] = "path", ["max_depth"] = 5 };
        int depth = e.Parameters.Integer("maxdepth", 5);
        if (depth < 0) throw new InputException(e.Where, $"maxdepth {depth}", "give 0 or more bounces");
        var label = $"Integrator \"{e.Type}\"";
        switch (e.Type)
        {
            case "path":
            case "volpath":
                e.Parameters.Find("regularize");
                e.Parameters.Find("lightsampler");
                break;
            case "directlighting":
                depth = 1;
                Note("converted", e, label, "direct illumination: our path tracer with max_depth 1 (light and BSDF samples, MIS)");
                break;
            case "bdpt":
            case "mlt":
            case "sppm":
            case "simplepath":
            case "simplevolpath":
            case "lightpath":
            case "randomwalk":
                Note("approximated", e, label, "rendered with our unidirectional path tracer (next-event estimation and MIS): "
                    + "the same picture converged, other noise");
                break;
            default:
                Note("approximated", e, label, $"'{e.Type}' has no counterpart: rendered with our path tracer");
                break;
        }
        ReportUnused(e, label);
        // pbrt's maxdepth counts as ours: 0 sees emitters only, 1 direct light.
        return new JsonObject { ["type"] = "path", ["max_depth"] = depth };
    }
}
