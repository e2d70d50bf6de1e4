using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

/// <summary>An object of the scene as render.json lists it: its id in object-id.png (1-based, 0 = background).</summary>
/// <param name="FlatNormal">The world normal of a flat shape (quad, plane), so analysis can tell a chart lit head-on; null otherwise.</param>
public sealed record ManifestObject(int Id, string Name, string Material, string? Reflectance, double[]? FlatNormal = null);

/// <summary>A light as render.json lists it: k in mask-lit-&lt;k&gt;.png, its kind ("point", "spot", "directional") and spectrum name.</summary>
/// <param name="Intensity">The scene's intensity, the factor on <paramref name="Spd"/>; <paramref name="IntensityUnit"/> says what it is in.</param>
/// <param name="Position">Point and spot lights; <paramref name="Direction"/> the direction spot and directional lights shine towards.</param>
/// <param name="Attenuation">[c0, c1, c2] of d = 1/(c0 + c1·r + c2·r²); null for directional lights (no attenuation).</param>
/// <param name="Photometric">The photometric value the scene gave instead of an intensity (physical radiometry), or null.</param>
public sealed record ManifestLight(int Index, string Name, string Kind, string? Spectrum, double Intensity = 1, string? IntensityUnit = null,
    bool HasAmbient = false, double[]? Position = null, double[]? Direction = null, double[]? Attenuation = null, TabulatedSpectrum? Spd = null,
    ManifestPhotometry? Photometric = null);

/// <summary>
/// A light's photometric value as render.json records it: the quantity (luminous_flux, luminous_intensity, illuminance,
/// luminance), its value in <paramref name="Unit"/>, the radiometric scale it gave (the light's intensity, the factor on
/// its spectrum) and K_m ∫V(λ)·S(λ) dλ of the spectrum, so that Value = scale × that × the light's geometric factor.
/// </summary>
public sealed record ManifestPhotometry(string Quantity, double Value, string Unit, double RadiometricScale, double LuminousPerUnit);

/// <summary>Rays traced, by kind, and the rate (million rays per second of render time).</summary>
public sealed record ManifestRays(long Primary, long Shadow, long Secondary, long Total, double MraysPerSecond);

/// <summary>
/// render.json, typed: what a render folder holds and how to read it (the band grid, eq. 3's weights, the
/// reference white, the objects of object-id.png, the lights of the masks). <see cref="ToJson"/> is the one place
/// its keys are written and <see cref="Read"/> the one place they are read back.
/// </summary>
public sealed record RenderManifest
{
    public const string FileName = "render.json";

