using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// Relight = re-render for textured materials under the Whitted integrator (issue 26): a scene with a spectral (ENVI) or
/// sRGB (PNG) texture on m_diff and/or m_spec, rendered under CIE A with the per-light outputs and relit to other lights
/// and intensities, against direct renders of the scene with those lights (the independent computation: the renderer
/// traces the scene again and builds its texel tables for the new lights; the relight traces nothing and multiplies the
/// recorded texel samples by the new lights' tent-function matrices). Bars: every band of every pixel (spectral.npy) within
/// 1e-5 relative (float rounding: the same exact products summed in another order), X, Y, Z of spectral.exr within 1e-5
/// relative and ΔE00 ≤ 1e-3, preview.png within one code value — under eq. 2's and physical radiometry, exact and weighted
/// integration, the texture seen directly, by a mirror and through Fresnel glass.
/// </summary>
public class TexturedRelightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    /// <summary>An 8 × 6 ENVI texture of 31 samples 400–700 nm (narrower than the bands: the texels' clamped ends count too),
    /// each texel a different smooth reflectance in [0.05, 0.95].</summary>
    static string DiffuseEnvi(string dir)
    {
        const int W = 8, H = 6;
        var wl = Enumerable.Range(0, 31).Select(j => 400.0 + 10 * j).ToArray();
        var texels = new float[W * H * wl.Length];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int j = 0; j < wl.Length; j++)
                    texels[(y * W + x) * wl.Length + j] = (float)(0.5 + 0.45 * Math.Sin(wl[j] / (25.0 + 4 * x) + 0.9 * y));
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "diffuse.img"), W, H, wl, texels);
        return """{ "texture": "diffuse.hdr" }""";
    }

    /// <summary>A 4 × 4 ENVI texture of 17 samples 380–780 nm: specular weights in [0.1, 0.7].</summary>
    static string SpecularEnvi(string dir)
    {
        const int W = 4, H = 4;
        var wl = Enumerable.Range(0, 17).Select(j => 380.0 + 25 * j).ToArray();
        var texels = new float[W * H * wl.Length];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int j = 0; j < wl.Length; j++)
                    texels[(y * W + x) * wl.Length + j] = (float)(0.4 + 0.3 * Math.Cos(j * 0.35 * (x + 1) - y));
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "specular.img"), W, H, wl, texels);
        return """{ "texture": "specular.hdr" }""";
    }

    /// <summary>A 6 × 4 sRGB PNG of saturated and neutral codes (uplifted to reflectances at load).</summary>
    static string RgbPng(string dir)
    {
        const int W = 6, H = 4;
        var rgb = new byte[W * H * 3];
        for (int i = 0; i < W * H; i++)
        {
            rgb[3 * i] = (byte)(40 + 37 * (i % 6));
            rgb[3 * i + 1] = (byte)(230 - 29 * (i % 7));
            rgb[3 * i + 2] = (byte)(60 + 50 * (i / 6));
        }
        PngWriter.WriteRgb8(Path.Combine(dir, "rgb.png"), W, H, rgb);
        return """{ "texture": "rgb.png" }""";
    }

    /// <summary>A textured quad facing the camera, a second light with its own ambient and a spot cone, the global ambient and a
    /// background; with <paramref name="chains"/> a tilted mirror quad and a tinted Fresnel glass sphere (a unit k_t would
    /// merge its chains into the direct terms) that show the quad again.</summary>
    static string Scene(string radiometry, string integration, string diffuse, string specular, string key, string fill,
        double fillIntensity, bool chains, double keyIntensity = 1)
    {
        double scale = radiometry == "paper" ? 0.01 : 2;
        string extra = chains ? """
            ,
            { "type": "quad", "name": "chrome", "center": [3.2, 0, 2], "size": [2, 3], "normal": [-1, 0, 0.5], "up": [0, 1, 0],
              "material": "mirror" },
            { "type": "sphere", "name": "lens", "center": [-1.2, -0.6, 3.5], "radius": 0.7, "material": "glass" }
            """ : "";
        return $$"""
        {
          "bands": "380:780:20", "integration": "{{integration}}", "radiometry": "{{radiometry}}", "white": "D65",
          "camera": { "position": [0, 0.5, 12], "look_at": [0, 0, 0], "fov": 34, "width": 48, "height": 36, "spp": 2 },
          "ambient": 0.03,
          "materials": {
            "tex": { "diffuse": {{diffuse}}, "specular": {{specular}}, "shininess": 25 },
            "mirror": { "diffuse": 0.05, "mirror": "colorchecker:19", "specular": 0.1 },
            "glass": { "diffuse": 0, "mirror": 1, "transmit": "colorchecker:20", "ior": 1.5, "fresnel": true }
          },
          "lights": [
            { "type": "point", "name": "key", "position": [1, 2, 6], "spectrum": "{{key}}",
              "intensity": {{(scale * keyIntensity).ToString(Inv)}} },
            { "type": "spot", "name": "fill", "position": [-2, -1, 7], "look_at": [0, 0, 0], "cutoff": 40, "exponent": 3,
              "spectrum": "{{fill}}", "intensity": {{(scale * fillIntensity).ToString(Inv)}}, "ambient": 0.02 }
          ],
          "objects": [
            { "type": "quad", "name": "canvas", "center": [-0.5, 0, 0], "size": [7, 5], "material": "tex" }{{extra}}
          ],
          "background": 0.01, "max_depth": 3
        }
        """;
    }

    static void Run(params string[] args)
    {
        var (code, _, err) = CliRunner.Run([.. args, "--quiet"]);
        Assert.True(code == 0, err);
    }

    /// <summary>
    /// Renders the scene under A (with lights/), relights it to D65 × 1.7 and <paramref name="fill"/> × 0.6, renders that scene
    /// directly and compares; returns the relit folder's lights/lights.json.
    /// </summary>
    JsonNode RelitEqualsDirect(string radiometry, string integration, Func<string, string> diffuse, Func<string, string> specular,
        bool chains = false, string fill = "led-blue")
    {
        var dir = Reference.TempDir();
        string d = diffuse(dir), s = specular(dir);
        var underA = Path.Combine(dir, "a.json");
        File.WriteAllText(underA, Scene(radiometry, integration, d, s, "A", "A", 1, chains));
        var target = Path.Combine(dir, "t.json");
        File.WriteAllText(target, Scene(radiometry, integration, d, s, "D65", fill, 0.6, chains, keyIntensity: 1.7));
        Run("render", underA, "-o", Path.Combine(dir, "A"), "--formats", "npy,exr,png,lights");
        Run("render", target, "-o", Path.Combine(dir, "direct"), "--formats", "npy,exr,png");
        double scale = radiometry == "paper" ? 0.01 : 2;
        string key = (scale * 1.7).ToString(Inv), fillI = (scale * 0.6).ToString(Inv);
        Run("relight", Path.Combine(dir, "A"), "-o", Path.Combine(dir, "relit"), "--light", "key=D65", "--light", $"fill={fill}",
            "--intensity", $"key={key}", "--intensity", $"fill={fillI}");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
        var lights = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "A", "lights", "lights.json")))!;
        Assert.Contains(lights["components"]!.AsArray(), c => c!["texels"] is not null);
        return lights;
    }

    /// <summary>Every band (1e-5 relative), X, Y, Z (1e-5 relative, ΔE00 ≤ 1e-3) and preview.png (one code value).</summary>
    void AssertSameRender(string direct, string relit)
    {
        double worstBand = 0, worstXyz = 0, worstDe = 0;
        using (var a = File.OpenRead(Path.Combine(direct, "spectral.npy")))
        using (var b = File.OpenRead(Path.Combine(relit, "spectral.npy")))
        {
            var (sa, da) = NpyReader.Read(a);
            var (sb, db) = NpyReader.Read(b);
            Assert.Equal(sa, sb);
            int nonzero = 0;
            for (int i = 0; i < da.Length; i++)
            {
                double diff = Math.Abs(da[i] - db[i]);
                Assert.True(diff <= 1e-5 * Math.Abs(da[i]) + 1e-30,
                    $"value {i} (pixel {i / sa[2]}, band {i % sa[2]}): direct {da[i]:R}, relit {db[i]:R}");
                if (da[i] != 0) { nonzero++; worstBand = Math.Max(worstBand, diff / Math.Abs(da[i])); }
            }
            Assert.True(nonzero > da.Length / 2, "the images are mostly black: the comparison would prove nothing");
        }
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(direct, "render.json")))!;
        var w = json["colour"]!["white_xyz"]!.AsArray().Select(v => (double)v!).ToArray();
        var white = new Xyz(w[0], w[1], w[2]);
        var ea = ExrReader.Read(Path.Combine(direct, "spectral.exr"));
        var eb = ExrReader.Read(Path.Combine(relit, "spectral.exr"));
        for (int i = 0; i < ea.OtherChannels["X"].Length; i++)
        {
            foreach (var ch in new[] { "X", "Y", "Z" })
            {
                double va = ea.OtherChannels[ch][i], vb = eb.OtherChannels[ch][i];
                Assert.True(Math.Abs(va - vb) <= 1e-5 * Math.Abs(va) + 1e-30, $"pixel {i} {ch}: direct {va:R}, relit {vb:R}");
                if (va != 0) worstXyz = Math.Max(worstXyz, Math.Abs(va - vb) / Math.Abs(va));
            }
            var xa = new Xyz(ea.OtherChannels["X"][i], ea.OtherChannels["Y"][i], ea.OtherChannels["Z"][i]);
            var xb = new Xyz(eb.OtherChannels["X"][i], eb.OtherChannels["Y"][i], eb.OtherChannels["Z"][i]);
            worstDe = Math.Max(worstDe, DeltaE2000.Between(Lab.FromXyz(xa, white), Lab.FromXyz(xb, white)));
        }
        Assert.True(worstDe <= 1e-3, $"worst ΔE00 {worstDe}");
        var pa = PngReader.Read(Path.Combine(direct, "preview.png"));
        var pb = PngReader.Read(Path.Combine(relit, "preview.png"));
        Assert.Equal(pa.Samples.Length, pb.Samples.Length);
        int codes = 0;
        for (int i = 0; i < pa.Samples.Length; i++) codes = Math.Max(codes, Math.Abs(pa.Samples[i] - pb.Samples[i]));
        Assert.True(codes <= 1, $"preview.png differs by {codes} codes");
        output.WriteLine($"relit vs direct: worst relative band {worstBand:0.###e0}, XYZ {worstXyz:0.###e0}, " +
            $"ΔE00 {worstDe:0.###e0}, preview codes {codes}");
    }

    static string Plain(string dir) => "0.3";

    [Theory]
    [InlineData("paper", "exact")]
    [InlineData("physical", "exact")]
    [InlineData("physical", "weighted")]
    public void Diffuse_texture_relit_equals_a_direct_render(string radiometry, string integration) =>
        RelitEqualsDirect(radiometry, integration, DiffuseEnvi, Plain);

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Specular_texture_relit_equals_a_direct_render(string radiometry) =>
        RelitEqualsDirect(radiometry, "exact", dir => "\"colorchecker:13\"", SpecularEnvi);

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Diffuse_and_specular_textures_relit_equal_a_direct_render(string radiometry) =>
        RelitEqualsDirect(radiometry, "exact", DiffuseEnvi, SpecularEnvi);

    [Fact]
    public void Rgb_png_texture_relit_equals_a_direct_render() =>
        RelitEqualsDirect("physical", "exact", RgbPng, Plain, fill: "FL11");

    /// <summary>The texture seen by a tinted mirror and through Fresnel glass: its terms are recorded with those chains too.</summary>
    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Textured_surface_seen_through_a_mirror_and_glass_relit_equals_a_direct_render(string radiometry)
    {
        var lights = RelitEqualsDirect(radiometry, "exact", DiffuseEnvi, SpecularEnvi, chains: true);
        var comps = lights["components"]!.AsArray();
        Assert.Contains(comps, c => c!["texels"] is not null && c["chain"]!.AsArray().Any(x => (string?)x!["weight"] == "mirror"));
        Assert.Contains(comps, c => c!["texels"] is not null && c["chain"]!.AsArray().Any(x => (string?)x!["weight"] == "transmit"));
    }

    /// <summary>The transfer's files are the same bytes for 1 and 2 threads.</summary>
    [Fact]
    public void Textured_transfer_files_are_byte_identical_for_one_and_two_threads()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "a.json");
        File.WriteAllText(scene, Scene("physical", "exact", DiffuseEnvi(dir), SpecularEnvi(dir), "A", "led-blue", 1, chains: true));
        Run("render", scene, "-o", Path.Combine(dir, "one"), "--formats", "lights", "--threads", "1");
        Run("render", scene, "-o", Path.Combine(dir, "two"), "--formats", "lights", "--threads", "2");
        var files = Directory.GetFiles(Path.Combine(dir, "one", "lights")).Select(Path.GetFileName).Order().ToArray();
        Assert.Contains("texels.npy", files);
        Assert.Contains("centre-texels.npy", files);
        foreach (var f in files)
        {
            var one = File.ReadAllBytes(Path.Combine(dir, "one", "lights", f!));
            var two = File.ReadAllBytes(Path.Combine(dir, "two", "lights", f!));
            Assert.True(one.AsSpan().SequenceEqual(two), $"lights/{f} differs between 1 and 2 threads");
        }
    }

    /// <summary>
    /// The camera's exact route reads the textured transfer: cie-xyz's raw (noise off, flat lens) is proportional to the
    /// render's exact XYZ at every lit pixel (the texel samples integrated per sample with the light's tent-function products,
    /// against the render's texel tables of XYZ), from lights/ and traced again without it.
    /// </summary>
    [Theory]
    [InlineData("exr,aov,lights")]
    [InlineData("exr,aov")]
    public void Exact_camera_route_of_a_textured_render_is_proportional_to_its_exact_xyz(string formats)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "a.json");
        // No coloured mirror or glass: a term through one takes the band route (and its pixel eq. 3), not the exact colour.
        File.WriteAllText(scene, Scene("physical", "exact", DiffuseEnvi(dir), SpecularEnvi(dir), "D65", "led-blue", 1, chains: false));
        var render = Path.Combine(dir, "render");
        Run("render", scene, "-o", render, "--formats", formats);
        var (raw, manifest) = Sensor.ExactSignalsTests.Camera(render, "cie-xyz");
        Assert.StartsWith("exact", (string)manifest["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        var exr = ExrReader.Read(Path.Combine(render, "spectral.exr"));
        var xyz = new[] { exr.OtherChannels["X"], exr.OtherChannels["Y"], exr.OtherChannels["Z"] };
        int n = xyz[1].Length, brightest = Enumerable.Range(0, n).MaxBy(i => xyz[1][i]);
        double ratio = raw[brightest * 3 + 1] / xyz[1][brightest], worst = 0;
        int lit = 0;
        for (int i = 0; i < n; i++)
        {
            if (!(xyz[1][i] > 1e-3 * xyz[1][brightest])) continue;
            lit++;
            for (int c = 0; c < 3; c++) worst = Math.Max(worst, Math.Abs(raw[i * 3 + c] / xyz[c][i] / ratio - 1));
        }
        output.WriteLine($"textured ({formats}): cie-xyz raw / exact XYZ over {lit} pixels, largest relative deviation {worst:E3}");
        Assert.True(lit > n / 2, $"only {lit} lit pixels");
        Assert.True(worst <= 1e-5, $"cie-xyz raw / exact XYZ varies by {worst:E3} relative");
    }

    /// <summary>The spectral viewer cannot sum texel samples in its page: a textured transfer is refused in one line (exit 2).</summary>
    [Fact]
    public void Viewer_refuses_a_textured_transfer_in_one_line()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "a.json");
        File.WriteAllText(scene, Scene("paper", "exact", DiffuseEnvi(dir), "0.3", "A", "A", 1, chains: false));
        Run("render", scene, "-o", Path.Combine(dir, "render"), "--formats", "png,lights");
        var (code, _, err) = CliRunner.Run("view", Path.Combine(dir, "render"));
        Assert.Equal(2, code);
        Assert.Contains("textured terms", err);
        Assert.Single(err.Trim().Split('\n'));
    }

    /// <summary>
    /// A fluorescent material with a diffuse texture (its reflective diagonal per texel, low below 420 nm where the OBA
    /// absorbs) beside the optically brightened paper's re-radiation matrix (scenes/oba-paper-matrix.csv), under D50 with UV
    /// relit to D65 × 0.8: the texel-independent shift is recorded as the factor and rebuilt from the new light; the relit
    /// render equals the direct one.
    /// </summary>
    [Fact]
    public void Fluorescent_textured_paper_relit_equals_a_direct_render()
    {
        var dir = Reference.TempDir();
        const int W = 4, H = 4;
        var wl = Enumerable.Range(0, 31).Select(j => 400.0 + 10 * j).ToArray();
        var texels = new float[W * H * wl.Length];
        for (int p = 0; p < W * H; p++)
            for (int j = 0; j < wl.Length; j++) texels[p * wl.Length + j] = (float)(j < 3 ? 0.1 : 0.35 + 0.2 * Math.Sin(j * 0.2 + p));
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "paper.img"), W, H, wl, texels);
        File.Copy(Repo.PathOf("scenes", "oba-paper-matrix.csv"), Path.Combine(dir, "oba-paper-matrix.csv"));
        string Paper(string light, double intensity) => $$"""
            {
              "bands": "300:780:24", "white": "D50", "integration": "exact",
              "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 30, "width": 40, "height": 30, "spp": 2 },
              "materials": {
                "brightened": { "diffuse": { "texture": "paper.hdr" }, "fluorescence": { "matrix": "oba-paper-matrix.csv" } }
              },
              "lights": [ { "type": "point", "name": "booth", "position": [1, 1, 5], "spectrum": "{{light}}",
                "intensity": {{intensity.ToString(Inv)}} } ],
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": [4, 3], "material": "brightened" } ],
              "background": 0
            }
            """;
        File.WriteAllText(Path.Combine(dir, "m1.json"), Paper("D50", 1));
        File.WriteAllText(Path.Combine(dir, "t.json"), Paper("D65", 0.8));
        Run("render", Path.Combine(dir, "m1.json"), "-o", Path.Combine(dir, "A"), "--formats", "npy,exr,png,lights");
        Run("render", Path.Combine(dir, "t.json"), "-o", Path.Combine(dir, "direct"), "--formats", "npy,exr,png");
        Run("relight", Path.Combine(dir, "A"), "-o", Path.Combine(dir, "relit"), "--light", "booth=D65", "--intensity", "booth=0.8");
        AssertSameRender(Path.Combine(dir, "direct"), Path.Combine(dir, "relit"));
    }

    /// <summary>The memory check counts the textured terms' per-pixel samples: its lights part is at least what the arrays
    /// of the traced transfer hold (texels.npy and centre-texels.npy, read back here), and nothing without textures.</summary>
    [Fact]
    public void Memory_check_counts_the_texel_samples_of_the_lights_product()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "a.json");
        File.WriteAllText(scene, Scene("physical", "exact", DiffuseEnvi(dir), SpecularEnvi(dir), "A", "led-blue", 1, chains: false));
        Run("render", scene, "-o", Path.Combine(dir, "render"), "--formats", "lights");
        long stored = 0;
        foreach (var f in new[] { "texels.npy", "centre-texels.npy" })
        {
            using var st = File.OpenRead(Path.Combine(dir, "render", "lights", f));
            stored += 4L * NpyReader.Read(st).Data.Length;
        }
        var lights = SpectralRenderer.Output.Products.OutputProductTable.Named(["lights"]);
        var parts = SpectralRenderer.Output.RenderMemory.Estimate(SpectralRenderer.Scenes.Loading.SceneLoader.Load(scene), 1, lights);
        var texels = Assert.Single(parts, p => p.Part.Contains("texel samples", StringComparison.Ordinal));
        output.WriteLine($"estimated {texels.Bytes} bytes of texel samples; the transfer stores {stored}");
        Assert.True(texels.Bytes >= stored, $"estimate {texels.Bytes} < stored {stored}");
        File.WriteAllText(scene, Scene("physical", "exact", "0.4", "0.3", "A", "led-blue", 1, chains: false));
        var plain = SpectralRenderer.Output.RenderMemory.Estimate(SpectralRenderer.Scenes.Loading.SceneLoader.Load(scene), 1, lights);
        Assert.DoesNotContain(plain, p => p.Part.Contains("texel samples", StringComparison.Ordinal));
    }
}
