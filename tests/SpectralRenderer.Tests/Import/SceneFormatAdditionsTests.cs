using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using Xunit;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// The scene-file additions importers write (docs/scene-format.md): an object's "transform": { "matrix" } (row-major, p' = M·p),
/// a mesh's "inline" block, and the { "rgb" } spectrum values, each against values worked out by hand.
/// </summary>
public class SceneFormatAdditionsTests
{
    static Scene Load(string objects, string extra = "") => SceneLoader.Parse(Encoding.UTF8.GetBytes($$"""
        { "bands": "380:780:80", "radiometry": "physical", "integrator": "path", {{extra}}
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "materials": { "grey": { "type": "lambertian", "reflectance": 0.5 } },
          "objects": [ {{objects}} ] }
        """), "additions.json");

    [Fact]
    public void A_row_major_matrix_maps_points_as_written()
    {
        // M = translate(1, 2, 3) · rotate 90° about z · scale 2: (1, 0, 0) → (0, 2, 0) → (1, 4, 3); (0, 1, 0) → (−2, 0, 0) → (−1, 2, 3).
        var scene = Load("""
            { "type": "sphere", "material": "grey", "transform": { "matrix": [0, -2, 0, 1,  2, 0, 0, 2,  0, 0, 2, 3,  0, 0, 0, 1] } }
            """);
        var m = scene.Objects[0].Shape!.ObjectToWorld;
        AssertNear(new Vector3(1, 4, 3), Vector3.Transform(Vector3.UnitX, m));
        AssertNear(new Vector3(-1, 2, 3), Vector3.Transform(Vector3.UnitY, m));
        AssertNear(new Vector3(1, 2, 5), Vector3.Transform(Vector3.UnitZ, m));
        // The sphere of radius 1 at the origin becomes one of radius 2 at (1, 2, 3): its bounds say so.
        var b = scene.Objects[0].Shape!.Bounds;
        AssertNear(new Vector3(-1, 0, 1), b.Min);
        AssertNear(new Vector3(3, 4, 5), b.Max);
    }

    [Fact]
    public void A_matrix_on_a_mesh_moves_its_vertices()
    {
        var scene = Load("""
            { "type": "mesh", "name": "tri", "material": "grey",
              "inline": { "positions": [0, 0, 0,  1, 0, 0,  0, 1, 0], "indices": [0, 1, 2] },
              "transform": { "matrix": [1, 0, 0, 10,  0, 1, 0, 0,  0, 0, -1, 0,  0, 0, 0, 1] } }
            """);
        var mesh = scene.Objects[0].Mesh!;
        AssertNear(new Vector3(10, 0, 0), mesh.Positions[0]);
        AssertNear(new Vector3(11, 0, 0), mesh.Positions[1]);
        AssertNear(new Vector3(10, 1, 0), mesh.Positions[2]);
    }

