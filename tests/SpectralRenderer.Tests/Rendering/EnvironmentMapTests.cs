using System.Buffers.Binary;
using System.Numerics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The environment-map sky ("sky": { "type": "envmap" }, Rendering/Emitters/EnvironmentEmitter.cs): Mitsuba 3's lat-long
/// directions written out here, a constant map against the uniform sky of the same colour, a patch of bright pixels against
/// the illuminance its interpolated radiance gives by 1D quadrature (E = c·∫a(φ)·g(φ) dφ · ∫b(θ)·h(θ) dθ for a separable cosine),
/// its transform, the sampling density integrated over the sphere, and the Radiance RGBE and PFM readers.
/// </summary>
public sealed class EnvironmentMapTests : IDisposable
{
    readonly string _dir = Directory.CreateTempSubdirectory("envmap-").FullName;

    public void Dispose() => Directory.Delete(_dir, true);

    /// <summary>A little-endian PFM file of <paramref name="w"/> × <paramref name="h"/> pixels (rows top to bottom in rgb).</summary>
    string Pfm(string name, int w, int h, Func<int, int, (float R, float G, float B)> pixel)
    {
        var path = Path.Combine(_dir, name);
        using var s = File.Create(path);
        s.Write(System.Text.Encoding.ASCII.GetBytes($"PF\n{w} {h}\n-1.0\n"));
        var b = new byte[4];
        for (int row = h - 1; row >= 0; row--)   // PFM stores the bottom row first
            for (int x = 0; x < w; x++)
            {
                var (r, g, bb) = pixel(x, row);
                foreach (var v in new[] { r, g, bb }) { BinaryPrimitives.WriteSingleLittleEndian(b, v); s.Write(b); }
            }
        return path;
    }

    static string Scene(string sky, Vector3 normal, int spp = 64) => $$"""
        { "radiometry": "physical", "bands": "400:700:50", "integrator": "path",
          "camera": { "position": [{{F(normal * 2 + new Vector3(0.01f, 0.02f, 0.015f))}}], "look_at": [0, 0, 0],
                      "width": 6, "height": 6, "fov": 10, "spp": {{spp}} },
          "sky": {{sky}},
          "materials": { "board": { "type": "lambertian", "reflectance": 0.5 } },
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [{{F(normal)}}], "material": "board" } ] }
        """;

    const string Camera =
        """ "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1], "width": 2, "height": 2 }, "materials": {}, "objects": []""";

    static string F(Vector3 v) => FormattableString.Invariant($"{v.X}, {v.Y}, {v.Z}");

    static double MeanBand(RenderResult r, int bands, int b)
    {
        double sum = 0;
        int n = r.Image.Data.Length / bands;
        for (int i = 0; i < n; i++) sum += r.Image.Data[i * bands + b];
        return sum / n;
    }

