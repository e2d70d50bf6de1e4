using System.Globalization;
using System.Numerics;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// Reads a scene file (docs/scene-format.md): JSON with comments and trailing commas. Every error
/// is one line naming file:line:column and the JSON path, what is wrong, and a hint. One file per concept: this one
/// the scene (top level, bands, radiometry, integration, output), then SceneLoader.Camera, .Spectra, .Materials, .Lights,
/// .Objects, .Meshes, and .Json (the readers and their errors).
/// </summary>
public sealed partial class SceneLoader
{
    public const int MaxResolution = 32768;

    /// <summary>
    /// The largest coordinate or length a scene may use, and the smallest size of a shape, in scene units:
    /// single-precision ray tracing keeps about 7 digits, so a scene spans at most 1e7 of its smallest feature
    /// of interest; beyond that, intersections and matrix inverses overflow or lose every digit.
    /// </summary>
    public const double MaxCoordinate = 1e7, MinSize = 1e-6;

    /// <summary>The largest magnitude of any number in a scene (spectral values, scales, intensities): far beyond
    /// any real one, and far enough below float's 3.4e38 that products of a few of them stay finite.</summary>
    public const double MaxMagnitude = 1e30;
    static readonly JsonReaderOptions ReaderOptions = new() { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true };

    readonly string _file;
    readonly string _dir;
    readonly JsonLocator _locator;
    readonly SceneOverrides _overrides;
    readonly Dictionary<string, (JsonElement Element, string Path)> _namedSpectra = new(StringComparer.Ordinal);
    readonly Dictionary<string, TabulatedSpectrum> _resolvedNamed = new(StringComparer.Ordinal);
    readonly List<string> _resolving = [];  // the names being resolved, outermost first (the search path)
    BandGrid _grid = BandGrid.Default;
    /// <summary>camera.target_error (or --target-error): adaptive sampling's target, 0 for off.</summary>
    double _targetError;
    Colorimeter? _colorimeter;
    Radiometry _radiometry;
    readonly List<string> _warnings = [];
    readonly Dictionary<float[], TabulatedSpectrum> _spectra = new(ReferenceEqualityComparer.Instance);

    /// <summary>The scene path that stands for standard input: its relative paths resolve from the working folder.</summary>
    public const string StandardInput = "-";
    const string StandardInputName = "<stdin>";

    SceneLoader(string file, JsonLocator locator, SceneOverrides overrides)
    {
        bool stdin = file == StandardInput;
        _file = stdin ? StandardInputName : file;
        _dir = stdin ? Directory.GetCurrentDirectory() : Path.GetDirectoryName(Path.GetFullPath(file))!;
        _locator = locator;
        _overrides = overrides;
    }

    public static Scene Load(string path, SceneOverrides? overrides = null)
    {
        return Parse(InputFile.ReadAllBytes(path, "scene file"), path, overrides ?? new SceneOverrides());
    }

    /// <summary>Reads a whole scene from a stream (standard input for <see cref="StandardInput"/>).</summary>
    public static byte[] ReadAll(Stream input)
    {
        using var buffer = new MemoryStream();
        input.CopyTo(buffer);
        return buffer.ToArray();
    }

    public static Scene Parse(byte[] utf8, string path, SceneOverrides? overrides = null)
    {
        var span = utf8.AsSpan();
        if (span.StartsWith((ReadOnlySpan<byte>)[0xEF, 0xBB, 0xBF])) span = span[3..];
        CheckUtf8(span, path);
        JsonDocument doc;
        try
        {
            doc = JsonDocument.Parse(span.ToArray(),
                new JsonDocumentOptions { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true });
        }
        catch (JsonException e)
        {
            string msg = e.Message;
            int cut = msg.IndexOf(" LineNumber:", StringComparison.Ordinal);
            if (cut > 0) msg = msg[..cut].TrimEnd('.', ' ');
            int eol = msg.IndexOfAny(['\r', '\n']);
            if (eol > 0) msg = msg[..eol].TrimEnd('.', ' ');
            throw new InputException($"{path}:{(e.LineNumber ?? 0) + 1}:{(e.BytePositionInLine ?? 0) + 1}", $"JSON syntax error: {msg}",
                "check for a missing comma, quote or bracket just before this place");
        }
        using (doc)
        {
            var locator = new JsonLocator(span, ReaderOptions);
            if (locator.Duplicate is { } dup)
            {
                string key = dup.Path[(dup.Path.LastIndexOf('.') + 1)..];
                throw new InputException($"{path}:{locator.Position(dup.Offset)}: {dup.Path}",
                    $"key {MessageText.Quote(key)} appears a second time in this object",
                    "each key may appear once: remove or rename one of them");
            }
            var loader = new SceneLoader(path, locator, overrides ?? new SceneOverrides());
            try { return loader.Build(doc.RootElement); }
            catch (InsufficientExecutionStackException)
            {
                throw new InputException(path, "the scene nests too deeply (spectrum names referring to names, thousands deep)",
                    "refer to spectra by fewer levels of names");
            }
            finally { loader.AbandonMeshReads(); }
        }
    }