    [Theory]
    [InlineData("[1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1]", "not [0, 0, 0, 1]")]
    [InlineData("[1, 0, 0, 0,  2, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]", "singular")]
    [InlineData("[1, 0, 0, 0]", "16 numbers")]
    public void A_bad_matrix_is_one_line_at_its_path(string matrix, string what)
    {
        var e = Assert.Throws<InputException>(() =>
            Load($$"""{ "type": "sphere", "material": "grey", "transform": { "matrix": {{matrix}} } }"""));
        Assert.Contains("$.objects[0].transform.matrix", e.Message);
        Assert.Contains(what, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }

    [Fact]
    public void A_matrix_with_translate_is_refused()
    {
        var e = Assert.Throws<InputException>(() => Load("""
            { "type": "sphere", "material": "grey",
              "transform": { "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "translate": [1, 0, 0] } }
            """));
        Assert.Contains("either \"matrix\" or translate", e.Message);
    }

    [Fact]
    public void An_inline_mesh_keeps_its_positions_normals_and_uvs()
    {
        var scene = Load("""
            { "type": "mesh", "name": "square", "material": "grey",
              "inline": { "positions": [0, 0, 0,  2, 0, 0,  2, 2, 0,  0, 2, 0], "indices": [0, 1, 2,  0, 2, 3],
                          "normals": [0, 0, 3,  0, 0, 1,  0, 0, 1,  0, 0, 1], "uvs": [0, 0,  1, 0,  1, 1,  0, 1] } }
            """);
        var mesh = scene.Objects[0].Mesh!;
        Assert.Equal(2, mesh.TriangleCount);
        Assert.Equal(new Vector3(2, 2, 0), mesh.Positions[2]);
        Assert.Equal(Vector3.UnitZ, mesh.Normals![0]);   // normalised
        // uvs per triangle corner: triangle 1 is vertices 0, 2, 3.
        Assert.Equal(new Vector2(0, 0), mesh.TexCoords![3]);
        Assert.Equal(new Vector2(1, 1), mesh.TexCoords![4]);
        Assert.Equal(new Vector2(0, 1), mesh.TexCoords![5]);
    }

    [Theory]
    [InlineData("\"positions\": [0, 0, 0, 1, 0, 0, 0, 1, 0], \"indices\": [0, 1, 3]", "$.objects[0].inline.indices[2]")]
    [InlineData("\"positions\": [0, 0, 0, 1, 0, 0, 0, 1], \"indices\": [0, 1, 2]", "$.objects[0].inline.positions")]
    [InlineData("\"positions\": [0, 0, 0, 1, 0, 0, 0, 1, 0], \"indices\": [0, 1, 2], \"normals\": [0, 0, 1]",
        "$.objects[0].inline.normals")]
    [InlineData("\"positions\": [0, 0, 0, 1, 0, 0, 0, 1, 0], \"indices\": [0, 1.5, 2]", "$.objects[0].inline.indices[1]")]
    public void A_bad_inline_mesh_is_one_line_at_its_path(string block, string path)
    {
        var e =
            Assert.Throws<InputException>(() => Load($$"""{ "type": "mesh", "name": "m", "material": "grey", "inline": { {{block}} } }"""));
        Assert.Contains(path, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }

    [Fact]
    public void A_mesh_with_file_and_inline_is_refused()
    {
        var e = Assert.Throws<InputException>(() => Load("""
            { "type": "mesh", "name": "m", "material": "grey", "file": "x.ply",
              "inline": { "positions": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2] } }
            """));
        Assert.Contains("either \"file\" or \"inline\"", e.Message);
    }

    [Fact]
    public void An_rgb_grey_reflectance_is_that_constant()
    {
        // Grey lies near the sigmoid's centre line (c = 0 gives S = ½ everywhere); the 4-decimal sRGB matrix's white is D65 under
        // the CIE table to about 1e-3, so the solved grey is flat 0.5 to that.
        var scene = Load("""{ "type": "sphere", "material": { "type": "lambertian", "reflectance": { "rgb": [0.5, 0.5, 0.5] } } }""");
        var rho = scene.Materials[scene.Objects[0].Material].Diffuse;
        for (int b = 0; b < scene.Bands; b++) Assert.Equal(0.5, rho[b], 2e-3);
    }

    [Fact]
    public void An_rgb_reflectance_has_that_colour_under_D65()
    {
        // The band values' colour under D65 (CIE 1931 ȳ·D65 summed on the 5 nm bands) against IEC 61966-2-1's matrix × rgb.
        double[] rgb = [0.6, 0.25, 0.1];
        var scene = Load($$"""
            { "type": "sphere", "material": { "type": "lambertian", "reflectance": { "rgb": [{{rgb[0]}}, {{rgb[1]}}, {{rgb[2]}}] } } }
            """);
        var rho = scene.Materials[scene.Objects[0].Material].Diffuse;
        var d65 = SpectralRenderer.Spectra.SpectrumLibrary.Resolve("D65");
        var cmf = SpectralRenderer.Color.Observer.Cie1931;
        double x = 0, y = 0, z = 0, yw = 0;
        for (int b = 0; b < scene.Bands; b++)
        {
            double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b);
            double ex = SpectralRenderer.Spectra.TabulatedSpectrum.IntegrateProduct(cmf.XBar, d65, lo, hi);
            double ey = SpectralRenderer.Spectra.TabulatedSpectrum.IntegrateProduct(cmf.YBar, d65, lo, hi);
            double ez = SpectralRenderer.Spectra.TabulatedSpectrum.IntegrateProduct(cmf.ZBar, d65, lo, hi);
            x += rho[b] * ex; y += rho[b] * ey; z += rho[b] * ez; yw += ey;
        }
        double tx = 0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2];
        double ty = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
        double tz = 0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2];
        // Band means of a smooth spectrum against its exact integral: a few 1e-4 in the colour.
        Assert.Equal(tx, x / yw, 2e-3);
        Assert.Equal(ty, y / yw, 2e-3);
        Assert.Equal(tz, z / yw, 2e-3);
    }

    [Fact]
    public void An_rgb_white_emission_is_D65_at_luminance_factor_one()
    {
        // [1, 1, 1] × D65: s = 2, the uplift of ½ grey is ½, so S = D65/Ȳ with Ȳ = ∫ȳ·D65/∫ȳ = 98.9974 (Mitsuba's
        // MI_CIE_D65_NORMALIZATION = 1/98.99741751876255); D65 is 100.0 at 560 nm, so each band is D65's band mean / 98.997.
        var scene = Load("""
            { "type": "sphere", "material": { "type": "lambertian", "reflectance": 0.5,
              "emission": { "spectrum": { "rgb": [1, 1, 1], "illuminant": "D65" }, "radiance": 1 } } }
            """);
        var radiance = scene.Materials[scene.Objects[0].Material].Emission!.Radiance;
        int band = (int)((560 - scene.Grid.Start) / scene.Grid.Width);   // 560–565 nm
        var d65 = SpectralRenderer.Spectra.SpectrumLibrary.Resolve("D65");
        double expected = d65.Mean(scene.Grid.Lower(band), scene.Grid.Upper(band)) / 98.99741751876255;
        Assert.Equal(expected, radiance[band], 2e-3 * expected);
    }

    [Fact]
    public void An_rgb_reflectance_above_one_is_refused()
    {
        var e = Assert.Throws<InputException>(() =>
            Load("""{ "type": "sphere", "material": { "type": "lambertian", "reflectance": { "rgb": [1.5, 0, 0] } } }"""));
        Assert.Contains("$.objects[0].material.reflectance.rgb[0]", e.Message);
    }

    static void AssertNear(Vector3 expected, Vector3 actual)
    {
        Assert.True(Vector3.Distance(expected, actual) < 1e-5f, $"expected {expected}, found {actual}");
    }
}
