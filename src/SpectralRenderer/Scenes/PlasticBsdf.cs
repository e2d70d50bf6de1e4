using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// Plastic: a Lambertian base of reflectance ρ(λ) under a clear dielectric coat of index η, smooth (α = 0) or GGX-rough.
/// The coat reflects E(θo) of the light, colourless: smooth, the Fresnel reflectance F(cos θo) as a delta mirror lobe;
/// rough, the GGX dielectric lobe D·G₂·F(ωo·h)/(4 cos θo cos θi) (<see cref="Ggx"/>), whose directional albedo E(μ) is
/// tabulated once. What it transmits reaches the base, is reflected diffusely with the internal reflections of the coat
/// summed, ρ_eff = ρ(1 − F_int)/(1 − ρ·F_int) (F_int the coat's diffuse reflectance from inside, 2∫F(μ)μ dμ, total
/// internal reflection included), and leaves in proportion to 1 − E(θi):
/// f_d = ρ_eff·(1 − E(θo))(1 − E(θi))/(π(1 − E_avg)), E_avg = 2∫E(μ)μ dμ (the coupling of Kelemen &amp; Szirmay-Kalos 2001;
/// with a smooth coat, since 1 − F_dr,ext = η²(1 − F_int), it is the physically based plastic of Weidlich &amp; Wilkie / Mitsuba).
/// The albedo is E(θo) + (1 − E(θo))·ρ_eff ≤ 1 at every incidence, exactly 1 for ρ = 1; f is symmetric in ωo and ωi.
/// </summary>
public sealed class PlasticBsdf : Bsdf
{
    const int TableSize = 64;
    readonly float[] _effective, _white;   // ρ_eff per band; 1 on the bands, 0 on the padding
    readonly float[] _albedo;              // E(μ) at μ_j = (j + 0.5)/TableSize (rough coat)
    readonly float _meanEffective;         // ρ_eff averaged over the bands: the diffuse lobe's share in sampling
    readonly float _diffuseNorm;           // 1/(π(1 − E_avg))

    /// <param name="reflectance">the base's ρ per band (padded with 0)</param>
    /// <param name="white">1 on the bands, 0 on the padding (the coat reflects every band alike)</param>
    /// <param name="eta">the coat's index of refraction, &gt; 1</param>
    /// <param name="alpha">the coat's GGX roughness α ∈ [0, 1]; 0: smooth</param>
    public PlasticBsdf(float[] reflectance, float[] white, float eta, float alpha)
        : this(reflectance, white, eta, alpha, alpha > 0 ? AlbedoTable(eta, alpha) : []) { }

    PlasticBsdf(float[] reflectance, float[] white, float eta, float alpha, float[] albedo)
    {
        ArgumentOutOfRangeException.ThrowIfLessThanOrEqual(eta, 1f);
        ArgumentOutOfRangeException.ThrowIfLessThan(alpha, 0f);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(alpha, 1f);
        Reflectance = reflectance;
        _white = white;
        Eta = eta;
        Alpha = alpha;
        _albedo = albedo;
        InternalReflectance = (float)DiffuseReflectance(mu => Dielectric.Reflectance(mu, eta));
        AverageAlbedo = (float)DiffuseReflectance(CoatAlbedo);
        _diffuseNorm = 1 / (MathF.PI * (1 - AverageAlbedo));
        _effective = new float[reflectance.Length];
        double sum = 0, bands = 0;
        for (int i = 0; i < reflectance.Length; i++)
        {
            float rho = reflectance[i];
            _effective[i] = white[i] * rho * (1 - InternalReflectance) / (1 - rho * InternalReflectance);
            sum += _effective[i];
            bands += white[i];
        }
        _meanEffective = bands > 0 ? (float)(sum / bands) : 0;
        Lobes = BsdfFlags.Reflection | BsdfFlags.Diffuse | (alpha > 0 ? BsdfFlags.Glossy : BsdfFlags.Delta);
    }

    public float[] Reflectance { get; }
    public float Eta { get; }
    public float Alpha { get; }
    /// <summary>F_int: the coat's reflectance for diffuse light from inside, 2∫F(μ)μ dμ.</summary>
    public float InternalReflectance { get; }
    /// <summary>E_avg = 2∫E(μ)μ dμ: the coat's reflectance for diffuse light from outside.</summary>
    public float AverageAlbedo { get; }
    /// <summary>ρ_eff per band: the base seen through the coat, its internal reflections summed.</summary>
    public ReadOnlySpan<float> EffectiveReflectance => _effective;

    public override BsdfFlags Lobes { get; }

    public override Bsdf Resampled(Func<float[], float[]> resample) =>
        new PlasticBsdf(resample(Reflectance), resample(_white), Eta, Alpha, _albedo);

    /// <summary>E(μ): the share of light arriving at cos θ = μ that the coat reflects (F(μ) when smooth).</summary>
    public float CoatAlbedo(float mu)
    {
        if (Alpha == 0) return Dielectric.Reflectance(mu, 1 / Eta);
        float x = mu * TableSize - 0.5f;
        if (x <= 0) return _albedo[0];
        if (x >= TableSize - 1) return _albedo[TableSize - 1];
        int j = (int)x;
        float t = x - j;
        return _albedo[j] + t * (_albedo[j + 1] - _albedo[j]);
    }

