using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Loading;

// The integrator a scene asks for, and what a surface emits (area lights): path tracing's keys.
public sealed partial class SceneLoader
{
    /// <summary>
    /// "integrator": a registered name ("whitted", "path") or { "type": name, "max_depth": N, "rr_depth": N,
    /// "spectral_grid": nm, "sampler": "sobol" | "independent", "seed": N }; the name is checked against the registry when the
    /// render is built.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    IntegratorSettings? ParseIntegrator(JsonElement root)
    {
        if (!TryGet(root, "integrator", out var e)) return null;
        const string path = "$.integrator";
        if (e.ValueKind == JsonValueKind.String) return new IntegratorSettings(String(e, path).ToLowerInvariant());
        if (e.ValueKind != JsonValueKind.Object)
            throw Error(path, $"expected a name or an object, found {Kind(e)}", "e.g. \"integrator\": \"path\" or { \"type\": \"path\", \"max_depth\": 8 }");
        Keys(e, path, "type", "max_depth", "rr_depth", "spectral_grid", "sampler", "seed");
        var name = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        int maxDepth = Integer(e, "max_depth", path, -1, -1, 1_000_000);
        int rrDepth = Integer(e, "rr_depth", path, IntegratorSettings.DefaultRrDepth, 0, 1_000_000);
        // The internal grid: every output band split into equal sub-bands of at most this width (1 nm allowed).
        double grid = Number(e, "spectral_grid", path, IntegratorSettings.DefaultSpectralGrid, 1, 1000);
        SamplerKind? sampler = null;
        if (TryGet(e, "sampler", out var se))
        {
            var text = String(se, $"{path}.sampler");
            if (!Samplers.TryParse(text, out var kind))
                throw Error($"{path}.sampler", $"unknown sampler '{text}'",
                    InputException.DidYouMean(text, Samplers.Names) ?? $"samplers: {string.Join(", ", Samplers.Names)}");
            sampler = kind;
        }
        // The seed changes every random number (independent renders of the same scene); 0 is the default's.
        uint seed = (uint)Integer(e, "seed", path, 0, 0, int.MaxValue);
        return new IntegratorSettings(name, maxDepth, rrDepth, grid, sampler, seed);
    }

    /// <summary>
    /// A material's "emission": { "spectrum": …, "radiance": k, "two_sided": false } — spectral radiance spectrum × k in
    /// W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry only; or "luminance": cd/m² instead of "radiance", k = L_v/(K_m ∫V·S dλ).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    Emission? ParseEmission(JsonElement material, string materialPath)
    {
        if (!TryGet(material, "emission", out var e)) return null;
        string path = $"{materialPath}.emission";
        Object(e, path);
        Keys(e, path, "spectrum", "radiance", "luminance", "two_sided");
        if (_radiometry != Radiometry.Physical)
            throw Error(path, "emission is a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) and needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene (and render it with \"integrator\": \"path\")");
        var spectrum = Spectrum(Required(e, "spectrum", path), $"{path}.spectrum");
        double k = Luminance(e, path, spectrum) ?? Number(e, "radiance", path, 1, 0);
        var radiance = Bands(spectrum.Scaled(k), $"{path}.spectrum");
        return new Emission(radiance, Bool(e, "two_sided", path, false));
    }

    /// <summary>
    /// A radiance given as "luminance" (cd/m²) in <paramref name="e"/>: the factor k on <paramref name="spectrum"/> whose
    /// K_m ∫V·(k·S) dλ is it (683 lm/W, CIE 1924 V), or null when the key is absent; with "radiance" too, an error.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    double? Luminance(JsonElement e, string path, Spectra.TabulatedSpectrum spectrum)
    {
        if (!TryGet(e, "luminance", out _)) return null;
        if (TryGet(e, "radiance", out _)) throw Error($"{path}.luminance", "both radiance and luminance are given", "give one: luminance (cd/m²) sets the radiance");
        double value = Number(e, "luminance", path, 0, 0);
        double luminous = Color.Photometry.Luminous(spectrum);
        if (!(luminous > 0))
            throw Error($"{path}.spectrum", $"spectrum '{spectrum.Name}' emits no visible light (∫V·S dλ = 0), so luminance cannot scale it",
                "give \"radiance\" (radiometric) for an invisible emitter");
        return value / luminous;
    }

    /// <summary>
    /// "background": a spectrum (radiance of escaping rays), or { "spectrum": …, "luminance": cd/m² } — a uniform sky of that
    /// luminance (physical radiometry).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    float[] ParseBackground(JsonElement bg)
    {
        const string path = "$.background";
        if (bg.ValueKind != JsonValueKind.Object || !TryGet(bg, "luminance", out _)) return Bands(bg, path);
        Keys(bg, path, "spectrum", "luminance");
        if (_radiometry != Radiometry.Physical)
            throw Error($"{path}.luminance", "luminance (cd/m²) needs physical radiometry", "add \"radiometry\": \"physical\" to the scene, or give the background as a spectrum");
        var spectrum = Spectrum(Required(bg, "spectrum", path), $"{path}.spectrum");
        return Bands(spectrum.Scaled(Luminance(bg, path, spectrum)!.Value), $"{path}.spectrum");
    }
}
