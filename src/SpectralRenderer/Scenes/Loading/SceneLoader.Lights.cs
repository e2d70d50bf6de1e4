using System.Numerics;
using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Lights: the keys every light has, then its type's own (LightTypes).
public sealed partial class SceneLoader
{
    [MethodImpl(MethodImplOptions.NoOptimization)]
    Light ParseLight(JsonElement e, string path, int index)
    {
        Object(e, path);
        var type = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        var names = LightTypes.ByName.Keys.ToArray();
        if (!LightTypes.ByName.TryGetValue(type, out var kind))
            throw Error($"{path}.type", $"unknown light type '{type}'", InputException.DidYouMean(type, names) ?? $"use {string.Join(", ", names)}");
        Keys(e, path, [.. LightTypes.CommonKeys, .. kind.Keys]);
        var name = TryGet(e, "name", out var n) ? String(n, $"{path}.name") : $"light-{index}";
        var spectrum = Spectrum(Required(e, "spectrum", path), $"{path}.spectrum");
        float intensity = (float)Number(e, "intensity", path, 1, 0);
        var bands = Bands(spectrum, $"{path}.spectrum");
        for (int i = 0; i < bands.Length; i++)
        {
            bands[i] *= intensity;
            if (!(bands[i] <= MaxMagnitude))
                throw Error($"{path}.intensity", $"intensity × spectrum is {bands[i]:g3} in band {i}, beyond {MaxMagnitude:g}", "lower the intensity or the spectrum's scale");
        }
        _spectra[bands] = spectrum.Scaled(intensity);
        var ambient = OptionalBands(e, "ambient", path);
        // Physical radiometry: a point or spot light's spectrum × intensity is radiant intensity, so irradiance falls as 1/r².
        var falloff = _radiometry == Radiometry.Physical ? new DistanceFalloff(0, 0, 1) : DistanceFalloff.None;
        if (TryGet(e, "attenuation", out var att))
        {
            if (att.ValueKind != JsonValueKind.Array || att.GetArrayLength() != 3) throw Error($"{path}.attenuation", "expected [c0, c1, c2] with d = 1/(c0 + c1·r + c2·r²)", "e.g. \"attenuation\": [1, 0, 0.1]");
            float c0 = (float)Number(att[0], $"{path}.attenuation[0]", 0);
            float c1 = (float)Number(att[1], $"{path}.attenuation[1]", 0);
            float c2 = (float)Number(att[2], $"{path}.attenuation[2]", 0);
            if (c0 + c1 + c2 <= 0) throw Error($"{path}.attenuation", "all attenuation coefficients are zero", "use [1, 0, 0] for no attenuation");
            falloff = new DistanceFalloff(c0, c1, c2);
        }
        return kind.Make(new LightSource(this, e, path)
        {
            Name = name,
            Intensity = bands,
            Ambient = ambient,
            HasAmbient = SpectralMath.Any(ambient),
            Spectrum = spectrum,
            Falloff = falloff,
            Scale = intensity,
        });
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
        public required float[] Intensity { get; init; }
        public required float[] Ambient { get; init; }
        public required bool HasAmbient { get; init; }
        public required TabulatedSpectrum Spectrum { get; init; }
        /// <summary>The "intensity" factor the spectrum's band values were multiplied by.</summary>
        public required float Scale { get; init; }
        /// <summary>The "attenuation" [c0, c1, c2], or none.</summary>
        public required DistanceFalloff Falloff { get; init; }
        /// <summary>What every light emits, for the light type's constructor.</summary>
        public LightEmission Emission => new(Name, Intensity, Ambient, HasAmbient, Scale, Spectrum);

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A required point [x, y, z].</summary>
        public Vector3 Point(string key) => _loader.Vec3(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A required non-zero vector, normalised.</summary>
        public Vector3 Direction(string key) => _loader.Direction(_loader.Required(_e, key, _path), $"{_path}.{key}");
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
    }
}
