using System.Text;
using System.Text.Json.Nodes;

namespace SpectralRenderer.Output;

/// <summary>A light of the resolved scene: its name (or "light-K") and, where the scene gives them, its spectrum and intensity.</summary>
public sealed record ResolvedLight(string Name, string? Spectrum, double? Intensity);

/// <summary>
/// render.json's "resolved_scene": the scene file as the render read it (the fields the renderer used, with the named
/// spectra it used). It is kept whole, as the scene-file document it is (docs/scene-format.md), so that it is written
/// back byte for byte and relight can load the same scene again; what the other layers need from it is read here,
/// by name: the radiometry, the lights, whether a spectrum is one of its named ones, the scene with lights changed.
/// </summary>
public sealed class ManifestScene(JsonObject document)
{
    readonly JsonObject _document = document;

    /// <summary>The scene-file document (a copy).</summary>
    public JsonObject ToJson() => (JsonObject)_document.DeepClone();

    /// <summary>"paper" or "physical" where the scene says.</summary>
    public string? Radiometry => Text(_document["radiometry"]);

    /// <summary>The camera's vertical field of view (degrees) where the scene gives it.</summary>
    public double? CameraFov => _document["camera"]?["fov"] is JsonValue v && v.TryGetValue(out double d) ? d : null;

    /// <summary>The scene's lights in order.</summary>
    public IReadOnlyList<ResolvedLight> Lights => (_document["lights"] as JsonArray ?? []).Select((l, i) =>
        new ResolvedLight(Text(l?["name"]) ?? $"light-{i}", Text(l?["spectrum"]),
            l?["intensity"] is JsonValue v && v.TryGetValue(out double d) ? d : null)).ToArray();

    /// <summary>Whether <paramref name="name"/> is one of the scene's own named spectra.</summary>
    public bool NamesSpectrum(string name) => _document["spectra"] is JsonObject named && named.ContainsKey(name);

    /// <summary>
    /// The scene file (UTF-8) with light K's spectrum and/or intensity changed and the reference white replaced where given.
    /// </summary>
    public byte[] WithLights(IEnumerable<(int Light, string? Spectrum, double? Intensity)> changes, string? white)
    {
        var scene = ToJson();
        var lights = scene["lights"] as JsonArray ?? [];
        foreach (var (k, spectrum, intensity) in changes)
        {
            var l = lights[k]!.AsObject();
            if (spectrum is not null) l["spectrum"] = spectrum;
            if (intensity is not null)
            {
                // A new intensity replaces a photometric value (docs/scene-format.md); a new spectrum alone keeps it, so a light
                // swapped at the same lumens, candela or lux is rescaled to them.
                foreach (var key in PhotometricKeys) l.Remove(key);
                l["intensity"] = intensity;
            }
        }
        if (white is not null) scene["white"] = white;
        return Encoding.UTF8.GetBytes(scene.ToJsonString());
    }

    /// <summary>The scene file's photometric light keys (the light types' list in the scene loader).</summary>
    static readonly string[] PhotometricKeys = ["luminous_flux", "luminous_intensity", "illuminance", "luminance"];

    static string? Text(JsonNode? node) => node is JsonValue v && v.TryGetValue(out string? s) ? s : null;
}
