using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Color;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Spectral textures in the path integrator (issue 26): the 24 ColorChecker reflectances of the reference table
/// (data/colorchecker-ohta.csv) as an ENVI cube on one flat quad, rendered with direct light only (max_depth 1), against
/// 24 untextured quads of the same spectra given inline — every band and X, Y, Z at each patch centre to float rounding;
/// under a uniform sky (its radiance the same at every wavelength) against the analytic ρ·L_sky, ρ's band mean
/// integrated here from the table's straight segments.
/// </summary>
public class PathTextureTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const int PerPatch = SpectralTextureTests.PerPatch;

    static string Scene(string objects, string light, string background, string materials = "{}") => $$"""
        {
          "bands": "380:780:20", "integration": "exact", "radiometry": "physical", "white": "D65",
          "integrator": { "type": "path", "max_depth": 1 },
          "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
          "lights": [ {{light}} ],
          "materials": {{materials}},
          "objects": [ {{objects}} ],
          "background": {{background}}
        }
        """;

    const string Directional = """{ "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 0.03 }""";
    const string Point = """{ "type": "point", "position": [1, 2, 6], "spectrum": "A", "intensity": 1 }""";

    /// <summary>The 24 patches as untextured unit quads, each material given inline (<paramref name="material"/> of its spectrum pairs).</summary>
    static string UntexturedObjects(double[] wl, double[][] patches, Func<string, string> material)
    {
        var inv = CultureInfo.InvariantCulture;
        var objects = new StringBuilder();
        for (int p = 0; p < 24; p++)
        {
            var pairs = string.Join(", ", wl.Select((l, j) => $"[{l.ToString(inv)}, {((float)patches[p][j]).ToString("R", inv)}]"));
            if (p > 0) objects.Append(", ");
            objects.Append(inv, $$"""{ "type": "quad", "center": [{{p % 6 - 2.5}}, {{1.5 - p / 6}}, 0], "size": 1, "material": {{material($"[{pairs}]")}} }""");
        }
        return objects.ToString();
    }

    static string TexturedObject(string material) => $$"""{ "type": "quad", "center": [0, 0, 0], "size": [6, 4], "material": {{material}} }""";

    static (Scene Scene, RenderResult Result) Render(string json, string dir)
    {
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
        var path = Integrators.Create(scene, new SceneGeometry(scene), scene.Integrator!.Name);
        Assert.IsType<PathIntegrator>(path);
        return (scene, Renderer.Render(scene, path, threads: 2));
    }

    static (int X, int Y) Centre(Scene scene, int p)
    {
        var px = scene.Camera.Project(new Vector3(p % 6 - 2.5f, 1.5f - p / 6, 0))!.Value;
        return ((int)px.X, (int)px.Y);
    }

    /// <summary>Every patch centre: each band and X, Y, Z of the two renders to <paramref name="relative"/> (float rounding).</summary>
    void SamePatches(RenderResult a, RenderResult b, Scene scene, double relative = 1e-5)
    {
        int n = scene.Bands, w = scene.Camera.Width;
        double worst = 0;
        for (int p = 0; p < 24; p++)
        {
            var (x, y) = Centre(scene, p);
            Assert.True(b.Image[x, y, 10] > 1e-3, $"patch {p + 1}: the untextured render is black at its centre");
            for (int k = 0; k < n; k++)
            {
                double d = Math.Abs(a.Image[x, y, k] - b.Image[x, y, k]) / Math.Abs(b.Image[x, y, k]);
                worst = Math.Max(worst, d);
                Assert.True(d <= relative, $"patch {p + 1} band {k}: {a.Image[x, y, k]:R} textured vs {b.Image[x, y, k]:R}");
            }
            int i = y * w + x;
            for (int c = 0; c < 3; c++)
                Assert.True(Math.Abs(a.Xyz![3 * i + c] - b.Xyz![3 * i + c]) <= relative * Math.Abs(b.Xyz[3 * i + c]), $"patch {p + 1} XYZ lane {c}");
        }
        output.WriteLine($"largest relative band difference {worst:G3}");
    }

    static string WriteChart(string dir, double[] wl, double[][] patches)
    {
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "chart.img"), 6 * PerPatch, 4 * PerPatch, wl, SpectralTextureTests.ChartTexels(patches, wl.Length, v => (float)v));
        return """{ "texture": "chart.hdr" }""";
    }

    [Theory]
    [InlineData(Directional)]
    [InlineData(Point)]
    public void A_ColorChecker_texture_lit_directly_equals_the_untextured_patches(string light)
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        var (scene, plain) = Render(Scene(UntexturedObjects(wl, patches, s => $$"""{ "diffuse": {{s}} }"""), light, "0"), dir);
        var (_, textured) = Render(Scene(TexturedObject($$"""{ "diffuse": {{texture}} }"""), light, "0"), dir);
        SamePatches(textured, plain, scene);
    }

    /// <summary>
    /// With a plain specular lobe (f = m_diff,texel/π + m_spec·N·factor under a point light), and with a mirror under a
    /// sky: the lobe choice's channel share (m_diff + m_spec against k_r) comes from the texel, so the choice and the MIS
    /// weights are the untextured patch's, sample for sample. (A glossy lobe under a sky is left out: the BSDF's own
    /// diffuse/glossy draw uses the material's spectra — the texture's mean — an unbiased choice, not the patch's.)
    /// </summary>
    [Theory]
    [InlineData("\"specular\": 0.2, \"shininess\": 20", "0")]
    [InlineData("\"mirror\": 0.3", "0.02")]
    public void A_textured_diffuse_beside_plain_lobes_equals_the_untextured_patches(string lobes, string sky)
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        var (scene, plain) = Render(Scene(UntexturedObjects(wl, patches, s => $$"""{ "diffuse": {{s}}, {{lobes}} }"""), Point, sky), dir);
        var (_, textured) = Render(Scene(TexturedObject($$"""{ "diffuse": {{texture}}, {{lobes}} }"""), Point, sky), dir);
        SamePatches(textured, plain, scene);
    }

    /// <summary>∫ of the piecewise-linear table (x, y) over [lo, hi] (inside its range), segment by segment, exactly.</summary>
    static double Integral(double[] x, double[] y, double lo, double hi)
    {
        double sum = 0;
        for (int i = 0; i + 1 < x.Length; i++)
        {
            double a = Math.Max(lo, x[i]), b = Math.Min(hi, x[i + 1]);
            if (!(b > a)) continue;
            double Y(double t) => y[i] + (y[i + 1] - y[i]) * (t - x[i]) / (x[i + 1] - x[i]);
            sum += (b - a) * (Y(a) + Y(b)) / 2;
        }
        return sum;
    }

    [Fact]
    public void A_textured_quad_under_a_uniform_sky_reflects_rho_times_L_sky()
    {
        // A Lambertian surface under a sky of radiance L from every direction reflects L_o = ρ·L (∫ ρ/π·L·cos θ dω = ρ·L);
        // with max_depth 1 the sky is reached by next-event estimation and by the BSDF's bounce, MIS-weighted, each sample
        // exactly ρ·L. Band b's value: L·(1/Δλ)∫_b ρ(λ) dλ. No scene light.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        const double sky = 0.7;
        string json = Scene(TexturedObject($$"""{ "diffuse": {{texture}} }"""), "", sky.ToString(CultureInfo.InvariantCulture)).Replace("\"lights\": [  ],", "");
        var (scene, r) = Render(json, dir);
        double worst = 0;
        for (int p = 0; p < 24; p++)
        {
            var (x, y) = Centre(scene, p);
            var rho = patches[p].Select(v => (double)(float)v).ToArray();
            for (int b = 0; b < scene.Bands; b++)
            {
                double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b);
                double expected = sky * Integral(wl, rho, lo, hi) / (hi - lo);
                double d = Math.Abs(r.Image[x, y, b] / expected - 1);
                worst = Math.Max(worst, d);
                Assert.True(d <= 1e-5, $"patch {p + 1} band {b}: {r.Image[x, y, b]:R} vs ρ·L = {expected:R}");
            }
        }
        output.WriteLine($"largest relative difference from ρ·L_sky {worst:G3}");
    }
}
