using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// A textured specular weight m_spec in the Whitted integrator (issue 26), beside the textured m_diff: ColorChecker
/// reflectances of the reference table (data/colorchecker-ohta.csv) written as ENVI cubes — one spectrum everywhere, or
/// one per half of the texture — on a quad under point lights with a visible highlight, against untextured quads whose
/// m_spec (and m_diff) are those spectra given inline: every band and X, Y, Z to 1e-6 relative (float rounding: the texel
/// tables are the same exact products summed another way, by the tent functions of the texture's samples), in eq. 2's and
/// in physical radiometry (its specular normalisation), Blinn–Phong and Phong, seen directly and by a chain of two mirrors.
/// </summary>
public class WhittedTextureTests(Xunit.Abstractions.ITestOutputHelper output)
{
    // Two point lights of different spectra, each with a highlight on the quad (at about (0.77, 1.54) and (−0.77, −1.54) for
    // the camera at z = 20): the highlight of each lies in another half of the quad.
    const string Lights = """
        { "type": "point", "position": [1, 2, 6], "spectrum": "A", "intensity": INTENSITY, "ambient": AMBIENT },
        { "type": "point", "position": [-1, -2, 6], "spectrum": "D65", "intensity": INTENSITY, "ambient": AMBIENT }
        """;

    static string Scene(string radiometry, string objects, int maxDepth = 0, double ambient = 0)
    {
        var inv = CultureInfo.InvariantCulture;
        var lights = Lights.Replace("INTENSITY", radiometry == "paper" ? "0.01" : "2").Replace("AMBIENT", (ambient * 0.5).ToString(inv));
        return $$"""
        {
          "bands": "380:780:20", "integration": "exact", "radiometry": "{{radiometry}}", "white": "D65",
          "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
          "ambient": {{ambient.ToString(inv)}},
          "lights": [ {{lights}} ],
          "objects": [ {{objects}} ],
          "background": 0, "max_depth": {{maxDepth}}
        }
        """;
    }

    static string Quad(string material) => $$"""{ "type": "quad", "center": [0, 0, 0], "size": [6, 4], "material": {{material}} }""";

    /// <summary>A spectrum inline: its (wavelength, value) pairs, the values as the texture's floats hold them.</summary>
    static string Pairs(double[] wl, double[] values)
    {
        var inv = CultureInfo.InvariantCulture;
        return "[" + string.Join(", ", wl.Select((l, j) => $"[{l.ToString(inv)}, {((float)values[j]).ToString("R", inv)}]")) + "]";
    }

