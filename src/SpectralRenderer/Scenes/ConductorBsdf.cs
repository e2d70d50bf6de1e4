using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A metal: a GGX microfacet conductor (Walter et al. 2007) with the height-correlated Smith G₂ and the exact Fresnel
/// reflectance of its complex index n(λ) + ik(λ) per band, f(ωo, ωi) = D(h)·G₂(ωo, ωi)·F(ωo·h)/(4 cos θo cos θi) with
/// h = (ωo + ωi)/|ωo + ωi| (see <see cref="Ggx"/>, <see cref="Conductor"/>); ωi drawn from the visible normals (Heitz 2018).
/// Roughness α = 0 is the smooth metal: a delta mirror lobe of weight F(cos θo) per band. Two-sided, like eq. 2's surfaces
/// (the side ωo is on is the front); f is symmetric in ωo and ωi (D, G₂ and F(ωo·h) = F(ωi·h) all are).
/// </summary>
public sealed class ConductorBsdf : Bsdf
{
    readonly float[] _n, _k;

    /// <param name="n">the real part of the index per band (padded; a band where n and k are both 0 is padding and reflects
    /// nothing)</param>
    /// <param name="k">the extinction coefficient per band</param>
    /// <param name="alpha">GGX roughness α ∈ [0, 1]; 0: the smooth mirror</param>
    public ConductorBsdf(float[] n, float[] k, float alpha)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(alpha, 0f);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(alpha, 1f);
        _n = n;
        _k = k;
        Alpha = alpha;
        Lobes = alpha > 0 ? BsdfFlags.Reflection | BsdfFlags.Glossy : BsdfFlags.Reflection | BsdfFlags.Delta;
    }

    public float Alpha { get; }
    public ReadOnlySpan<float> N => _n;
    public ReadOnlySpan<float> K => _k;

    public override BsdfFlags Lobes { get; }

    public override Bsdf Resampled(Func<float[], float[]> resample) => new ConductorBsdf(resample(_n), resample(_k), Alpha);

    /// <summary>F(cos) per band into <paramref name="f"/>, each times <paramref name="scale"/>.</summary>
    void Fresnel(float cos, float scale, Span<float> f)
    {
        int count = Math.Min(f.Length, _n.Length);
        for (int i = 0; i < count; i++)
            f[i] = _n[i] == 0 && _k[i] == 0 ? 0 : scale * Conductor.Reflectance(cos, _n[i], _k[i]);
        f[count..].Clear();
    }

    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, Span<float> f)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cosO = Vector3.Dot(front, wo), cosI = Vector3.Dot(front, wi);
        if (Alpha == 0 || !(cosO > 0 && cosI > 0)) { f.Clear(); return; }
        var h = Vector3.Normalize(wo + wi);
        float d = Ggx.D(Vector3.Dot(front, h), Alpha);
        float g = Ggx.G2(cosO, cosI, Alpha);
        Fresnel(Vector3.Dot(wo, h), d * g / (4 * cosO * cosI), f);
    }

    public override float Pdf(Vector3 wo, Vector3 wi, Vector3 n)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cosO = Vector3.Dot(front, wo), cosI = Vector3.Dot(front, wi);
        if (Alpha == 0 || !(cosO > 0 && cosI > 0)) return 0;
        var h = Vector3.Normalize(wo + wi);
        return Ggx.ReflectionPdf(cosO, Vector3.Dot(front, h), Alpha);
    }

    public override bool Sample(Vector3 wo, Vector3 n, Vector2 u, Span<float> f, out BsdfSample sample)
    {
        sample = default;
        if (Alpha == 0) return false;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        var (t, b) = Frame(front);
        var local = Ggx.ToLocal(wo, t, b, front);
        if (!(local.Z > 0)) return false;
        var m = Ggx.SampleVisibleNormal(local, Alpha, u);
        var h = m.X * t + m.Y * b + m.Z * front;
        var wi = Vector3.Normalize(2 * Vector3.Dot(wo, h) * h - wo);
        if (!(Vector3.Dot(front, wi) > 0)) return false;   // reflected below the surface: the masked share of the energy
        float pdf = Pdf(wo, wi, n);
        if (!(pdf > 0) || !float.IsFinite(pdf)) return false;
        sample = new BsdfSample(wi, pdf, BsdfFlags.Reflection | BsdfFlags.Glossy);
        Evaluate(wo, wi, n, f);
        return true;
    }

    /// <summary>The smooth metal (α = 0): the mirror direction and F(cos θo) per band.</summary>
    public override bool SampleMirror(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        if (Alpha > 0) return false;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cos = Vector3.Dot(front, wo);
        wi = Vector3.Normalize(2 * cos * front - wo);
        Fresnel(cos, 1, weight);
        return true;
    }
}
