using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Eq. 2 against closed forms, pixel by pixel, band by band. Where a light and a material both vary in a band the
/// scenes ask for the "weighted" scheme, whose band value of a term is the product of the factors' band means; the
/// default exact band means are checked against an independent integral in <see cref="GroundTruthTests"/>.
/// </summary>
public class AnalyticSceneTests
{
    static float[] Project(Scene s, string name) => SpectralMath.ToPadded(s.Colorimeter.Project(SpectrumLibrary.Resolve(name)));

    static void Close(double expected, double actual, double rel, string what) =>
        Assert.True(Math.Abs(actual - expected) <= rel * Math.Max(Math.Abs(expected), 1e-6),
            $"{what}: expected {expected:G9}, got {actual:G9}");

    /// <summary>Ray–sphere in double precision, nearest t &gt; 0.</summary>
    static double? HitSphere(Ray r, Vector3 c, double radius)
    {
        var o = r.Origin - c;
        double b = Vector3.Dot(o, r.Direction), cc = Vector3.Dot(o, o) - radius * radius, a = Vector3.Dot(r.Direction, r.Direction);
        double disc = b * b - a * cc;
        if (disc < 0) return null;
        double t = (-b - Math.Sqrt(disc)) / a;
        return t > 0 ? t : null;
    }

    [Fact]
    public void Diffuse_sphere_under_a_point_light_equals_the_closed_form_in_every_band()
    {
        var scene = SceneText.Load("""
        { "integration": "weighted", "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40, "width": 48, "height": 40 },
          "materials": { "orange": { "diffuse": "colorchecker:7" } },
          "lights": [ { "type": "point", "position": [3, 4, 5], "spectrum": "D65", "intensity": 0.5, "attenuation": [1, 0.2, 0.05] } ],
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "orange" } ] }
        """);
        var img = Integrators.Render(scene).Image;
        var light = Project(scene, "D65");
        var m = Project(scene, "colorchecker:7");
        var lp = new Vector3(3, 4, 5);
        int lit = 0, dark = 0;
        for (int y = 0; y < 40; y += 3)
            for (int x = 0; x < 48; x += 3)
            {
                var ray = scene.Camera.Generate(x + 0.5f, y + 0.5f);
                var t = HitSphere(ray, Vector3.Zero, 1);
                if (t is null) { for (int b = 0; b < scene.Bands; b++) Assert.Equal(0f, img[x, y, b]); continue; }
                var p = ray.Origin + (float)t.Value * ray.Direction;
                var n = Vector3.Normalize(p);
                var toL = lp - p;
                double r = toL.Length();
                double nl = Math.Max(0, Vector3.Dot(n, toL / (float)r));
                double d = 1 / (1 + 0.2 * r + 0.05 * r * r);
                if (nl > 0) lit++; else dark++;
                for (int b = 0; b < scene.Bands; b++)
                    Close(0.5 * light[b] * m[b] * nl * d, img[x, y, b], 2e-4, $"pixel ({x},{y}) band {b}");
            }
        Assert.True(lit > 20 && dark >= 3, $"{lit} lit and {dark} unlit sphere samples");
    }

    [Fact]
    public void A_point_in_shadow_gets_only_the_ambient_terms()
    {
        var scene = SceneText.Load("""
        { "camera": { "position": [0, 3, 6], "look_at": [0, 0, 0], "fov": 50, "width": 60, "height": 50 },
          "materials": { "floor": { "diffuse": 0.5, "ambient": 0.3 }, "ball": { "diffuse": 0.8 } },
          "ambient": "constant:0.1",
          "lights": [ { "type": "point", "position": [0, 6, 0], "spectrum": "E", "intensity": 0.01, "ambient": 0.2 } ],
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor", "name": "floor" },
                       { "type": "sphere", "center": [0, 2, 0], "radius": 1, "material": "ball", "name": "ball" } ] }
        """);
        var result = Integrators.Render(scene);
        var img = result.Image;
        int floor = scene.Objects.FindIndex(o => o.Name == "floor");
        int shadowed = 0, lit = 0;
        for (int y = 0; y < 50; y++)
            for (int x = 0; x < 60; x++)
            {
                if (result.ObjectIds[y * 60 + x] != floor) continue;
                var ray = scene.Camera.Generate(x + 0.5f, y + 0.5f);
                double t = -ray.Origin.Y / ray.Direction.Y;
                var p = ray.Origin + (float)t * ray.Direction;
                double rho = Math.Sqrt(p.X * p.X + p.Z * p.Z);
                // The sphere's shadow from a point light 4 above its centre: a disc of radius 6·tan(asin(1/4)).
                double shadowRadius = 6 * Math.Tan(Math.Asin(0.25));
                if (rho < shadowRadius - 0.05)
                {
                    shadowed++;
                    for (int b = 0; b < scene.Bands; b++) Close(0.1 * 0.3 + 0.2 * 0.3, img[x, y, b], 1e-5, $"shadowed ({x},{y}) band {b}");
                }
                else if (rho > shadowRadius + 0.05)
                {
                    lit++;
                    var toL = new Vector3(0, 6, 0) - p;
                    double cos = toL.Y / toL.Length();
                    var e = Project(scene, "E");
                    for (int b = 0; b < scene.Bands; b++)
                        Close(0.09 + 0.01 * e[b] * 0.5 * cos, img[x, y, b], 1e-4, $"lit ({x},{y}) band {b}");
                }
            }
        Assert.True(shadowed > 10 && lit > 100, $"{shadowed} shadowed, {lit} lit floor pixels");
    }