    public string Tool { get; init; } = "spectral";
    public string? Version { get; init; }
    /// <summary>
    /// The engine build that wrote the folder: its assembly's module version id (a new one for every change of the code,
    /// the same for the same code). Files of a folder written by this very build are what it would write again.
    /// </summary>
    public string? Build { get; init; }
    public required string Scene { get; init; }
    public required string CreatedUtc { get; init; }
    public required int Width { get; init; }
    public required int Height { get; init; }
    public required int SamplesPerPixel { get; init; }
    public required BandGrid Grid { get; init; }
    /// <summary>The radiance that band PNG level 65535 stands for (the brightest band value of the render).</summary>
    public required float BandImageScale { get; init; }
    public required BandIntegration Integration { get; init; }
    public required int ObserverDegrees { get; init; }
    public required TabulatedSpectrum ReferenceWhite { get; init; }
    /// <summary>κ of eq. 3.</summary>
    public required double Kappa { get; init; }
    public required Xyz White { get; init; }
    /// <summary>Eq. 3's weights per band: X = Σ_b Wx[b]·L[b] and so on.</summary>
    public required double[] Wx { get; init; }
    public required double[] Wy { get; init; }
    public required double[] Wz { get; init; }
    public required string Rgb { get; init; }
    public required double Exposure { get; init; }
    public required bool Adapt { get; init; }
    /// <summary>"fixed" or "auto (…)": how <see cref="Exposure"/> was chosen for preview.png.</summary>
    public string ExposureMode { get; init; } = "fixed";
    /// <summary>The preview's gamut mapping, "clip" or "desaturate".</summary>
    public string Gamut { get; init; } = "clip";
    /// <summary>"paper" or "physical" (docs/scene-format.md, Radiometry).</summary>
    public string Radiometry { get; init; } = "paper";
    /// <summary>What a band value is, with its unit.</summary>
    public string? BandUnit { get; init; }
    /// <summary>What X, Y, Z mean (relative to the white, or absolute in cd/m²).</summary>
    public string? XyzUnit { get; init; }
    /// <summary>How the pixels' colours (preview, spectral.exr X Y Z) were computed.</summary>
    public string? PixelXyz { get; init; }
    /// <summary>Pixels whose colour fell back to eq. 3 on their bands (a term with more than a light and a material spectrum).</summary>
    public long FallbackPixels { get; init; }
    /// <summary>True when the scene has a global ambient a_glob.</summary>
    public bool GlobalAmbient { get; init; }
    public required IReadOnlyList<ManifestObject> Objects { get; init; }
    public required IReadOnlyList<ManifestLight> Lights { get; init; }
    public required double HighlightFraction { get; init; }
    public required double RenderSeconds { get; init; }
    public required ManifestRays Rays { get; init; }
    public required int Threads { get; init; }
    public required int Tiles { get; init; }
    /// <summary>How the render ran (command line, load and build times, overrides, what it was relit from).</summary>
    public ManifestRun? Run { get; init; }
    /// <summary>The files the render wrote, relative to its folder.</summary>
    public IReadOnlyList<string>? Files { get; init; }
    /// <summary>The resolved scene: the scene file as the render read it.</summary>
    public ManifestScene? ResolvedScene { get; init; }
    /// <summary>What the render computes (<see cref="Output.SceneHash"/>): equal for the shards of one render.</summary>
    public string? SceneHash { get; init; }
    /// <summary>
    /// A partial render (--crop, --shard): the film pixels this folder holds, X1 and Y1 exclusive; null for the whole
    /// film. Its images are crop-sized; the ENVI and NPY cubes start at film pixel (X0, Y0), the EXRs say it in dataWindow.
    /// </summary>
    public Rendering.PixelRect? Crop { get; init; }
    /// <summary>The sampler and how exact the render is (per-pixel standard errors, adaptive sampling); null: the independent sampler, no statistics.</summary>
    public ManifestSampling? Sampling { get; init; }

    /// <summary>Eq. 3 with the render's own weights.</summary>
    public Xyz ToXyz(ReadOnlySpan<double> bands) => Colorimeter.ToXyz(Wx, Wy, Wz, bands);

