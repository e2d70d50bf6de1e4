using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Validation;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The CIE standard overcast sky (<c>"distribution": "cie-overcast"</c>): its emitter's density integrates to 1 and is the
/// density of its draws, its power is ∫L dω·πR²; camera rays see L_z·(1 + 2 cos θ)/3 and nothing below the horizon; a
/// Lambertian plane under it shines at ρ/π·(7π/9)·L_z (path tracing: next-event estimation and escaping rays under MIS); the
/// path-traced gather measures (7π/9)·L_z; bad input and the whitted integrator are refused in one line.
/// </summary>
public class OvercastSkyTests
{
    static double G(double mu) => mu > 0 ? (1 + 2 * mu) / 3 : 0;

    static readonly Vector3[] Fronts =
        [Vector3.UnitY, Vector3.UnitX, Vector3.Normalize(new Vector3(1, 1, 0.3f)), Vector3.Normalize(new Vector3(0.2f, -1, 0.5f)),
            Vector3.Zero];

    /// <summary>∫ f dω over the sphere by the midpoint rule in (cos θ, φ) about +Y, n × 2n cells.</summary>
    static double Sphere(Func<Vector3, double> f, int n = 400)
    {
        double sum = 0;
        for (int i = 0; i < n; i++)
        {
            double mu = -1 + (i + 0.5) * 2 / n, s = Math.Sqrt(1 - mu * mu);
            for (int j = 0; j < 2 * n; j++)
            {
                double phi = (j + 0.5) * Math.PI / n;
                sum += f(new Vector3((float)(s * Math.Cos(phi)), (float)mu, (float)(s * Math.Sin(phi))));
            }
        }
        return sum * (2.0 / n) * (Math.PI / n);
    }

    [Fact]
    public void Its_density_integrates_to_one_and_is_that_of_its_draws_and_its_power_is_the_skys_radiance_through_the_disc()
    {
        var sky = new OvercastSkyEmitter([1f], Vector3.UnitY);
        foreach (var front in Fronts)
            Assert.Equal(1, Sphere(w => sky.Pdf(default, front, w, default, default)), 2e-4);
        Assert.Equal(4 * Math.PI / 3, Sphere(w => sky.Emitted(default, -w)), 2e-4);
        Assert.Equal(Sphere(w => sky.Emitted(default, -w)) * Math.PI * 4, sky.PowerPerRadiance(2), 2e-3);
        Assert.Equal(1, sky.Emitted(default, -Vector3.UnitY), 1e-7);
        Assert.Equal((1 + 2 * 1e-3) / 3, sky.Emitted(default, -Vector3.Normalize(new Vector3(1, 1e-3f, 0))), 1e-6);
        Assert.Equal(0, sky.Emitted(default, Vector3.Normalize(new Vector3(1, 0.01f, 0))));
        Assert.Equal(0, sky.Emitted(default, -Vector3.UnitX));   // the horizon itself: the sky's edge, nothing
        // Each draw's density and factor are Pdf's and g's; the mean of g·cos/p estimates the closed forms.
        var random = new Random(43);
        foreach (var (front, expected) in new[] { (Vector3.UnitY, 7 * Math.PI / 9), (Vector3.UnitX, Math.PI / 6 + 4.0 / 9) })
        {
            const int n = 200_000;
            double s1 = 0, s2 = 0;
            for (int i = 0; i < n; i++)
            {
                var u = new Vector2(random.NextSingle(), random.NextSingle());
                if (!sky.Sample(default, front, u, out var s)) continue;
                Assert.Equal(sky.Pdf(default, front, s.Direction, default, default), s.Pdf, s.Pdf * 1e-5);
                Assert.Equal(G(s.Direction.Y), s.Factor, 1e-5);
                Assert.True(s.Direction.Y > 0);
                double v = s.Factor * Math.Max(0, Vector3.Dot(front, s.Direction)) / s.Pdf;
                s1 += v;
                s2 += v * v;
            }
            double mean = s1 / n, sigma = Math.Sqrt((s2 / n - mean * mean) / n);
            Assert.InRange(Math.Abs(mean - expected), 0, 4 * sigma);
            Assert.InRange(sigma / expected, 0, 3e-3);   // so the check above resolves ~1 %
        }
    }