    /// <summary>A scene file is UTF-8: any other encoding (Latin-1, UTF-16 without a byte order mark) is named at its first bad
    /// byte.</summary>
    static void CheckUtf8(ReadOnlySpan<byte> span, string path)
    {
        if (System.Text.Unicode.Utf8.IsValid(span)) return;
        int at = 0, line = 1, column = 1;
        var rest = span;
        while (rest.Length > 0)
        {
            var status = System.Text.Rune.DecodeFromUtf8(rest, out var rune, out int used);
            if (status != System.Buffers.OperationStatus.Done) break;
            if (rune.Value == '\n') { line++; column = 1; } else column++;
            at += used;
            rest = rest[used..];
        }
        throw new InputException($"{path}:{line}:{column}", $"byte 0x{span[at]:X2} is not valid UTF-8",
            "save the scene file as UTF-8 (it looks like Latin-1 or another legacy encoding)");
    }


    // ---- the scene ----------------------------------------------------------------------------

    static readonly string[] TopKeys = ["name", "description", "bands", "wave", "integration", "radiometry", "observer", "white", "scaling",
        "spectra", "materials", "lights", "objects", "background", "sky", "ambient", "max_depth", "integrator", "min_ray_weight",
        "ray_budget", "camera", "output", "calculation_grids", "medium", "prototypes"];

