using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Spectral textures in the path integrator (issue 26): the 24 ColorChecker reflectances of the reference table
/// (data/colorchecker-ohta.csv) as an ENVI cube on one flat quad, rendered with direct light only (max_depth 1), against
/// 24 untextured quads of the same spectra given inline — every band and X, Y, Z at each patch centre to float rounding;
/// under a uniform sky (its radiance the same at every wavelength) against the analytic ρ·L_sky, ρ's band mean
/// integrated here from the table's straight segments. Both on the uniform 5 nm grid (<c>"spectral_grid": 5</c>): the default
/// adaptive grid follows the plain materials' spectra, not a texture's texels, so it would differ between the two.
/// </summary>
public class PathTextureTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const int PerPatch = SpectralTextureTests.PerPatch;

    static string Scene(string objects, string light, string background, string materials = "{}", int maxDepth = 1) => $$"""
        {
          "bands": "380:780:20", "integration": "exact", "radiometry": "physical", "white": "D65",
          "integrator": { "type": "path", "max_depth": {{maxDepth}}, "spectral_grid": 5 },
          "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
          "lights": [ {{light}} ],
          "materials": {{materials}},
          "objects": [ {{objects}} ],
          "background": {{background}}
        }
        """;

    const string Directional = """{ "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 0.03 }""";
    const string Point = """{ "type": "point", "position": [1, 2, 6], "spectrum": "A", "intensity": 1 }""";

    /// <summary>The 24 patches as untextured unit quads, each material given inline (<paramref name="material"/> of its spectrum
    /// pairs).</summary>
    static string UntexturedObjects(double[] wl, double[][] patches, Func<string, string> material)
    {
        var inv = CultureInfo.InvariantCulture;
        var objects = new StringBuilder();
        for (int p = 0; p < 24; p++)
        {
            var pairs = string.Join(", ", wl.Select((l, j) => $"[{l.ToString(inv)}, {((float)patches[p][j]).ToString("R", inv)}]"));
            if (p > 0) objects.Append(", ");
            string quad = material($"[{pairs}]");
            objects.Append(inv,
                $$"""{ "type": "quad", "center": [{{p % 6 - 2.5}}, {{1.5 - p / 6}}, 0], "size": 1, "material": {{quad}} }""");
        }
        return objects.ToString();
    }

    static string TexturedObject(string material) =>
        $$"""{ "type": "quad", "center": [0, 0, 0], "size": [6, 4], "material": {{material}} }""";

    static (Scene Scene, RenderResult Result) Render(string json, string dir)
    {
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
        var path = Integrators.Create(scene, new SceneGeometry(scene), scene.Integrator!.Name);
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
                Assert.True(Math.Abs(a.Xyz![3 * i + c] - b.Xyz![3 * i + c]) <= relative * Math.Abs(b.Xyz[3 * i + c]),
                    $"patch {p + 1} XYZ lane {c}");
        }
        output.WriteLine($"largest relative band difference {worst:G3}");
    }

    static string WriteChart(string dir, double[] wl, double[][] patches)
    {
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "chart.img"), 6 * PerPatch, 4 * PerPatch, wl,
            SpectralTextureTests.ChartTexels(patches, wl.Length, v => (float)v));
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
    /// Issue 42: a `lambertian` material's "reflectance" takes a texture under path, as the docs say (it was refused): the
    /// textured chart equals 24 untextured lambertian patches of the same spectra at every patch centre.
    /// </summary>
    [Theory]
    [InlineData(Directional)]
    [InlineData(Point)]
    public void A_lambertian_ColorChecker_texture_equals_untextured_lambertian_patches(string light)
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        var patchQuads = UntexturedObjects(wl, patches, s => $$"""{ "type": "lambertian", "reflectance": {{s}} }""");
        var (scene, plain) = Render(Scene(patchQuads, light, "0"), dir);
        var (_, textured) = Render(Scene(TexturedObject($$"""{ "type": "lambertian", "reflectance": {{texture}} }"""), light, "0"), dir);
        SamePatches(textured, plain, scene);
    }

    /// <summary>
    /// The chart seen through a tilted slab of dispersive glass (Cauchy, Fresnel transmission only), which splits every
    /// camera path into one sub-path per output band: each sub-path looks the texture up where its band's refraction lands,
    /// so every band at each patch centre equals the untextured patches' seen through the same slab, to float rounding
    /// (camera → slab → slab → chart → a low directional light whose shadow rays pass beside the slab; max_depth 3).
    /// </summary>
    [Fact]
    public void A_ColorChecker_texture_seen_through_dispersive_glass_equals_the_untextured_patches_through_it()
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        const string Slab = """, { "type": "box", "name": "slab", "center": [0, 0, 0], "size": [8, 6, 0.5], """
            + """ "transform": { "rotate": [0, 10, 0], "translate": [0, 0, 3] }, "material": "glass" }""";
        const string Glass = """{ "glass": { "diffuse": 0, "ambient": 0, "transmit": 1, "fresnel": true, """
            + """ "ior": { "cauchy": [1.5, 20000] } } }""";
        const string Low = """{ "type": "directional", "direction": [-1, 0, -0.3], "spectrum": "D65", "intensity": 0.3 }""";
        var patchQuads = UntexturedObjects(wl, patches, s => $$"""{ "diffuse": {{s}} }""");
        var (scene, plain) = Render(Scene(patchQuads + Slab, Low, "0", Glass, 3), dir);
        var (_, textured) = Render(Scene(TexturedObject($$"""{ "diffuse": {{texture}} }""") + Slab, Low, "0", Glass, 3), dir);
        Assert.True(scene.Materials[scene.Materials.FindIndex(m => m.Name == "glass")].Dispersive);
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
        string json = Scene(TexturedObject($$"""{ "diffuse": {{texture}} }"""), "", sky.ToString(CultureInfo.InvariantCulture))
            .Replace("\"lights\": [  ],", "");
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

    [Fact]
    public void A_ColorChecker_texture_on_the_specular_weight_equals_untextured_specular_patches()
    {
        // f = m_diff/π + m_spec,texel·(s + 2)/(2π)·(r·v)^s under a point light (next-event estimation only, no sky).
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        const string rest = "\"diffuse\": 0.1, \"shininess\": 8, \"model\": \"phong\"";
        var (scene, plain) = Render(Scene(UntexturedObjects(wl, patches, s => $$"""{ "specular": {{s}}, {{rest}} }"""), Point, "0"), dir);
        var (_, textured) = Render(Scene(TexturedObject($$"""{ "specular": {{texture}}, {{rest}} }"""), Point, "0"), dir);
        SamePatches(textured, plain, scene);
    }

    [Fact]
    public void A_textured_emitter_seen_directly_shows_its_texel_radiance()
    {
        // L = k·L_texel(λ): band b's value k·(1/Δλ)∫_b L_texel dλ, integrated here from the table's straight segments.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        const double k = 3;
        var (scene, r) = Render(
            Scene(TexturedObject($$"""{ "diffuse": 0, "emission": { "spectrum": {{texture}}, "radiance": {{k}} } }"""), "", "0")
            .Replace("\"lights\": [  ],", ""), dir);
        for (int p = 0; p < 24; p++)
        {
            var (x, y) = Centre(scene, p);
            var le = patches[p].Select(v => (double)(float)v).ToArray();
            for (int b = 0; b < scene.Bands; b++)
            {
                double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b);
                double expected = k * Integral(wl, le, lo, hi) / (hi - lo);
                Assert.True(Math.Abs(r.Image[x, y, b] / expected - 1) <= 1e-5,
                    $"patch {p + 1} band {b}: {r.Image[x, y, b]:R} vs k·L_texel = {expected:R}");
            }
        }
    }

    [Theory]
    [InlineData("""{ "type": "quad", "center": [0, 2, 0], "normal": [0, -1, 0], "up": [0, 0, 1], "size": 1.5, "material": "lamp" }""")]
    [InlineData("""{ "type": "sphere", "center": [0, 2, 0], "radius": 0.5, "material": "lamp" }""")]
    [InlineData("""{ "type": "mesh", "file": "lamp.obj", "material": "lamp" }""")]
    public void A_uniformly_textured_emitter_lights_a_room_as_its_spectrum_does(string lamp)
    {
        // Next-event samples on the emitter look the texture up at the point drawn, BSDF bounces where they hit it: a texture
        // of one spectrum everywhere gives the untextured emitter's picture, sample for sample (max_depth 3: interreflection).
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "lamp.obj"), "v -0.7 2 -0.7\nv 0.7 2 -0.7\nv 0.7 2 0.7\nv -0.7 2 0.7\nf 1 4 3 2\n");
        int w = 8, h = 8;
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "lamp.img"), w, h, wl,
            Enumerable.Range(0, w * h).SelectMany(_ => patches[18].Select(v => (float)v)).ToArray());
        var inv = CultureInfo.InvariantCulture;
        var pairs =
            "[" + string.Join(", ", wl.Select((l, j) => $"[{l.ToString(inv)}, {((float)patches[18][j]).ToString("R", inv)}]")) + "]";
        string Room(string spectrum) => $$"""
            { "bands": "380:780:20", "radiometry": "physical", "integrator": { "type": "path", "max_depth": 3 },
              "camera": { "position": [0, 1, 4], "look_at": [0, 0.5, 0], "width": 24, "height": 16, "spp": 4 },
              "materials": { "lamp": { "diffuse": 0, "emission": { "spectrum": {{spectrum}}, "radiance": 5, "two_sided": true } },
                             "wall": { "diffuse": 0.6 } },
              "objects": [ {{lamp}}, { "type": "plane", "material": "wall" },
                           { "type": "box", "center": [0.8, 0.4, 0], "size": [0.8, 0.8, 0.8], "material": "wall" } ] }
            """;
        var (scene, plain) = Render(Room(pairs), dir);
        var (_, textured) = Render(Room("""{ "texture": "lamp.hdr" }"""), dir);
        double worst = 0;
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 24; x++)
                for (int b = 0; b < scene.Bands; b++)
                {
                    float a = textured.Image[x, y, b], e = plain.Image[x, y, b];
                    worst = Math.Max(worst, Math.Abs(a - e) / Math.Max(Math.Abs(e), 1e-3));
                }
        output.WriteLine($"largest relative difference {worst:G3}");
        Assert.True(worst <= 1e-4, $"largest relative difference {worst:G3}");
        Assert.True(plain.Image[12, 12, 10] > 0, "the floor is dark");
    }

    [Theory]
    [InlineData("""
        { "type": "quad", "center": [0.2, 2, 0.1], "normal": [0.3, -1, 0.2], "up": [0, 0, 1], "size": [1.5, 0.7], "material": "lamp" }
        """)]
    [InlineData(
        """{ "type": "box", "center": [0, 2, 0], "size": [1, 0.6, 0.8], "transform": { "rotate": [10, 30, 0] }, "material": "lamp" }""")]
    [InlineData("""{ "type": "sphere", "center": [0, 2, 0], "radius": 0.5, "material": "lamp" }""")]
    [InlineData("""{ "type": "mesh", "file": "lamp.obj", "material": "lamp" }""")]
    [InlineData("""{ "type": "mesh", "file": "lamp-uv.obj", "material": "lamp" }""")]
    public void A_point_drawn_on_an_emitter_has_the_uv_a_ray_hitting_it_finds(string lamp)
    {
        // Next-event estimation looks an emitter's texture up at the point it draws (AreaEmitter.TexCoord, from the face and
        // the point); a ray from the shading point to that point meets the surface there, where SceneGeometry.TexCoord
        // gives the hit's uv another way (the intersection's barycentrics or the shape's own coordinates). Both agree.
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "lamp.obj"), "v -0.7 2 -0.7\nv 0.7 2 -0.7\nv 0.7 2.3 0.7\nv -0.7 2 0.7\nf 1 4 3 2\n");
        File.WriteAllText(Path.Combine(dir, "lamp-uv.obj"),
            "v -0.7 2 -0.7\nv 0.7 2 -0.7\nv 0.7 2.3 0.7\nv -0.7 2 0.7\nvt 0.1 0.2\nvt 0.9 0.1\nvt 0.8 "
                + "0.95\nvt 0.05 0.7\nf 1/1 4/4 3/3 2/2\n");
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes($$"""
            { "bands": "400:700:50", "radiometry": "physical", "integrator": "path",
              "camera": { "position": [0, 1, 4], "look_at": [0, 0.5, 0], "width": 4, "height": 4 },
              "materials": { "lamp": { "diffuse": 0, "emission": { "spectrum": 1, "two_sided": true } } },
              "objects": [ {{lamp}} ] }
            """), Path.Combine(dir, "scene.json"));
        var geometry = new SceneGeometry(scene);
        var emitter = new AreaEmitter(scene.Objects[0], new float[8], true, "test");
        var rng = new Random(26);
        var p = new Vector3(0.1f, 0.3f, 0.2f);
        int checkedPoints = 0;
        for (int i = 0; i < 400; i++)
        {
            var u = new Vector2((float)rng.NextDouble(), (float)rng.NextDouble());
            if (!emitter.Sample(p, u, out var x, out _, out _, out int face)) continue;
            var d = x - p;
            var ray = new Ray(p, Vector3.Normalize(d), d.Length() * 1.001f);
            // a nearer face in the way
            if (!geometry.Intersect(ref ray, out var hit) || Vector3.Distance(hit.Position, x) > 1e-4f) continue;
            var expected = geometry.TexCoord(in hit, out float density);
            var uv = emitter.TexCoord(face, x, out float emitterDensity);
            Assert.True(Vector2.Distance(uv, expected) < 1e-4f, $"point {x}: uv {uv} drawn, {expected} hit");
            Assert.Equal(density, emitterDensity, 1e-4f);
            checkedPoints++;
        }
        output.WriteLine($"{checkedPoints} points compared");
        Assert.True(checkedPoints > 50);   // a box: the faces turned away from p are hidden
    }

    [Theory]
    [InlineData("path", """{ "diffuse": 0, "emission": { "spectrum": TEX, "luminous_flux": 100 } }""",
        "$.objects[0].material.emission.luminous_flux", "not by luminous_flux")]
    [InlineData("path", """{ "type": "plastic", "diffuse": TEX }""", "$.objects[0].material.diffuse",
        "eq. 2 and lambertian materials only")]
    [InlineData("path", """{ "diffuse": 0.5, "ambient": TEX }""", "$.objects[0].material.ambient", "can be a texture so far")]
    public void What_cannot_be_textured_is_bad_input_naming_its_place(string integrator, string material, string where, string what)
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        var json = Scene(TexturedObject(material.Replace("TEX", texture)), Point, "0")
            .Replace("\"type\": \"path\"", $"\"type\": \"{integrator}\"");
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => Render(json, dir));
        output.WriteLine(e.Message);
        Assert.Contains(where, e.Message);
        Assert.Contains(what, e.Message);
    }

    [Fact]
    public void The_memory_check_states_the_texture_spectra_once_for_all_threads()
    {
        // The 24 × 16 chart as diffuse and as specular: its mip levels 24×16, 12×8, 6×4, 3×2, 1×1 hold 511 texels; on the
        // path's 5-nm grid each 20-nm band is 4 sub-bands, padded (with the 3 colour lanes every spectrum array keeps) to whole
        // SIMD registers; 4 bytes a float, two textures.
        // The Whitted route: per texel 1 + 2 × lights tables of the padded bands for the diffuse texture, and one per light for
        // the specular one. Any thread count.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteChart(dir, wl, patches);
        var json = Scene(TexturedObject($$"""{ "diffuse": {{texture}}, "specular": {{texture}} }"""), Point, "0");
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
        int texels = 0;
        for (int w = 24, h = 16; ; w = Math.Max(1, w / 2), h = Math.Max(1, h / 2))
        {
            texels += w * h;
            if (w == 1 && h == 1) break;
        }
        Assert.Equal(511, texels);
        Assert.Equal(20, scene.Grid.Width, 9);
        int lanes = Vector<float>.Count, padded = (scene.Bands * 4 + 3 + lanes - 1) / lanes * lanes;
        foreach (int threads in new[] { 1, 2, 16 })
        {
            var part = SpectralRenderer.Output.RenderMemory.Estimate(scene, threads)
                .Single(p => p.Part.StartsWith("texture", StringComparison.Ordinal));
            Assert.Equal(("texture spectra (fine grid)", 2L * texels * padded * 4), part);
            var whitted = SpectralRenderer.Output.RenderMemory.Estimate(scene, threads, integrator: "whitted")
                .Single(p => p.Part.StartsWith("texture", StringComparison.Ordinal));
            Assert.Equal(("texture tables", (long)texels * ((1 + 2 * 1) + 1) * scene.PaddedBands * 4), whitted);
        }
    }
}
