using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A surface's lobes, each a spectral weight as band values (padded for SIMD): ambient m_amb, diffuse m_diff
/// and specular m_spec of eq. 2 (the specular lobe's shape given by its <see cref="SpecularModel"/>), the
/// Whitted mirror weight k_r and transmittance k_t, and the index of refraction per band (constant, or
/// Cauchy n(λ) = A + B/λ² which makes refraction dispersive). A lobe whose weight is zero in every band is absent.
/// </summary>
public sealed class Material
{
    public required string Name { get; init; }
    /// <summary>Where the material is in the scene file: $.materials.NAME, or an inline material's own path (its name).</summary>
    public string JsonPath => Name.StartsWith("$.", StringComparison.Ordinal) ? Name : $"$.materials.{Name}";
    public required float[] Ambient { get; init { field = value; HasAmbient = Spectra.SpectralMath.Any(value); } }
    public required float[] Diffuse { get; init; }
    public required float[] Specular { get; init { field = value; HasSpecular = Spectra.SpectralMath.Any(value); } }
    public float Shininess { get; init; } = 32;
    public SpecularModel Model { get; init; } = SpecularModels.Default;
    public required float[] Mirror { get; init { field = value; HasMirror = Spectra.SpectralMath.Any(value); } }
    public required float[] Transmit { get; init { field = value; HasTransmission = Spectra.SpectralMath.Any(value); } }
    /// <summary>Index of refraction per band.</summary>
    public required float[] Ior { get; init; }
    public bool Dispersive { get; init; }
    /// <summary>Scale k_r by the dielectric Fresnel reflectance and k_t by its complement.</summary>
    public bool Fresnel { get; init; }
    /// <summary>The tabulated diffuse reflectance (ground truth for analysis), when it was a spectrum.</summary>
    public Spectra.TabulatedSpectrum? DiffuseSpectrum { get; init; }
    /// <summary>A spectral texture on m_diff (and on m_amb when that defaults to m_diff), or null; <see cref="Diffuse"/> then holds
    /// the texture's mean (the renderer's texture tables look the texels up).</summary>
    public Textures.TextureBinding? DiffuseTexture { get; set; }
    /// <summary>A spectral texture on m_spec, or null; <see cref="Specular"/> then holds the texture's mean (the renderer's texture
    /// tables look the texels up, as for <see cref="DiffuseTexture"/>).</summary>
    public Textures.TextureBinding? SpecularTexture { get; set; }
    /// <summary>What the surface emits ("emission", an area light for the path tracer), or null.</summary>
    public Emission? Emission { get; set; }
    /// <summary>The re-radiation (Donaldson) matrix whose diagonal is <see cref="Diffuse"/> ("fluorescence"), or null.</summary>
    public Spectra.ReradiationMatrix? Fluorescence { get; set; }

    /// <summary>
    /// The material as a BSDF in physical radiometry (f in 1/sr, sampling, pdf, delta lobes): eq. 2's lobes as
    /// <see cref="Eq2Bsdf"/> unless its material model gives its own. The Whitted integrator uses the lobes above.
    /// </summary>
    public Bsdf Bsdf { get => field ??= new Eq2Bsdf(this); init; }

    public bool HasAmbient { get; private init; }
    public bool HasSpecular { get; private init; }
    public bool HasMirror { get; private init; }
    public bool HasTransmission { get; private init; }

    /// <summary>The specular lobe's scalar factor for unit normal n, light direction l, view direction v and n·l > 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float SpecularFactor(Vector3 n, Vector3 l, Vector3 v, float nl) => Model.Evaluate(n, l, v, nl, Shininess);

    /// <summary>η = n_i / n_t for a ray arriving from outside (n_i = 1) or inside, at band <paramref name="band"/> (−1: all bands, band 0's
    /// index).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Eta(bool outside, int band)
    {
        float ior = Ior[band < 0 ? 0 : band];
        return outside ? 1f / ior : ior;
    }

    /// <summary>The factor on k_r: the dielectric Fresnel reflectance when <see cref="Fresnel"/>, else 1.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float MirrorFactor(float cosI, bool outside, int band) => Fresnel ? Dielectric.Reflectance(cosI, Eta(outside, band)) : 1f;

    /// <summary>The factor on k_t for a refracted (not totally reflected) ray: 1 − Fresnel reflectance when <see cref="Fresnel"/>, else
    /// 1.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float TransmitFactor(float cosI, float eta) => Fresnel ? 1 - Dielectric.Reflectance(cosI, eta) : 1f;
}

/// <summary>A dielectric interface (Hecht, Optics §4.6).</summary>
public static class Dielectric
{
    /// <summary>Unpolarised Fresnel reflectance, eta = n_i / n_t; 1 under total internal reflection.</summary>
    public static float Reflectance(float cosI, float eta)
    {
        float sin2T = eta * eta * (1 - cosI * cosI);
        if (sin2T >= 1) return 1;
        float cosT = MathF.Sqrt(1 - sin2T);
        float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
        float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
        return 0.5f * (rs * rs + rp * rp);
    }
}
