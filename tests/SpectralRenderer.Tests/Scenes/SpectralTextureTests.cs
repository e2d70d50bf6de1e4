using System.Buffers.Binary;
using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// Spectral textures (issue 26): the 24 ColorChecker reflectances (read here from data/colorchecker-ohta.csv, the
/// reference table) written as a texture — ENVI cube, spectral EXR (T.&lt;λ&gt;nm) and 16-bit PNG stack — on one flat quad
/// head-on under D65 (intensity 0.01: band values of order 1, so 1e-6 is some 16 float ulps), against 24 untextured quads whose materials
/// are the same spectra given inline: band values to 1e-6 and colour to ΔE00 0.001 at every patch centre. A textured OBJ mesh (vt rotated
/// by 90°) shows the texel its uv says. Mip levels keep the texture's mean.
/// </summary>
public class SpectralTextureTests(Xunit.Abstractions.ITestOutputHelper output)
{
    internal const int PerPatch = 4;   // texels per patch side: a patch centre's bilinear taps stay inside the patch

    /// <summary>The reference table: wavelengths and the 24 reflectances (patch-major).</summary>
    internal static (double[] Wavelengths, double[][] Patches) ColorCheckerTable()
    {
        var lines = File.ReadAllLines(Path.Combine(DataDirectory.Path, "colorchecker-ohta.csv"))
            .Where(l => l.Length > 0 && char.IsDigit(l[0])).ToArray();
        var wl = lines.Select(l => double.Parse(l.Split(',')[0], CultureInfo.InvariantCulture)).ToArray();
        var patches = Enumerable.Range(1, 24)
            .Select(p => lines.Select(l => double.Parse(l.Split(',')[p], CultureInfo.InvariantCulture)).ToArray()).ToArray();
        return (wl, patches);
    }

