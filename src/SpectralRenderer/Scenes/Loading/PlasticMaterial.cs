using System.Globalization;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// The "plastic" material model: a Lambertian base ("diffuse", a reflectance) under a clear dielectric coat of index
/// "ior" (a number &gt; 1, 1.5 by default), smooth or GGX-rough ("roughness" α ∈ [0, 1], 0 by default) —
/// <see cref="PlasticBsdf"/>. For the Whitted integrator it is eq. 2's m_diff = ρ_eff·(1 − E_avg) (the base through the
/// coat, for diffuse light) with, when smooth, k_r = 1 under the dielectric Fresnel factor of the coat's index, else
/// m_spec = the coat's normal-incidence albedo with a Blinn–Phong lobe of shininess 2/α² − 2 — an approximation; the path
/// integrator uses the BSDF.
/// </summary>
public static class PlasticMaterial
{
    public static readonly string[] Keys = ["diffuse", "ior", "roughness"];

    public static Material Make(SceneLoader.MaterialSource s)
    {
        var rho = s.RequiredReflectance("diffuse");
        var bands = s.Bands(rho, "diffuse");
        double eta = s.Number("ior", 1.5, double.MinValue, double.MaxValue);
        if (!(eta > 1 && eta <= 4))
            throw s.Error("ior",
                $"a coat of index {eta.ToString(CultureInfo.InvariantCulture)} reflects nothing or is no dielectric: "
                    + $"the coat's index lies in (1, 4]",
                "plastics and varnishes are 1.4–1.6, e.g. \"ior\": 1.5");
        float alpha = ConductorMaterial.Roughness(s);
        var white = s.Bands(TabulatedSpectrum.Constant(1, "constant:1"), "ior");
        var ior = s.Bands(TabulatedSpectrum.Constant(eta, $"constant:{eta.ToString(CultureInfo.InvariantCulture)}"), "ior");
        var bsdf = new PlasticBsdf(bands, white, (float)eta, alpha);
        var diffuse = s.Zero();
        for (int i = 0; i < diffuse.Length; i++) diffuse[i] = bsdf.EffectiveReflectance[i] * (1 - bsdf.AverageAlbedo);
        var coat = s.Zero();
        for (int i = 0; i < coat.Length; i++) coat[i] = white[i] * bsdf.CoatAlbedo(1);
        return new Material
        {
            Name = s.Name,
            Ambient = diffuse,
            Diffuse = diffuse,
            Specular = alpha > 0 ? coat : s.Zero(),
            Shininess = alpha > 0 ? MathF.Max(0, 2 / (alpha * alpha) - 2) : 32,
            Mirror = alpha > 0 ? s.Zero() : white,
            Transmit = s.Zero(),
            Ior = ior,
            Fresnel = alpha == 0,
            Bsdf = bsdf,
        };
    }
}