    public JsonObject ToJson()
    {
        static JsonArray Arr(ReadOnlySpan<double> v)
        {
            var a = new JsonArray();
            foreach (double x in v) a.Add((JsonNode)JsonValue.Create(x));
            return a;
        }
        var centres = new double[Grid.Count];
        for (int b = 0; b < centres.Length; b++) centres[b] = Grid.Centre(b);
        var objects = new JsonArray();
        foreach (var o in Objects)
        {
            var e = new JsonObject { ["id"] = o.Id, ["name"] = o.Name, ["material"] = o.Material, ["reflectance"] = o.Reflectance };
            if (o.FlatNormal is { } fn) e["flat_normal"] = Arr(fn);
            objects.Add((JsonNode)e);
        }
        var lights = new JsonArray();
        foreach (var l in Lights)
        {
            var e = new JsonObject
            {
                ["index"] = l.Index,
                ["name"] = l.Name,
                ["kind"] = l.Kind,
                ["spectrum"] = l.Spectrum,
                ["intensity"] = l.Intensity,
                ["intensity_unit"] = l.IntensityUnit,
                ["has_ambient"] = l.HasAmbient,
            };
            if (l.Position is { } lp) e["position"] = Arr(lp);
            if (l.Direction is { } ld) e["direction"] = Arr(ld);
            if (l.Attenuation is { } la) e["attenuation"] = Arr(la);
            if (l.Spd is { } spd) e["spd"] = new JsonObject { ["wavelengths_nm"] = Arr(spd.Wavelengths), ["values"] = Arr(spd.Values) };
            if (l.Photometric is { } ph)
                e["photometric"] = new JsonObject
                {
                    ["quantity"] = ph.Quantity,
                    ["value"] = ph.Value,
                    ["unit"] = ph.Unit,
                    ["radiometric_scale"] = ph.RadiometricScale,
                    ["luminous_per_unit_scale"] = ph.LuminousPerUnit,
                    ["note"] = "value = radiometric_scale × luminous_per_unit_scale (683 lm/W · ∫V(λ)·spectrum dλ, CIE 1924 V) × the light's solid angle (4π sr for a point light's lm, the spot's ∫c_spot dΩ; 1 for cd and lx)",
                };
            lights.Add((JsonNode)e);
        }
        JsonArray? files = null;
        if (Files is not null) { files = []; foreach (var f in Files) files.Add((JsonNode)JsonValue.Create(f)); }
        var json = new JsonObject
        {
            ["tool"] = Tool,
            ["version"] = Version,
            ["build"] = Build,
            ["scene"] = Scene,
            ["created_utc"] = CreatedUtc,
            ["width"] = Width,
            ["height"] = Height,
            ["spp"] = SamplesPerPixel,
            ["bands"] = new JsonObject
            {
                ["grid"] = Grid.ToString(),
                ["count"] = Grid.Count,
                ["edges_nm"] = Arr(Grid.Edges()),
                ["centres_nm"] = Arr(centres),
                ["band_image_scale"] = BandImageScale,
            },
            ["radiometry"] = new JsonObject
            {
                ["mode"] = Radiometry,
                ["band_values"] = BandUnit,
                ["xyz"] = XyzUnit,
            },
            ["colour"] = new JsonObject
            {
                ["integration"] = BandIntegrations.Name(Integration),
                ["pixel_xyz"] = PixelXyz,
                ["fallback_pixels"] = FallbackPixels,
                ["observer"] = ObserverDegrees,
                ["reference_white"] = ReferenceWhite.Name,
                ["reference_white_spd"] = new JsonObject { ["wavelengths_nm"] = Arr(ReferenceWhite.Wavelengths), ["values"] = Arr(ReferenceWhite.Values) },
                ["kappa"] = Kappa,
                ["white_xyz"] = Arr([White.X, White.Y, White.Z]),
                ["weights_x"] = Arr(Wx),
                ["weights_y"] = Arr(Wy),
                ["weights_z"] = Arr(Wz),
                ["rgb"] = Rgb,
                ["exposure"] = Exposure,
                ["exposure_mode"] = ExposureMode,
                ["gamut"] = Gamut,
                ["adapt"] = Adapt,
            },
            ["objects"] = objects,
            ["lights"] = lights,
            ["global_ambient"] = GlobalAmbient,
            ["aov"] = new JsonObject { ["highlight_fraction"] = HighlightFraction },
            ["timings_s"] = new JsonObject { ["render"] = RenderSeconds },
            ["rays"] = new JsonObject
            {
                ["primary"] = Rays.Primary,
                ["shadow"] = Rays.Shadow,
                ["secondary"] = Rays.Secondary,
                ["total"] = Rays.Total,
                ["mrays_per_s"] = Rays.MraysPerSecond,
            },
            ["threads"] = Threads,
            ["tiles"] = Tiles,
            ["run"] = Run is null ? null : RunJson(Run),
            ["files"] = files,
            ["resolved_scene"] = ResolvedScene?.ToJson(),
        };
        if (SceneHash is not null) json["scene_hash"] = SceneHash;
        if (Crop is { } c) json["crop"] = new JsonObject { ["x0"] = c.X0, ["y0"] = c.Y0, ["x1"] = c.X1, ["y1"] = c.Y1 };
        if (Sampling is { } sampling) json["sampling"] = sampling.ToJson();
        return json;
    }