    Scene Build(JsonElement root)
    {
        Object(root, "$");
        Keys(root, "$", TopKeys);
        StartMeshReads(root);

        _grid = ParseBands(root);
        var integration = ParseIntegration(_overrides.Integration, root);
        var observer = TryGet(root, "observer", out var obs)
            ? Observer.FromDegrees(obs.ValueKind == JsonValueKind.Number
                ? obs.GetRawText()
                : obs.ValueKind == JsonValueKind.String
                ? obs.GetString()!
                : "?",
                Where("$.observer"))
            : Observer.Cie1931;

        if (TryGet(root, "spectra", out var spectra))
            foreach (var p in Object(spectra, "$.spectra").EnumerateObject())
                _namedSpectra[p.Name] = (p.Value, $"$.spectra.{p.Name}");

        // The reference white fixes κ (eq. 3): the named one, else the first light's spectrum, else D65.
        TabulatedSpectrum white;
        if (TryGet(root, "white", out var w)) white = Spectrum(w, "$.white");
        else if (TryGet(root, "lights", out var ls) && ls.ValueKind == JsonValueKind.Array && ls.GetArrayLength() > 0 &&
                 ls[0].ValueKind == JsonValueKind.Object && TryGet(ls[0], "spectrum", out var ls0)) white =
                     Spectrum(ls0, "$.lights[0].spectrum");
        else white = SpectrumLibrary.Resolve("D65");
        string whitePath = TryGet(root, "white", out _) ? "$.white" : "$.lights[0].spectrum";
        if (!white.Covers(_grid.Start, _grid.End))
            throw Error(whitePath,
                $"spectrum '{white.Name}' covers {white.First:0.###}–{white.Last:0.###} nm but the bands need "
                    + $"{_grid.Start:0.###}–{_grid.End:0.###} nm",
                "choose bands inside its range or give it \"extrapolate\": \"clamp\" or \"zero\"");
        bool absolute = false;
        if (TryGet(root, "scaling", out var scaling))
            absolute = String(scaling, "$.scaling").ToLowerInvariant() switch
            {
                "relative" => false,
                "absolute" => true,
                var other => throw Error("$.scaling", $"unknown scaling '{other}'", "relative (white Y = 1) or absolute (κ = 683 lm/W)"),
            };
        _radiometry = Radiometry.Paper;
        if (TryGet(root, "radiometry", out var rad))
            _radiometry = String(rad, "$.radiometry").ToLowerInvariant() switch
            {
                "paper" => Radiometry.Paper,
                "physical" => Radiometry.Physical,
                var other => throw Error("$.radiometry", $"unknown radiometry '{other}'",
                    "paper (eq. 2 as the paper writes it, relative units) or physical (W·sr⁻¹·nm⁻¹ lights, ρ/π, radiance out)"),
            };
        // Relative κ gives a perfect white diffuser lit head-on by the reference white at unit intensity Y = 1 in both
        // radiometries: its radiance per unit irradiance is 1 (paper) or 1/π (physical).
        _colorimeter = new Colorimeter(_grid, observer, white, integration, absolute, _radiometry == Radiometry.Physical ? 1 / Math.PI : 1);
        // κ = 1 / Y(white): a white that is (nearly) dark in these bands makes every colour meaningless.
        if (!absolute && !(_colorimeter.Kappa > 0 && _colorimeter.Kappa < 1e12))
            throw Error(whitePath, $"the reference white '{white.Name}' has no luminance over the bands {_grid}",
                "choose a white (or first light) that emits visible light inside the bands");

        var camera = ParseCamera(Required(root, "camera", "$"), "$.camera");
        var materials = new List<Material>();
        var materialIndex = new Dictionary<string, int>(StringComparer.Ordinal);
        if (TryGet(root, "materials", out var mats))
            foreach (var p in Object(mats, "$.materials").EnumerateObject())
            {
                materialIndex[p.Name] = materials.Count;
                materials.Add(ParseMaterial(p.Value, $"$.materials.{p.Name}", p.Name));
            }

        var lights = new List<Light>();
        if (TryGet(root, "lights", out var lightArray))
        {
            if (lightArray.ValueKind != JsonValueKind.Array)
                throw Error("$.lights", $"expected an array of lights, found {Kind(lightArray)}",
                    "e.g. \"lights\": [{\"type\": \"point\", …}]");
            int i = 0;
            foreach (var l in lightArray.EnumerateArray()) { lights.Add(ParseLight(l, $"$.lights[{i}]", i)); i++; }
        }

        ParsePrototypes(root);
        var objects = new List<SceneObject>();
        var objectsElement = Required(root, "objects", "$");
        if (objectsElement.ValueKind != JsonValueKind.Array)
            throw Error("$.objects", $"expected an array of objects, found {Kind(objectsElement)}",
                "e.g. \"objects\": [{\"type\": \"sphere\", …}]");
        {
            int i = 0;
            foreach (var o in objectsElement.EnumerateArray())
            {
                int before = objects.Count;
                ParseObject(o, $"$.objects[{i}]", i, objects, materials, materialIndex);
                if (TryGet(o, "medium", out var interior))
                {
                    int medium = ParseMedium(interior, $"$.objects[{i}].medium", objects[before..]);
                    for (int j = before; j < objects.Count; j++)
                    {
                        if (!Encloses(objects[j]))
                            throw Error($"$.objects[{i}].medium", $"object '{objects[j].Name}' is not closed, so it bounds no interior",
                                "give the medium to a sphere, a box or a closed (watertight) mesh, or make it the scene's \"medium\"");
                        objects[j].Medium = medium;
                    }
                }
                i++;
            }
        }
        CopyEmittingInstances(objects, materials, materialIndex);
        ScaleFluxEmission(materials, materialIndex, objects);
        var names = new HashSet<string>(StringComparer.Ordinal);
        foreach (var o in objects)
            if (!names.Add(o.Name))
                throw Error("$.objects", $"two objects are named '{o.Name}'",
                    "object names must be unique (they label the object-id image)");

        var output = ParseOutput(root);
        var calculationGrids = ParseCalculationGrids(root);
        // A scene's calculation grids are written with every render of it (the grids product).
        if (calculationGrids.Count > 0) output.Products |= OutputProducts.Grids;
        int depth = Integer(root, "max_depth", "$", 5, 0, 64);
        var integrator = ParseIntegrator(root);
        float minWeight = (float)Number(root, "min_ray_weight", "$", Scene.DefaultMinRayWeight, 0, 1);
        int budget = Integer(root, "ray_budget", "$", Scene.DefaultRayBudget, 1, 1_000_000_000);
        var background = TryGet(root, "background", out var bg) ? ParseBackground(bg) : new float[SpectralMath.Padded(_grid.Count)];
        if (TryGet(root, "sky", out var sky))
        {
            if (TryGet(root, "background", out _))
                throw Error("$.sky", "a scene gives both \"sky\" and \"background\"", "the sky is the background: keep one");
            background = ParseSky(sky);
        }
        int sceneMedium = TryGet(root, "medium", out var around) ? ParseMedium(around, "$.medium") : -1;
        bool hasAmbient = TryGet(root, "ambient", out var amb);
        var ambient = hasAmbient ? Bands(amb, "$.ambient") : new float[SpectralMath.Padded(_grid.Count)];

        CheckFramebuffer(camera);
        WarnIfBlack(lights, materials, objects, hasAmbient && SpectralMath.Any(ambient), SpectralMath.Any(background));

        return new Scene
        {
            SourcePath = _file == StandardInputName ? StandardInputName : Path.GetFullPath(_file),
            Grid = _grid,
            Integration = integration,
            Observer = observer,
            ReferenceWhite = white,
            Colorimeter = _colorimeter,
            Radiometry = _radiometry,
            Warnings = _warnings,
            Spectra = _spectra,
            Camera = camera,
            Materials = materials,
            Lights = lights,
            Objects = objects,
            Portals = _portals,
            Background = background,
            Environment = _environment,
            SkyDistribution = _skyDistribution,
            Zenith = _zenith,
            Media = _media,
            Medium = sceneMedium,
            GlobalAmbient = ambient,
            HasGlobalAmbient = hasAmbient && SpectralMath.Any(ambient),
            MaxDepth = depth,
            Integrator = integrator,
            TargetError = _targetError,
            MinRayWeight = minWeight,
            RayBudget = budget,
            Output = output,
            CalculationGrids = calculationGrids,
            Resolved = Resolved(root),
        };
    }

