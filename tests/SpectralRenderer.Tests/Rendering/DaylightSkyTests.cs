using System.Globalization;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The CIE daylight sky (issue 23): its spectral radiance against the published D65 table (CCT 6504 K), its luminance
/// against K_m∫V·L dλ summed here on the CIE 1931 table, and a diffuse plane under it at radiance ρ·L_sky.
/// </summary>
public class DaylightSkyTests
{
    /// <summary>A column of a CSV table under data/ (wavelength first) as a linear interpolant.</summary>
    static Func<double, double> Table(string file, string column)
    {
        var lines = File.ReadAllLines(Repo.PathOf("data", file)).Where(l => l.Length > 0 && !l.StartsWith('#')).ToArray();
        int c = Array.IndexOf(lines[0].Split(','), column);
        var rows = lines.Skip(1).Select(l => l.Split(','))
            .Select(p => (W: double.Parse(p[0], CultureInfo.InvariantCulture), V: double.Parse(p[c], CultureInfo.InvariantCulture)))
            .ToArray();
        return l =>
        {
            int i = Array.FindLastIndex(rows, r => r.W <= l);
            if (i < 0 || i == rows.Length - 1) return i < 0 ? rows[0].V : rows[^1].V;
            double t = (l - rows[i].W) / (rows[i + 1].W - rows[i].W);
            return rows[i].V + t * (rows[i + 1].V - rows[i].V);
        };
    }

    static string Scene(string sky) => $$"""
        { "radiometry": "physical", "bands": "380:780:8", "integrator": "path",
          "camera": { "position": [0, 2, 0.01], "look_at": [0, 0, 0], "width": 8, "height": 8, "spp": 4 },
          "sky": {{sky}},
          "materials": { "board": { "type": "lambertian", "reflectance": 0.5 } },
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "board" } ] }
        """;

    [Fact]
    public void The_sky_at_6504_K_is_the_published_D65_table_and_lights_a_diffuse_plane_to_rho_times_its_radiance()
    {
        var scene = SceneText.Load(Scene("""{ "type": "daylight", "cct": 6504, "radiance": 2 }"""));
        var d65 = Table("illuminants.csv", "D65");
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
        for (int b = 0; b < scene.Bands; b++)
        {
            // radiance 2 at 560 nm: the D65 table (100 at 560 nm) × 0.02, band means by the midpoint rule at 0.01 nm
            double sky = 0.02 * PathIntegratorTests.BandMean(d65, scene.Grid.Lower(b), scene.Grid.Upper(b));
            Assert.Equal(sky, scene.Background[b], sky * 2e-3);
            for (int i = 0; i < 64; i++) Assert.Equal(0.5 * sky, r.Image.Data[i * scene.Bands + b], sky * 3e-3);
        }
    }

    [Fact]
    public void Its_luminance_is_the_one_given_and_its_colour_that_of_the_CCT()
    {
        var scene = SceneText.Load(Scene("""{ "type": "daylight", "cct": 5000, "luminance": 4000 }"""));
        var d50 = Table("illuminants.csv", "D50");   // CIE D50, the D SPD of 5003 K; the sky's is 5000 K
        var ybar = Table("cie1931-2deg-cmf.csv", "ybar");
        // The band values are the D SPD × s; s from the first band against the table, then 683 Σ ȳ·L at 1 nm = 4000 cd/m².
        double s = scene.Background[3] / PathIntegratorTests.BandMean(d50, scene.Grid.Lower(3), scene.Grid.Upper(3));
        double lv = 0;
        for (int l = 360; l <= 830; l++) lv += 683 * ybar(l) * d50(Math.Clamp(l, 380, 780)) * s;
        Assert.InRange(lv, 4000 * 0.99, 4000 * 1.01);
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            SceneText.Load(Scene("""{ "type": "daylight", "cct": 3000, "luminance": 1 }""")));
        Assert.Contains("$.sky.cct", e.Message);
        e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            SceneText.Load(Scene("""{ "type": "daylight", "cct": 6500 }""")));
        Assert.Contains("luminance", e.Message);
    }
}
