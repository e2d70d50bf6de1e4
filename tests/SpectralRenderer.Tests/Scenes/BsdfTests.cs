using System.Numerics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// BSDFs against independent computations: the hemisphere integral ∫ f cos θ dω by midpoint quadrature in (θ, φ),
/// Fresnel at normal incidence ((n − 1)/(n + 1))², Snell's law; sampling checked against <see cref="Bsdf.Pdf"/> and the quadrature.
/// </summary>
public class BsdfTests
{
    const int Bands = 3;

    static float[] Spectrum(params float[] v)
    {
        var a = new float[SpectralRenderer.Spectra.SpectralMath.Padded(v.Length)];
        v.CopyTo(a, 0);
        return a;
    }

    static Material Eq2(float[] diffuse, float[] specular, SpecularModel? model = null, float shininess = 32, float[]? mirror = null,
        float[]? transmit = null, float ior = 1.5f, bool fresnel = false) => new()
        {
            Name = "m",
            Ambient = diffuse,
            Diffuse = diffuse,
            Specular = specular,
            Shininess = shininess,
            Model = model ?? SpecularModels.Default,
            Mirror = mirror ?? Spectrum(0, 0, 0),
            Transmit = transmit ?? Spectrum(0, 0, 0),
            Ior = Spectrum(ior, ior, ior),
            Fresnel = fresnel,
        };

    static Vector3 Incidence(double degrees) => new((float)Math.Sin(degrees * Math.PI / 180), 0, (float)Math.Cos(degrees * Math.PI / 180));

    /// <summary>∫ f(ωo, ωi) cos θ_i dωi over the upper hemisphere (n = +z), per band, by the midpoint rule.</summary>
    static double[] Albedo(Bsdf bsdf, Vector3 wo, int nt = 300, int np = 600)
    {
        var sum = new double[Bands];
        Span<float> f = stackalloc float[Bands];
        double dt = Math.PI / 2 / nt, dp = 2 * Math.PI / np;
        for (int i = 0; i < nt; i++)
        {
            double t = (i + 0.5) * dt;
            for (int j = 0; j < np; j++)
            {
                double p = (j + 0.5) * dp;
                var wi = new Vector3((float)(Math.Sin(t) * Math.Cos(p)), (float)(Math.Sin(t) * Math.Sin(p)), (float)Math.Cos(t));
                bsdf.Evaluate(wo, wi, Vector3.UnitZ, f);
                double w = Math.Cos(t) * Math.Sin(t) * dt * dp;
                for (int b = 0; b < Bands; b++) sum[b] += f[b] * w;
            }
        }
        return sum;
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(45.0)]
    [InlineData(80.0)]
    public void A_Lambertian_integrates_to_its_albedo_at_every_incidence(double theta)
    {
        var rho = Spectrum(1f, 0.5f, 0.18f);
        foreach (var bsdf in new Bsdf[] { new LambertianBsdf(rho), Eq2(rho, Spectrum(0, 0, 0)).Bsdf })
        {
            var a = Albedo(bsdf, Incidence(theta));
            for (int b = 0; b < Bands; b++) Assert.Equal(rho[b], a[b], 1e-4);
        }
    }

    public static TheoryData<string, float> Lobes => new()
    {
        { "blinn-phong", 1 }, { "blinn-phong", 20 }, { "blinn-phong", 300 }, { "phong", 0 }, { "phong", 20 }, { "phong", 300 },
    };

    [Theory]
    [MemberData(nameof(Lobes))]
    public void Sampling_draws_with_the_density_Pdf_gives_and_estimates_the_quadrature_albedo(string model, float shininess)
    {
        var m = Eq2(Spectrum(0.3f, 0.1f, 0.05f), Spectrum(0.5f, 0.5f, 0.2f), SpecularModels.ByName[model], shininess);
        var bsdf = m.Bsdf;
        Span<float> f = stackalloc float[Bands], g = stackalloc float[Bands];
        foreach (double theta in new[] { 0.0, 35.0, 70.0 })
        {
            var wo = Incidence(theta);
            var reference = Albedo(bsdf, wo, 600, 1200);
            const int n = 256;
            var estimate = new double[Bands];
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                {
                    var u = new Vector2((i + 0.5f) / n, (j + 0.5f) / n);   // stratified
                    if (!bsdf.Sample(wo, Vector3.UnitZ, u, f, out var s)) continue;
                    Assert.Equal(bsdf.Pdf(wo, s.Wi, Vector3.UnitZ), s.Pdf, s.Pdf * 1e-5f);
                    bsdf.Evaluate(wo, s.Wi, Vector3.UnitZ, g);
                    for (int b = 0; b < Bands; b++)
                    {
                        Assert.Equal(g[b], f[b]);
                        estimate[b] += f[b] * s.Wi.Z / s.Pdf / (n * n);
                    }
                }
            for (int b = 0; b < Bands; b++)
                Assert.True(Math.Abs(estimate[b] - reference[b]) <= 0.01 * reference[b] + 1e-4,
                    $"{model} s={shininess} θ={theta} band {b}: sampled {estimate[b]:G5}, quadrature {reference[b]:G5}");
        }
    }