    static string Scene(string camera, string objects = "") => $$"""
        { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
          "camera": {{camera}},
          "sky": { "type": "daylight", "cct": 6504, "luminance": 3000, "distribution": "cie-overcast", "zenith": [0, 0, 1] },
          "materials": { "board": { "type": "lambertian", "reflectance": 0.5 } },
          "objects": [ { "type": "sphere", "center": [0, 0, -100], "radius": 1, "material": "board" }{{objects}} ] }
        """;

    [Theory]
    [InlineData(90)]
    [InlineData(30)]
    [InlineData(2)]
    [InlineData(-10)]
    public void A_camera_ray_that_escapes_sees_the_zenith_radiance_times_the_gradation_and_nothing_below_the_horizon(double elevation)
    {
        // The zenith turned to +Z: a camera ray at elevation α sees L_z·(1 + 2 sin α)/3 (the pixels within 0.001° of α: g
        // within 2e-5 of its value there).
        double a = elevation * Math.PI / 180;
        var look = new Vector3((float)Math.Cos(a), 0, (float)Math.Sin(a));
        var scene = SceneText.Load(Scene($$"""
            { "position": [0, 0, 0], "look_at": [{{look.X}}, {{look.Y}}, {{look.Z}}], "up": [0, 1, 0], "fov": 0.002,
              "width": 2, "height": 2, "spp": 1 }
            """.Replace(",", ", ")));
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
        for (int b = 0; b < scene.Bands; b++)
            for (int i = 0; i < 4; i++)
                Assert.Equal(G(Math.Sin(a)) * scene.Background[b], r.Image.Data[i * scene.Bands + b], scene.Background[b] * 1e-4);
    }

    [Fact]
    public void A_lambertian_plane_under_it_shines_at_rho_times_seven_ninths_of_the_zenith_radiance()
    {
        var scene = SceneText.Load(Scene("""
            { "position": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 20, "width": 8, "height": 8, "spp": 256 }
            """, """, { "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "board" }"""));
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
        for (int b = 0; b < scene.Bands; b++)
        {
            double mean = 0;
            for (int i = 0; i < 64; i++) mean += r.Image.Data[i * scene.Bands + b] / 64;
            Assert.Equal(0.5 * 7.0 / 9 * scene.Background[b], mean, scene.Background[b] * 0.5 * 7.0 / 9 * 5e-3);
        }
    }

    [Fact]
    public void The_path_traced_gather_measures_seven_ninths_pi_times_the_zenith_luminance()
    {
        var scene = SceneText.Load(Scene("""
            { "position": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0], "width": 2, "height": 2, "spp": 256 }
            """));
        var e = CaseScenes.Gathered(scene, [(new Vector3(0, 0, 0), Vector3.UnitZ), (new Vector3(3, 1, 0), Vector3.UnitZ)], 4,
            new CaseContext(true, 2, default));
        foreach (var (mean, sigma) in e)
        {
            Assert.InRange(Math.Abs(mean - 7 * Math.PI / 9 * 3000), 0, 3 * sigma + 1e-3 * mean);
            Assert.InRange(sigma, 0, 2e-3 * mean);
        }
    }

    [Fact]
    public void The_whitted_integrator_and_an_unknown_distribution_are_refused_in_one_line()
    {
        var scene = SceneText.Load(Scene("""{ "position": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0] }"""));
        var e = Assert.Throws<InputException>(() => Integrators.Create(scene, new SceneGeometry(scene), "whitted"));
        Assert.Contains("$.sky.distribution", e.Message);
        Assert.Contains("path", e.Hint);
        Assert.DoesNotContain('\n', e.Message);
        e = Assert.Throws<InputException>(() => SceneText.Load(Scene("""{ "position": [0, 0, 1], "look_at": [0, 0, 0] }""")
            .Replace("cie-overcast", "overcast")));
        Assert.Contains("$.sky.distribution: unknown sky distribution 'overcast'", e.Message);
    }
}