    /// <summary>A scene whose every pixel must be black is almost always a mistake: say so on stderr (the render still runs).</summary>
    void WarnIfBlack(List<Light> lights, List<Material> materials, List<SceneObject> objects, bool globalAmbient, bool background)
    {
        if (background) return;
        bool lit = globalAmbient || lights.Any(l => SpectralMath.Any(l.Intensity) || l.HasAmbient)
            || materials.Any(m => m.Emission is { } e && SpectralMath.Any(e.Radiance));
        if (!lit)
        {
            _warnings.Add($"{_file}: warning: the scene can only render black: "
                + $"{(lights.Count == 0 ? "it has no light" : "no light emits inside the bands " + _grid)}, no "
                + $"ambient light and a black background " +
                "(add a light with a spectrum and \"intensity\" > 0, an \"ambient\" or a \"background\")");
            return;
        }
        bool reflects = objects.Any(o => materials[o.Material] is var m
            && (m.HasAmbient || SpectralMath.Any(m.Diffuse) || m.HasSpecular || m.HasMirror || m.HasTransmission));
        if (!reflects)
            _warnings.Add($"{_file}: warning: the scene can only render black: no object's material reflects or transmits "
                + $"light and the background is black");
    }

    /// <summary>
    /// The scene as the manifest records it: the fields the renderer read, with the named spectra it used.
    /// "name" and "description" are short strings; named spectra nothing refers to are left out.
    /// </summary>
    JsonObject Resolved(JsonElement root)
    {
        var o = new JsonObject();
        foreach (var p in root.EnumerateObject())
        {
            if (p.Value.ValueKind == JsonValueKind.Null) continue;
            if (p.Name is "name" or "description")
            {
                var text = String(p.Value, $"$.{p.Name}");
                if (text.Length > MaxDescription)
                    throw Error($"$.{p.Name}", $"is {text.Length} characters long, more than {MaxDescription}",
                        "keep names and descriptions short; long notes belong in a file beside the scene");
                o[p.Name] = text;
                continue;
            }
            if (p.Name == "spectra")
            {
                var used = new JsonObject();
                foreach (var s in p.Value.EnumerateObject())
                    if (_resolvedNamed.ContainsKey(s.Name))
                        used[s.Name] = JsonNode.Parse(s.Value.GetRawText(), documentOptions: NodeOptions);
                o[p.Name] = used;
                continue;
            }
            o[p.Name] = JsonNode.Parse(p.Value.GetRawText(), documentOptions: NodeOptions);
        }
        return o;
    }

