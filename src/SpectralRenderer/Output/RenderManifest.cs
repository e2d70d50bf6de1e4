using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

/// <summary>An object of the scene as render.json lists it: its id in object-id.png (1-based, 0 = background).</summary>
/// <param name="FlatNormal">The world normal of a flat shape (quad, plane), so analysis can tell a chart lit head-on; null
/// otherwise.</param>
public sealed record ManifestObject(int Id, string Name, string Material, string? Reflectance, double[]? FlatNormal = null);

/// <summary>A light as render.json lists it: k in mask-lit-&lt;k&gt;.png, its kind ("point", "spot", "directional") and spectrum
/// name.</summary>
/// <param name="Intensity">The scene's intensity, the factor on <paramref name="Spd"/>; <paramref name="IntensityUnit"/> says what it is
/// in.</param>
/// <param name="Position">Point and spot lights; <paramref name="Direction"/> the direction spot and directional lights shine
/// towards.</param>
/// <param name="Attenuation">[c0, c1, c2] of d = 1/(c0 + c1·r + c2·r²); null for directional lights (no attenuation).</param>
/// <param name="Photometric">The photometric value the scene gave instead of an intensity (physical radiometry), or null.</param>
public sealed record ManifestLight(int Index, string Name, string Kind, string? Spectrum, double Intensity = 1,
    string? IntensityUnit = null,
    bool HasAmbient =
        false, double[]? Position = null, double[]? Direction = null, double[]? Attenuation = null, TabulatedSpectrum? Spd = null,
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
    /// <summary>The sampler and how exact the render is (per-pixel standard errors, adaptive sampling); null: the independent sampler, no
    /// statistics.</summary>
    public ManifestSampling? Sampling { get; init; }

    /// <summary>
    /// A whole render's manifest, for the commands that read the film whole (analysis, camera, viewer, relight); a crop or
    /// shard (<see cref="Crop"/>) is refused naming what it is and how to get the whole render.
    /// </summary>
    public RenderManifest Whole(string dir)
    {
        if (Crop is not { } c) return this;
        throw new InputException(dir,
            $"holds a crop of the film (pixels {c.X0}–{c.X1 - 1} × {c.Y0}–{c.Y1 - 1} of {Width}×{Height}, from --crop "
                + $"or --shard), not a whole render",
            "assemble the shards with 'spectral merge SHARD_DIR… -o OUT' first, or render without --crop");
    }

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
                    ["note"] = "value = radiometric_scale × luminous_per_unit_scale (683 lm/W · ∫V(λ)·spectrum dλ, CIE 1924 V) × the "
                        + "light's solid angle (4π sr for a point light's lm, the spot's ∫c_spot dΩ; 1 for cd and lx)",
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
                ["reference_white_spd"] =
                    new JsonObject { ["wavelengths_nm"] = Arr(ReferenceWhite.Wavelengths), ["values"] = Arr(ReferenceWhite.Values) },
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
        Put("integrator", run.Integrator, run.Integrator is not null);
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
        Put("imported", run.Imported?.DeepClone(), run.Imported is not null);
        return o;
    }

    static JsonObject OverridesJson(ManifestOverrides v)
    {
        var o = Overrides(v);
        if (v.Exposure is not null) o["exposure"] = v.Exposure;   // only when given (--exposure): earlier folders' bytes kept
        return o;
    }

    static JsonObject Overrides(ManifestOverrides v) => new()
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

    /// <summary>What a damaged render.json's message suggests.</summary>
    const string Rerender = "render.json is not as a render writes it: render the folder again with this version";

    /// <summary>
    /// The render.json of folder <paramref name="dir"/>, validated (<see cref="Parse"/>) and its files checked on disk: none
    /// it lists leads out of the folder through a symbolic link. A missing or broken one is bad input (file, JSON path, hint).
    /// </summary>
    public static RenderManifest Read(string dir)
    {
        var path = Path.Combine(dir, FileName);
        if (!File.Exists(path)) throw new InputException(dir, $"has no {FileName}", "give the -o folder of a 'spectral render' run");
        var manifest = Parse(JsonFields.ParseFile(path, FileName, Rerender), path);
        var fields = new JsonFields(path, Rerender);
        for (int i = 0; i < (manifest.Files?.Count ?? 0); i++) fields.StaysInside(dir, manifest.Files![i], $"$.files[{i}]");
        return manifest;
    }

    /// <summary>
    /// A manifest from render.json's JSON; <paramref name="path"/> names it in errors. Nothing in it is trusted: every
    /// field is typed and ranged (<see cref="JsonFields"/>), the arrays sized by the band grid, the crop inside the film,
    /// the files' names inside the folder, and the object ids in order.
    /// </summary>
    public static RenderManifest Parse(JsonObject json, string path)
    {
        var r = new JsonFields(path, Rerender);
        int width = r.Int(json, "width", "$", 1, 32768), height = r.Int(json, "height", "$", 1, 32768);
        var bands = r.Object(json, "bands", "$");
        string grid = r.String(bands, "grid", "$.bands");
        var parsedGrid = BandGrid.Parse(grid, $"{path}: $.bands.grid");
        int n = parsedGrid.Count;
        if (r.OptInt(bands, "count", "$.bands", 1, int.MaxValue) is { } count && count != n)
            throw r.Bad("$.bands.count", $"is {count}, but the grid {grid} has {n} bands");
        var colour = r.Object(json, "colour", "$");
        var spd = r.Object(colour, "reference_white_spd", "$.colour");
        var w = r.Numbers(colour, "white_xyz", "$.colour", 3);
        if (!(w[1] > 0)) throw r.Bad("$.colour.white_xyz[1]", "is not positive: the white must have Y > 0");
        var objects = r.Array(json, "objects", "$", max: 65535).Select((node, i) =>
        {
            string at = $"$.objects[{i}]";
            var o = r.Object(node, at);
            int id = r.Int(o, "id", at, 1, 65535);
            if (id != i + 1) throw r.Bad($"{at}.id", $"is {id}, expected {i + 1} (ids count from 1 in order)");
            return new ManifestObject(id, r.String(o, "name", at), r.String(o, "material", at), r.OptString(o, "reflectance", at),
                r.OptNumbers(o, "flat_normal", at, 3));
        }).ToArray();
        var lights = r.Array(json, "lights", "$", max: 1 << 16).Select((node, i) =>
        {
            string at = $"$.lights[{i}]";
            var l = r.Object(node, at);
            string name = r.OptString(l, "name", at) ?? $"light {i}";
            TabulatedSpectrum? lightSpd = null;
            if (r.OptObject(l, "spd", at) is { } so)
            {
                var (lw, lv) = Table(r, so, $"{at}.spd");
                lightSpd = new TabulatedSpectrum(name, lw, lv, Extrapolation.Clamp);
            }
            ManifestPhotometry? photometric = null;
            if (r.OptObject(l, "photometric", at) is { } po)
            {
                string pat = $"{at}.photometric";
                photometric =
                    new ManifestPhotometry(r.String(po, "quantity", pat), r.OptNumber(po, "value", pat) ?? 0, r.String(po, "unit", pat),
                    r.OptNumber(po, "radiometric_scale", pat) ?? 0, r.OptNumber(po, "luminous_per_unit_scale", pat) ?? 0);
            }
            // Light k's files are named by its index (mask-lit-k.png; lights/ ids): a render writes them in order from 0.
            int index = r.OptInt(l, "index", at, 0, int.MaxValue) ?? i;
            if (index != i) throw r.Bad($"{at}.index", $"is {index}, expected {i} (light indices count from 0 in order)");
            return new ManifestLight(index, name, r.OptString(l, "kind", at) ?? "point",
                r.OptString(l, "spectrum", at), r.OptNumber(l, "intensity", at) ?? 1, r.OptString(l, "intensity_unit", at),
                r.OptBool(l, "has_ambient", at) ?? false, r.OptNumbers(l, "position", at, 3), r.OptNumbers(l, "direction", at, 3),
                r.OptNumbers(l, "attenuation", at, 3), lightSpd, photometric);
        }).ToArray();
        var radiometry = r.OptObject(json, "radiometry", "$");
        var rays = r.OptObject(json, "rays", "$");
        var (spdWavelengths, spdValues) = Table(r, spd, "$.colour.reference_white_spd");
        var aov = r.OptObject(json, "aov", "$");
        var timings = r.OptObject(json, "timings_s", "$");
        string[]? files = null;
        if (r.OptArray(json, "files", "$") is { } fs)
        {
            files = fs.Select((f, i) => r.RelativeName(f, $"$.files[{i}]")).ToArray();
            var seen = new HashSet<string>(StringComparer.Ordinal);
            for (int i = 0; i < files.Length; i++)
                if (!seen.Add(files[i])) throw r.Bad($"$.files[{i}]", $"lists {MessageText.Quote(files[i], 60)} a second time");
        }
        Rendering.PixelRect? crop = null;
        if (r.OptObject(json, "crop", "$") is { } c)
        {
            int x0 = r.Int(c, "x0", "$.crop", 0, width - 1), y0 = r.Int(c, "y0", "$.crop", 0, height - 1);
            crop = new Rendering.PixelRect(x0, y0, r.Int(c, "x1", "$.crop", x0 + 1, width), r.Int(c, "y1", "$.crop", y0 + 1, height));
        }
        const double Huge = 1e300;
        return new RenderManifest
        {
            Tool = r.OptString(json, "tool", "$") ?? "spectral",
            Version = r.OptString(json, "version", "$"),
            Build = r.OptString(json, "build", "$"),
            Scene = r.OptString(json, "scene", "$") ?? "",
            CreatedUtc = r.OptString(json, "created_utc", "$") ?? "",
            Width = width,
            Height = height,
            SamplesPerPixel = r.OptInt(json, "spp", "$", 1, 1 << 20) ?? 1,
            Grid = parsedGrid,
            BandImageScale = (float)(r.OptNumber(bands, "band_image_scale", "$.bands", 0, float.MaxValue) ?? 0),
            Integration = BandIntegrations.Parse(r.String(colour, "integration", "$.colour"), $"{path}: $.colour.integration"),
            ObserverDegrees = r.Int(colour, "observer", "$.colour", 2, 10) is var deg && deg is 2 or 10 ? deg
                : throw r.Bad("$.colour.observer", $"is {deg}, expected 2 or 10 (the CIE 1931 or 1964 observer)"),
            ReferenceWhite = new TabulatedSpectrum(r.OptString(colour, "reference_white", "$.colour") ?? "white",
                spdWavelengths, spdValues, Extrapolation.Clamp),
            Kappa = r.OptNumber(colour, "kappa", "$.colour", 0, Huge) ?? 0,
            White = new Xyz(w[0], w[1], w[2]),
            Wx = r.Numbers(colour, "weights_x", "$.colour", n),
            Wy = r.Numbers(colour, "weights_y", "$.colour", n),
            Wz = r.Numbers(colour, "weights_z", "$.colour", n),
            Rgb = r.OptString(colour, "rgb", "$.colour") ?? "srgb",
            Exposure = r.OptNumber(colour, "exposure", "$.colour", 0, Huge) ?? 1,
            Adapt = r.OptBool(colour, "adapt", "$.colour") ?? false,
            ExposureMode = r.OptString(colour, "exposure_mode", "$.colour") ?? "fixed",
            Gamut = r.OptString(colour, "gamut", "$.colour") ?? "clip",
            Radiometry = radiometry is null ? "paper" : r.OptString(radiometry, "mode", "$.radiometry") ?? "paper",
            BandUnit = radiometry is null ? null : r.OptString(radiometry, "band_values", "$.radiometry"),
            XyzUnit = radiometry is null ? null : r.OptString(radiometry, "xyz", "$.radiometry"),
            PixelXyz = r.OptString(colour, "pixel_xyz", "$.colour"),
            FallbackPixels = r.OptLong(colour, "fallback_pixels", "$.colour", 0, (long)width * height) ?? 0,
            GlobalAmbient = r.OptBool(json, "global_ambient", "$") ?? false,
            Objects = objects,
            Lights = lights,
            HighlightFraction = aov is null ? 0.1 : r.OptNumber(aov, "highlight_fraction", "$.aov", 0, 1) ?? 0.1,
            RenderSeconds = timings is null ? 0 : r.OptNumber(timings, "render", "$.timings_s", 0, Huge) ?? 0,
            Rays = rays is null ? new ManifestRays(0, 0, 0, 0, 0)
                : new ManifestRays(r.OptLong(rays, "primary", "$.rays", 0) ?? 0, r.OptLong(rays, "shadow", "$.rays", 0) ?? 0,
                    r.OptLong(rays, "secondary", "$.rays", 0) ?? 0, r.OptLong(rays, "total", "$.rays", 0) ?? 0,
                    r.OptNumber(rays, "mrays_per_s", "$.rays", 0, Huge) ?? 0),
            Threads = r.OptInt(json, "threads", "$", 0) ?? 0,
            Tiles = r.OptInt(json, "tiles", "$", 0) ?? 0,
            Run = r.OptObject(json, "run", "$") is { } run ? ReadRun(r, run) : null,
            Files = files,
            ResolvedScene = r.OptObject(json, "resolved_scene", "$") is { } resolved ? new ManifestScene(resolved) : null,
            SceneHash = r.OptString(json, "scene_hash", "$"),
            Crop = crop,
            Sampling = ManifestSampling.Parse(r.OptObject(json, "sampling", "$")),
        };
    }

    /// <summary>A tabulated spectrum's wavelengths_nm (ascending, 1–100000 nm) and as many finite values.</summary>
    static (double[] Wavelengths, double[] Values) Table(JsonFields r, JsonObject o, string at)
    {
        var wl = r.Numbers(o, "wavelengths_nm", at, null, 1, 100_000);
        if (wl.Length < 1) throw r.Bad($"{at}.wavelengths_nm", "is empty");
        for (int i = 1; i < wl.Length; i++)
            if (!(wl[i] > wl[i - 1]))
                throw r.Bad($"{at}.wavelengths_nm[{i}]", $"is {wl[i]}, not above the one before (wavelengths ascend)");
        return (wl, r.Numbers(o, "values", at, wl.Length));
    }

    static ManifestRun ReadRun(JsonFields r, JsonObject o)
    {
        const string at = "$.run";
        ManifestOverrides? overrides = null;
        if (r.OptObject(o, "overrides", at) is { } v)
        {
            const string ov = "$.run.overrides";
            var models = r.OptArray(v, "models", ov) is { } ms ? ms.Select((m, i) => r.String(m, $"{ov}.models[{i}]")).ToArray() : [];
            overrides =
                new ManifestOverrides(r.OptInt(v, "width", ov, 1, 32768), r.OptInt(v, "height", ov, 1, 32768), r.OptString(v, "bands", ov),
                r.OptString(v, "wave", ov), r.OptInt(v, "spp", ov, 1, 1 << 20), r.OptString(v, "rgb", ov),
                    r.OptString(v, "integration", ov),
                r.OptString(v, "formats", ov), r.OptString(v, "exr_compression", ov), models, r.OptString(v, "exposure", ov));
        }
        return new ManifestRun
        {
            CommandLine = r.OptString(o, "command_line", at),
            Integrator = r.OptString(o, "integrator", at),
            MergedShards = r.OptInt(o, "merged_shards", at, 1),
            SweepJob = r.OptString(o, "sweep_job", at),
            LoadSeconds = r.OptNumber(o, "load_s", at, 0),
            BuildSeconds = r.OptNumber(o, "build_s", at, 0),
            Triangles = r.OptInt(o, "triangles", at, 0),
            DegenerateTrianglesSkipped = r.OptInt(o, "degenerate_triangles_skipped", at, 0),
            MinRayWeight = r.OptNumber(o, "min_ray_weight", at, 0),
            RayBudget = r.OptInt(o, "ray_budget", at, 0),
            RaysPrunedByWeight = r.OptLong(o, "rays_pruned_by_weight", at, 0),
            CameraRaysOverBudget = r.OptLong(o, "camera_rays_over_budget", at, 0),
            Shard = r.OptString(o, "shard", at),
            LightTransferSeconds = r.OptNumber(o, "light_transfer_s", at, 0),
            HasOverrides = o.ContainsKey("overrides"),
            Overrides = overrides,
            Relit = r.OptObject(o, "relit", at) is { } relit ? Relit(r, relit) : null,
            WriteSeconds = r.OptNumber(o, "write_s", at, 0),
            Imported = r.OptObject(o, "imported", at)?.DeepClone().AsObject(),
        };
    }

    static ManifestRelit Relit(JsonFields r, JsonObject o)
    {
        const string at = "$.run.relit";
        RelightMetrics? metrics = null;
        if (r.OptObject(o, "metrics", at) is { } m)
        {
            const string mt = "$.run.relit.metrics";
            metrics = new RelightMetrics(r.OptString(m, "white", mt) ?? "",
                r.Array(m, "lights", mt).Select((node, i) =>
                {
                    string a = $"{mt}.lights[{i}]";
                    var l = r.Object(node, a);
                    return new RelightLightMetrics(r.OptString(l, "light", a) ?? "", r.OptString(l, "spectrum", a), r.OptNumber(l, "Ra", a),
                        r.OptNumber(l, "Rf", a), r.OptNumber(l, "cct_K", a));
                }).ToArray(),
                r.Array(m, "objects", mt).Select((node, i) =>
                {
                    string a = $"{mt}.objects[{i}]";
                    var x = r.Object(node, a);
                    return new RelightObjectMetrics(r.OptString(x, "object", a) ?? "", r.OptInt(x, "pixels", a, 0) ?? 0,
                        r.OptNumber(x, "mean_dE00", a, 0) ?? 0, r.OptNumber(x, "max_dE00", a, 0) ?? 0);
                }).ToArray());
        }
        return new ManifestRelit
        {
            From = r.OptString(o, "from", at) ?? "",
            FromCreatedUtc = r.OptString(o, "from_created_utc", at) ?? "",
            Method = r.OptString(o, "method", at) ?? "",
            Changes = r.OptArray(o, "changes", at) is { } changes ? changes.Select((node, i) =>
            {
                string a = $"{at}.changes[{i}]";
                var c = r.Object(node, a);
                return new ManifestLightChange(r.OptString(c, "light", a) ?? "", r.OptString(c, "spectrum", a),
                    r.OptNumber(c, "intensity", a));
            }).ToArray() : [],
            White = r.OptString(o, "white", at),
            ComputeSeconds = r.OptNumber(o, "compute_s", at, 0) ?? 0,
            Metrics = metrics,
            CopiedFiles = r.OptArray(o, "copied_files", at) is { } cf
                ? cf.Select((f, i) => r.RelativeName(f, $"{at}.copied_files[{i}]")).ToArray()
                : null,
        };
    }

    /// <summary>"yyyy-MM-ddTHH:mm:ssZ" of now, as render.json records it.</summary>
    public static string Now() => DateTime.UtcNow.ToString("yyyy-MM-ddTHH:mm:ssZ", CultureInfo.InvariantCulture);
}