    static JsonObject RunJson(ManifestRun run)
    {
        var o = new JsonObject();
        void Put(string key, JsonNode? value, bool present) { if (present) o[key] = value; }
        Put("command_line", run.CommandLine, run.CommandLine is not null);
        Put("merged_shards", run.MergedShards, run.MergedShards is not null);
        Put("sweep_job", run.SweepJob, run.SweepJob is not null);
        Put("load_s", run.LoadSeconds, run.LoadSeconds is not null);
        Put("build_s", run.BuildSeconds, run.BuildSeconds is not null);
        Put("triangles", run.Triangles, run.Triangles is not null);
        Put("degenerate_triangles_skipped", run.DegenerateTrianglesSkipped, run.DegenerateTrianglesSkipped is not null);
        Put("min_ray_weight", run.MinRayWeight, run.MinRayWeight is not null);
        Put("ray_budget", run.RayBudget, run.RayBudget is not null);
        Put("rays_pruned_by_weight", run.RaysPrunedByWeight, run.RaysPrunedByWeight is not null);
        Put("camera_rays_over_budget", run.CameraRaysOverBudget, run.CameraRaysOverBudget is not null);
        Put("shard", run.Shard, run.Shard is not null);
        Put("light_transfer_s", run.LightTransferSeconds, run.LightTransferSeconds is not null);
        Put("overrides", run.Overrides is { } v ? OverridesJson(v) : null, run.HasOverrides || run.Overrides is not null);
        Put("relit", run.Relit is { } relit ? RelitJson(relit) : null, run.Relit is not null);
        Put("write_s", run.WriteSeconds, run.WriteSeconds is not null);
        return o;
    }

    static JsonObject OverridesJson(ManifestOverrides v) => new()
    {
        ["width"] = v.Width,
        ["height"] = v.Height,
        ["bands"] = v.Bands,
        ["wave"] = v.Wave,
        ["spp"] = v.SamplesPerPixel,
        ["rgb"] = v.Rgb,
        ["integration"] = v.Integration,
        ["formats"] = v.Formats,
        ["exr_compression"] = v.ExrCompression,
        ["models"] = new JsonArray(v.Models.Select(d => (JsonNode)JsonValue.Create(d)).ToArray()),
    };

    static JsonObject RelitJson(ManifestRelit relit)
    {
        var o = new JsonObject
        {
            ["from"] = relit.From,
            ["from_created_utc"] = relit.FromCreatedUtc,
            ["method"] = relit.Method,
            ["changes"] = new JsonArray(relit.Changes.Select(c => (JsonNode)new JsonObject
            { ["light"] = c.Light, ["spectrum"] = c.Spectrum, ["intensity"] = c.Intensity }).ToArray()),
            ["white"] = relit.White,
            ["compute_s"] = relit.ComputeSeconds,
        };
        if (relit.Metrics is { } m)
            o["metrics"] = new JsonObject
            {
                ["white"] = m.White,
                ["lights"] = new JsonArray(m.Lights.Select(l => (JsonNode)new JsonObject
                { ["light"] = l.Light, ["spectrum"] = l.Spectrum, ["Ra"] = l.Ra, ["Rf"] = l.Rf, ["cct_K"] = l.CctKelvin }).ToArray()),
                ["objects"] = new JsonArray(m.Objects.Select(x => (JsonNode)new JsonObject
                { ["object"] = x.Object, ["pixels"] = x.Pixels, ["mean_dE00"] = x.MeanDeltaE00, ["max_dE00"] = x.MaxDeltaE00 }).ToArray()),
            };
        if (relit.CopiedFiles is { } copied) o["copied_files"] = new JsonArray(copied.Select(f => (JsonNode)f).ToArray());
        return o;
    }