    static readonly JsonDocumentOptions NodeOptions = new() { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true };

    /// <summary>The longest scene name or description, in characters.</summary>
    public const int MaxDescription = 4096;

    string Where(string path) => _locator.Locate(path) is { } pos ? $"{_file}:{pos}: {path}" : $"{_file}: {path}";

    /// <summary>The band grid: --wave or --bands, else the scene's "wave" (centres) or "bands" (edges), else 380:780:20.</summary>
    BandGrid ParseBands(JsonElement root)
    {
        if (_overrides.Wave is not null && _overrides.Bands is not null)
            throw new InputException("--wave", "--wave and --bands both give the bands",
                "use one: --wave 400:10:700 (centres) or --bands 395:705:31 (edges)");
        if (_overrides.Wave is { } w) return BandGrid.ParseWave(w);
        if (_overrides.Bands is { } b) return BandGrid.Parse(b);
        bool hasBands = TryGet(root, "bands", out var bands), hasWave = TryGet(root, "wave", out var wave);
        if (hasBands && hasWave)
            throw Error("$.wave", "the scene gives both \"bands\" and \"wave\"",
                "keep one: \"wave\": \"400:10:700\" (centres) or \"bands\": \"395:705:31\" (edges)");
        if (hasWave)
        {
            if (wave.ValueKind != JsonValueKind.String)
                throw Error("$.wave", $"expected a string such as \"400:10:700\", found {Kind(wave)}",
                    "give start:step:end in nm, e.g. \"400:10:700\"");
            return BandGrid.ParseWave(wave.GetString()!, Where("$.wave"));
        }
        return hasBands ? ParseGrid(bands, "$.bands") : BandGrid.Default;
    }

