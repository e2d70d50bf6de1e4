using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Lights: the keys every light has, then its type's own (LightTypes).
public sealed partial class SceneLoader
{
    Light ParseLight(JsonElement e, string path, int index)
    {
        Object(e, path);
        var type = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        var names = LightTypes.ByName.Keys.ToArray();
        if (!LightTypes.ByName.TryGetValue(type, out var kind))
            throw Error($"{path}.type", $"unknown light type '{type}'",
                InputException.DidYouMean(type, names) ?? $"use {string.Join(", ", names)}");
        // Photometric keys are checked by ParsePhotometric, which names the ones this type takes.
        Keys(e, path, [.. LightTypes.CommonKeys, .. kind.Keys, .. LightTypes.PhotometricKeys]);
        var name = TryGet(e, "name", out var n) ? String(n, $"{path}.name") : $"light-{index}";
        var spectrum = FilteredLight(e, path, Spectrum(Required(e, "spectrum", path), $"{path}.spectrum"));
        var keys = new LightSource(this, e, path) { Name = name, Spectrum = spectrum };
        var photometric = ParsePhotometric(e, path, type, kind, keys, spectrum);
        float intensity = photometric is { } ph ? (float)ph.RadiometricScale : (float)Number(e, "intensity", path, 1, 0);
        var bands = Bands(spectrum, $"{path}.spectrum");
        for (int i = 0; i < bands.Length; i++)
        {
            bands[i] *= intensity;
            if (!(bands[i] <= MaxMagnitude))
                throw Error(photometric is null ? $"{path}.intensity" : $"{path}.{photometric.Quantity}",
                    $"intensity × spectrum is {bands[i]:g3} in band {i}, beyond {MaxMagnitude:g}",
                        "lower the intensity or the spectrum's scale");
        }
        _spectra[bands] = spectrum.Scaled(intensity);
        var ambient = OptionalBands(e, "ambient", path);
        // Physical radiometry: a point or spot light's spectrum × intensity is radiant intensity, so irradiance falls as 1/r².
        var falloff = _radiometry == Radiometry.Physical ? new DistanceFalloff(0, 0, 1) : DistanceFalloff.None;
        if (TryGet(e, "attenuation", out var att))
        {
            if (att.ValueKind != JsonValueKind.Array || att.GetArrayLength() != 3)
                throw Error($"{path}.attenuation", "expected [c0, c1, c2] with d = 1/(c0 + c1·r + c2·r²)",
                    "e.g. \"attenuation\": [1, 0, 0.1]");
            float c0 = (float)Number(att[0], $"{path}.attenuation[0]", 0);
            float c1 = (float)Number(att[1], $"{path}.attenuation[1]", 0);
            float c2 = (float)Number(att[2], $"{path}.attenuation[2]", 0);
            if (c0 + c1 + c2 <= 0)
                throw Error($"{path}.attenuation", "all attenuation coefficients are zero", "use [1, 0, 0] for no attenuation");
            falloff = new DistanceFalloff(c0, c1, c2);
        }
        keys.Intensity = bands;
        keys.Ambient = ambient;
        keys.HasAmbient = SpectralMath.Any(ambient);
        keys.Falloff = falloff;
        keys.Scale = intensity;
        keys.Photometric = photometric;
        return kind.Make(keys);
    }