    /// <summary>The band radiances of a uniform sky of rgb [k, k, k] uplifted as a D65 illuminant (the loader's rgb path).</summary>
    static float[] White(double k) => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "400:700:50", {{Camera}},
          "background": { "rgb": [{{k}}, {{k}}, {{k}}], "illuminant": "D65" } }
        """).Background;

    [Fact]
    public void Directions_follow_Mitsubas_lat_long_convention()
    {
        // Mitsuba 3 envmap: d = (sin φ sin θ, cos θ, −cos φ sin θ), φ = 2πu, θ = πv.
        AssertNear(new Vector3(0, 1, 0), EnvironmentMap.Direction(0.3, 0));          // top row: +Y
        AssertNear(new Vector3(0, 0, 1), EnvironmentMap.Direction(0.5, 0.5));        // image centre: +Z
        AssertNear(new Vector3(1, 0, 0), EnvironmentMap.Direction(0.25, 0.5));       // a quarter across: +X
        AssertNear(new Vector3(0, 0, -1), EnvironmentMap.Direction(0, 0.5));         // the edges: −Z
        var uv = EnvironmentMap.Uv(new Vector3(-1, -1, 0));
        Assert.Equal(0.75, uv.X, 1e-6);
        Assert.Equal(0.75, uv.Y, 1e-6);
    }

    static void AssertNear(Vector3 expected, Vector3 actual) => Assert.True(Vector3.Distance(expected, actual) < 1e-6f, $"{actual}");

    [Fact]
    public void A_constant_map_lights_a_plane_as_the_uniform_sky_does_pi_L()
    {
        var map = Pfm("grey.pfm", 8, 5, (_, _) => (1, 1, 1));
        var scene = SceneText.Load(Scene($$"""{ "type": "envmap", "file": "{{map}}", "scale": 2 }""", Vector3.UnitY));
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
        var sky = White(2);
        for (int b = 0; b < scene.Bands; b++)
        {
            // E = π·L over the upper hemisphere; a lambertian of ρ = 0.5 sends ρ·E/π = 0.5·L.
            Assert.Equal(sky[b], scene.Background[b], sky[b] * 1e-4);
            Assert.Equal(0.5 * sky[b], MeanBand(r, scene.Bands, b), sky[b] * 5e-3);
        }
        // Camera rays that escape see the map (path) and the background, its mean (Whitted): the same for a constant map.
        var open = SceneText.Load($$"""
            { "radiometry": "physical", "bands": "400:700:50", "camera": { "position": [0, 0, 0], "look_at": [0.3, 1, 0.2],
              "width": 2, "height": 2, "spp": 1 }, "materials": {}, "objects": [],
              "sky": { "type": "envmap", "file": "{{map}}", "scale": 2 } }
            """);
        foreach (var integrator in new[] { "path", "whitted" })
        {
            var seen = Renderer.Render(open, Integrators.Create(open, new SceneGeometry(open), integrator));
            for (int b = 0; b < open.Bands; b++) Assert.Equal(sky[b], seen.Image.Data[b], sky[b] * 1e-4);
        }
    }

    /// <summary>∫ f over [a, b] by Simpson's rule on n (even) intervals.</summary>
    static double Simpson(Func<double, double> f, double a, double b, int n = 20000)
    {
        double h = (b - a) / n, sum = f(a) + f(b);
        for (int i = 1; i < n; i++) sum += (i % 2 == 1 ? 4 : 2) * f(a + i * h);
        return sum * h / 3;
    }

    /// <summary>The 1D weight of a run of bright pixels [first, last] on a grid of spacing <paramref name="step"/> starting at
    /// <paramref name="origin"/>: 1 between their centres, falling linearly to 0 one step outside (bilinear interpolation).</summary>
    static Func<double, double> Plateau(double origin, double step, int first, int last) => x =>
    {
        double a = origin + first * step, b = origin + last * step;
        return x < a - step || x > b + step ? 0 : x < a ? 1 - (a - x) / step : x > b ? 1 - (x - b) / step : 1;
    };

    [Theory]
    [InlineData("zenith")]
    [InlineData("east")]
    [InlineData("rotated")]
    public void A_patch_of_bright_pixels_lights_from_its_direction_with_its_bilinear_illuminance(string where)
    {
        const int W = 16, H = 9;
        // zenith: rows 1–2 (θ = 22.5°, 45°), columns 3–4; east: rows 3–5 (θ = 67.5°–112.5°), columns 3–4 (u = 3.5/16 to 4.5/16,
        // about φ = 90°: +X); rotated: east's patch under a 90° turn about +Y (+X → −Z).
        var (rows, cols) = where == "zenith" ? ((1, 2), (3, 4)) : ((3, 5), (3, 4));
        const float c = 3;
        var map = Pfm($"{where}.pfm", W, H, (x, y) =>
            y >= rows.Item1 && y <= rows.Item2 && x >= cols.Item1 && x <= cols.Item2 ? (c, c, c) : (0, 0, 0));
        string transform = where == "rotated" ? """, "transform": { "rotate": [0, 90, 0] }""" : "";
        var normal = where switch { "zenith" => Vector3.UnitY, "east" => Vector3.UnitX, _ => -Vector3.UnitZ };
        var sky = $$"""{ "type": "envmap", "file": "{{map}}"{{transform}} }""";
        // The bilinear weight of the bright pixels is a(φ)·b(θ); Mitsuba interpolates the unit spectrum and the scale apart,
        // each black pixel's both 0, so the radiance is c·(a·b)² — c on the plateau, falling as the square across a ramp.
        var pa = Plateau(2 * Math.PI * 0.5 / W, 2 * Math.PI / W, cols.Item1, cols.Item2);   // over φ, columns at (x + ½)/W
        var pb = Plateau(0, Math.PI / (H - 1), rows.Item1, rows.Item2);                     // over θ, rows at πy/(H − 1)
        Func<double, double> a = p => pa(p) * pa(p), b = t => pb(t) * pb(t);
        // E = c ∫∫ a(φ) b(θ) (ω·n) sin θ dθ dφ, with ω·n = cos θ (zenith) or sin φ sin θ (east, in the map's frame).
        double e = where == "zenith"
            ? Simpson(a, 0, 2 * Math.PI) * Simpson(t => b(t) * Math.Sin(t) * Math.Cos(t), 0, Math.PI / 2)
            : Simpson(p => a(p) * Math.Sin(p), 0, Math.PI) * Simpson(t => b(t) * Math.Sin(t) * Math.Sin(t), 0, Math.PI);
        var scene = SceneText.Load(Scene(sky, normal, 256));
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
        var white = White(c);   // the band radiance of pixel value c (white, a lattice colour: uplifted exactly)
        for (int k = 0; k < scene.Bands; k++)
            Assert.Equal(0.5 / Math.PI * e * white[k], MeanBand(r, scene.Bands, k), 0.5 / Math.PI * e * white[k] * 0.01);
        // The opposite face sees none of it.
        var back = SceneText.Load(Scene(sky, -normal, 16));
        var dark = Renderer.Render(back, Integrators.Create(back, new SceneGeometry(back), "path"));
        Assert.All(dark.Image.Data, v => Assert.Equal(0, v));
    }

    [Fact]
    public void The_sampling_density_integrates_to_one_over_the_sphere_and_matches_its_samples()
    {
        var rng = new Random(7);
        var map = Pfm("noise.pfm", 12, 7, (x, y) => x is >= 4 and <= 6 ? (0, 0, 0)
            : ((float)rng.NextDouble() * 4, (float)rng.NextDouble(), (float)rng.NextDouble() * 0.5f));
        var scene = SceneText.Load($$"""
            { "radiometry": "physical", "bands": "400:700:50", {{Camera}},
              "sky": { "type": "envmap", "file": "{{map}}", "transform": { "rotate": [20, 30, 0] } } }
            """);
        var set = new EmitterSet(scene, new SubBandGrid(scene, 5), 1);
        var env = Assert.IsType<EnvironmentEmitter>(set[set.Sky]);
        // Midpoint quadrature over (θ, φ) of p(ω) sin θ.
        const int NT = 1200, NP = 2400;
        double integral = 0;
        for (int i = 0; i < NT; i++)
        {
            double t = Math.PI * (i + 0.5) / NT;
            for (int j = 0; j < NP; j++)
            {
                double p = 2 * Math.PI * (j + 0.5) / NP;
                var w = new Vector3((float)(Math.Sin(t) * Math.Cos(p)), (float)Math.Cos(t), (float)(Math.Sin(t) * Math.Sin(p)));
                integral += env.Pdf(default, default, w, default, default) * Math.Sin(t);
            }
        }
        integral *= Math.PI / NT * 2 * Math.PI / NP;
        Assert.Equal(1, integral, 2e-3);
        // Each sample's density is the density of its direction, and no sample falls where the map is black.
        var radiance = new float[new SubBandGrid(scene, 5).Padded];
        for (int k = 0; k < 2000; k++)
        {
            Assert.True(env.Sample(default, default, new Vector2((float)rng.NextDouble(), (float)rng.NextDouble()), out var s));
            Assert.Equal(env.Pdf(default, default, s.Direction, default, default), s.Pdf, s.Pdf * 2e-3);
            env.Lookup(s.Direction, radiance);
            Assert.True(radiance.Max() > 0, $"a sample at {s.Direction} where the map is black");
        }
    }

    [Fact]
    public void Radiance_RGBE_pictures_decode_flat_and_run_length_scanlines()
    {
        // 8 pixels wide (the run-length form starts at 8): row 0 run-length, row 1 flat. (128, 64, 32, e = 129) = 1, ½, ¼.
        var bytes = new List<byte>();
        bytes.AddRange("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1\n\n-Y 2 +X 8\n"u8.ToArray());
        bytes.AddRange([2, 2, 0, 8]);
        bytes.AddRange([128 + 8, 128]);                  // R: a run of eight 128s
        bytes.AddRange([8, 64, 64, 64, 64, 0, 0, 0, 1]); // G: eight literals
        bytes.AddRange([128 + 8, 32]);                   // B
        bytes.AddRange([128 + 8, 129]);                  // E
        for (int x = 0; x < 8; x++) bytes.AddRange([(byte)(16 * x), 0, 0, 136]);   // e = 136: R = 16x exactly
        var img = RgbeReader.Read([.. bytes], "test.hdr");
        Assert.Equal((8, 2), (img.Width, img.Height));
        Assert.Equal([1f, 0.5f, 0.25f], img.Rgb[..3]);
        Assert.Equal([1f, 1f / 128, 0.25f], img.Rgb[21..24]);   // pixel 7: G's literal 1 with e = 129 is 1·2^(129 − 136)
        Assert.Equal(16f * 5, img.Rgb[3 * (8 + 5)]);
    }

    [Fact]
    public void PFM_rows_are_read_top_down_and_a_grey_map_fills_rgb()
    {
        var path = Pfm("rows.pfm", 2, 3, (x, y) => (y, x, 10 * y + x));
        var img = PfmReader.Read(path);
        Assert.Equal(2f, img.Rgb[3 * (2 * 2 + 0)]);     // row 2 (bottom), column 0: R = y
        Assert.Equal(21f, img.Rgb[3 * (2 * 2 + 1) + 2]);
        byte[] grey = [.. "Pf\n1 1\n-1\n"u8, 0, 0, 0x40, 0x40];   // 3.0f little-endian
        Assert.Equal([3f, 3f, 3f], PfmReader.Read(grey, "grey.pfm").Rgb);
    }
}