    BandGrid ParseGrid(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.String)
            throw Error(path, $"expected a string such as \"380:780:20\", found {Kind(e)}",
                "give start:end:count in nm, e.g. \"380:780:20\"");
        return BandGrid.Parse(e.GetString()!, Where(path));
    }

    BandIntegration ParseIntegration(string? fromCli, JsonElement root)
    {
        if (fromCli is not null) return ParseIntegration(fromCli, "--integration");
        if (!TryGet(root, "integration", out var e)) return BandIntegration.Exact;
        return ParseIntegration(String(e, "$.integration"), Where("$.integration"));
    }

    static BandIntegration ParseIntegration(string s, string where) => BandIntegrations.Parse(s, where);

    void CheckFramebuffer(Camera camera)
    {
        long bytes = (long)camera.Width * camera.Height * _grid.Count * sizeof(float);
        long available = GC.GetGCMemoryInfo().TotalAvailableMemoryBytes;
        long elements = (long)camera.Width * camera.Height * _grid.Count;
        if (elements > Array.MaxLength || bytes > available / 2)
            throw Error("$.camera",
                $"a {camera.Width}×{camera.Height} framebuffer of {_grid.Count} bands needs {Size(bytes)}, more than this machine can "
                    + $"hold ({Size(available)} of memory)",
                "lower the width, height or band count");
    }

    static string Size(long bytes) => bytes >= 1L << 30 ? $"{bytes / (double)(1L << 30):0.#} GiB" : $"{bytes / (double)(1L << 20):0.#} MiB";

    OutputOptions ParseOutput(JsonElement root)
    {
        var o = new OutputOptions();
        if (TryGet(root, "output", out var e))
        {
            Object(e, "$.output");
            Keys(e, "$.output", "rgb", "exposure", "gamut", "adapt", "formats", "highlight_fraction", "exr_compression", "light_groups");
            o.HighlightFraction = Number(e, "highlight_fraction", "$.output", 0.1, 0, 1e6);
            if (TryGet(e, "rgb", out var rgb)) o.Rgb = RgbSpace.Parse(String(rgb, "$.output.rgb"), Where("$.output.rgb"));
            if (TryGet(e, "exposure", out var ex) && ex.ValueKind == JsonValueKind.String)
            {
                if (!string.Equals(ex.GetString(), "auto", StringComparison.OrdinalIgnoreCase))
                    throw Error("$.output.exposure", $"unknown exposure '{ex.GetString()}'",
                        "a number (XYZ multiplier) or \"auto\" (the 99th percentile of the brightest channel → 1)");
                o.ExposureAuto = true;
            }
            else o.Exposure = Number(e, "exposure", "$.output", 1.0, 0, 1e12);
            if (TryGet(e, "gamut", out var gm))
                o.Gamut = String(gm, "$.output.gamut").ToLowerInvariant() switch
                {
                    "clip" => GamutMapping.Clip,
                    "desaturate" => GamutMapping.Desaturate,
                    var other => throw Error("$.output.gamut", $"unknown gamut mapping '{other}'",
                        "clip (per channel, colorimetric in gamut) or desaturate (toward white at constant "
                            + "luminance, then scale: keeps hue)"),
                };
            o.Adapt = Bool(e, "adapt", "$.output", false);
            if (TryGet(e, "formats", out var f))
            {
                if (f.ValueKind != JsonValueKind.Array)
                    throw Error("$.output.formats", $"expected an array of format names, found {Kind(f)}",
                        "e.g. \"formats\": [\"png\", \"exr\"]");
                o.Products =
                    ParseFormats(f.EnumerateArray().Select((x, i) => String(x, $"$.output.formats[{i}]")), Where("$.output.formats"));
            }
            // "light_groups": true adds the per-light transfer outputs (lights/) to the formats.
            if (Bool(e, "light_groups", "$.output", false)) o.Products |= OutputProducts.Lights;
            if (TryGet(e, "exr_compression", out var c))
                o.ExrCompression = ParseExrCompression(String(c, "$.output.exr_compression"), Where("$.output.exr_compression"));
        }
        if (_overrides.ExrCompression is { } ec) o.ExrCompression = ParseExrCompression(ec, "--exr-compression");
        if (_overrides.Rgb is { } r) o.Rgb = RgbSpace.Parse(r);
        if (_overrides.Exposure is { } x)
        {
            (o.ExposureAuto, o.Exposure) = OutputOptions.ParseExposure(x);
        }
        if (_overrides.Formats is { } fs)
            o.Products = ParseFormats(fs.Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries), "--formats");
        return o;
    }

    static ExrCompressionChoice ParseExrCompression(string name, string where)
    {
        var n = name.ToLowerInvariant();
        foreach (var (choice, known) in OutputNames.ExrCompressions) if (known == n) return choice;
        throw new InputException(where, $"unknown EXR compression '{name}'",
            InputException.DidYouMean(name, OutputNames.ExrCompressionNames)
                ?? "zip (deflate where samples repeat), zip-all (smallest file) or none");
    }

    public static OutputProducts ParseFormats(IEnumerable<string> names, string where)
    {
        var set = OutputProducts.None;
        var all = OutputNames.ProductNames;
        foreach (var n in names)
        {
            var f = n.ToLowerInvariant();
            if (f == "all") { set |= OutputProducts.All; continue; }
            int i = Array.IndexOf(all, f);
            if (i < 0)
                throw new InputException(where, $"unknown output format {MessageText.Quote(n)}",
                    InputException.DidYouMean(n, all) ?? $"formats: {string.Join(", ", all)}, all");
            set |= OutputNames.Products[i].Product;
        }
        if (set == OutputProducts.None)
            throw new InputException(where, "names no output format", $"give at least one of {string.Join(", ", all)} or all");
        return set;
    }
}
