using System.Globalization;
using System.Numerics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The illuminance's direct share comes from the emitter set (Illuminance.Direct): an emitting disk lights a calculation
/// grid without a gather (the Whitted integrator), E_v = πL_v·r²/(r² + h²) on its axis at four heights (the disk's form
/// factor), and a point light beside it adds its I·cos³θ/h²; a roof between them blocks the disk.
/// </summary>
public class EmitterIlluminanceTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    const double R = 0.5, Lv = 100, I = 50;
    static readonly Vector3 Lamp = new(3, 1.5f, 0);   // its rays pass beside the disk and the roof

    static Scene Load(double height, bool roof = false)
    {
        var dir = Reference.TempDir();
        string roofObject = roof
            ? ", { \"type\": \"quad\", \"name\": \"roof\", \"center\": [0, 0.5, 0], \"size\": 0.6, \"normal\": [0, 1, 0], "
                + "\"up\": [0, 0, -1], \"material\": \"grey\" }"
            : "";
        File.WriteAllText(Path.Combine(dir, "scene.json"), $$"""
            { "radiometry": "physical", "bands": "380:780:40",
              "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 4, "height": 4 },
              "materials": {
                "grey": { "diffuse": 0.5 },
                "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "E", "luminance": {{F(Lv)}} } } },
              "lights": [ { "type": "point", "name": "bulb", "position": [{{F(Lamp.X)}}, {{F(Lamp.Y)}}, {{F(Lamp.Z)}}],
                "spectrum": "D65", "luminous_intensity": {{F(I)}} } ],
              "objects": [
                { "type": "disk", "name": "disk", "center": [0, {{F(height)}}, 0], "radius": {{F(R)}}, "normal": [0, -1, 0],
                  "up": [0, 0, 1], "material": "lamp" }{{roofObject}} ] }
            """);
        return SceneLoader.Load(Path.Combine(dir, "scene.json"));
    }

    [Theory]
    [InlineData(0.25)]
    [InlineData(0.5)]
    [InlineData(1.0)]
    [InlineData(2.0)]
    public void An_emitting_disk_lights_a_grid_on_its_axis_by_its_form_factor_beside_a_point_light(double h)
    {
        var scene = Load(h);
        var illuminance = new Illuminance(scene, new SceneGeometry(scene));
        // 24 × 24 points within 0.1 mm of the axis, facing up (u × v = +y): the disk's E is the same at each to 1e-7.
        var grid = new CalculationGrid("axis", new Vector3(-5e-5f, 0, 5e-5f), new Vector3(1e-4f, 0, 0), new Vector3(0, 0, -1e-4f),
            24, 24);
        var lux = illuminance.OnGrid(grid, null, threads: 2);
        var disk = new double[lux.Length];
        for (int i = 0; i < 24; i++)
            for (int j = 0; j < 24; j++)
            {
                // The point light's share, I·cos θ/d² = I·cos³θ/h_p² (h_p its height above the grid, θ from the normal).
                var toLamp = Lamp - grid.Point(i, j);
                double d2 = toLamp.LengthSquared(), cos = toLamp.Y / Math.Sqrt(d2);
                disk[j * 24 + i] = lux[j * 24 + i] - I * cos / d2;
            }
        double mean = disk.Average(), sigma = Math.Sqrt(disk.Sum(e => (e - mean) * (e - mean)) / (disk.Length - 1) / disk.Length);
        double exact = Math.PI * Lv * R * R / (R * R + h * h);
        output.WriteLine($"h {h}: E {mean:G6} ± {sigma:E2} lx, πL·r²/(r² + h²) {exact:G6} lx");
        Assert.InRange(mean, exact - 3 * sigma - 1e-4 * exact, exact + 3 * sigma + 1e-4 * exact);
        Assert.True(sigma < 0.02 * exact, $"σ {sigma} too large to tell");
    }

    [Fact]
    public void A_roof_between_the_disk_and_the_grid_leaves_the_point_lights_share()
    {
        var scene = Load(1, roof: true);
        var illuminance = new Illuminance(scene, new SceneGeometry(scene));
        var grid = new CalculationGrid("axis", new Vector3(-5e-3f, 0, 5e-3f), new Vector3(1e-2f, 0, 0), new Vector3(0, 0, -1e-2f), 4, 4);
        var lux = illuminance.OnGrid(grid, null, threads: 1);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
            {
                var toLamp = Lamp - grid.Point(i, j);
                double d2 = toLamp.LengthSquared(), point = I * (toLamp.Y / Math.Sqrt(d2)) / d2;
                Assert.Equal(point, lux[j * 4 + i], point * 1e-5);
            }
    }
}