    /// <summary>A w × h ENVI texture whose texel (x, y) (row 0 the top) is <paramref name="spectrum"/>(x, y).</summary>
    static string WriteTexture(string dir, string name, double[] wl, int w, int h, Func<int, int, double[]> spectrum)
    {
        var texels = new float[w * h * wl.Length];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                var s = spectrum(x, y);
                for (int j = 0; j < wl.Length; j++) texels[(y * w + x) * wl.Length + j] = (float)s[j];
            }
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, name + ".img"), w, h, wl, texels);
        return $$"""{ "texture": "{{name}}.hdr" }""";
    }

    static (Scene Scene, RenderResult Result) Render(string json, string dir, int threads = 2)
    {
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
        return (scene, Integrators.Render(scene, threads));
    }

    /// <summary>Every band and X, Y, Z of pixel (x, y) of <paramref name="a"/> against <paramref name="b"/> to
    /// <paramref name="relative"/>; the largest relative difference.</summary>
    static double WorstRelative(RenderResult a, RenderResult b, int x, int y, int bands, double relative, string where)
    {
        double worst = 0;
        void Check(double va, double vb, string what)
        {
            double d = Math.Abs(va - vb), scale = Math.Abs(vb);
            Assert.True(d <= relative * scale, $"{where} {what}: {va:R} textured vs {vb:R}");
            if (scale > 0) worst = Math.Max(worst, d / scale);
        }
        for (int k = 0; k < bands; k++) Check(a.Image[x, y, k], b.Image[x, y, k], $"band {k}");
        int i = y * a.Image.Width + x;
        for (int c = 0; c < 3; c++) Check(a.Xyz![3 * i + c], b.Xyz![3 * i + c], $"XYZ lane {c}");
        return worst;
    }

    static (int X, int Y) Pixel(Scene scene, float x, float y)
    {
        var p = scene.Camera.Project(new Vector3(x, y, 0))!.Value;
        return ((int)p.X, (int)p.Y);
    }

    [Theory]
    [InlineData("paper", "blinn-phong")]
    [InlineData("physical", "blinn-phong")]
    [InlineData("paper", "phong")]
    [InlineData("physical", "phong")]
    public void A_uniform_specular_texture_renders_as_the_untextured_specular(string radiometry, string model)
    {
        // Every texel patch 12 (orange yellow); m_diff patch 13 (blue), shininess 20: a broad highlight of each light.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteTexture(dir, "uniform", wl, 8, 4, (_, _) => patches[11]);
        string Material(string specular) =>
            $$"""{ "diffuse": {{Pairs(wl, patches[12])}}, "specular": {{specular}}, "shininess": 20, "model": "{{model}}" }""";
        var (scene, plain) = Render(Scene(radiometry, Quad(Material(Pairs(wl, patches[11])))), dir);
        var (_, textured) = Render(Scene(radiometry, Quad(Material(texture))), dir);
        var (_, matte) = Render(Scene(radiometry, Quad(Material("0"))), dir);
        int n = scene.Bands, w = scene.Camera.Width, h = scene.Camera.Height;
        double worst = 0;
        int seen = 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                worst = Math.Max(worst, WorstRelative(textured, plain, x, y, n, 1e-6, $"pixel ({x}, {y})"));
                seen += plain.ObjectIds[y * w + x] == 0 ? 1 : 0;
            }
        Assert.True(seen > w * h / 2);
        Assert.Equal(plain.Highlights, textured.Highlights);   // the analysis's specular Y from the texels
        // The highlights are visible: there the specular term is a good part of the pixel (Y over the matte quad's).
        foreach (var (hx, hy) in new[] { (0.77f, 1.54f), (-0.77f, -1.54f) })
        {
            var (x, y) = Pixel(scene, hx, hy);
            int i = 3 * (y * w + x) + 1;
            output.WriteLine($"highlight ({hx}, {hy}): Y {plain.Xyz![i]:G4} with m_spec, {matte.Xyz![i]:G4} without");
            Assert.True(plain.Xyz[i] > 1.2 * matte.Xyz[i], $"no highlight at ({hx}, {hy})");
        }
        output.WriteLine($"largest relative difference {worst:G3}");
    }

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void A_two_half_specular_texture_shows_each_half_s_spectrum(string radiometry)
    {
        // Left half (x < 0 on the quad, texels 0–3 of 8) patch 7 (orange), right half patch 18 (cyan); m_diff a constant.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        double[] a = patches[6], b = patches[17];
        var texture = WriteTexture(dir, "halves", wl, 8, 4, (x, _) => x < 4 ? a : b);
        string Material(string specular) => $$"""{ "diffuse": 0.2, "specular": {{specular}}, "shininess": 20 }""";
        var (scene, textured) = Render(Scene(radiometry, Quad(Material(texture))), dir);
        var (_, left) = Render(Scene(radiometry, Quad(Material(Pairs(wl, a)))), dir);
        var (_, right) = Render(Scene(radiometry, Quad(Material(Pairs(wl, b)))), dir);
        // Points at least 0.9 from the seam (1.2 texels; the bilinear taps reach half a texel, a pixel is 0.09 wide) and
        // 0.5 from the edges x = ±3 (the repeat wrap's taps), each highlight among them.
        var points = new List<(float, float)> { (-0.77f, -1.54f), (0.77f, 1.54f) };
        foreach (float x in new[] { -2.5f, -1.5f, -0.9f, 0.9f, 1.5f, 2.5f })
            foreach (float y in new[] { -1.5f, -0.5f, 0.5f, 1.5f })
                points.Add((x, y));
        double worst = 0;
        foreach (var (px, py) in points)
        {
            var (x, y) = Pixel(scene, px, py);
            var expected = px < 0 ? left : right;
            var other = px < 0 ? right : left;
            Assert.NotEqual(expected.Image[x, y, 10], other.Image[x, y, 10]);   // the two spectra differ there
            worst = Math.Max(worst, WorstRelative(textured, expected, x, y, scene.Bands, 1e-6, $"point ({px}, {py})"));
        }
        output.WriteLine($"largest relative difference {worst:G3}");
    }

    /// <summary>A quad whose m_diff is textured top (patch 19, white) / bottom (patch 2, light skin) and m_spec left (patch 7) /
    /// right (patch 13), under global and the lights' ambient (m_amb defaults to m_diff, so it is the texture too).</summary>
    static (string Textured, Func<int, int, string> Plain) QuarterScene(string dir, string radiometry, double[] wl, double[][] patches)
    {
        double[] top = patches[18], bottom = patches[1], left = patches[6], right = patches[12];
        var diffuse = WriteTexture(dir, "rows", wl, 8, 8, (_, y) => y < 4 ? top : bottom);
        var specular = WriteTexture(dir, "columns", wl, 8, 8, (x, _) => x < 4 ? left : right);
        string Material(string d, string s) => $$"""{ "diffuse": {{d}}, "specular": {{s}}, "shininess": 20 }""";
        var textured = Scene(radiometry, Quad(Material(diffuse, specular)), ambient: 0.02);
        string Plain(int row, int column) =>
            Scene(radiometry, Quad(Material(Pairs(wl, row == 0 ? top : bottom), Pairs(wl, column == 0 ? left : right))), ambient: 0.02);
        return (textured, Plain);
    }

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Diffuse_and_specular_textured_by_different_files_show_each_quarter(string radiometry)
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var (texturedJson, plainJson) = QuarterScene(dir, radiometry, wl, patches);
        var (scene, textured) = Render(texturedJson, dir);
        double worst = 0;
        for (int row = 0; row < 2; row++)
            for (int column = 0; column < 2; column++)
            {
                var (_, plain) = Render(plainJson(row, column), dir);
                float sx = column == 0 ? -1 : 1, sy = row == 0 ? 1 : -1;
                // Away from both seams (x = 0, y = 0) and the edges; (0.77, 1.54) mirrored is a light's highlight in two quarters.
                foreach (var (px, py) in new[] { (1.5f, 1f), (2.4f, 1.5f), (0.9f, 0.6f), (0.77f, 1.54f) })
                {
                    var (x, y) = Pixel(scene, sx * px, sy * py);
                    var where = $"quarter ({row}, {column}) point ({sx * px}, {sy * py})";
                    worst = Math.Max(worst, WorstRelative(textured, plain, x, y, scene.Bands, 1e-6, where));
                }
            }
        output.WriteLine($"largest relative difference {worst:G3}");
    }

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void A_fine_specular_checker_seen_from_afar_is_its_mean(string radiometry)
    {
        // An 8 × 8 checker of patches 7 and 18 repeated 64 times across the quad: a pixel spans several texels, so the lookup
        // reads coarse mip levels of the specular tables — from level 1 (4 × 4) on every texel is the mean of the two spectra.
        // Every pixel equals the untextured quad whose m_spec is the mean spectrum, computed here.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        double[] a = patches[6], b = patches[17];
        var mean = a.Zip(b, (x, y) => ((double)(float)x + (float)y) / 2).ToArray();
        var texture = WriteTexture(dir, "checker", wl, 8, 8, (x, y) => (x + y) % 2 == 0 ? a : b)
            .Replace(" }", """, "uv_transform": { "scale": 64 } }""");
        string Material(string specular) => $$"""{ "diffuse": 0.2, "specular": {{specular}}, "shininess": 20 }""";
        var (scene, textured) = Render(Scene(radiometry, Quad(Material(texture))), dir);
        var (_, plain) = Render(Scene(radiometry, Quad(Material(Pairs(wl, mean)))), dir);
        var (_, first) = Render(Scene(radiometry, Quad(Material(Pairs(wl, a)))), dir);
        var (hx, hy) = Pixel(scene, 0.77f, 1.54f);
        Assert.True(Math.Abs(first.Image[hx, hy, 10] - plain.Image[hx, hy, 10]) > 1e-3 * plain.Image[hx, hy, 10]);   // not one patch
        double worst = 0;
        for (int y = 0; y < scene.Camera.Height; y++)
            for (int x = 0; x < scene.Camera.Width; x++)
                worst = Math.Max(worst, WorstRelative(textured, plain, x, y, scene.Bands, 1e-6, $"pixel ({x}, {y})"));
        output.WriteLine($"largest relative difference {worst:G3}");
    }

    [Fact]
    public void A_textured_render_is_the_same_on_one_and_two_threads()
    {
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var (json, _) = QuarterScene(dir, "physical", wl, patches);
        var (_, one) = Render(json, dir, threads: 1);
        var (_, two) = Render(json, dir, threads: 2);
        Assert.Equal(one.Image.Data, two.Image.Data);
        Assert.Equal(one.Xyz, two.Xyz);
        Assert.Equal(one.Highlights, two.Highlights);
    }

    [Fact]
    public void The_memory_estimate_counts_the_specular_tables()
    {
        // A 24 × 16 texture: mip levels 24×16, 12×8, 6×4, 3×2, 1×1 hold 511 texels. Per texel the diffuse texture keeps
        // 1 + 2 × lights padded tables (global ambient, each light's ambient and diffuse term), the specular one a table per
        // light: two lights, so 5 and 2.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        var texture = WriteTexture(dir, "chart", wl, 24, 16, (x, y) => patches[(y / 4) * 6 + x / 4]);
        long Tables(string material)
        {
            var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(Scene("paper", Quad(material))), Path.Combine(dir, "scene.json"));
            Assert.Equal(2, scene.Lights.Count);
            var parts = RenderMemory.Estimate(scene, 2, integrator: "whitted");
            var part = parts.SingleOrDefault(p => p.Part == "texture tables");
            int lanes = Vector<float>.Count, padded = (scene.Bands + 3 + lanes - 1) / lanes * lanes;
            Assert.Equal(padded, scene.PaddedBands);
            return part.Bytes / (511L * padded * sizeof(float));
        }
        Assert.Equal(0, Tables("""{ "diffuse": 0.5, "specular": 0.5 }"""));
        Assert.Equal(5, Tables($$"""{ "diffuse": {{texture}}, "specular": 0.5 }"""));
        Assert.Equal(2, Tables($$"""{ "diffuse": 0.5, "specular": {{texture}} }"""));
        Assert.Equal(7, Tables($$"""{ "diffuse": {{texture}}, "specular": {{texture}} }"""));
    }

    [Fact]
    public void A_specular_texture_seen_by_a_chain_of_two_mirrors_shows_each_half()
    {
        // The camera looks along +x at mirror 1 (x + z = 30), which sends the rays down −z to mirror 2 (x = z), which sends them
        // along −x onto the textured quad in the plane x = 0 (facing +x, lit by a point light on its side): two bounces,
        // through a spectral k_r on the first mirror. The quad's halves (texels 0–3 and 4–7 along u) hold patches 7 and 18;
        // every pixel where the quad's specular term tells the halves apart shows one half's untextured render to 1e-6, except
        // along the seam, and both halves are seen in good numbers.
        var (wl, patches) = SpectralTextureTests.ColorCheckerTable();
        var dir = Reference.TempDir();
        double[] a = patches[6], b = patches[17];
        // Clamped: at the quad's edges the taps stay in their half.
        var texture = WriteTexture(dir, "halves", wl, 8, 4, (x, _) => x < 4 ? a : b)
            .Replace(" }", """, "uv_transform": { "wrap": "clamp" } }""");
        string Json(string specular) => $$"""
            {
              "bands": "380:780:20", "integration": "exact", "radiometry": "paper", "white": "D65",
              "camera": { "position": [0, 0, 20], "look_at": [10, 0, 20], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
              "lights": [ { "type": "point", "position": [5, 1, 12], "spectrum": "A", "intensity": 0.01 } ],
              "materials": { "m1": { "mirror": {{Pairs(wl, patches[18])}} }, "m2": { "mirror": 0.9 } },
              "objects": [
                { "type": "quad", "center": [10, 0, 20], "size": 12, "normal": [-1, 0, -1], "material": "m1" },
                { "type": "quad", "center": [10, 0, 10], "size": 12, "normal": [-1, 0, 1], "material": "m2" },
                { "type": "quad", "center": [0, 0, 10], "size": [8, 6], "normal": [1, 0, 0], "up": [0, 1, 0],
                  "material": { "diffuse": 0.2, "specular": {{specular}}, "shininess": 10 } }
              ],
              "background": 0, "max_depth": 2
            }
            """;
        var (scene, textured) = Render(Json(texture), dir);
        var (_, first) = Render(Json(Pairs(wl, a)), dir);
        var (_, second) = Render(Json(Pairs(wl, b)), dir);
        int w = scene.Camera.Width, h = scene.Camera.Height, n = scene.Bands;
        int asFirst = 0, asSecond = 0, neither = 0, specularSeen = 0;
        static bool Same(RenderResult x, RenderResult y, int px, int py, int bands)
        {
            for (int k = 0; k < bands; k++)
                if (Math.Abs(x.Image[px, py, k] - y.Image[px, py, k]) > 1e-6 * Math.Abs(y.Image[px, py, k])) return false;
            int i = 3 * (py * x.Image.Width + px);
            for (int c = 0; c < 3; c++)
                if (Math.Abs(x.Xyz![i + c] - y.Xyz![i + c]) > 1e-6 * Math.Abs(y.Xyz![i + c])) return false;
            return true;
        }
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                // Where the quad's specular term tells the halves apart (elsewhere: another object, or too far from the highlight).
                if (!(Math.Abs(first.Image[x, y, 10] - second.Image[x, y, 10]) > 1e-4 * first.Image[x, y, 10])) continue;
                specularSeen++;
                if (Same(textured, first, x, y, n)) asFirst++;
                else if (Same(textured, second, x, y, n)) asSecond++;
                else neither++;
            }
        output.WriteLine($"{specularSeen} pixels tell the halves apart by the mirrors: {asFirst} show the first half, " +
            $"{asSecond} the second, " +
            $"{neither} neither (the seam)");
        Assert.True(asFirst > 200 && asSecond > 200, $"{asFirst} and {asSecond}");
        // The seam: the pixels whose bilinear taps straddle it (within half a texel of it: a band 1 unit of the quad wide, some
        // 8 pixels at 30 units), vertical across the quad's height.
        Assert.True(neither <= 16 * h, $"{neither} pixels match neither half");
        Assert.True(neither < (asFirst + asSecond) / 4, $"{neither} pixels match neither half");
    }
}