    /// <summary>Texel-major values of the 6 × 4 chart, <see cref="PerPatch"/>² texels per patch, row 0 the chart's top row.</summary>
    internal static float[] ChartTexels(double[][] patches, int samples, Func<double, float> value)
    {
        int w = 6 * PerPatch, h = 4 * PerPatch;
        var v = new float[w * h * samples];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                int p = (y / PerPatch) * 6 + x / PerPatch;
                for (int j = 0; j < samples; j++) v[(y * w + x) * samples + j] = value(patches[p][j]);
            }
        return v;
    }

    static string Scene(string objects, string materials = "{}") => $$"""
        {
          "bands": "380:780:20", "integration": "exact", "radiometry": "paper", "white": "D65",
          "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 0.01 } ],
          "materials": {{materials}},
          "objects": [ {{objects}} ],
          "background": 0, "max_depth": 0
        }
        """;

    /// <summary>The untextured chart: 24 unit quads, each with its spectrum inline.</summary>
    static string UntexturedChart(double[] wl, Func<int, int, double> value)
    {
        var inv = CultureInfo.InvariantCulture;
        var objects = new StringBuilder();
        for (int p = 0; p < 24; p++)
        {
            int row = p / 6, col = p % 6;
            var pairs = string.Join(", ", wl.Select((l, j) => $"[{l.ToString(inv)}, {value(p, j).ToString("R", inv)}]"));
            if (p > 0) objects.Append(", ");
            objects.Append(inv,
                $$"""{ "type": "quad", "center": [{{col - 2.5}}, {{1.5 - row}}, 0], "size": 1, "material": { "diffuse": [{{pairs}}] } }""");
        }
        return Scene(objects.ToString());
    }

    static string TexturedChart(string texture) =>
        Scene($$"""{ "type": "quad", "center": [0, 0, 0], "size": [6, 4], "material": { "diffuse": {{texture}} } }""");

    static RenderResult Render(string json, string dir) =>
        Integrators.Render(SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json")));

    /// <summary>Every patch centre: band values to 1e-6 and ΔE00 ≤ 0.001 between the two renders.</summary>
    void SamePatches(string textured, string untextured, string dir)
    {
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(untextured), Path.Combine(dir, "scene.json"));
        var a = Render(textured, dir);
        var b = Integrators.Render(scene);
        int n = scene.Bands, w = scene.Camera.Width;
        var white = scene.Colorimeter.White;
        double worstBand = 0, worstDe = 0;
        for (int p = 0; p < 24; p++)
        {
            var px = scene.Camera.Project(new Vector3(p % 6 - 2.5f, 1.5f - p / 6, 0))!.Value;
            int x = (int)px.X, y = (int)px.Y, i = y * w + x;
            for (int k = 0; k < n; k++) worstBand = Math.Max(worstBand, Math.Abs(a.Image[x, y, k] - b.Image[x, y, k]));
            Assert.True(b.Image[x, y, 10] > 0.005, $"patch {p + 1}: the untextured render is black at its centre");
            var la = Lab.FromXyz(new Xyz(a.Xyz![3 * i], a.Xyz[3 * i + 1], a.Xyz[3 * i + 2]), white);
            var lb = Lab.FromXyz(new Xyz(b.Xyz![3 * i], b.Xyz[3 * i + 1], b.Xyz[3 * i + 2]), white);
            worstDe = Math.Max(worstDe, DeltaE2000.Between(la, lb));
        }
        output.WriteLine($"largest band difference {worstBand:G3}, largest ΔE00 {worstDe:G3}");
        Assert.True(worstBand <= 1e-6, $"largest band difference {worstBand:G3}");
        Assert.True(worstDe <= 0.001, $"largest ΔE00 {worstDe:G3}");
    }

    internal static void WriteEnvi(string image, int w, int h, double[] wl, float[] texels)
    {
        int n = wl.Length;
        var inv = CultureInfo.InvariantCulture;
        File.WriteAllText(Path.ChangeExtension(image, ".hdr"),
            $"ENVI\nsamples = {w}\nlines = {h}\nbands = {n}\nheader offset = 0\nfile type = ENVI Standard\ndata type = "
                + $"4\ninterleave = bsq\nbyte order = 0\n" +
            $"wavelength units = Nanometers\nwavelength = {{{string.Join(", ", wl.Select(l => l.ToString(inv)))}}}\n");
        var bytes = new byte[4 * w * h * n];
        for (int b = 0; b < n; b++)
            for (int p = 0; p < w * h; p++)
                BinaryPrimitives.WriteSingleLittleEndian(bytes.AsSpan(4 * (b * w * h + p)), texels[p * n + b]);
        File.WriteAllBytes(image, bytes);
    }

    [Fact]
    public void A_ColorChecker_ENVI_cube_on_a_quad_equals_the_untextured_patches()
    {
        var (wl, patches) = ColorCheckerTable();
        var dir = Reference.TempDir();
        WriteEnvi(Path.Combine(dir, "chart.img"), 6 * PerPatch, 4 * PerPatch, wl, ChartTexels(patches, wl.Length, v => (float)v));
        SamePatches(TexturedChart("""{ "texture": "chart.hdr" }"""), UntexturedChart(wl, (p, j) => (float)patches[p][j]), dir);
    }

    [Fact]
    public void A_ColorChecker_spectral_EXR_on_a_quad_equals_the_untextured_patches()
    {
        var (wl, patches) = ColorCheckerTable();
        var dir = Reference.TempDir();
        double step = wl[1] - wl[0];
        var grid = new BandGrid(wl[0] - step / 2, wl[^1] + step / 2, wl.Length);
        var image = new SpectralImage(6 * PerPatch, 4 * PerPatch, grid, ChartTexels(patches, wl.Length, v => (float)v));
        ExrWriter.Write(Path.Combine(dir, "chart.exr"), image, new ExrOptions { Reflective = true, Rgb = false });
        Assert.True(ExrReader.Read(Path.Combine(dir, "chart.exr")).Reflective);   // T.<λ>nm channels
        SamePatches(TexturedChart("""{ "texture": "chart.exr" }"""), UntexturedChart(wl, (p, j) => (float)patches[p][j]), dir);
    }

    [Fact]
    public void A_ColorChecker_PNG_stack_on_a_quad_equals_the_untextured_patches()
    {
        // 16-bit bands: the untextured patches take the same quantised values, q / 65535.
        var (wl, patches) = ColorCheckerTable();
        var dir = Reference.TempDir();
        int w = 6 * PerPatch, h = 4 * PerPatch, n = wl.Length;
        static ushort Q(double v) => (ushort)Math.Round(v * 65535);
        var texels = ChartTexels(patches, n, v => Q(v));
        for (int j = 0; j < n; j++)
        {
            var band = new ushort[w * h];
            for (int p = 0; p < w * h; p++) band[p] = (ushort)texels[p * n + j];
            using var f = File.Create(Path.Combine(dir, $"chart_{wl[j].ToString(CultureInfo.InvariantCulture)}.png"));
            PngWriter.WriteGray16(f, w, h, band);
        }
        var list = string.Join(", ", wl.Select(l => l.ToString(CultureInfo.InvariantCulture)));
        SamePatches(TexturedChart($$"""{ "texture": "chart_{nm}.png", "wavelengths": [{{list}}] }"""),
            UntexturedChart(wl, (p, j) => Q(patches[p][j]) / 65535.0), dir);
    }

    [Theory]
    [InlineData("square.obj")]
    [InlineData("square.ply")]
    public void A_textured_mesh_shows_the_texel_its_uv_names(string mesh)
    {
        // A 2 × 2 chart of constant reflectances, 4 × 4 texels each; the square [−1, 1]² in z = 0 with vt turned by 90°:
        // corner (s, t) of the square (s, t ∈ {0, 1}) has uv = (1 − t, s). Around a quarter's centre the bilinear taps stay
        // inside its block.
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "square.obj"),
            "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0 0\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
        File.WriteAllText(Path.Combine(dir, "square.ply"),
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float "
                + "z\nproperty float s\nproperty float t\n" +
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n-1 -1 0 1 0\n1 -1 0 1 1\n1 1 "
                + "0 0 1\n-1 1 0 0 0\n4 0 1 2 3\n");
        double[] rho = [0.1, 0.3, 0.5, 0.7];   // texel (x, y) = rho[y·2 + x], row 0 at the top (v = 1)
        var texels = new float[8 * 8 * 2];
        for (int y = 0; y < 8; y++)
            for (int x = 0; x < 8; x++) texels[2 * (y * 8 + x)] = texels[2 * (y * 8 + x) + 1] = (float)rho[y / 4 * 2 + x / 4];
        WriteEnvi(Path.Combine(dir, "four.img"), 8, 8, [380, 780], texels);
        string Mesh(string material) => Scene($$"""{ "type": "mesh", "file": "{{mesh}}", "material": {{material}} }""");
        var textured = Render(Mesh("""{ "diffuse": { "texture": "four.hdr" } }"""), dir);
        var white = Render(Mesh("""{ "diffuse": 1 }"""), dir);
        var camera = SceneLoader.Parse(Encoding.UTF8.GetBytes(Mesh("1")), Path.Combine(dir, "scene.json")).Camera;
        foreach (var (s, t) in new[] { (0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75) })
        {
            double u = 1 - t, v = s;
            int texel = (int)((1 - v) * 2) * 2 + (int)(u * 2);
            var px = camera.Project(new Vector3((float)(2 * s - 1), (float)(2 * t - 1), 0))!.Value;
            for (int k = 0; k < 20; k++)
                Assert.Equal((float)rho[texel] * white.Image[(int)px.X, (int)px.Y, k], textured.Image[(int)px.X, (int)px.Y, k], 1e-6);
        }
    }

    [Fact]
    public void Mip_levels_keep_the_mean_of_the_texture()
    {
        // An odd-sized random texture: every level's mean table equals the full-resolution mean (area-weighted averaging).
        var rng = new Random(26);
        int w = 37, h = 23;
        double[] wl = [380, 480, 580, 680, 780];
        var values = new float[w * h * wl.Length];
        for (int i = 0; i < values.Length; i++) values[i] = (float)rng.NextDouble();
        var dir = Reference.TempDir();
        WriteEnvi(Path.Combine(dir, "noise.img"), w, h, wl, values);
        var scene =
            SceneLoader.Parse(Encoding.UTF8.GetBytes(TexturedChart("""{ "texture": "noise.hdr" }""")), Path.Combine(dir, "scene.json"));
        var terms = new TermTables(scene).Textures!.Diffuse.Single(t => t is not null)!;
        Assert.True(terms.Levels >= 6);
        int padded = scene.PaddedBands, stride = terms.Slots * padded;
        double[] Mean(int level)
        {
            var m = new double[stride];
            int lw = terms.LevelWidth(level), lh = terms.LevelHeight(level);
            for (int y = 0; y < lh; y++)
                for (int x = 0; x < lw; x++)
                {
                    var texel = terms.Texel(level, x, y);
                    for (int i = 0; i < stride; i++) m[i] += texel[i] / ((double)lw * lh);
                }
            return m;
        }
        var full = Mean(0);
        for (int l = 1; l < terms.Levels; l++)
        {
            var m = Mean(l);
            for (int i = 0; i < stride; i++)
                Assert.True(Math.Abs(m[i] - full[i]) <= 1e-4 * Math.Max(1e-3, Math.Abs(full[i])),
                    $"level {l}, entry {i}: {m[i]} vs {full[i]}");
        }
        // The mean table is the product table of the mean texel spectrum (linearity), computed here another way: the
        // untextured material of the texture's mean spectrum.
        var meanSpectrum = new double[wl.Length];
        for (int i = 0; i < values.Length; i++) meanSpectrum[i % wl.Length] += values[i] / ((double)w * h);
        string meanDiffuse =
            string.Join(", ", wl.Select((l, j) => $"[{l}, {meanSpectrum[j].ToString("R", CultureInfo.InvariantCulture)}]"));
        var plain = SceneLoader.Parse(
            Encoding.UTF8.GetBytes(Scene($$"""{ "type": "quad", "size": 1, "material": { "diffuse": [{{meanDiffuse}}] } }""")),
            Path.Combine(dir, "scene.json"));
        var diffuse = new TermTables(plain).Diffuse[0];
        int slot = 1 + scene.Lights.Count;
        for (int k = 0; k < scene.Bands + 3; k++)
            Assert.Equal(diffuse[k], full[slot * padded + k], 1e-5);
    }

    [Fact]
    public void The_uv_transform_wraps_repeat_clamp_and_mirror()
    {
        Assert.Equal([2, 3, 0, 1, 2, 3, 0], Enumerable.Range(-2, 7).Select(i => UvTransform.WrapIndex(i, 4, TextureWrap.Repeat)));
        Assert.Equal([0, 0, 0, 1, 2, 3, 3], Enumerable.Range(-2, 7).Select(i => UvTransform.WrapIndex(i, 4, TextureWrap.Clamp)));
        // Mirror: … 1 0 | 0 1 2 3 | 3 2 …
        Assert.Equal([1, 0, 0, 1, 2, 3, 3, 2], Enumerable.Range(-2, 8).Select(i => UvTransform.WrapIndex(i, 4, TextureWrap.Mirror)));
        var t = new UvTransform(new Vector2(2, 3), new Vector2(0.5f, 0.25f), 90, TextureWrap.Repeat);
        var uv = t.Apply(new Vector2(1, 1));   // scale (2, 3), turn 90° → (−3, 2), offset → (−2.5, 2.25)
        Assert.Equal(-2.5f, uv.X, 5);
        Assert.Equal(2.25f, uv.Y, 5);
    }
}