    /// <summary>
    /// A photometric key in place of "intensity" (docs/scene-format.md, "Photometric units"): its value X_v and the
    /// radiometric scale it gives, X_v / (K_m ∫V·S dλ · G); null when the light gives none.
    /// </summary>
    LightPhotometry? ParsePhotometric(JsonElement e, string path, string type, LightType kind, LightSource keys, TabulatedSpectrum spectrum)
    {
        string? key = null;
        foreach (var k in LightTypes.PhotometricKeys)
        {
            if (!TryGet(e, k, out _)) continue;
            var accepted = kind.Photometric ?? new Dictionary<string, PhotometricKey>();
            if (!accepted.ContainsKey(k))
                throw Error($"{path}.{k}", $"a {type} light takes no {k}",
                    accepted.Count == 0
                        ? "give its strength as \"intensity\""
                        : $"use {string.Join(" or ", accepted.Select(a => $"{a.Key} ({a.Value.Unit})"))}");
            if (_radiometry != Radiometry.Physical)
                throw Error($"{path}.{k}", $"{k} needs physical radiometry (paper radiometry has relative units)",
                    "add \"radiometry\": \"physical\" to the scene, or give the light a relative \"intensity\"");
            if (key is not null) throw Error($"{path}.{k}", $"the light gives both {key} and {k}", "give one photometric value");
            key = k;
        }
        if (key is null) return null;
        if (TryGet(e, "intensity", out _))
            throw Error($"{path}.intensity", $"the light gives both intensity and {key}", $"give one: {key} sets the intensity");
        var pk = kind.Photometric![key];
        double value = Number(e, key, path, 0, 0);
        double luminous = Color.Photometry.Luminous(spectrum);
        if (!(luminous > 0))
            throw Error($"{path}.spectrum", $"spectrum '{spectrum.Name}' emits no visible light (∫V·S dλ = 0), so {key} cannot scale it",
                "use \"intensity\" (radiometric) for an invisible light");
        double g = pk.Geometry(keys);
        return new LightPhotometry(key, value, pk.Unit, value / (luminous * g), luminous);
    }

    /// <summary>
    /// What a light type's factory (<see cref="LightTypes"/>) gets: the parts every light has, already parsed, and
    /// readers for its own keys that report bad input with the file, line:column and JSON path.
    /// </summary>
    public sealed class LightSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal LightSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public required string Name { get; init; }
        /// <summary>I_k: the spectrum's band values × intensity.</summary>
        public float[] Intensity { get; internal set; } = [];
        public float[] Ambient { get; internal set; } = [];
        public bool HasAmbient { get; internal set; }
        public required TabulatedSpectrum Spectrum { get; init; }
        /// <summary>The "intensity" factor the spectrum's band values were multiplied by.</summary>
        public float Scale { get; internal set; } = 1;
        /// <summary>The "attenuation" [c0, c1, c2], or none.</summary>
        public DistanceFalloff Falloff { get; internal set; } = DistanceFalloff.None;
        /// <summary>The photometric value that set <see cref="Scale"/>, or null.</summary>
        public LightPhotometry? Photometric { get; internal set; }
        /// <summary>What every light emits, for the light type's constructor.</summary>
        public LightEmission Emission => new(Name, Intensity, Ambient, HasAmbient, Scale, Spectrum, Photometric);

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>The scene's radiometry (a light type that needs units checks it).</summary>
        public Radiometry Radiometry => _loader._radiometry;

        readonly Dictionary<string, object> _memo = new(StringComparer.Ordinal);
        /// <summary>A value computed once per light (e.g. a file its factory and its photometric key both read).</summary>
        public T Memo<T>(string key, Func<T> make) where T : class
        {
            if (_memo.TryGetValue(key, out var v)) return (T)v;
            var made = make();
            _memo[key] = made;
            return made;
        }

        /// <summary>The text of the file the string key names, relative to the scene's folder: (full path, text).</summary>
        public (string Path, string Text) ReadText(string key, string what)
        {
            var name = _loader.String(_loader.Required(_e, key, _path), $"{_path}.{key}");
            var full = System.IO.Path.IsPathRooted(name) ? name : System.IO.Path.Combine(_loader._dir, name);
            if (!File.Exists(full))
                throw Error(key, $"{what} {Diagnostics.MessageText.Quote(name, 80)} not found",
                    "a relative path starts at the scene's folder");
            return (full, InputFile.ReadAllText(full, what));
        }
        /// <summary>A required point [x, y, z].</summary>
        public Vector3 Point(string key) => _loader.Vec3(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A required non-zero vector, normalised.</summary>
        public Vector3 Direction(string key) => _loader.Direction(_loader.Required(_e, key, _path), $"{_path}.{key}");
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
    }
}
