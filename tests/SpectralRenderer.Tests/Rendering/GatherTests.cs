using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Rendering.Registry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The illuminance gather under the path integrator (issue 42): next-event estimation and MIS through the emitter set,
/// against the analytic illuminance under a uniform Lambertian rectangle, E = π·L_v·F, F the form factor from a
/// differential area to a parallel rectangle (the sum of the four corner terms of the differential-area-to-rectangle
/// factor, as in Howell's catalogue of radiation configuration factors).
/// </summary>
public class GatherTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const double Luminance = 1000, Height = 1.5;

    /// <summary>A 2 × 1 m panel of luminance 1000 cd/m² facing down at 1.5 m over a 13 × 13 grid on a 3 × 2 m floor area.</summary>
    static string PanelScene(int spp) => $$"""
        { "radiometry": "physical", "bands": "380:780:80", "integrator": "path",
          "camera": { "position": [0, 0.5, 4], "look_at": [0, 0.5, 0], "width": 4, "height": 4, "spp": {{spp}} },
          "materials": { "panel": { "type": "lambertian", "reflectance": 0,
            "emission": { "spectrum": "D65", "luminance": {{Luminance}} } } },
          "objects": [ { "type": "quad", "center": [0, {{Height}}, 0], "size": [2, 1], "normal": [0, -1, 0], "up": [0, 0, -1],
            "material": "panel" } ],
          "calculation_grids": [ { "name": "floor", "origin": [-1.5, 0, 1], "u": [3, 0, 0], "v": [0, 0, -2], "points": [13, 13] } ] }
        """;

    /// <summary>The factor from a differential area facing up at the origin to the rectangle [0, a] × [0, b] at height h
    /// above it (parallel), odd in a and in b.</summary>
    static double Corner(double a, double b, double h)
    {
        double ra = Math.Sqrt(a * a + h * h), rb = Math.Sqrt(b * b + h * h);
        return (a / ra * Math.Atan(b / ra) + b / rb * Math.Atan(a / rb)) / (2 * Math.PI);
    }

    /// <summary>E = π·L_v·F at (x, z) under the panel [−1, 1] × [−0.5, 0.5].</summary>
    static double Analytic(double x, double z)
    {
        double F = Corner(1 - x, 0.5 - z, Height) - Corner(-1 - x, 0.5 - z, Height) - Corner(1 - x, -0.5 - z, Height)
            + Corner(-1 - x, -0.5 - z, Height);
        return Math.PI * Luminance * F;
    }

    [Fact]
    public void A_13_by_13_grid_under_a_panel_is_within_5_percent_RMS_of_the_rectangle_formula_and_its_error_column_is_right()
    {
        var scene = SceneText.Load(PanelScene(spp: 1));
        var geometry = new SceneGeometry(scene);
        var gather = (IGatherIntegrator)Integrators.Create(scene, geometry, "path");
        var grid = scene.CalculationGrids[0];
        var result = new Illuminance(scene, geometry).OnGridWithError(grid, gather, 2, 0, 0, null);
        var points = grid.Points();
        double real2 = 0, reported2 = 0, relative2 = 0;
        for (int k = 0; k < points.Length; k++)
        {
            double e = Analytic(points[k].X, points[k].Z), d = result.Lux[k] - e;
            real2 += d * d;
            relative2 += d * d / (e * e);
            reported2 += result.StandardError![k] * result.StandardError[k];
            Assert.Equal(Illuminance.GatherRays(scene), result.Rays[k]);
        }
        double rms = Math.Sqrt(relative2 / points.Length), ratio = Math.Sqrt(reported2 / real2);
        output.WriteLine($"default gather ({Illuminance.GatherRays(scene)} rays): RMS relative error {rms:P3}, " +
            $"RMS reported/real error {ratio:F3}; centre {result.Lux[84]:F2} lx, analytic {Analytic(points[84].X, points[84].Z):F2} lx");
        Assert.InRange(rms, 0, 0.05);
        Assert.InRange(ratio, 0.8, 1.25);
    }
}
