using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Participating media: an object's "medium" (its interior) and the scene's "medium" (around the objects), each
// { "type": NAME, …its keys } of a registered medium type (MediumTypes.cs).
public sealed partial class SceneLoader
{
    /// <summary>The scene's media in the order they were read (<see cref="Scene.Media"/>).</summary>
    readonly List<Medium> _media = [];

    /// <summary>The medium <paramref name="e"/> at <paramref name="path"/>, added to the scene's media: its index there.</summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    int ParseMedium(JsonElement e, string path)
    {
        Object(e, path);
        var type = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        var registered = MediumTypes.ByName;
        if (!registered.TryGetValue(type, out var kind))
        {
            var types = registered.Keys.Order(StringComparer.Ordinal).ToArray();
            throw Error($"{path}.type", $"unknown medium type '{type}'", types.Length == 0
                ? "this build has no participating media yet (issue 41); remove \"medium\""
                : InputException.DidYouMean(type, types) ?? $"types: {string.Join(", ", types)}");
        }
        Keys(e, path, ["type", .. kind.Keys]);
        _media.Add(kind.Make(new MediumSource(this, e, path)));
        return _media.Count - 1;
    }

    /// <summary>
    /// What a medium type's factory (<see cref="MediumTypes"/>) gets: readers for its own keys that resolve spectra onto the
    /// scene's bands and report bad input with the file, line:column and JSON path. Coefficients are per scene length unit.
    /// </summary>
    public sealed class MediumSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal MediumSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A required spectrum.</summary>
        public TabulatedSpectrum Spectrum(string key) => _loader.Spectrum(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A spectrum's padded band values on the scene's grid (a renderer resamples its tabulated spectrum exactly).</summary>
        public float[] Bands(TabulatedSpectrum s, string key) => _loader.Bands(s, $"{_path}.{key}");
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
        public BandGrid Grid => _loader._grid;
    }
}