    [Theory]
    [MemberData(nameof(Lobes))]
    public void The_eq2_lobes_are_reciprocal_and_keep_energy_in_physical_radiometry(string model, float shininess)
    {
        // m_diff + m_spec = 1 in every band: the directional albedo may not exceed 1 at any incidence. Phong's
        // (s+2)/(2π) is exact at normal incidence; Blinn–Phong's (s+8)/(8π) is the usual approximation of the exact
        // normalisation and gives up to ~6 % more than m_spec near normal incidence (measured here: the lobe alone
        // reaches 1.061 at s = 20), so it is held to 1.07, not to 1.
        double limit = model == "phong" ? 1 + 2e-3 : 1.07;
        var bsdf = Eq2(Spectrum(0.4f, 0, 0.5f), Spectrum(0.6f, 1, 0.5f), SpecularModels.ByName[model], shininess).Bsdf;
        foreach (double theta in new[] { 0.0, 30.0, 60.0, 85.0 })
        {
            var a = Albedo(bsdf, Incidence(theta));
            for (int b = 0; b < Bands; b++) Assert.True(a[b] <= limit, $"{model} s={shininess} θ={theta} band {b}: albedo {a[b]:G5}");
        }
        var rng = new Random(7);
        Span<float> f = stackalloc float[Bands], g = stackalloc float[Bands];
        for (int i = 0; i < 200; i++)
        {
            var wo = Bsdf.CosineHemisphere(Vector3.UnitZ, new Vector2(rng.NextSingle(), rng.NextSingle()));
            var wi = Bsdf.CosineHemisphere(Vector3.UnitZ, new Vector2(rng.NextSingle(), rng.NextSingle()));
            bsdf.Evaluate(wo, wi, Vector3.UnitZ, f);
            bsdf.Evaluate(wi, wo, Vector3.UnitZ, g);
            for (int b = 0; b < Bands; b++) Assert.Equal(f[b], g[b], Math.Max(f[b], 1e-3f) * 2e-4f);
        }
    }

    [Fact]
    public void The_mirror_and_transmission_lobes_follow_Fresnel_and_Snell()
    {
        var k = Spectrum(1, 0.5f, 0.25f);
        var glass = Eq2(Spectrum(0, 0, 0), Spectrum(0, 0, 0), mirror: k, transmit: k, ior: 1.5f, fresnel: true).Bsdf;
        Assert.Equal(BsdfFlags.Reflection | BsdfFlags.Transmission | BsdfFlags.Delta, glass.Lobes);
        Span<float> w = stackalloc float[Bands];
        // Normal incidence: R = ((n − 1)/(n + 1))² = 0.04.
        Assert.True(glass.SampleMirror(Vector3.UnitZ, Vector3.UnitZ, -1, w, out var r));
        Assert.Equal(Vector3.UnitZ, r);
        for (int b = 0; b < Bands; b++) Assert.Equal(0.04f * k[b], w[b], 1e-6f);
        Assert.True(glass.SampleTransmission(Vector3.UnitZ, Vector3.UnitZ, -1, w, out var t));
        Assert.Equal(-Vector3.UnitZ, t);
        for (int b = 0; b < Bands; b++) Assert.Equal(0.96f * k[b], w[b], 1e-6f);
        // 30° from outside: sin θ_t = sin 30° / 1.5, bent towards the normal, on the far side.
        var wo = Incidence(30);
        Assert.True(glass.SampleTransmission(wo, Vector3.UnitZ, -1, w, out t));
        Assert.Equal(0.5 / 1.5, -t.X, 1e-6);
        Assert.True(t.Z < 0);
        // From inside at 60°: beyond the critical angle (41.8°), everything is reflected.
        var inside = -Incidence(60);
        Assert.False(glass.SampleTransmission(inside, Vector3.UnitZ, -1, w, out _));
        Assert.True(glass.SampleMirror(inside, Vector3.UnitZ, -1, w, out r));
        Assert.Equal(k[0], w[0], 1e-6f);
        Assert.Equal(Vector3.Dot(inside, Vector3.UnitZ), Vector3.Dot(r, Vector3.UnitZ), 1e-6f);
        // Without Fresnel the k_t share is sent along the mirror direction under total internal reflection.
        var plain = Eq2(Spectrum(0, 0, 0), Spectrum(0, 0, 0), mirror: k, transmit: k, ior: 1.5f).Bsdf;
        Assert.True(plain.SampleTransmission(inside, Vector3.UnitZ, -1, w, out t));
        Assert.Equal(r, t);
        Assert.Equal(k[1], w[1]);
        // No smooth lobe: nothing to sample or evaluate.
        Assert.False(glass.Sample(Vector3.UnitZ, Vector3.UnitZ, new Vector2(0.3f, 0.3f), w, out _));
        Assert.Equal(0f, glass.Pdf(Vector3.UnitZ, Vector3.UnitZ, Vector3.UnitZ));
    }
}