    /// <summary>2∫₀¹ g(μ)μ dμ by the midpoint rule on 4096 intervals.</summary>
    static double DiffuseReflectance(Func<float, float> g)
    {
        const int n = 4096;
        double s = 0;
        for (int i = 0; i < n; i++)
        {
            float mu = (i + 0.5f) / n;
            s += g(mu) * mu;
        }
        return 2 * s / n;
    }

    /// <summary>
    /// The rough coat's directional albedo E(μ) = ∫ f_s cos θi dωi = E over visible normals of F(ωo·h)·G₂/G₁(ωo) (reflections
    /// below the surface count 0), by 64 × 64 stratified visible normals per node.
    /// </summary>
    static float[] AlbedoTable(float eta, float alpha)
    {
        const int n = 64;
        var table = new float[TableSize];
        for (int j = 0; j < TableSize; j++)
        {
            float mu = (j + 0.5f) / TableSize;
            var wo = new Vector3(MathF.Sqrt(1 - mu * mu), 0, mu);
            double s = 0;
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++)
                {
                    var h = Ggx.SampleVisibleNormal(wo, alpha, new Vector2((a + 0.5f) / n, (b + 0.5f) / n));
                    float oh = Vector3.Dot(wo, h);
                    var wi = 2 * oh * h - wo;
                    if (!(wi.Z > 0) || !(oh > 0)) continue;
                    s += Dielectric.Reflectance(oh, 1 / eta) * Ggx.G2(mu, wi.Z, alpha) / Ggx.G1(mu, alpha);
                }
            table[j] = (float)(s / (n * n));
        }
        return table;
    }

    /// <summary>The probability of drawing the coat's glossy lobe rather than the base's diffuse one, for cos θo.</summary>
    float GlossyShare(float cosO)
    {
        float e = CoatAlbedo(cosO), d = (1 - e) * _meanEffective;
        return e + d > 0 ? e / (e + d) : 1;
    }

    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, Span<float> f)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cosO = Vector3.Dot(front, wo), cosI = Vector3.Dot(front, wi);
        if (!(cosO > 0 && cosI > 0)) { f.Clear(); return; }
        float diffuse = (1 - CoatAlbedo(cosO)) * (1 - CoatAlbedo(cosI)) * _diffuseNorm;
        float glossy = 0;
        if (Alpha > 0)
        {
            var h = Vector3.Normalize(wo + wi);
            glossy = Ggx.D(Vector3.Dot(front, h), Alpha) * Ggx.G2(cosO, cosI, Alpha)
                   * Dielectric.Reflectance(Vector3.Dot(wo, h), 1 / Eta) / (4 * cosO * cosI);
        }
        int count = Math.Min(f.Length, _effective.Length);
        for (int i = 0; i < count; i++) f[i] = _effective[i] * diffuse + _white[i] * glossy;
        f[count..].Clear();
    }

    public override float Pdf(Vector3 wo, Vector3 wi, Vector3 n)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cosO = Vector3.Dot(front, wo), cosI = Vector3.Dot(front, wi);
        if (!(cosO > 0 && cosI > 0)) return 0;
        float pdf = cosI / MathF.PI;
        if (Alpha == 0) return pdf;
        float g = GlossyShare(cosO);
        var h = Vector3.Normalize(wo + wi);
        return (1 - g) * pdf + g * Ggx.ReflectionPdf(cosO, Vector3.Dot(front, h), Alpha);
    }

    public override bool Sample(Vector3 wo, Vector3 n, Vector2 u, Span<float> f, out BsdfSample sample)
    {
        sample = default;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cosO = Vector3.Dot(front, wo);
        if (!(cosO > 0)) return false;
        Vector3 wi;
        var lobe = BsdfFlags.Reflection | BsdfFlags.Diffuse;
        float g = Alpha > 0 ? GlossyShare(cosO) : 0;
        // One random number picks the lobe and, rescaled, is reused for its direction.
        if (u.X < g)
        {
            var (t, b) = Frame(front);
            var m = Ggx.SampleVisibleNormal(Ggx.ToLocal(wo, t, b, front), Alpha, new Vector2(u.X / g, u.Y));
            var h = m.X * t + m.Y * b + m.Z * front;
            wi = Vector3.Normalize(2 * Vector3.Dot(wo, h) * h - wo);
            lobe = BsdfFlags.Reflection | BsdfFlags.Glossy;
        }
        else wi = CosineHemisphere(front, new Vector2((u.X - g) / (1 - g), u.Y));
        if (!(Vector3.Dot(front, wi) > 0)) return false;
        float pdf = Pdf(wo, wi, n);
        if (!(pdf > 0) || !float.IsFinite(pdf)) return false;
        sample = new BsdfSample(wi, pdf, lobe);
        Evaluate(wo, wi, n, f);
        return true;
    }

    /// <summary>The smooth coat's mirror lobe: F(cos θo), colourless.</summary>
    public override bool SampleMirror(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        if (Alpha > 0) return false;
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        float cos = Vector3.Dot(front, wo);
        wi = Vector3.Normalize(2 * cos * front - wo);
        float r = Dielectric.Reflectance(cos, 1 / Eta);
        int count = Math.Min(weight.Length, _white.Length);
        for (int i = 0; i < count; i++) weight[i] = _white[i] * r;
        weight[count..].Clear();
        return true;
    }
}