    public string ToJsonText() => ToJson().ToJsonString(new JsonSerializerOptions { WriteIndented = true });

    /// <summary>The render.json of folder <paramref name="dir"/>; a missing or broken one is bad input (file, JSON path, hint).</summary>
    public static RenderManifest Read(string dir)
    {
        var path = Path.Combine(dir, FileName);
        if (!File.Exists(path)) throw new InputException(dir, $"has no {FileName}", "give the -o folder of a 'spectral render' run");
        JsonObject json;
        try { json = JsonNode.Parse(InputFile.ReadAllText(path, FileName)) as JsonObject ?? throw new InputException($"{path}: $", "is not a JSON object", "render.json must be the manifest a render wrote: render the folder again"); }
        catch (JsonException e)
        {
            string msg = e.Message;
            int cut = msg.IndexOf(" LineNumber:", StringComparison.Ordinal);
            if (cut > 0) msg = msg[..cut].TrimEnd('.', ' ');
            throw new InputException($"{path}:{(e.LineNumber ?? 0) + 1}:{(e.BytePositionInLine ?? 0) + 1}", $"broken JSON: {msg}", "render.json is damaged: render the folder again");
        }
        return Parse(json, path);
    }

    /// <summary>A manifest from render.json's JSON; <paramref name="path"/> names it in errors.</summary>
    public static RenderManifest Parse(JsonObject json, string path)
    {
        var r = new Reader(path);
        var bands = r.Obj(json, "bands", "$");
        var colour = r.Obj(json, "colour", "$");
        var spd = r.Obj(colour, "reference_white_spd", "$.colour");
        var w = r.Numbers(colour, "white_xyz", "$.colour");
        if (w.Length != 3) throw r.Missing("$.colour.white_xyz", "three numbers X, Y, Z");
        var objects = r.Arr(json, "objects", "$").Select((o, i) => new ManifestObject(
            r.Int(o, "id", $"$.objects[{i}]"), r.Str(o, "name", $"$.objects[{i}]"), r.Str(o, "material", $"$.objects[{i}]"), r.OptStr(o, "reflectance"),
            r.OptNumbers(o, "flat_normal", $"$.objects[{i}]"))).ToArray();
        var lights = r.Arr(json, "lights", "$").Select((l, i) =>
        {
            string at = $"$.lights[{i}]";
            string name = r.OptStr(l, "name") ?? $"light {i}";
            TabulatedSpectrum? spd = l["spd"] is JsonObject so
                ? new TabulatedSpectrum(name, r.Numbers(so, "wavelengths_nm", $"{at}.spd"), r.Numbers(so, "values", $"{at}.spd"), Extrapolation.Clamp) : null;
            return new ManifestLight(r.OptInt(l, "index") ?? i, name, r.OptStr(l, "kind") ?? "point", r.OptStr(l, "spectrum"),
                r.OptNumber(l, "intensity") ?? 1, r.OptStr(l, "intensity_unit"), (bool?)r.Value(l, "has_ambient") ?? false,
                r.OptNumbers(l, "position", at), r.OptNumbers(l, "direction", at), r.OptNumbers(l, "attenuation", at), spd,
                l["photometric"] is JsonObject po ? new ManifestPhotometry(r.Str(po, "quantity", $"{at}.photometric"),
                    r.OptNumber(po, "value") ?? 0, r.Str(po, "unit", $"{at}.photometric"), r.OptNumber(po, "radiometric_scale") ?? 0,
                    r.OptNumber(po, "luminous_per_unit_scale") ?? 0) : null);
        }).ToArray();
        var radiometry = json["radiometry"] as JsonObject;
        var rays = json["rays"] as JsonObject;
        string grid = r.Str(bands, "grid", "$.bands");
        var spdWavelengths = r.Numbers(spd, "wavelengths_nm", "$.colour.reference_white_spd");
        var spdValues = r.Numbers(spd, "values", "$.colour.reference_white_spd");
        if (spdWavelengths.Length == 0 || spdValues.Length != spdWavelengths.Length)
            throw r.Missing("$.colour.reference_white_spd.values", $"as many values as wavelengths_nm ({spdWavelengths.Length})");
        for (int i = 1; i < spdWavelengths.Length; i++)
            if (!(spdWavelengths[i] > spdWavelengths[i - 1])) throw r.Missing($"$.colour.reference_white_spd.wavelengths_nm[{i}]", "ascending");
        var parsed = new RenderManifest
        {
            Tool = r.OptStr(json, "tool") ?? "spectral",
            Version = r.OptStr(json, "version"),
            Build = r.OptStr(json, "build"),
            Scene = r.OptStr(json, "scene") ?? "",
            CreatedUtc = r.OptStr(json, "created_utc") ?? "",
            Width = r.Int(json, "width", "$"),
            Height = r.Int(json, "height", "$"),
            SamplesPerPixel = r.OptInt(json, "spp") ?? 1,
            Grid = BandGrid.Parse(grid, $"{path}: $.bands.grid"),
            BandImageScale = (float)(r.OptNumber(bands, "band_image_scale") ?? 0),
            Integration = BandIntegrations.Parse(r.Str(colour, "integration", "$.colour"), $"{path}: $.colour.integration"),
            ObserverDegrees = r.Int(colour, "observer", "$.colour"),
            ReferenceWhite = new TabulatedSpectrum(r.OptStr(colour, "reference_white") ?? "white",
                spdWavelengths, spdValues, Extrapolation.Clamp),
            Kappa = r.OptNumber(colour, "kappa") ?? 0,
            White = new Xyz(w[0], w[1], w[2]),
            Wx = r.Numbers(colour, "weights_x", "$.colour"),
            Wy = r.Numbers(colour, "weights_y", "$.colour"),
            Wz = r.Numbers(colour, "weights_z", "$.colour"),
            Rgb = r.OptStr(colour, "rgb") ?? "srgb",
            Exposure = r.OptNumber(colour, "exposure") ?? 1,
            Adapt = r.Value(colour, "adapt") is { } adapt && adapt.TryGetValue(out bool b) && b,
            ExposureMode = r.OptStr(colour, "exposure_mode") ?? "fixed",
            Gamut = r.OptStr(colour, "gamut") ?? "clip",
            Radiometry = radiometry is null ? "paper" : r.OptStr(radiometry, "mode") ?? "paper",
            BandUnit = radiometry is null ? null : r.OptStr(radiometry, "band_values"),
            XyzUnit = radiometry is null ? null : r.OptStr(radiometry, "xyz"),
            PixelXyz = r.OptStr(colour, "pixel_xyz"),
            FallbackPixels = r.OptLong(colour, "fallback_pixels") ?? 0,
            GlobalAmbient = r.Value(json, "global_ambient") is { } ga && ga.TryGetValue(out bool g) && g,
            Objects = objects,
            Lights = lights,
            HighlightFraction = json["aov"] is JsonObject aov ? r.OptNumber(aov, "highlight_fraction") ?? 0.1 : 0.1,
            RenderSeconds = json["timings_s"] is JsonObject t ? r.OptNumber(t, "render") ?? 0 : 0,
            Rays = rays is null ? new ManifestRays(0, 0, 0, 0, 0)
                : new ManifestRays(r.OptLong(rays, "primary") ?? 0, r.OptLong(rays, "shadow") ?? 0, r.OptLong(rays, "secondary") ?? 0,
                    r.OptLong(rays, "total") ?? 0, r.OptNumber(rays, "mrays_per_s") ?? 0),
            Threads = r.OptInt(json, "threads") ?? 0,
            Tiles = r.OptInt(json, "tiles") ?? 0,
            Run = json["run"] is JsonObject run ? r.Run(run) : null,
            Files = json["files"] is JsonArray fs ? fs.Select(f => (string?)f ?? "").ToArray() : null,
            ResolvedScene = json["resolved_scene"] is JsonObject resolved ? new ManifestScene(resolved) : null,
            SceneHash = r.OptStr(json, "scene_hash"),
            Crop = json["crop"] is JsonObject crop
                ? new Rendering.PixelRect(r.Int(crop, "x0", "$.crop"), r.Int(crop, "y0", "$.crop"), r.Int(crop, "x1", "$.crop"), r.Int(crop, "y1", "$.crop"))
                : null,
            Sampling = ManifestSampling.Parse(json["sampling"] as JsonObject),
        };
        // Consistent with itself: what the analysis commands compute from these must mean something.
        if (parsed.Width is < 1 or > 32768) throw r.Missing("$.width", "a width of 1 to 32768 pixels");
        if (parsed.Height is < 1 or > 32768) throw r.Missing("$.height", "a height of 1 to 32768 pixels");
        foreach (var (key, weights) in new[] { ("weights_x", parsed.Wx), ("weights_y", parsed.Wy), ("weights_z", parsed.Wz) })
            if (weights.Length != parsed.Grid.Count) throw r.Missing($"$.colour.{key}", $"{parsed.Grid.Count} weights, one per band of {grid}");
        if (!(w.All(double.IsFinite) && w[1] > 0)) throw r.Missing("$.colour.white_xyz", "a white with finite X, Y, Z and Y > 0");
        for (int i = 0; i < objects.Length; i++)
            if (objects[i].Id != i + 1) throw r.Missing($"$.objects[{i}].id", $"id {i + 1} (ids count from 1 in order)");
        return parsed;
    }