    [Fact]
    public void Spotlight_factor_is_cos_to_the_exponent_inside_the_cone_and_zero_outside()
    {
        var scene = SceneText.Load("""
        { "camera": { "position": [0, 8, 0.01], "look_at": [0, 0, 0], "fov": 60, "width": 64, "height": 64 },
          "materials": { "floor": { "diffuse": 0.6 } },
          "lights": [ { "type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "cutoff": 20, "exponent": 8,
                        "spectrum": "A", "intensity": 0.05, "ambient": 0.1 } ],
          "objects": [ { "type": "plane", "material": "floor" } ] }
        """);
        var img = Integrators.Render(scene).Image;
        var a = Project(scene, "A");
        int inside = 0, outside = 0;
        for (int y = 0; y < 64; y += 2)
            for (int x = 0; x < 64; x += 2)
            {
                var ray = scene.Camera.Generate(x + 0.5f, y + 0.5f);
                float t = -ray.Origin.Y / ray.Direction.Y;
                var p = ray.Origin + t * ray.Direction;
                var fromLight = Vector3.Normalize(p - new Vector3(0, 4, 0));
                double cosTheta = -fromLight.Y;
                double cosCut = Math.Cos(20 * Math.PI / 180);
                if (Math.Abs(cosTheta - cosCut) < 2e-3) continue;   // too close to the cone's edge to call
                double spot = cosTheta >= cosCut ? Math.Pow(cosTheta, 8) : 0;
                if (spot > 0) inside++; else outside++;
                var toL = new Vector3(0, 4, 0) - p;
                double r = toL.Length(), nl = toL.Y / r;
                for (int b = 0; b < scene.Bands; b++)
                    Close(spot * (0.1 * 0.6 + 0.05 * a[b] * 0.6 * nl), img[x, y, b], 2e-4, $"({x},{y}) band {b}");
            }
        Assert.True(inside > 20 && outside > 20, $"{inside} inside, {outside} outside");
    }

    [Theory]
    [InlineData(2.0)]
    [InlineData(5.0)]
    [InlineData(11.0)]
    public void Attenuation_is_one_over_c0_plus_c1_r_plus_c2_r_squared(double r)
    {
        var scene = SceneText.Load($$"""
        { "integration": "weighted", "camera": { "position": [0, 0, {{r}}], "look_at": [0, 0, 0], "fov": 10, "width": 9, "height": 9 },
          "materials": { "patch": { "diffuse": "colorchecker:13" } },
          "lights": [ { "type": "point", "position": [0, 0, {{r}}], "spectrum": "D65", "attenuation": [0.5, 0.3, 0.2] } ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": [100, 100], "material": "patch" } ] }
        """);
        var img = Integrators.Render(scene).Image;
        var e = Project(scene, "D65");
        var m = Project(scene, "colorchecker:13");
        for (int b = 0; b < scene.Bands; b++)
            Close(e[b] * m[b] / (0.5 + 0.3 * r + 0.2 * r * r), img[4, 4, b], 1e-5, $"band {b}");
    }

