using System.Globalization;
using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// Beer–Lambert in both integrators: a uniform sky of radiance L_e (a diffuse emitter filling the view) seen through a
/// box of pure water (σ_a = the built-in "water", Pope &amp; Fry 1997 / Smith &amp; Baker 1981, strongly chromatic: 0.0044
/// to 2.5 per metre) of thickness d = 1 m is L_e·exp(−σ̄_a,b·d) in every 5 nm band b from 380 to 780 nm, σ̄_a,b the band
/// mean of the table — computed here from data/water-absorption.csv by integrating its straight pieces exactly, a second
/// way to the band means. The box is bounded by an index-matched surface (a null boundary) or by a Fresnel dielectric of
/// index 1.333 (a glass of water), where the reflections enter the expected value in closed form.
/// </summary>
public class BeerLambertTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const double Le = 2, D = 1;

    static Scene WaterBox(string boundary, int maxDepth) => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "380:780:80", "max_depth": {{maxDepth}},
          "integrator": { "type": "path", "spectral_grid": 5, "rr_depth": 1000, "sampler": "independent" },
          "background": "constant:{{Le}}",
          "camera": { "position": [0, 0, -3], "look_at": [0, 0, 0] },
          "materials": { "boundary": {{boundary}} },
          "objects": [ { "type": "box", "center": [0, 0, 0], "size": [2, 2, {{D}}], "material": "boundary",
                         "medium": { "sigma_a": "water" } } ] }
        """);

    static readonly Ray Straight = new(new Vector3(0.1f, 0.05f, -3), Vector3.UnitZ);

    /// <summary>exp(−σ̄_a·d) per 5 nm band from 380 nm, σ̄_a the band mean of the table's piecewise-linear σ_a(λ).</summary>
    static double[] Transmittance()
    {
        var rows = File.ReadAllLines(Path.Combine(Repo.Root, "data", "water-absorption.csv")).Skip(1)
            .Select(l => l.Split(',')).Select(c => (X: double.Parse(c[0], CultureInfo.InvariantCulture),
                Y: double.Parse(c[1], CultureInfo.InvariantCulture))).ToArray();
        double Integral(double lo, double hi)
        {
            double sum = 0;
            for (int i = 0; i + 1 < rows.Length; i++)
            {
                double a = Math.Max(lo, rows[i].X), b = Math.Min(hi, rows[i + 1].X);
                if (b <= a) continue;
                double Y(double x) => rows[i].Y + (rows[i + 1].Y - rows[i].Y) * (x - rows[i].X) / (rows[i + 1].X - rows[i].X);
                sum += (b - a) * (Y(a) + Y(b)) / 2;   // a straight piece: the trapezoid is exact
            }
            return sum;
        }
        return Enumerable.Range(0, 80).Select(b => Math.Exp(-Integral(380 + 5 * b, 385 + 5 * b) / 5 * D)).ToArray();
    }

    [Theory]
    [InlineData("whitted")]
    [InlineData("path")]
    public void Pure_water_through_a_null_boundary_is_L_e_exp_minus_sigma_a_d_in_every_band(string integrator)
    {
        var (seen, _) = PathIntegratorTests.Estimate(WaterBox("{ \"transmit\": 1, \"ior\": 1 }", 8), Straight, 4, integrator);
        var t = Transmittance();
        Assert.True(t.Min() < 0.1 && t.Max() > 0.99);   // strongly chromatic: the red is gone, the blue passes
        double worst = 0;
        for (int b = 0; b < 80; b++)
        {
            double expected = Le * t[b];
            worst = Math.Max(worst, Math.Abs(seen[b] - expected) / expected);
            Assert.True(Math.Abs(seen[b] - expected) <= 1e-4 * expected, $"band {b}: {seen[b]} vs {expected}");
        }
        output.WriteLine($"{integrator}: largest relative error over 80 bands {worst:g3}; T from {t.Min():g4} to {t.Max():g6}");
    }

    /// <summary>
    /// A glass of water at normal incidence: the front face reflects R = ((n − 1)/(n + 1))² of the sky, the rest enters, crosses
    /// the water (T), and leaves through the back face ((1 − R) again); inside, light bounces between the faces and leaves
    /// through either, and the sky is L_e on both sides. Inside, the radiance X going forward and Y going back obey
    /// X = T·[(1 − R)·L_e + R·Y] and Y = T·[(1 − R)·L_e + R·X], so X = Y = T(1 − R)·L_e/(1 − RT) and the path tracer's
    /// L = L_e·[R + (1 − R)²·T/(1 − RT)] (L_e at T = 1: lossless glass in a uniform sky is invisible). Whitted to depth 2
    /// keeps the reflection and the straight crossing, L = L_e·[R + (1 − R)²·T]. Radiance scales by n² going in, 1/n² out.
    /// </summary>
    [Theory]
    [InlineData("whitted", 2)]
    [InlineData("path", 64)]
    public void A_glass_of_water_is_its_fresnel_reflections_and_the_water_s_transmittance(string integrator, int depth)
    {
        const double n = 1.333, r = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
        var scene = WaterBox($"{{ \"mirror\": 1, \"transmit\": 1, \"ior\": {n}, \"fresnel\": true }}", depth);
        var (seen, error) = PathIntegratorTests.Estimate(scene, Straight, integrator == "path" ? 20000 : 2, integrator);
        var t = Transmittance();
        for (int b = 0; b < 80; b += 5)
        {
            double expected = integrator == "whitted" ? Le * (r + (1 - r) * (1 - r) * t[b])
                : Le * (r + (1 - r) * (1 - r) * t[b] / (1 - r * t[b]));
            output.WriteLine($"{integrator}, band {b}: {seen[b]:g6} ± {error[b]:g3} vs {expected:g6}");
            Assert.True(Math.Abs(seen[b] - expected) <= 3 * error[b] + 1e-4 * expected, $"band {b}: {seen[b]} vs {expected}");
        }
    }
}