    /// <summary>Typed reads of render.json's fields; a missing or mistyped field is bad input naming its JSON path.</summary>
    sealed class Reader(string path)
    {
        public InputException Missing(string at, string what) =>
            new($"{path}: {at}", $"is missing or not {what}", "re-render the scene with this version");

        public JsonValue? Value(JsonObject o, string key) => o[key] as JsonValue;

        public JsonObject Obj(JsonObject o, string key, string at) => o[key] as JsonObject ?? throw Missing($"{at}.{key}", "an object");

        public JsonObject[] Arr(JsonObject o, string key, string at) =>
            (o[key] as JsonArray ?? throw Missing($"{at}.{key}", "an array")).Select((e, i) => e as JsonObject ?? throw Missing($"{at}.{key}[{i}]", "an object")).ToArray();

        public ManifestRun Run(JsonObject o)
        {
            ManifestOverrides? overrides = o["overrides"] is JsonObject v
                ? new ManifestOverrides(OptInt(v, "width"), OptInt(v, "height"), OptStr(v, "bands"), OptStr(v, "wave"), OptInt(v, "spp"), OptStr(v, "rgb"),
                    OptStr(v, "integration"), OptStr(v, "formats"), OptStr(v, "exr_compression"),
                    v["models"] is JsonArray ms ? ms.Select(m => m is JsonValue mv && mv.TryGetValue(out string? d) ? d : null).OfType<string>().ToArray() : [])
                : null;
            return new ManifestRun
            {
                CommandLine = OptStr(o, "command_line"),
                MergedShards = OptInt(o, "merged_shards"),
                SweepJob = OptStr(o, "sweep_job"),
                LoadSeconds = OptNumber(o, "load_s"),
                BuildSeconds = OptNumber(o, "build_s"),
                Triangles = OptInt(o, "triangles"),
                DegenerateTrianglesSkipped = OptInt(o, "degenerate_triangles_skipped"),
                MinRayWeight = OptNumber(o, "min_ray_weight"),
                RayBudget = OptInt(o, "ray_budget"),
                RaysPrunedByWeight = OptLong(o, "rays_pruned_by_weight"),
                CameraRaysOverBudget = OptLong(o, "camera_rays_over_budget"),
                Shard = OptStr(o, "shard"),
                LightTransferSeconds = OptNumber(o, "light_transfer_s"),
                HasOverrides = o.ContainsKey("overrides"),
                Overrides = overrides,
                Relit = o["relit"] is JsonObject relit ? Relit(relit) : null,
                WriteSeconds = OptNumber(o, "write_s"),
            };
        }

