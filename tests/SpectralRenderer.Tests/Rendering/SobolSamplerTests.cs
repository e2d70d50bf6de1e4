using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The Owen-scrambled Sobol sampler (issue 23): its points are nets (the stratification that makes it low-discrepancy), its
/// error on smooth analytic integrals falls well below independent random numbers, its dimensions are uncorrelated, and it
/// depends on (pixel, sample, dimension, seed) only.
/// </summary>
public class SobolSamplerTests
{
    static readonly SamplerSettings Sobol = new(SamplerKind.Sobol);

    /// <summary>The (0, m, 2)-net property: every elementary interval of area 1/2^m holds exactly one of the first 2^m points.</summary>
    [Theory]
    [InlineData(0, 4)]
    [InlineData(2, 6)]
    [InlineData(10, 8)]
    public void The_first_power_of_two_samples_of_a_dimension_pair_are_a_net(int dimension, int m)
    {
        int n = 1 << m;
        foreach (var (x, y) in new[] { (0, 0), (5, 9), (123, 77) })
        {
            // The pixel's randomisation g holds its samples g, g + R, g + 2R, … (R = Sampler.Randomisations): its own net.
            int g = (x + y) % Sampler.Randomisations;
            var points = new (float U, float V)[n];
            for (int s = 0; s < n; s++) points[s] = new Sampler(x, y, s * Sampler.Randomisations + g, dimension, Sobol).Next2D();
            for (int a = 0; a <= m; a++)
            {
                // intervals 2^-a wide and 2^-(m-a) high
                var seen = new bool[n];
                foreach (var (u, v) in points)
                {
                    int cell = (int)(u * (1 << a)) * (1 << (m - a)) + (int)(v * (1 << (m - a)));
                    Assert.False(seen[cell], $"pixel {x},{y} dimension {dimension}: two points in interval {cell} of 2^{a} × 2^{m - a}");
                    seen[cell] = true;
                }
            }
        }
    }

    /// <summary>RMS error over many pixels of the n-sample mean of f(u, v) = e^u·sin(πv), ∫ = (e − 1)·2/π.</summary>
    static double RmsError(SamplerSettings settings, int n, int dimension)
    {
        double exact = (Math.E - 1) * 2 / Math.PI, sum2 = 0;
        const int pixels = 64;
        for (int p = 0; p < pixels; p++)
        {
            double sum = 0;
            for (int s = 0; s < n; s++)
            {
                var sampler = new Sampler(p % 8, p / 8, s, dimension, settings);
                // two 1D draws for the independent sampler; a 2D pair for Sobol
                var (u, v) = sampler.Next2D();
                sum += Math.Exp(u) * Math.Sin(Math.PI * v);
            }
            double e = sum / n - exact;
            sum2 += e * e;
        }
        return Math.Sqrt(sum2 / pixels);
    }

    [Fact]
    public void Its_error_on_a_smooth_integral_falls_far_below_independent_random_numbers()
    {
        // n samples are R = 8 independent randomisations of n/8 points each (Sampler.Randomisations).
        foreach (int n in new[] { 64, 1024 })
        {
            double sobol = RmsError(Sobol, n, 4), random = RmsError(SamplerSettings.Independent, n, 4);
            // Independent: σ/√n (σ ≈ 0.53 for this f); scrambled Sobol: O(n^-3/2) for smooth f (Owen 1997).
            Assert.InRange(random * Math.Sqrt(n), 0.3, 0.8);
            Assert.True(sobol < random / (n == 64 ? 3 : 10), $"n = {n}: Sobol RMS error {sobol:G3} against independent {random:G3}");
        }
        // Convergence order: from 64 to 1024 samples the Sobol error falls by far more than √16 = 4.
        Assert.True(RmsError(Sobol, 1024, 4) < RmsError(Sobol, 64, 4) / 12);
    }

    [Fact]
    public void Different_dimensions_are_uncorrelated_and_uniform()
    {
        // E[(u − ½)(v − ½)] = 0 for independent u, v; E[u] = ½; checked over 64 pixels × 64 samples for 1D draws 2, 3 and a
        // 2D pair after them, whose shuffles must decorrelate the shared sample index.
        double cross = 0, mean = 0, cross2 = 0;
        int count = 0;
        for (int p = 0; p < 64; p++)
            for (int s = 0; s < 64; s++)
            {
                var sampler = new Sampler(p, 3, s, 2, Sobol);
                float a = sampler.Next1D(), b = sampler.Next1D();
                var (c, d) = sampler.Next2D();
                cross += (a - 0.5) * (b - 0.5);
                cross2 += (a - 0.5) * (c - 0.5) + (b - 0.5) * (d - 0.5);
                mean += a + b + c + d;
                count++;
            }
        // Under independence each mean of 4096 products has standard deviation 1/12/√4096 ≈ 0.0013.
        Assert.InRange(cross / count, -0.006, 0.006);
        Assert.InRange(cross2 / count / 2, -0.006, 0.006);
        Assert.InRange(mean / count / 4, 0.495, 0.505);
    }

    [Fact]
    public void Its_numbers_depend_on_pixel_sample_dimension_and_seed_only()
    {
        var a = new Sampler(3, 4, 5, 6, Sobol);
        var b = new Sampler(3, 4, 5, 6, Sobol);
        Assert.Equal(a.Next1D(), b.Next1D());
        Assert.Equal(a.Next2D(), b.Next2D());
        Assert.NotEqual(new Sampler(3, 4, 5, 6, Sobol).Next1D(), new Sampler(4, 4, 5, 6, Sobol).Next1D());
        Assert.NotEqual(new Sampler(3, 4, 5, 6, Sobol).Next1D(),
            new Sampler(3, 4, 5, 6, new SamplerSettings(SamplerKind.Sobol, 1)).Next1D());
        // The independent sampler with seed 0 is the one every render before seeds used.
        Assert.Equal(new Sampler(3, 4, 5).Next2D(), new Sampler(3, 4, 5, 0, SamplerSettings.Independent).Next2D());
        Assert.NotEqual(new Sampler(3, 4, 5).Next2D(), new Sampler(3, 4, 5, 0, new SamplerSettings(SamplerKind.Independent, 7)).Next2D());
    }

    [Fact]
    public void The_path_integrator_uses_Sobol_by_default_and_the_scene_can_choose()
    {
        string Scene(string integrator) => $$"""
            { "radiometry": "physical", "bands": "400:700:3", "integrator": {{integrator}},
              "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 8, "height": 8, "spp": 4 },
              "background": 0.5, "materials": { "m": { "type": "lambertian", "reflectance": 0.5 } },
              "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] }
            """;
        IIntegrator Make(string integrator)
        {
            var scene = SceneText.Load(Scene(integrator));
            return Integrators.Create(scene, new SceneGeometry(scene), "path");
        }
        Assert.Equal(new SamplerSettings(SamplerKind.Sobol), Make("\"path\"").Sampler);
        Assert.Equal(new SamplerSettings(SamplerKind.Independent, 3),
            Make("""{ "type": "path", "sampler": "independent", "seed": 3 }""").Sampler);
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            SceneText.Load(Scene("""{ "type": "path", "sampler": "sobl" }""")));
        Assert.Contains("$.integrator.sampler", e.Message);
        Assert.Contains("sobol", e.Message);
        // Whitted keeps the independent sampler (its pictures do not change).
        var w = SceneText.Load(Scene("\"whitted\""));
        Assert.Equal(SamplerSettings.Independent, Integrators.Create(w, new SceneGeometry(w), "whitted").Sampler);
    }
}
