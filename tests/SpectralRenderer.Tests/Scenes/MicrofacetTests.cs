using System.Globalization;
using System.Numerics;
using SpectralRenderer.Scenes;
using Complex = System.Numerics.Complex;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// The GGX conductor and the coated plastic against independent computations written here: the Fresnel equations of a
/// conductor in complex arithmetic (Snell's law with a complex index), the hemisphere integral ∫ f cos θ dω and ∫ pdf dω by
/// midpoint quadrature in (θ, φ), energy balances (a lossless metal, a white base under the coat), reciprocity.
/// </summary>
public class MicrofacetTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const int Bands = 3;

    static float[] Spectrum(params float[] v)
    {
        var a = new float[SpectralRenderer.Spectra.SpectralMath.Padded(v.Length)];
        v.CopyTo(a, 0);
        return a;
    }

    static Vector3 Incidence(double degrees) => new((float)Math.Sin(degrees * Math.PI / 180), 0, (float)Math.Cos(degrees * Math.PI / 180));

    /// <summary>
    /// Unpolarised reflectance of the interface from vacuum to the complex index N = n + ik at incidence θ (Hecht §4.6 with a
    /// complex index): cos θ_t = √(1 − sin²θ/N²), r_s = (cos θ − N cos θ_t)/(cos θ + N cos θ_t),
    /// r_p = (N cos θ − cos θ_t)/(N cos θ + cos θ_t), R = (|r_s|² + |r_p|²)/2.
    /// </summary>
    internal static double FresnelComplex(double cos, double n, double k)
    {
        var eta = new Complex(n, k);
        double sin2 = 1 - cos * cos;
        var cosT = Complex.Sqrt(1 - sin2 / (eta * eta));
        var rs = (cos - eta * cosT) / (cos + eta * cosT);
        var rp = (eta * cos - cosT) / (eta * cos + cosT);
        return (rs.Magnitude * rs.Magnitude + rp.Magnitude * rp.Magnitude) / 2;
    }

    /// <summary>∫ g(ωi) dωi over the upper hemisphere (n = +z) by the midpoint rule in (θ, φ).</summary>
    static double Hemisphere(Func<Vector3, double> g, int nt = 400, int np = 400)
    {
        double sum = 0, dt = Math.PI / 2 / nt, dp = 2 * Math.PI / np;
        for (int i = 0; i < nt; i++)
        {
            double t = (i + 0.5) * dt, st = Math.Sin(t), ct = Math.Cos(t);
            for (int j = 0; j < np; j++)
            {
                double p = (j + 0.5) * dp;
                sum += g(new Vector3((float)(st * Math.Cos(p)), (float)(st * Math.Sin(p)), (float)ct)) * st * dt * dp;
            }
        }
        return sum;
    }

    /// <summary>∫ f(ωo, ωi) cos θi dωi per band (the directional albedo), every band in one pass.</summary>
    static double[] Albedo(Bsdf bsdf, Vector3 wo, int nt = 400, int np = 400)
    {
        var a = new double[Bands];
        var f = new float[SpectralRenderer.Spectra.SpectralMath.Padded(Bands)];
        double dt = Math.PI / 2 / nt, dp = 2 * Math.PI / np;
        for (int i = 0; i < nt; i++)
        {
            double t = (i + 0.5) * dt, st = Math.Sin(t), ct = Math.Cos(t);
            for (int j = 0; j < np; j++)
            {
                double p = (j + 0.5) * dp;
                var wi = new Vector3((float)(st * Math.Cos(p)), (float)(st * Math.Sin(p)), (float)ct);
                bsdf.Evaluate(wo, wi, Vector3.UnitZ, f);
                for (int b = 0; b < Bands; b++) a[b] += f[b] * ct * st * dt * dp;
            }
        }
        return a;
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(30.0)]
    [InlineData(60.0)]
    [InlineData(85.0)]
    public void Conductor_Fresnel_agrees_with_complex_arithmetic_and_at_normal_incidence_with_the_n_k_formula(double theta)
    {
        float cos = (float)Math.Cos(theta * Math.PI / 180);
        foreach (var (n, k) in new[] { (0.14, 3.697), (1.46, 1.958), (0.05, 4.483), (1.366, 7.4052), (2.5, 0.3), (0.0, 1.0) })
        {
            double expected = FresnelComplex(cos, n, k);
            Assert.Equal(expected, Conductor.Reflectance(cos, (float)n, (float)k), 2e-5 + 2e-5 * expected);
            if (theta == 0) Assert.Equal(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), expected, 1e-12);
        }
    }

    [Fact]
    public void The_smooth_conductor_is_a_mirror_weighted_by_Fresnel_per_band()
    {
        var n = Spectrum(0.14f, 1.46f, 0.05f);
        var k = Spectrum(3.697f, 1.958f, 4.483f);
        var bsdf = new ConductorBsdf(n, k, 0);
        Assert.Equal(BsdfFlags.Reflection | BsdfFlags.Delta, bsdf.Lobes);
        var w = new float[n.Length];
        var wo = Incidence(40);
        Assert.True(bsdf.SampleMirror(wo, Vector3.UnitZ, -1, w, out var wi));
        Assert.Equal(-wo.X, wi.X, 1e-6f);
        Assert.Equal(wo.Z, wi.Z, 1e-6f);
        for (int b = 0; b < Bands; b++) Assert.Equal(FresnelComplex(wo.Z, n[b], k[b]), w[b], 3e-5);
        for (int b = Bands; b < w.Length; b++) Assert.Equal(0f, w[b]);   // the padding reflects nothing
        Assert.False(bsdf.Sample(wo, Vector3.UnitZ, new Vector2(0.3f, 0.6f), w, out _));
        Assert.Equal(0f, bsdf.Pdf(wo, wi, Vector3.UnitZ));
    }

    /// <summary>The directional albedo per band by the sampling estimator f·cos θi/pdf over n × n stratified draws.</summary>
    static double[] SampledAlbedo(Bsdf bsdf, Vector3 wo, int n = 128)
    {
        var f = new float[8];
        var sum = new double[Bands];
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
                if (bsdf.Sample(wo, Vector3.UnitZ, new Vector2((i + 0.5f) / n, (j + 0.5f) / n), f, out var s))
                    for (int b = 0; b < Bands; b++) sum[b] += f[b] * s.Wi.Z / s.Pdf / (n * n);
        return sum;
    }

    /// <summary>
    /// A lossless metal (n = 0: ε = −k² is real and negative, so R = 1 at every angle, checked in complex arithmetic here)
    /// in the white furnace: its albedo is what the microsurface does not mask, at most 1, and close to 1 when polished.
    /// The albedo is the sampling estimator's (checked against quadrature in the next test); at normal incidence it is at
    /// most the share of visible normals tilted by less than 45°, 1/(1 + α²).
    /// </summary>
    [Theory]
    [InlineData(0.01f)]
    [InlineData(0.05f)]
    [InlineData(0.2f)]
    [InlineData(0.5f)]
    [InlineData(1f)]
    public void A_lossless_rough_metal_keeps_at_most_all_the_energy_and_nearly_all_when_polished(float alpha)
    {
        foreach (double c in new[] { 1.0, 0.7, 0.2 }) Assert.Equal(1, FresnelComplex(c, 0, 1), 1e-12);
        var bsdf = new ConductorBsdf(Spectrum(0, 0, 0), Spectrum(1, 2, 5), alpha);
        foreach (double theta in new[] { 0.0, 45.0, 80.0 })
        {
            var albedo = SampledAlbedo(bsdf, Incidence(theta));
            double a = albedo[0];
            output.WriteLine($"α = {alpha}, θo = {theta}°: albedo {a:F4}");
            Assert.True(a <= 1 + 1e-4, $"α {alpha} θ {theta}: albedo {a:F5} > 1");
            Assert.Equal(a, albedo[2], 1e-5);
            // At α = 1 and normal incidence D = 1/π and G₂ = 2 cos θi/(1 + cos θi), so the albedo is ∫₀¹ μ/(1 + μ) dμ = 1 − ln 2.
            if (alpha == 1 && theta == 0) Assert.Equal(1 - Math.Log(2), Albedo(bsdf, Incidence(0), 300, 64)[0], 1e-3);
            // (The 128 strata resolve the tail of tilts beyond 45° only from α ≈ 0.1 on.)
            if (theta == 0 && alpha >= 0.1f) Assert.True(a <= 1 / (1 + alpha * alpha) + 1e-4, $"α {alpha}: albedo {a:F5} > 1/(1 + α²)");
            // Polished: α = 0.01 within 0.1 % of all the light up to 45°, α = 0.05 within 0.5 %, α = 0.2 within 8 %.
            double floor = alpha switch
            {
                <= 0.01f => theta < 60 ? 0.999 : 0.98,
                <= 0.05f => theta < 60 ? 0.995 : 0.9,
                <= 0.2f => theta < 60 ? 0.92 : 0.85,
                _ => 0,
            };
            Assert.True(a >= floor, $"α {alpha} θ {theta}: albedo {a:F5} < {floor}");
        }
    }

    /// <summary>
    /// The visible-normal sampling: ∫ pdf dω over the hemisphere is the share of draws that stay above the surface (≈ 1
    /// unless rough and grazing), every draw's pdf is <see cref="Bsdf.Pdf"/>'s, and the estimator f·cos/pdf over stratified
    /// draws gives the quadrature albedo.
    /// </summary>
    [Theory]
    [InlineData(0.1f)]
    [InlineData(0.3f)]
    [InlineData(1f)]
    public void The_sampled_density_integrates_to_the_share_of_draws_and_estimates_the_albedo(float alpha)
    {
        var bsdf = new ConductorBsdf(Spectrum(0.14f, 1.46f, 1.2f), Spectrum(3.697f, 1.958f, 2.6f), alpha);
        var f = new float[8];
        var g = new float[8];
        foreach (double theta in new[] { 0.0, 60.0 })
        {
            var wo = Incidence(theta);
            double mass = Hemisphere(wi => bsdf.Pdf(wo, wi, Vector3.UnitZ), alpha < 0.2f ? 300 : 200, 200);
            const int n = 128;
            int kept = 0;
            var estimate = new double[Bands];
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                {
                    if (!bsdf.Sample(wo, Vector3.UnitZ, new Vector2((i + 0.5f) / n, (j + 0.5f) / n), f, out var s)) continue;
                    kept++;
                    Assert.Equal(bsdf.Pdf(wo, s.Wi, Vector3.UnitZ), s.Pdf, s.Pdf * 1e-5f);
                    bsdf.Evaluate(wo, s.Wi, Vector3.UnitZ, g);
                    for (int b = 0; b < Bands; b++)
                    {
                        Assert.Equal(g[b], f[b]);
                        estimate[b] += f[b] * s.Wi.Z / s.Pdf / (n * n);
                    }
                }
            double share = kept / (double)(n * n);
            output.WriteLine($"α = {alpha}, θo = {theta}°: ∫pdf dω = {mass:F4}, share of draws above the surface {share:F4}");
            Assert.Equal(share, mass, 0.01);
            // At normal incidence the visible normals are D(h)·cos θh, whose tilt obeys P(tan²θh ≤ t) = t/(α² + t) (the GGX
            // slope distribution), and ωi stays above the surface iff θh < 45°: ∫pdf dω = 1/(1 + α²).
            if (theta == 0)
                Assert.True(Math.Abs(mass - 1 / (1 + alpha * alpha)) < 2e-3, $"∫pdf = {mass}, 1/(1 + α²) = {1 / (1 + alpha * alpha)}");
            var reference = Albedo(bsdf, wo, alpha < 0.2f ? 300 : 200, 200);
            for (int b = 0; b < Bands; b++)
                Assert.True(Math.Abs(estimate[b] - reference[b]) <= 0.01 * reference[b],
                    $"α {alpha} θ {theta} band {b}: sampled {estimate[b]:G5}, quadrature {reference[b]:G5}");
        }
    }

    [Fact]
    public void The_rough_conductor_and_plastic_are_reciprocal()
    {
        var white = Spectrum(1, 1, 1);
        foreach (var bsdf in new Bsdf[]
        {
            new ConductorBsdf(Spectrum(0.14f, 1.46f, 0.05f), Spectrum(3.697f, 1.958f, 4.483f), 0.3f),
            new PlasticBsdf(Spectrum(0.8f, 0.4f, 0.05f), white, 1.5f, 0.25f),
            new PlasticBsdf(Spectrum(0.8f, 0.4f, 0.05f), white, 1.5f, 0),
        })
        {
            var rng = new Random(11);
            var f = new float[8];
            var g = new float[8];
            for (int i = 0; i < 300; i++)
            {
                var wo = Bsdf.CosineHemisphere(Vector3.UnitZ, new Vector2(rng.NextSingle(), rng.NextSingle()));
                var wi = Bsdf.CosineHemisphere(Vector3.UnitZ, new Vector2(rng.NextSingle(), rng.NextSingle()));
                bsdf.Evaluate(wo, wi, Vector3.UnitZ, f);
                bsdf.Evaluate(wi, wo, Vector3.UnitZ, g);
                for (int b = 0; b < Bands; b++) Assert.Equal(f[b], g[b], Math.Max(f[b], 1e-3f) * 1e-4f);
            }
        }
    }

    /// <summary>The coat's reflectance for diffuse light from inside, 2∫F(μ)μ dμ with the dielectric Fresnel written here.</summary>
    static double InternalReflectance(double eta)
    {
        const int n = 20000;
        double s = 0;
        for (int i = 0; i < n; i++)
        {
            double mu = (i + 0.5) / n, sin2T = eta * eta * (1 - mu * mu);
            double r = 1;
            if (sin2T < 1)
            {
                double cosT = Math.Sqrt(1 - sin2T);
                double rs = (eta * mu - cosT) / (eta * mu + cosT), rp = (mu - eta * cosT) / (mu + eta * cosT);
                r = (rs * rs + rp * rp) / 2;
            }
            s += r * mu;
        }
        return 2 * s / n;
    }

    /// <summary>
    /// Plastic in the white furnace: with a white base (ρ = 1) the coat's reflection plus the light through it is all the
    /// light, at every incidence (the smooth coat's mirror lobe F(θ) added to the quadrature of f cos θ); with a coloured base
    /// never more. The smooth coat's albedo is F(θ) + (1 − F(θ))·ρ(1 − F_int)/(1 − ρF_int), F_int computed here.
    /// </summary>
    [Theory]
    [InlineData(0f)]
    [InlineData(0.1f)]
    [InlineData(0.4f)]
    public void Plastic_keeps_all_the_energy_over_a_white_base_and_at_most_all_over_a_coloured_one(float alpha)
    {
        const double eta = 1.5;
        var white = Spectrum(1, 1, 1);
        var rho = Spectrum(1, 0.5f, 0.1f);
        var bsdf = new PlasticBsdf(rho, white, (float)eta, alpha);
        Assert.Equal(InternalReflectance(eta), bsdf.InternalReflectance, 1e-4);
        double fInt = InternalReflectance(eta);
        var w = new float[8];
        foreach (double theta in new[] { 0.0, 60.0, 85.0 })
        {
            var wo = Incidence(theta);
            // Smooth: the quadrature of the diffuse lobe; rough: the sampling estimator (checked against quadrature below),
            // which resolves the narrow glossy lobe at grazing incidence where a (θ, φ) grid does not.
            var a = alpha == 0 ? Albedo(bsdf, wo, 250, 250) : SampledAlbedo(bsdf, wo, 192);
            double mirror = 0;
            if (alpha == 0)
            {
                Assert.True(bsdf.SampleMirror(wo, Vector3.UnitZ, -1, w, out _));
                mirror = w[0];
                Assert.Equal(w[0], w[2]);
            }
            output.WriteLine($"α = {alpha}, θo = {theta}°: albedo {a[0] + mirror:F5} (white base), {a[2] + mirror:F5} (ρ = 0.1)");
            Assert.Equal(1, a[0] + mirror, alpha == 0 ? 1.5e-3 : 4e-3);
            for (int b = 1; b < Bands; b++) Assert.True(a[b] + mirror < a[0] + mirror, $"band {b}");
            if (alpha == 0)
                for (int b = 0; b < Bands; b++)
                {
                    double r = FresnelComplex(wo.Z, 1.5, 0);
                    double expected = r + (1 - r) * rho[b] * (1 - fInt) / (1 - rho[b] * fInt);
                    Assert.Equal(expected, a[b] + mirror, 2e-3);
                }
        }
    }

    [Theory]
    [InlineData(0.1f)]
    [InlineData(0.5f)]
    public void Plastic_sampling_draws_with_the_density_Pdf_gives_and_estimates_the_albedo(float alpha)
    {
        var bsdf = new PlasticBsdf(Spectrum(0.9f, 0.3f, 0.02f), Spectrum(1, 1, 1), 1.5f, alpha);
        var f = new float[8];
        foreach (double theta in new[] { 0.0, 70.0 })
        {
            var wo = Incidence(theta);
            const int n = 128;
            var estimate = new double[Bands];
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                {
                    if (!bsdf.Sample(wo, Vector3.UnitZ, new Vector2((i + 0.5f) / n, (j + 0.5f) / n), f, out var s)) continue;
                    Assert.Equal(bsdf.Pdf(wo, s.Wi, Vector3.UnitZ), s.Pdf, s.Pdf * 1e-5f);
                    for (int b = 0; b < Bands; b++) estimate[b] += f[b] * s.Wi.Z / s.Pdf / (n * n);
                }
            var reference = Albedo(bsdf, wo, alpha < 0.2f ? 300 : 200, 200);
            for (int b = 0; b < Bands; b++)
                Assert.True(Math.Abs(estimate[b] - reference[b]) <= 0.01 * reference[b] + 1e-4,
                    $"α {alpha} θ {theta} band {b}: sampled {estimate[b]:G5}, quadrature {reference[b]:G5}");
        }
    }

    /// <summary>The metal tables in data/ read here as plain text, (λ nm, n, k) per row, for the given column prefix.</summary>
    internal static (double[] L, double[] N, double[] K) MetalTable(string file, string metal)
    {
        var lines = File.ReadAllLines(Path.Combine(Repo.Root, "data", file));
        var header = lines[0].Split(',');
        int cn = Array.IndexOf(header, metal + "_n"), ck = Array.IndexOf(header, metal + "_k");
        var rows = lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')).ToArray();
        double P(string s) => double.Parse(s, CultureInfo.InvariantCulture);
        return (rows.Select(r => P(r[0])).ToArray(), rows.Select(r => P(r[cn])).ToArray(), rows.Select(r => P(r[ck])).ToArray());
    }
}