        ManifestRelit Relit(JsonObject o)
        {
            var at = "$.run.relit";
            RelightMetrics? metrics = null;
            if (o["metrics"] is JsonObject m)
                metrics = new RelightMetrics(OptStr(m, "white") ?? "",
                    Arr(m, "lights", $"{at}.metrics").Select(l => new RelightLightMetrics(OptStr(l, "light") ?? "", OptStr(l, "spectrum"),
                        OptNumber(l, "Ra"), OptNumber(l, "Rf"), OptNumber(l, "cct_K"))).ToArray(),
                    Arr(m, "objects", $"{at}.metrics").Select(x => new RelightObjectMetrics(OptStr(x, "object") ?? "", OptInt(x, "pixels") ?? 0,
                        OptNumber(x, "mean_dE00") ?? 0, OptNumber(x, "max_dE00") ?? 0)).ToArray());
            return new ManifestRelit
            {
                From = OptStr(o, "from") ?? "",
                FromCreatedUtc = OptStr(o, "from_created_utc") ?? "",
                Method = OptStr(o, "method") ?? "",
                Changes = o["changes"] is JsonArray ? Arr(o, "changes", at).Select(c => new ManifestLightChange(OptStr(c, "light") ?? "",
                    OptStr(c, "spectrum"), OptNumber(c, "intensity"))).ToArray() : [],
                White = OptStr(o, "white"),
                ComputeSeconds = OptNumber(o, "compute_s") ?? 0,
                Metrics = metrics,
                CopiedFiles = o["copied_files"] is JsonArray cf ? cf.Select(f => f is JsonValue fv && fv.TryGetValue(out string? s) ? s : "").ToArray() : null,
            };
        }

