using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// RGB textures (issue 26): the 24 sRGB codes of the ColorChecker (data/reference/colorchecker-ohta-d65-2deg.csv)
/// uplifted to reflectances stay within [0, 1] and return to their sRGB colour under D65 within ΔE00 0.01 — the colour
/// integrated here independently (1 nm midpoint sums of the CIE 1931 table × D65 × the spectrum), the target decoded
/// here from IEC 61966-2-1; and the same through a render of an RGB PNG on a quad.
/// </summary>
public class RgbTextureTests(Xunit.Abstractions.ITestOutputHelper output)
{
    internal static List<(int R, int G, int B)> Codes() =>
        Reference.Rows("colorchecker-ohta-d65-2deg.csv").Select(r => ((int)r.D("srgb8_r"), (int)r.D("srgb8_g"), (int)r.D("srgb8_b")))
            .ToList();

    /// <summary>IEC 61966-2-1: the decoding curve and the RGB → XYZ matrix (white Y = 1).</summary>
    internal static Xyz Target(int r, int g, int b)
    {
        static double L(int c) { double v = c / 255.0; return v <= 0.04045 ? v / 12.92 : Math.Pow((v + 0.055) / 1.055, 2.4); }
        double lr = L(r), lg = L(g), lb = L(b);
        return new Xyz(0.4124 * lr + 0.3576 * lg + 0.1805 * lb, 0.2126 * lr + 0.7152 * lg + 0.0722 * lb,
            0.0193 * lr + 0.1192 * lg + 0.9505 * lb);
    }

