using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// Eq. 2's lobes read as a BSDF in physical radiometry (docs/scene-format.md, "Radiometry"): the Lambertian m_diff/π plus
/// the energy-normalised specular lobe m_spec·N(s)·factor (Blinn–Phong (s+8)/(8π)·(n·h)^s, Phong (s+2)/(2π)·(r·v)^s);
/// the Whitted mirror k_r and transmission k_t, with the material's Fresnel factors and index of refraction, are its
/// delta lobes. The ambient m_amb is eq. 2's stand-in for light from everywhere, not a lobe. Smooth lobes are drawn in
/// proportion to their spectral sums: the diffuse one with density cos θ/π, the specular one by its model's own sampling.
/// </summary>
public sealed class Eq2Bsdf : Bsdf
{
    readonly Material _m;
    readonly float _specularNorm;
    readonly float _diffuseShare;   // the probability of drawing the diffuse lobe

    public Eq2Bsdf(Material material)
    {
        _m = material;
        _specularNorm = (float)material.Model.EnergyNormalisation(material.Shininess);
        double d = Sum(material.Diffuse), s = material.HasSpecular ? Sum(material.Specular) : 0;
        _diffuseShare = d + s > 0 ? (float)(d / (d + s)) : 0;
        Lobes = (d > 0 ? BsdfFlags.Reflection | BsdfFlags.Diffuse : 0) | (s > 0 ? BsdfFlags.Reflection | BsdfFlags.Glossy : 0)
              | (material.HasMirror ? BsdfFlags.Reflection | BsdfFlags.Delta : 0)
              | (material.HasTransmission ? BsdfFlags.Transmission | BsdfFlags.Delta : 0);
    }

    static double Sum(float[] a)
    {
        double s = 0;
        foreach (var v in a) s += Math.Max(v, 0);
        return s;
    }

    public override BsdfFlags Lobes { get; }

    /// <summary>Eq. 2's lobes with every spectrum (and the index of refraction) on another grid.</summary>
    public override Bsdf Resampled(Func<float[], float[]> resample) => new Eq2Bsdf(new Material
    {
        Name = _m.Name,
        Ambient = resample(_m.Ambient),
        Diffuse = resample(_m.Diffuse),
        Specular = resample(_m.Specular),
        Shininess = _m.Shininess,
        Model = _m.Model,
        Mirror = resample(_m.Mirror),
        Transmit = resample(_m.Transmit),
        Ior = resample(_m.Ior),
        Dispersive = _m.Dispersive,
        Fresnel = _m.Fresnel,
    });

    bool HasSmooth => (Lobes & (BsdfFlags.Diffuse | BsdfFlags.Glossy)) != 0;

    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, Span<float> f)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float nl = Vector3.Dot(front, wi);
        if (!(nl > 0 && Vector3.Dot(front, wo) > 0)) { f.Clear(); return; }
        float spec = _m.HasSpecular ? _specularNorm * _m.SpecularFactor(front, wi, wo, nl) : 0;
        for (int i = 0; i < f.Length; i++) f[i] = _m.Diffuse[i] / MathF.PI + _m.Specular[i] * spec;
    }

    public override bool TakesTextures => true;

    /// <summary>f = m_diff/π + m_spec·N(s)·factor with a texel's m_diff and/or m_spec (empty: the material's own).</summary>
    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, ReadOnlySpan<float> diffuse, ReadOnlySpan<float> specular,
        Span<float> f)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float nl = Vector3.Dot(front, wi);
        if (!(nl > 0 && Vector3.Dot(front, wo) > 0)) { f.Clear(); return; }
        float spec = _m.HasSpecular ? _specularNorm * _m.SpecularFactor(front, wi, wo, nl) : 0;
        ReadOnlySpan<float> d = diffuse.IsEmpty ? _m.Diffuse : diffuse, s = specular.IsEmpty ? _m.Specular : specular;
        for (int i = 0; i < f.Length; i++) f[i] = d[i] / MathF.PI + s[i] * spec;
    }

    public override float Pdf(Vector3 wo, Vector3 wi, Vector3 n)
    {
        if (!HasSmooth) return 0;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float nl = Vector3.Dot(front, wi);
        if (!(nl > 0 && Vector3.Dot(front, wo) > 0)) return 0;
        float pdf = _diffuseShare * nl / MathF.PI;
        if (_diffuseShare < 1) pdf += (1 - _diffuseShare) * _m.Model.LobePdf(front, wo, wi, _m.Shininess);
        return pdf;
    }

    public override bool Sample(Vector3 wo, Vector3 n, Vector2 u, Span<float> f, out BsdfSample sample)
    {
        sample = default;
        if (!HasSmooth) return false;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        Vector3 wi;
        BsdfFlags lobe;
        // One random number picks the lobe and, rescaled, is reused for its direction.
        if (u.X < _diffuseShare)
        {
            wi = CosineHemisphere(front, new Vector2(u.X / _diffuseShare, u.Y));
            lobe = BsdfFlags.Reflection | BsdfFlags.Diffuse;
        }
        else
        {
            wi = _m.Model.SampleLobe(front, wo, new Vector2((u.X - _diffuseShare) / (1 - _diffuseShare), u.Y), _m.Shininess);
            lobe = BsdfFlags.Reflection | BsdfFlags.Glossy;
        }
        float pdf = Pdf(wo, wi, n);
        if (!(pdf > 0)) return false;
        sample = new BsdfSample(wi, pdf, lobe);
        Evaluate(wo, wi, n, f);
        return true;
    }

    /// <summary>
    /// k_r times the Fresnel reflectance when the material has it (per band's own index when it is dispersive and
    /// <paramref name="band"/> is −1).
    /// </summary>
    public override bool SampleMirror(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        if (!_m.HasMirror) return false;
        bool outside = Vector3.Dot(wo, n) >= 0;
        var front = outside ? n : -n;
        float cosI = Vector3.Dot(front, wo);
        wi = Vector3.Normalize(2 * cosI * front - wo);
        bool perBand = _m.Fresnel && _m.Dispersive && band < 0;
        float factor = _m.MirrorFactor(cosI, outside, band);
        for (int i = 0; i < weight.Length; i++) weight[i] = _m.Mirror[i] * (perBand ? _m.MirrorFactor(cosI, outside, i) : factor);
        return true;
    }

    /// <summary>
    /// k_t along the refracted direction (times 1 − Fresnel when the material has it). Under total internal reflection
    /// a Fresnel material transmits nothing (the mirror lobe reflects everything); without Fresnel the k_t share is sent
    /// along the mirror direction, as the Whitted integrator does.
    /// </summary>
    public override bool SampleTransmission(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        if (!_m.HasTransmission) return false;
        bool outside = Vector3.Dot(wo, n) >= 0;
        var front = outside ? n : -n;
        float cosI = Vector3.Dot(front, wo);
        float eta = _m.Eta(outside, band);
        float sin2T = eta * eta * (1 - cosI * cosI);
        float factor = 1;
        if (sin2T >= 1)
        {
            if (_m.Fresnel) return false;
            wi = Vector3.Normalize(2 * cosI * front - wo);
        }
        else
        {
            float cosT = MathF.Sqrt(1 - sin2T);
            wi = Vector3.Normalize(-eta * wo + (eta * cosI - cosT) * front);
            factor = _m.TransmitFactor(cosI, eta);
        }
        for (int i = 0; i < weight.Length; i++) weight[i] = _m.Transmit[i] * factor;
        return true;
    }
}