    [Fact]
    public void A_mirror_shows_the_reflected_patch_spectrum_times_k_r()
    {
        var scene = SceneText.Load("""
        { "integration": "weighted", "camera": { "position": [0, 2, 0], "look_at": [0, 1.2, -5], "fov": 70, "width": 40, "height": 60 },
          "materials": { "mirror": { "diffuse": 0, "mirror": 0.8 }, "red": { "diffuse": "colorchecker:15" } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65" } ],
          "objects": [ { "type": "plane", "material": "mirror", "name": "mirror" },
                       { "type": "quad", "center": [0, 0, -10], "size": [60, 60], "material": "red", "name": "red" } ] }
        """);
        var result = Integrators.Render(scene);
        var red = SpectralMath.ToPadded(scene.Colorimeter.Project(ColorChecker.Patch(15)));
        var d65 = Project(scene, "D65");
        int mirror = scene.Objects.FindIndex(o => o.Name == "mirror"), patch = scene.Objects.FindIndex(o => o.Name == "red");
        int seenDirect = 0, seenInMirror = 0;
        for (int i = 0; i < result.ObjectIds.Length; i++)
        {
            int id = result.ObjectIds[i];
            if (id != mirror && id != patch) continue;
            double k = id == patch ? 1.0 : 0.8;
            if (id == patch) seenDirect++; else seenInMirror++;
            for (int b = 0; b < scene.Bands; b++)
                Close(k * d65[b] * red[b], result.Image.Data[i * scene.Bands + b], 1e-5, $"pixel {i} band {b}");
        }
        Assert.True(seenDirect > 100 && seenInMirror > 100);
    }

    [Fact]
    public void A_Blinn_Phong_highlight_peaks_where_the_half_vector_meets_the_normal_with_the_light_spectrum()
    {
        var scene = SceneText.Load("""
        { "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 30, "width": 121, "height": 121 },
          "materials": { "gloss": { "diffuse": 0, "specular": 1, "shininess": 60 } },
          "lights": [ { "type": "directional", "direction": [-1, -1, -1], "spectrum": "led-blue" } ],
          "objects": [ { "type": "sphere", "radius": 1, "material": "gloss" } ] }
        """);
        var img = Integrators.Render(scene).Image;
        var blue = Project(scene, "led-blue");
        int peakBand = Array.IndexOf(blue, blue.Max());
        int bx = 0, by = 0;
        for (int y = 0; y < 121; y++) for (int x = 0; x < 121; x++) if (img[x, y, peakBand] > img[bx, by, peakBand]) { bx = x; by = y; }
        var ray = scene.Camera.Generate(bx + 0.5f, by + 0.5f);
        var p = ray.Origin + (float)HitSphere(ray, Vector3.Zero, 1)!.Value * ray.Direction;
        var n = Vector3.Normalize(p);
        var h = Vector3.Normalize(Vector3.Normalize(new Vector3(1, 1, 1)) + Vector3.Normalize(-ray.Direction));
        Assert.True(Vector3.Dot(n, h) > 0.999, $"n·h at the peak = {Vector3.Dot(n, h)}");
        // The highlight's colour is the light's: L_b / I_b is the same in every band.
        double ratio = img[bx, by, peakBand] / blue[peakBand];
        Assert.True(ratio > 0.9, $"peak (n·h)^s·(n·l)-free factor {ratio}");
        for (int b = 0; b < scene.Bands; b++) Close(ratio * blue[b], img[bx, by, b], 1e-5, $"band {b}");
    }

    [Fact]
    public void A_dispersive_glass_sphere_bends_400_nm_and_700_nm_to_different_pixels()
    {
        var scene = SceneText.Load("""
        { "bands": "400:700:15",
          "camera": { "position": [0, 0, 8], "look_at": [0, 0, 0], "fov": 30, "width": 160, "height": 160 },
          "materials": { "glass": { "diffuse": 0, "ambient": 0, "transmit": 1, "ior": { "cauchy": [1.5, 20000] } },
                         "strip": { "diffuse": 0, "ambient": 1 } },
          "ambient": 1,
          "objects": [ { "type": "sphere", "radius": 1.5, "material": "glass", "name": "glass" },
                       { "type": "quad", "center": [0.9, 0, -4], "size": [0.1, 40], "material": "strip", "name": "strip" } ],
          "max_depth": 4 }
        """);
        var result = Integrators.Render(scene);
        int glass = scene.Objects.FindIndex(o => o.Name == "glass");
        int row = 80, w = 160;
        int Peak(int band)
        {
            int best = -1; float v = 0;
            for (int x = 0; x < w; x++)
                if (result.ObjectIds[row * w + x] == glass && result.Image[x, row, band] > v) { v = result.Image[x, row, band]; best = x; }
            Assert.True(v > 0.5f, $"band {band}: no bright feature through the glass");
            return best;
        }
        int blue = Peak(0), red = Peak(14);
        Assert.True(Math.Abs(blue - red) >= 2, $"400 nm peak at x={blue}, 700 nm peak at x={red}");
        // Seen directly (not through the glass) the strip is at the same pixels in both bands.
        for (int x = 0; x < w; x++)
            if (result.ObjectIds[row * w + x] != glass) Assert.Equal(result.Image[x, row, 0], result.Image[x, row, 14]);
    }
}
