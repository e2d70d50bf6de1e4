using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The physically based materials (issue 23) in the path integrator: a smooth metal at normal incidence against the
/// Fresnel formula from the measured n, k read here from data/; a rough lossless metal and a white plastic under a uniform
/// sky against the hemisphere integral of their BSDF (energy balances); the scene keys and their errors.
/// </summary>
public class PathMaterialTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static double Lerp(double[] x, double[] y, double v)
    {
        int i = Array.BinarySearch(x, v);
        if (i >= 0) return y[i];
        i = ~i;
        return y[i - 1] + (y[i] - y[i - 1]) * (v - x[i - 1]) / (x[i] - x[i - 1]);
    }

    static Scene Sky(string material, string bands = "400:700:10") => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "{{bands}}", "integrator": "path",
          "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "background": { "name": "D65", "scale": 0.01 },
          "materials": { "m": {{material}} },
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] }
        """);

    /// <summary>
    /// A smooth metal sphere under a uniform sky, seen along its normal: L = R(λ)·L_sky with R = ((n − 1)² + k²)/((n + 1)² + k²)
    /// at every wavelength, n and k interpolated linearly in the published table, band means at 0.01 nm here.
    /// </summary>
    [Theory]
    [InlineData("Au", "metals-johnson-christy-1972.csv")]
    [InlineData("silver", "metals-johnson-christy-1972.csv")]
    [InlineData("Cu", "metals-johnson-christy-1972.csv")]
    [InlineData("aluminium", "aluminium-rakic-1995.csv")]
    public void A_smooth_metal_at_normal_incidence_reflects_the_Fresnel_reflectance_of_its_n_and_k(string metal, string file)
    {
        string symbol = metal switch { "silver" => "Ag", "aluminium" => "Al", _ => metal };
        var scene = Sky($$"""{ "type": "conductor", "conductor": "{{metal}}" }""", "380:780:20");
        var (l, n, k) = MicrofacetTests.MetalTable(file, symbol);
        var (mean, _) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0, 0, 3), -Vector3.UnitZ), 4);
        var d65 = SpectrumLibrary.Resolve("D65");
        double worst = 0;
        for (int b = 0; b < scene.Bands; b++)
        {
            double expected = PathIntegratorTests.BandMean(x =>
            {
                double nx = Lerp(l, n, x), kx = Lerp(l, k, x);
                return ((nx - 1) * (nx - 1) + kx * kx) / ((nx + 1) * (nx + 1) + kx * kx) * 0.01 * d65.Evaluate(x);
            }, scene.Grid.Lower(b), scene.Grid.Upper(b));
            worst = Math.Max(worst, Math.Abs(mean[b] / expected - 1));
            Assert.True(Math.Abs(mean[b] - expected) < 2e-3 * expected, $"{metal} band {b}: {mean[b]:g6} vs R·L_sky = {expected:g6}");
        }
        output.WriteLine($"{metal}: largest relative difference over 20 bands {worst:e2}");
    }

    /// <summary>
    /// Under a uniform sky a convex surface returns its directional albedo times the sky: ∫ f cos θ dω·L_sky, the albedo by
    /// quadrature of the material's BSDF here. A lossless rough metal (n = 0, k = 1: R = 1) loses only what its
    /// microsurface masks; a plastic over a white base returns all of the sky. Next-event estimation of the sky and BSDF
    /// sampling are combined by MIS, so this checks both against the integral.
    /// </summary>
    [Theory]
    [InlineData("""{ "type": "conductor", "conductor": { "n": 0, "k": 1 }, "roughness": 0.3 }""", 35.0)]
    [InlineData("""{ "type": "conductor", "conductor": { "n": 0, "k": 1 }, "roughness": 0.8 }""", 60.0)]
    [InlineData("""{ "type": "plastic", "diffuse": 1, "roughness": 0.3 }""", 50.0)]
    [InlineData("""{ "type": "plastic", "diffuse": 1 }""", 50.0)]
    [InlineData("""{ "type": "plastic", "diffuse": 1, "ior": 1.4, "roughness": 0.05 }""", 20.0)]
    public void Under_a_uniform_sky_a_surface_returns_its_albedo_times_the_sky(string material, double theta)
    {
        var scene = Sky(material, "400:700:3");
        var bsdf = scene.Materials[0].Bsdf;
        // The ray meets the unit sphere where its normal is at θ from the reversed ray.
        double t = theta * Math.PI / 180;
        var p = new Vector3((float)Math.Sin(t), 0, (float)Math.Cos(t));
        var origin = new Vector3(p.X, 0, 3);
        var (mean, error) = PathIntegratorTests.Estimate(scene, new Ray(origin, -Vector3.UnitZ), 2000);
        // The albedo in the surface's frame: ωo at θ from n = +z.
        var wo = new Vector3(-(float)Math.Sin(t), 0, (float)Math.Cos(t));
        double albedo = 0, dt = Math.PI / 2 / 300, dp = 2 * Math.PI / 300;
        var f = new float[16];
        for (int i = 0; i < 300; i++)
            for (int j = 0; j < 300; j++)
            {
                double a = (i + 0.5) * dt, c = (j + 0.5) * dp;
                var wi = new Vector3((float)(Math.Sin(a) * Math.Cos(c)), (float)(Math.Sin(a) * Math.Sin(c)), (float)Math.Cos(a));
                bsdf.Evaluate(wo, wi, Vector3.UnitZ, f);
                albedo += f[0] * Math.Cos(a) * Math.Sin(a) * dt * dp;
            }
        var w = new float[16];
        if (bsdf.SampleMirror(wo, Vector3.UnitZ, -1, w, out _)) albedo += w[0];
        var d65 = SpectrumLibrary.Resolve("D65");
        for (int b = 0; b < scene.Bands; b++)
        {
            double sky = PathIntegratorTests.BandMean(x => 0.01 * d65.Evaluate(x), scene.Grid.Lower(b), scene.Grid.Upper(b));
            double expected = albedo * sky;
            output.WriteLine($"band {b}: {mean[b]:g5} ± {error[b]:g2} vs albedo {albedo:F4} × L_sky = {expected:g5}");
            Assert.True(Math.Abs(mean[b] - expected) < 4 * error[b] + 3e-3 * expected, $"band {b}: {mean[b]:g6} vs {expected:g6}");
        }
        if (material.Contains("plastic")) Assert.Equal(1, albedo, 4e-3);
    }

    [Fact]
    public void The_materials_render_with_both_integrators()
    {
        const string scene = """
        { "radiometry": "physical", "bands": "400:700:6", "integrator": "INTEGRATOR",
          "camera": { "position": [0, 1, 4], "look_at": [0, 0.5, 0], "width": 16, "height": 12, "spp": 2 },
          "background": { "name": "D65", "scale": 0.01 },
          "materials": { "gold": { "type": "conductor", "conductor": "gold", "roughness": 0.2 },
                         "copper": { "type": "conductor", "conductor": "Cu" },
                         "red": { "type": "plastic", "diffuse": "colorchecker:red", "roughness": 0.1 },
                         "blue": { "type": "plastic", "diffuse": "colorchecker:blue" } },
          "lights": [ { "type": "point", "position": [1, 3, 2], "spectrum": "D65", "intensity": 0.5 } ],
          "objects": [ { "type": "sphere", "center": [-0.6, 0.5, 0], "radius": 0.5, "material": "gold" },
                       { "type": "sphere", "center": [0.6, 0.5, 0], "radius": 0.5, "material": "copper" },
                       { "type": "sphere", "center": [0, 0.5, -1.2], "radius": 0.5, "material": "blue" },
                       { "type": "plane", "material": "red" } ] }
        """;
        foreach (var integrator in new[] { "path", "whitted" })
        {
            var result = SceneText.Render(scene.Replace("INTEGRATOR", integrator));
            double sum = 0;
            foreach (var v in result.Image.Data)
            {
                Assert.True(float.IsFinite(v) && v >= 0, $"{integrator}: {v}");
                sum += v;
            }
            Assert.True(sum > 0, integrator);
        }
    }

    static InputException Refused(string material) =>
        Assert.Throws<InputException>(() => Sky(material));

    [Theory]
    [InlineData("""{ "type": "conductor", "conductor": "Pt" }""", "$.materials.m.conductor", "unknown metal 'Pt'",
        "Au (gold), Ag (silver), Cu (copper), Al (aluminium)")]
    [InlineData("""{ "type": "conductor", "conductor": "Au", "roughness": 1.5 }""", "$.materials.m.roughness",
        "roughness 1.5 is out of range", "[0, 1]")]
    [InlineData("""{ "type": "conductor", "conductor": "Au", "roughness": -0.1 }""", "$.materials.m.roughness", "out of range", "smooth")]
    [InlineData("""{ "type": "conductor", "conductor": { "n": 1.2 } }""", "$.materials.m.conductor", "missing required field 'k'", "")]
    [InlineData("""{ "type": "conductor", "conductor": { "n": 0, "k": 0 } }""", "$.materials.m.conductor", "n and k are both 0",
        "measured n and k")]
    [InlineData("""{ "type": "conductor", "conductor": { "n": 1, "k": 2, "r": 3 } }""", "$.materials.m.conductor.r", "unknown field 'r'",
        "")]
    [InlineData("""{ "type": "conductor", "conductor": "Au", "diffuse": 0.5 }""", "$.materials.m.diffuse", "unknown field 'diffuse'",
        "roughness")]
    [InlineData("""{ "type": "conductor", "emission": { "spectrum": "D65" } }""", "$.materials.m", "missing required field 'conductor'",
        "")]
    [InlineData("""{ "model": "conductor", "conductor": "Au" }""", "$.materials.m.conductor", "unknown field 'conductor'", "")]
    [InlineData("""{ "model": "conductor" }""", "$.materials.m.model", "unknown specular model 'conductor'",
        "write \"type\": \"conductor\"")]
    [InlineData("""{ "type": "plastic", "diffuse": 0.5, "ior": 1 }""", "$.materials.m.ior", "a coat of index 1", "(1, 4]")]
    [InlineData("""{ "type": "plastic", "diffuse": 0.5, "roughness": 2 }""", "$.materials.m.roughness", "out of range", "[0, 1]")]
    [InlineData("""{ "type": "plastic", "diffuse": 50 }""", "$.materials.m.diffuse", "cannot exceed 1", "scale")]
    [InlineData("""{ "type": "plastic", "reflectance": 0.5 }""", "$.materials.m.reflectance", "unknown field 'reflectance'", "diffuse")]
    public void Materials_that_make_no_sense_are_refused_with_the_JSON_path_and_a_hint(string material, string where, string what,
        string hint)
    {
        var e = Refused(material);
        output.WriteLine(e.Message);
        Assert.Contains(where, e.Message);
        Assert.Contains(what, e.Message);
        Assert.Contains(hint, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }

    [Fact]
    public void A_bad_material_on_the_command_line_is_one_line_and_exit_2()
    {
        var dir = Reference.TempDir();
        var file = Path.Combine(dir, "scene.json");
        File.WriteAllText(file, """
        { "radiometry": "physical", "integrator": "path",
          "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "materials": { "m": { "type": "conductor", "conductor": "gld" } },
          "objects": [ { "type": "sphere", "radius": 1, "material": "m" } ] }
        """);
        var (code, _, err) = SpectralRenderer.Tests.Cli.CliRunner.Run("render", file, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains("scene.json:3:", err);
        Assert.Contains("$.materials.m.conductor", err);
        Assert.Contains("unknown metal 'gld'", err);
    }
}