        public string Str(JsonObject o, string key, string at) => OptStr(o, key) ?? throw Missing($"{at}.{key}", "a string");

        public string? OptStr(JsonObject o, string key) => Value(o, key) is { } v && v.TryGetValue(out string? s) ? s : null;

        public int Int(JsonObject o, string key, string at) => OptInt(o, key) ?? throw Missing($"{at}.{key}", "an integer");

        public int? OptInt(JsonObject o, string key) => OptNumber(o, key) is { } d && d == Math.Floor(d) && Math.Abs(d) <= int.MaxValue ? (int)d : null;

        public long? OptLong(JsonObject o, string key) => OptNumber(o, key) is { } d && d == Math.Floor(d) ? (long)d : null;

        public double? OptNumber(JsonObject o, string key) => Value(o, key) is { } v && v.TryGetValue(out double d) ? d : null;

        public double[]? OptNumbers(JsonObject o, string key, string at) => o[key] is null ? null : Numbers(o, key, at);

        public double[] Numbers(JsonObject o, string key, string at)
        {
            var a = o[key] as JsonArray ?? throw Missing($"{at}.{key}", "an array of numbers");
            var r = new double[a.Count];
            for (int i = 0; i < r.Length; i++)
                r[i] = a[i] is JsonValue v && v.TryGetValue(out double d) ? d : throw Missing($"{at}.{key}[{i}]", "a number");
            return r;
        }
    }

    /// <summary>"yyyy-MM-ddTHH:mm:ssZ" of now, as render.json records it.</summary>
    public static string Now() => DateTime.UtcNow.ToString("yyyy-MM-ddTHH:mm:ssZ", CultureInfo.InvariantCulture);
}
