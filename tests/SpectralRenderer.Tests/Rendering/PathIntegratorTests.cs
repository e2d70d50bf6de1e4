using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path integrator against analytic radiance (issue 23, "How it is checked"): the white furnace, a diffuse plane under
/// a uniform sky, a Lambertian surface lit by a small spherical area light. Each reference is computed here from the
/// scene's spectra by quadrature at 0.01 nm, not by the engine's band projection.
/// </summary>
public class PathIntegratorTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>Mean and standard error per output band of <paramref name="n"/> path samples along one ray.</summary>
    internal static (double[] Mean, double[] Error) Estimate(Scene scene, Ray ray, int n, string integrator = "path")
    {
        var geometry = new SceneGeometry(scene);
        var path = Integrators.Create(scene, geometry, integrator);
        var result = new float[scene.PaddedBands];
        var scratch = new float[path.ScratchLength];
        var counters = new RayCounters();
        int bands = scene.Bands;
        var sum = new double[bands];
        var sum2 = new double[bands];
        for (int s = 0; s < n; s++)
        {
            path.Radiance(new CameraSample(s % 97, s / 97, s, ray), result, scratch, ref counters);
            for (int b = 0; b < bands; b++) { sum[b] += result[b]; sum2[b] += (double)result[b] * result[b]; }
        }
        var mean = new double[bands];
        var error = new double[bands];
        for (int b = 0; b < bands; b++)
        {
            mean[b] = sum[b] / n;
            error[b] = Math.Sqrt(Math.Max(0, sum2[b] / n - mean[b] * mean[b]) / (n - 1));
        }
        return (mean, error);
    }

    /// <summary>The mean of f over [lo, hi] by the midpoint rule at 0.01 nm (a second way to the band means).</summary>
    internal static double BandMean(Func<double, double> f, double lo, double hi)
    {
        int steps = (int)Math.Round((hi - lo) / 0.01);
        double s = 0, h = (hi - lo) / steps;
        for (int i = 0; i < steps; i++) s += f(lo + (i + 0.5) * h);
        return s / steps;
    }

    static double Lerp(double l, double a0, double a1) => a0 + (a1 - a0) * (l - 380) / 400;

    /// <summary>The white furnace: a closed sphere of albedo ρ(λ) emitting L_e(λ) on its inside.</summary>
    internal static Scene Furnace(string integrator) => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "380:780:20", "integrator": {{integrator}},
          "camera": { "position": [0, 0, 0], "look_at": [0, 0, -1], "width": 8, "height": 8 },
          "materials": { "wall": { "type": "lambertian", "reflectance": [[380, 0.2], [780, 0.8]],
                                   "emission": { "spectrum": [[380, 1], [780, 2]], "radiance": 1, "two_sided": true } } },
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wall" } ] }
        """);

    /// <summary>
    /// Every ray in the furnace sees L_e/(1 − ρ) (the Neumann series Σ ρ^k L_e of a uniformly lit closed Lambertian
    /// enclosure). ρ and L_e vary linearly over the range, so each band's value is the band mean of the ratio — not the ratio
    /// of band means (2e-3 apart at 20-nm bands where ρ = 0.8). Converged (Russian roulette only from depth 60, where
    /// ρ^60 ≤ 2e-6): to 1e-3 in every band. With roulette from depth 5 (the default): within 4 standard errors (unbiased).
    /// </summary>
    [Theory]
    [InlineData(60, 1e-3)]
    [InlineData(IntegratorSettings.DefaultRrDepth, 0)]
    public void White_furnace_radiance_is_Le_over_one_minus_albedo_in_every_band(int rrDepth, double tolerance)
    {
        var scene = Furnace($$"""{ "type": "path", "rr_depth": {{rrDepth}} }""");
        var (mean, error) = Estimate(scene, new Ray(new Vector3(0.1f, 0.2f, 0.3f), Vector3.Normalize(new Vector3(1, -2, 0.5f))), 20_000);
        var grid = scene.Grid;
        double worst = 0;
        for (int b = 0; b < grid.Count; b++)
        {
            double expected = BandMean(l => Lerp(l, 1, 2) / (1 - Lerp(l, 0.2, 0.8)), grid.Lower(b), grid.Upper(b));
            // Without the converged tolerance: 4 standard errors, plus 2e-4 for the 5-nm grid's ratio of sub-band means.
            double allowed = tolerance > 0 ? tolerance * expected : 4 * error[b] + 2e-4 * expected;
            worst = Math.Max(worst, Math.Abs(mean[b] / expected - 1));
            if (tolerance > 0)
                Assert.True(error[b] < tolerance * expected / 3,
                    $"band {b}: standard error {error[b]:g3} is too large to judge {tolerance:g}");
            Assert.True(Math.Abs(mean[b] - expected) < allowed,
                $"band {b}: {mean[b]:F5} vs L_e/(1 − ρ) = {expected:F5} (±{error[b]:g2}, {Math.Abs(mean[b] / expected - 1):e2} relative)");
        }
        output.WriteLine($"furnace, rr_depth {rrDepth}: largest relative error over the bands {worst:e2}");
    }

    [Fact]
    public void Diffuse_plane_under_a_uniform_sky_returns_albedo_times_sky_radiance()
    {
        // L = ρ·L_sky: the sky fills the plane's hemisphere (cos-weighted integral 1/π·π = 1).
        var scene = SceneText.Load("""
        { "radiometry": "physical", "bands": "400:700:10", "integrator": "path",
          "camera": { "position": [0, 1, 2], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "background": { "name": "D65", "scale": 0.01 },
          "materials": { "ground": { "type": "lambertian", "reflectance": "colorchecker:orange" } },
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "ground" } ] }
        """);
        var (mean, _) = Estimate(scene, new Ray(new Vector3(0, 1, 2), Vector3.Normalize(new Vector3(0.1f, -1, -2))), 2000);
        var d65 = SpectrumLibrary.Resolve("D65");
        var rho = SpectrumLibrary.Resolve("colorchecker:orange");
        for (int b = 0; b < scene.Bands; b++)
        {
            double expected = BandMean(l => rho.Evaluate(l) * 0.01 * d65.Evaluate(l), scene.Grid.Lower(b), scene.Grid.Upper(b));
            Assert.True(Math.Abs(mean[b] - expected) < 2e-3 * expected, $"band {b}: {mean[b]:g6} vs ρ·L_sky = {expected:g6}");
        }
    }

    [Fact]
    public void Lambertian_surface_under_a_small_sphere_light_follows_the_irradiance_formula()
    {
        // A sphere of radius r and radiance L seen from a point at distance d, its centre at angle θ from the normal and
        // wholly above the horizon: E = π·L·(r/d)²·cos θ, so a Lambertian surface of albedo ρ returns ρ·L·(r/d)²·cos θ.
        var scene = SceneText.Load("""
        { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
          "camera": { "position": [0, 1, 4], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "materials": { "ground": { "type": "lambertian", "reflectance": 0.5 },
                         "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 2 } } },
          "objects": [ { "type": "plane", "material": "ground" },
                       { "type": "sphere", "center": [0.6, 1.5, 0], "radius": 0.1, "material": "lamp" } ] }
        """);
        var target = new Vector3(0, 0, 0);
        var origin = new Vector3(0, 1, 4);
        var (mean, error) = Estimate(scene, new Ray(origin, Vector3.Normalize(target - origin)), 4000);
        double dx = 0.6, h = 1.5, r = 0.1, d2 = dx * dx + h * h, d = Math.Sqrt(d2);
        var d65 = SpectrumLibrary.Resolve("D65");
        for (int b = 0; b < scene.Bands; b++)
        {
            double le = BandMean(l => 2 * d65.Evaluate(l), scene.Grid.Lower(b), scene.Grid.Upper(b));
            double expected = 0.5 * le * r * r / d2 * (h / d);
            Assert.True(Math.Abs(mean[b] - expected) < 3e-3 * expected,
                $"band {b}: {mean[b]:g6} vs ρ·L·(r/d)²·cos θ = {expected:g6} (±{error[b]:g2})");
        }
    }

    [Fact]
    public void Paper_radiometry_is_refused_with_a_hint()
    {
        var scene = SceneText.Load("""
        { "integrator": "path", "camera": { "position": [0, 1, 4], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "lights": [ { "type": "point", "position": [0, 3, 0], "spectrum": "D65" } ],
          "objects": [ { "type": "plane", "material": "colorchecker:white" } ] }
        """);
        var e = Assert.Throws<InputException>(() => Integrators.Create(scene, new SceneGeometry(scene), "path"));
        Assert.Contains("physical", e.Message);
    }

    [Fact]
    public void Emission_needs_physical_radiometry()
    {
        var e = Assert.Throws<InputException>(() => SceneText.Load("""
        { "camera": { "position": [0, 1, 4], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "materials": { "lamp": { "diffuse": 0, "emission": { "spectrum": "D65" } } },
          "objects": [ { "type": "sphere", "material": "lamp" } ] }
        """));
        Assert.Contains("$.materials.lamp.emission", e.Message);
    }

    [Fact]
    public void An_emitting_infinite_plane_is_refused()
    {
        var scene = SceneText.Load("""
        { "radiometry": "physical", "integrator": "path", "camera": { "position": [0, 1, 4], "look_at": [0, 0, 0], "width": 8,
          "height": 8 },
          "materials": { "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65" } } },
          "objects": [ { "type": "plane", "material": "lamp" } ] }
        """);
        var e = Assert.Throws<InputException>(() => Integrators.Create(scene, new SceneGeometry(scene), "path"));
        Assert.Contains("infinite plane", e.Message);
    }
}
