using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Relighting;

/// <summary>
/// The spectral viewer of a render folder: <c>viewer.html</c> (a self-contained page: no network reference, its
/// script inline) and <c>viewer-data.js</c> beside it (the data, so the page also opens from file://). The data are
/// the band grid and the render's eq. 3 weights, the object seen per pixel with its ground-truth reflectance, and
/// either the per-light transfer (lights/: factors and each component's band values and XYZ, plus the same under
/// candidate lights — computed from the render's term tables with each light given that spectrum, so the page's colour
/// is the render's exact colour — with their CIE 13.3 Ra and CIE 224 Rf) or, without it, the spectral cube.
/// </summary>
public static class SpectralViewer
{
    /// <summary>Lights offered in the page's light picker besides each light's own spectrum.</summary>
    public static readonly string[] Presets =
    [
        "D65", "A", "D50", "E", "FL2", "FL11", "led-blue", "led-green", "led-rgb", "led-yag",
        "blackbody:2700", "blackbody:3000", "blackbody:4000", "blackbody:5000", "daylight:5000", "daylight:6504", "daylight:7500",
    ];

    public static IReadOnlyList<string> Write(string dir)
    {
        if (!Directory.Exists(dir)) throw new InputException(dir, "no such render folder", "give the -o folder of a 'spectral render' run");
        var manifest = RenderManifest.Read(dir).Whole(dir);
        var grid = manifest.Grid;
        var scheme = manifest.Integration;
        var observer = manifest.ObserverDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931;
        var cm = new Colorimeter(grid, observer, manifest.ReferenceWhite, scheme);
        int width = manifest.Width, height = manifest.Height, n = width * height;
        static JsonArray Nums(IEnumerable<double> v) => new(v.Select(x => (JsonNode)JsonValue.Create(x)).ToArray());

        var data = new JsonObject
        {
            ["title"] = Path.GetFileName(Path.GetFullPath(dir).TrimEnd(Path.DirectorySeparatorChar)),
            ["width"] = width,
            ["height"] = height,
            ["bands"] = grid.Count,
            ["edges"] = new JsonArray(grid.Edges().Select(e => (JsonNode)JsonValue.Create(e)).ToArray()),
            ["centres"] = new JsonArray(Enumerable.Range(0, grid.Count).Select(b => (JsonNode)JsonValue.Create(grid.Centre(b))).ToArray()),
            ["wx"] = Nums(manifest.Wx),
            ["wy"] = Nums(manifest.Wy),
            ["wz"] = Nums(manifest.Wz),
            ["white"] = Nums([manifest.White.X, manifest.White.Y, manifest.White.Z]),
            // The page opens at the render's own exposure (render.json $.colour.exposure: given, or the one auto chose).
            ["exposure"] = manifest.Exposure,
        };

        var lightsJson = Path.Combine(dir, TransferFormat.Folder, "lights.json");
        // Only a transfer of eq. 2's terms (CameraRoute.Terms: Whitted's) has the components the page's sliders recombine;
        // of any other (a path render's) the page shows its cube.
        JsonObject? transfer = File.Exists(lightsJson) && TermsIn(dir) ? JsonNode.Parse(File.ReadAllText(lightsJson))!.AsObject() : null;
        // Per-light outputs the page does not recombine (a path render's lights/) are still there for `spectral relight`.
        data["other_transfer"] = transfer is null && File.Exists(lightsJson);
        // Read through the transfer's own reader first: a lights.json that is not as a render writes it is one line
        // naming its field (our files are never trusted when read back), before the page reads it as plain JSON.
        Relighter.Source? src = null;
        TransferComponent[]? components = null;
        if (transfer is not null)
        {
            src = Relighter.Open(dir);
            components = ((ITermRoute)TransferFiles.Read(dir, Relighter.ChangedScene(src, [], null))).Components;
        }
        // A textured term's entries are texel samples (issue 26), which the page's F · P sum cannot take.
        if (transfer?["components"] is JsonArray tc && tc.Any(c => c?["texels"] is not null))
            throw new InputException(lightsJson,
                "holds textured terms (texels.npy): the viewer relights per-pixel factors × per-term spectra only",
                "relight textured renders with 'spectral relight', or render without the lights format to view the cube");
        var objects = new JsonArray();
        foreach (var o in manifest.Objects)
        {
            var mat = o.Material;
            JsonNode? reflectance = transfer?["materials"]?.AsArray()
                .FirstOrDefault(m => (string?)m!["name"] == mat && m["diffuse_spectrum"] is not null)?["diffuse_band_values"]?.DeepClone();
            if (reflectance is null && o.Reflectance is { } name)
            {
                try { reflectance = Numbers(cm.Project(SpectrumLibrary.Resolve(name))); }
                catch (InputException) { /* a scene-named or inline spectrum: no ground truth in the page */ }
            }
            objects.Add((JsonNode)new JsonObject { ["name"] = o.Name, ["material"] = mat, ["reflectance"] = reflectance });
        }
        data["objects"] = objects;

        // The photometry product: luminance (cd/m²) and illuminance (lx) maps as views, on photometry.exr's false-colour scales.
        var binary = new Dictionary<string, byte[]>();
        JsonObject? photometry = null;
        var photometryExr = Path.Combine(dir, PhotometryProduct.Exr);
        if (File.Exists(photometryExr))
        {
            var (window, planes) = ExrChannelWriter.Read(photometryExr);
            if (window != new ExrChannelWriter.PixelWindow(0, 0, width, height)
                || !planes.ContainsKey("luminance") || !planes.ContainsKey("illuminance"))
                throw new InputException(photometryExr, $"does not hold luminance and illuminance of the whole {width}×{height} film",
                    "render the folder again with --formats …,photometry");
            var probe = new Rendering.Illumination.Illuminance(Relighter.ChangedScene(Relighter.Open(dir), [], null), null);
            var scales = new JsonObject();
            foreach (var (q, unit) in new[] { ("luminance", "cd/m²"), ("illuminance", "lx") })
            {
                var scale = FalseColour.For(planes[q], char.ToUpperInvariant(q[0]) + q[1..], unit);
                scales[q] = new JsonObject
                {
                    ["unit"] = unit,
                    ["low"] = scale.Low,
                    ["high"] = scale.High,
                    ["log"] = scale.Log,
                    ["legend"] = scale.Legend($"{q}.png's scale; values: the page's (relit) values"),
                };
                binary[q] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(planes[q].AsSpan()).ToArray();
            }
            photometry = new JsonObject
            {
                ["scales"] = scales,
                // Luminance of the relit pixel: K_m/κ · Y of its exact colour (ȳ = V), else Σ_b L_b K_m∫_b V dλ.
                ["y_to_luminance"] = probe.YToLuminance,
                ["band_v"] = Numbers(probe.BandV),
            };
            data["photometry"] = photometry;
        }

        var ids = new ushort[n];
        // Large arrays go into the data file as base64 strings, written in pieces (no one giant JSON string).
        if (transfer is not null && src is not null && components is not null)
        {
            // Candidate lights: P of every component that follows a light, per unit intensity, from the term tables of
            // the render's scene with every light given that spectrum (so the page's colour is exact, not eq. 3 on bands).
            var resolvedLights = manifest.ResolvedScene?.Lights;
            var comps = transfer["components"]!.AsArray();
            var presets = new JsonArray();
            var lights = new JsonArray();
            JsonArray PresetComponents(Func<int, float[]?> p) => new(Enumerable.Range(0, comps.Count)
                .Select(c => p(c) is { } v ? (JsonNode)Numbers(v.Select(x => (double)x)) : null).ToArray());
            void Add(string name, JsonArray values, TabulatedSpectrum? spectrum)
            {
                double? ra = null, rf = null;
                if (spectrum is not null)
                {
                    try { ra = ColorRenderingIndex.Of(spectrum).Ra; rf = ColorFidelityIndex.Of(spectrum).Rf; }
                    catch (Exception e) when (e is ArgumentException or InvalidOperationException) { }
                }
                presets.Add((JsonNode)new JsonObject { ["name"] = name, ["components"] = values, ["ra"] = ra, ["rf"] = rf });
            }
            var tl = transfer["lights"]!.AsArray();
            // Photometry (a render with photometry.exr): each light's luminous value K_m∫V·I dλ per unit intensity under
            // each preset, so the page's illuminance follows the lights (Illuminance.LightFactorMaps).
            // The scene with its meshes (the shadow rays need every triangle).
            var sourceScene = photometry is not null
                ? Relighter.ChangedScene(src with { Overrides = src.Overrides with { LoadMeshes = true } }, [], null) : null;
            bool relitPhotometry = sourceScene is not null && sourceScene.Lights.Count == tl.Count;
            var luminous0 = relitPhotometry ? new Rendering.Illumination.Illuminance(sourceScene!, null) : null;
            var presetLuminous = new List<JsonArray?>();
            for (int k = 0; k < tl.Count; k++)
            {
                var l = tl[k]!;
                // The resolved scale render.json lists (a photometric light's radiometric scale), else the scene's intensity.
                var listed = k < manifest.Lights.Count ? manifest.Lights[k] : null;
                double intensity = listed?.Intensity ?? (resolvedLights is { } rl && k < rl.Count ? rl[k].Intensity : null) ?? 1;
                string spectrumName = (string?)l["spectrum"] ?? $"light {k}";
                string preset = $"render: {spectrumName} ({l["name"]})";
                TabulatedSpectrum? s = null;
                try { s = SpectrumLibrary.Resolve(spectrumName); } catch (InputException) { }
                int kk = k;
                Add(preset, PresetComponents(c => components[c].FollowsLight && components[c].Light == kk && intensity > 0
                    ? comps[c]!["band_values"]!.AsArray().Concat(comps[c]!["xyz"]!.AsArray()).Select(v => (float)((double)v! / intensity))
                        .ToArray() : null),
                        s);
                presetLuminous.Add(luminous0 is null ? null : new JsonArray(Enumerable.Range(0, tl.Count)
                    .Select(j => j == kk && intensity > 0 ? (JsonNode)JsonValue.Create(luminous0.LuminousOf(kk) / intensity) : null)
                    .ToArray()));
                var ph = listed?.Photometric;
                lights.Add((JsonNode)new JsonObject
                {
                    ["name"] = (string?)l["name"],
                    ["preset"] = preset,
                    ["intensity"] = intensity,
                    // Photometric units shown beside the slider: the value per unit of the scale (cd, lm, lx, cd/m²).
                    ["photometric"] = ph is null || !(ph.RadiometricScale > 0) ? null
                        : new JsonObject
                        {
                            ["quantity"] = ph.Quantity,
                            ["unit"] = ph.Unit,
                            ["per_intensity"] = ph.Value / ph.RadiometricScale
                        },
                });
            }
            foreach (var name in Presets)
            {
                var scene = Relighter.ChangedScene(src, src.LightNames.Select(l => new LightChange(l, name, 1)).ToList(), null);
                var tables = new Rendering.Terms.TermTables(scene);
                var p = new float[scene.PaddedBands];
                Add(name, PresetComponents(c =>
                {
                    if (!components[c].FollowsLight) return null;
                    components[c].BandValues(tables, p);
                    return p.AsSpan(0, grid.Count + 3).ToArray();
                }), SpectrumLibrary.Resolve(name));
                var luminous = relitPhotometry ? new Rendering.Illumination.Illuminance(scene, null) : null;
                presetLuminous.Add(luminous is null ? null : Numbers(Enumerable.Range(0, tl.Count).Select(luminous.LuminousOf)));
            }
            if (relitPhotometry)
            {
                // K_m∫V·I dλ of each preset per unit intensity (null where a render's own spectrum is not that light's), the
                // render's own, and each light's lx per unit of it at every pixel's surface.
                for (int q = 0; q < presets.Count; q++) presets[q]!["luminous"] = presetLuminous[q];
                photometry!["luminous"] = Numbers(Enumerable.Range(0, tl.Count).Select(luminous0!.LuminousOf));
                var factors = new Rendering.Illumination.Illuminance(sourceScene!, new Rendering.SceneGeometry(sourceScene!))
                    .LightFactorMaps(0);
                var planes = factors.SelectMany(m => m).ToArray();
                binary["light_factors"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(planes.AsSpan()).ToArray();
            }
            data["lights"] = lights;
            data["presets"] = presets;
            data["components"] = new JsonArray(comps.Select(c => (JsonNode)new JsonObject
            {
                ["light"] = (int)c!["light"]!,
                ["follows_light"] = (bool)c["follows_light"]!,
                ["key"] = (string?)c["key"],
                ["offset"] = (int)c["offset"]!,
                ["count"] = (int)c["count"]!,
                ["band_values"] = c["band_values"]!.DeepClone(),
                ["xyz"] = c["xyz"]!.DeepClone(),
            }).ToArray());
            var (_, f) = ReadNpy(Path.Combine(dir, TransferFormat.Folder, "factors.npy"));
            using (var ps = File.OpenRead(Path.Combine(dir, TransferFormat.Folder, "pixels.npy")))
                binary["pixels"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(NpyInt32.Read(ps).Data.AsSpan()).ToArray();
            binary["factors"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(f.AsSpan()).ToArray();
            var (_, idp) = ReadNpy(Path.Combine(dir, TransferFormat.Folder, "ids.npy"));
            for (int i = 0; i < n; i++) ids[i] = (ushort)idp[i];
            var fallback = Enumerable.Range(0, n).Where(i => idp[2 * n + i] != 0).ToArray();
            binary["fallback"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(fallback.AsSpan()).ToArray();
        }
        else
        {
            var image = SpectralFiles.Read(dir, grid);
            binary["cube"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(image.Data.AsSpan()).ToArray();
            var idPath = Path.Combine(dir, "object-id.png");
            if (File.Exists(idPath))
            {
                var png = PngReader.Read(idPath);
                for (int i = 0; i < n; i++) ids[i] = png.Samples[i * png.Channels];
            }
        }
        binary["ids"] = System.Runtime.InteropServices.MemoryMarshal.AsBytes(ids.AsSpan()).ToArray();

        AtomicFile.Write(Path.Combine(dir, "viewer-data.js"), stream =>
        {
            using var w = new StreamWriter(stream, new UTF8Encoding(false), 1 << 16, leaveOpen: true);
            w.Write("// The data of viewer.html, written by `spectral view` (see its help). Arrays: little-endian, "
                + "base64.\nwindow.SPECTRAL_VIEWER = ");
            w.Write(data.ToJsonString());
            w.Write(";\n");
            foreach (var (name, bytes) in binary)
            {
                w.Write($"window.SPECTRAL_VIEWER.{name} = \"");
                const int Piece = 3 << 16;
                for (int at = 0; at < bytes.Length; at += Piece)
                    w.Write(Convert.ToBase64String(bytes, at, Math.Min(Piece, bytes.Length - at)));
                w.Write("\";\n");
            }
        });
        using var page = typeof(SpectralViewer).Assembly.GetManifestResourceStream("SpectralViewer.html")!;
        using var reader = new StreamReader(page);
        AtomicFile.WriteAllText(Path.Combine(dir, "viewer.html"), reader.ReadToEnd());
        return ["viewer.html", "viewer-data.js"];
    }

    static JsonArray Numbers(IEnumerable<double> v) => new(v.Select(x => (JsonNode)JsonValue.Create(x)).ToArray());

    /// <summary>Whether <paramref name="dir"/>'s lights/ hold eq. 2's terms (a format whose camera route is Terms).</summary>
    static bool TermsIn(string dir)
    {
        try { return TransferFiles.FormatOf(dir)?.Route == CameraRoute.Terms; }
        catch (InputException) { return false; }
    }

    static (int[], float[]) ReadNpy(string path)
    {
        using var s = File.OpenRead(path);
        return NpyReader.Read(s, path);
    }
}
