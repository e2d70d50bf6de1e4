using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// The sky: a CIE daylight of a correlated colour temperature, as the radiance of every ray that escapes the scene.
public sealed partial class SceneLoader
{
    /// <summary>
    /// "sky": { "type": "daylight", "cct": K, "luminance": cd/m² | "radiance": W·m⁻²·sr⁻¹·nm⁻¹ at 560 nm } — a uniform sky whose
    /// spectral radiance is the CIE D-series SPD of that CCT (CIE 015:2018 §4.1.2, S₀ + M₁S₁ + M₂S₂: <see cref="CieDaylight"/>),
    /// scaled to the luminance K_m∫V·L dλ or to the spectral radiance at 560 nm (where every D SPD is 100). The same in every
    /// direction; it is the scene's background (what escaping rays see), which the path integrator also lights the scene with.
    /// Physical radiometry only; instead of "background".
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    float[] ParseSky(JsonElement e)
    {
        const string path = "$.sky";
        Object(e, path);
        Keys(e, path, "type", "cct", "luminance", "radiance");
        if (_radiometry != Radiometry.Physical)
            throw Error(path, "a sky is a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) and needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene (and render it with \"integrator\": \"path\")");
        var type = String(Required(e, "type", path), $"{path}.type");
        if (type != "daylight")
            throw Error($"{path}.type", $"unknown sky type '{type}'", "the sky types are: daylight (a CIE daylight by \"cct\")");
        double cct = Number(e, "cct", path, 6504, CieDaylight.MinKelvin, CieDaylight.MaxKelvin);
        bool luminance = TryGet(e, "luminance", out _), radiance = TryGet(e, "radiance", out _);
        if (luminance == radiance)
            throw Error(path, luminance ? "gives both \"luminance\" and \"radiance\"" : "needs \"luminance\" or \"radiance\"",
                "give one: \"luminance\" in cd/m² (e.g. 5000 for an overcast sky) or \"radiance\" in W·m⁻²·sr⁻¹·nm⁻¹ at 560 nm");
        var spd = CieDaylight.Spectrum(cct);
        // Every D SPD is exactly 100 at 560 nm (S₁ = S₂ = 0 there), so radiance k is the factor k/100.
        double scale = radiance ? Number(e, "radiance", path, 0, 0) / 100 : Number(e, "luminance", path, 0, 0) / Photometry.Luminous(spd);
        return Bands(spd.Scaled(scale), path);
    }
}