    static double[] Column(string file, string column)
    {
        var lines = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, file)).Where(l => l.Length > 0).ToArray();
        int k = Array.IndexOf(lines[0].Split(','), column);
        return lines.Skip(1).Select(l => double.Parse(l.Split(',')[k], CultureInfo.InvariantCulture)).ToArray();
    }

    static double Linear(double[] x, double[] y, double at)
    {
        if (at <= x[0]) return y[0];
        if (at >= x[^1]) return y[^1];
        int i = Array.BinarySearch(x, at);
        if (i >= 0) return y[i];
        i = ~i;
        double f = (at - x[i - 1]) / (x[i] - x[i - 1]);
        return y[i - 1] + f * (y[i] - y[i - 1]);
    }

    /// <summary>XYZ of reflectance (wl, r) under a light of data/illuminants.csv (D65) by 0.1 nm midpoint sums over 380–780 nm, white Y =
    /// 1.</summary>
    internal static Xyz Integrate(double[] wl, double[] r, string light = "D65")
    {
        var cw = Column("cie1931-2deg-cmf.csv", "wavelength_nm");
        double[] xb = Column("cie1931-2deg-cmf.csv", "xbar"), yb = Column("cie1931-2deg-cmf.csv", "ybar"),
            zb = Column("cie1931-2deg-cmf.csv", "zbar");
        var dw = Column("illuminants.csv", "wavelength_nm");
        var d65 = Column("illuminants.csv", light);
        double x = 0, y = 0, z = 0, white = 0;
        for (double l = 380.05; l < 780; l += 0.1)
        {
            double e = Linear(dw, d65, l), rho = Linear(wl, r, l), ey = e * Linear(cw, yb, l);
            x += e * Linear(cw, xb, l) * rho; y += ey * rho; z += e * Linear(cw, zb, l) * rho; white += ey;
        }
        return new Xyz(x / white, y / white, z / white);
    }

    [Fact]
    public void The_24_ColorChecker_sRGB_codes_round_trip_within_0_01_with_reflectances_in_0_1()
    {
        var uplift = new SigmoidUplift();
        var wl = SigmoidUplift.Wavelengths;
        var white = Integrate(wl, [.. wl.Select(_ => 1.0)]);
        double worst = 0;
        foreach (var (r, g, b) in Codes())
        {
            var rho = uplift.FromSrgbCodes(r, g, b, 255);
            Assert.All(rho, v => Assert.InRange(v, 0.0, 1.0));
            double de = DeltaE2000.Between(Lab.FromXyz(Integrate(wl, rho), white), Lab.FromXyz(Target(r, g, b), white));
            worst = Math.Max(worst, de);
        }
        output.WriteLine($"uplift round trip: largest ΔE00 {worst:G3}");
        Assert.True(worst <= 0.01, $"largest ΔE00 {worst:G3}");
    }

    [Fact]
    public void An_sRGB_PNG_chart_on_a_quad_renders_its_sRGB_colours()
    {
        var codes = Codes();
        var dir = Reference.TempDir();
        const int Per = 4;
        int w = 6 * Per, h = 4 * Per;
        var rgb = new byte[3 * w * h];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                var (r, g, b) = codes[(y / Per) * 6 + x / Per];
                int i = 3 * (y * w + x);
                rgb[i] = (byte)r; rgb[i + 1] = (byte)g; rgb[i + 2] = (byte)b;
            }
        using (var f = File.Create(Path.Combine(dir, "chart.png"))) PngWriter.WriteRgb8(f, w, h, rgb);
        var json = """
            {
              "bands": "380:780:20", "integration": "exact", "radiometry": "paper", "white": "D65",
              "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 1 },
              "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 1 } ],
              "objects": [ { "type": "quad", "size": [6, 4], "material": { "diffuse": { "texture": "chart.png" } } } ],
              "background": 0, "max_depth": 0
            }
            """;
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
        var result = Integrators.Render(scene);
        var white = scene.Colorimeter.White;
        double worst = 0;
        for (int p = 0; p < 24; p++)
        {
            var px = scene.Camera.Project(new Vector3(p % 6 - 2.5f, 1.5f - p / 6, 0))!.Value;
            int i = (int)px.Y * scene.Camera.Width + (int)px.X;
            var xyz = new Xyz(result.Xyz![3 * i], result.Xyz[3 * i + 1], result.Xyz[3 * i + 2]);
            var (r, g, b) = codes[p];
            worst = Math.Max(worst, DeltaE2000.Between(Lab.FromXyz(xyz, white), Lab.FromXyz(Target(r, g, b), white)));
        }
        output.WriteLine($"rendered RGB chart: largest ΔE00 {worst:G3}");
        Assert.True(worst <= 0.01, $"largest ΔE00 {worst:G3}");
    }
    [Fact]
    public void A_png_given_inline_as_a_data_uri_renders_the_same_bits_as_the_file()
    {
        var dir = Reference.TempDir();
        var codes = Codes();
        var rgb = new byte[3 * 4 * 2];
        for (int p = 0; p < 8; p++) (rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]) = ((byte)codes[p].R, (byte)codes[p].G, (byte)codes[p].B);
        var file = Path.Combine(dir, "tiny.png");
        using (var f = File.Create(file)) PngWriter.WriteRgb8(f, 4, 2, rgb);
        string Scene(string texture) => $$"""
            {
              "bands": "380:780:20", "radiometry": "paper", "white": "D65",
              "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "fov": 12, "width": 16, "height": 8, "spp": 1 },
              "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 1 } ],
              "objects": [ { "type": "quad", "size": [4, 2], "material": { "diffuse": { "texture": "{{texture}}" } } } ],
              "max_depth": 0
            }
            """;
        float[] Render(string texture) =>
            Integrators.Render(SceneLoader.Parse(Encoding.UTF8.GetBytes(Scene(texture)), Path.Combine(dir, "scene.json"))).Image.Data;
        var inline = "data:image/png;base64," + Convert.ToBase64String(File.ReadAllBytes(file));
        Assert.True(Render("tiny.png").AsSpan().SequenceEqual(Render(inline)), "the data: URI texture differs from the file");
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => Render("data:image/png;base64,%%%"));
        Assert.Contains("$.objects[0].material.diffuse.texture: the data: URI is not valid base64", e.Message);
    }
}
