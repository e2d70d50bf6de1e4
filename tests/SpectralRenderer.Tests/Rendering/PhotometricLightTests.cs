using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 27's first bar: lights given in lumens, candela and lux light a diffuser with the illuminance and luminance of
/// the photometric laws (E = I/r², E = Φ/(4πr²), L = ρE/π), read from the rendered pixels (Y of the exact colour with
/// absolute κ = 683 lm/W is luminance in cd/m²), for D65, A and the blue LED; the radiometric scale against K_m ∫V·S
/// computed here by a midpoint sum on the 1 nm CIE table (not the engine's product integrals).
/// </summary>
public class PhotometricLightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    public static TheoryData<string> Spectra => new() { "D65", "A", "led-blue" };

    /// <summary>683 ∫ V(λ)·S(λ) dλ by a 0.01 nm midpoint sum over the spectrum's table (within V's 360–830 nm).</summary>
    static double Luminous(string name)
    {
        var s = SpectrumLibrary.Resolve(name);
        var v = Observer.Cie1931.YBar;
        double lo = Math.Max(s.First, 360), hi = Math.Min(s.Last, 830);
        int n = (int)Math.Round((hi - lo) / 0.01);
        double sum = 0;
        for (int i = 0; i < n; i++) { double l = lo + (i + 0.5) * (hi - lo) / n; sum += v.Evaluate(l) * s.Evaluate(l); }
        return 683 * sum * (hi - lo) / n;
    }

    static string Scene(string light, string rho = "1") => $$"""
        { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 1, "width": 1, "height": 1 },
          "materials": { "diffuser": { "diffuse": {{rho}} } },
          "lights": [ {{light}} ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "diffuser" } ] }
        """;

    /// <summary>Luminance (cd/m²) of the one pixel: Y of its exact colour with κ = 683 lm/W.</summary>
    static double Luminance(string json) => SceneText.Render(json).Xyz![1];

    void Check(string what, double luminance, double expected, double tolerance = 1e-3)
    {
        double rel = Math.Abs(luminance - expected) / expected;
        output.WriteLine($"{what}: {luminance:G7} vs {expected:G7} cd/m² ({rel:E2} relative)");
        Assert.True(rel <= tolerance, $"{what}: {luminance} vs {expected} cd/m², {rel:E2} relative");
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_point_light_of_1000_cd_at_2_m_gives_a_white_diffuser_250_lx_and_250_over_pi_cd_per_m2(string spectrum)
    {
        string json = Scene($$"""{ "type": "point", "position": [0, 0, 2], "spectrum": "{{spectrum}}", "luminous_intensity": 1000 }""");
        double l = Luminance(json);
        Check($"{spectrum} 1000 cd at 2 m, luminance", l, 250 / Math.PI);
        Check($"{spectrum} 1000 cd at 2 m, illuminance π·L/ρ (lx)", Math.PI * l, 250);
        // The scale: I_e = I_v / (683 ∫V·S), the factor on the spectrum.
        var scene = SceneText.Load(json);
        double scale = 1000 / Luminous(spectrum);
        Assert.True(Math.Abs(scene.Lights[0].Scale - scale) / scale <= 1e-5, $"scale {scene.Lights[0].Scale} vs {scale}");
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_directional_light_of_500_lx_on_a_diffuser_of_reflectance_half_gives_500_times_half_over_pi(string spectrum)
    {
        double l = Luminance(
            Scene($$"""{ "type": "directional", "direction": [0, 0, -1], "spectrum": "{{spectrum}}", "illuminance": 500 }""", "0.5"));
        Check($"{spectrum} 500 lx, ρ = 0.5", l, 500 * 0.5 / Math.PI);
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_point_light_of_1000_lm_gives_1000_over_4_pi_r2_lux(string spectrum)
    {
        foreach (double r in new[] { 1.5, 3.0 })
        {
            double l =
                Luminance(Scene($$"""{ "type": "point", "position": [0, 0, {{r}}], "spectrum": "{{spectrum}}", "luminous_flux": 1000 }"""));
            Check($"{spectrum} 1000 lm at {r} m, illuminance (lx)", Math.PI * l, 1000 / (4 * Math.PI * r * r));
        }
    }

    [Theory, MemberData(nameof(Spectra))]
    public void A_spot_light_of_1000_lm_spreads_it_over_its_cone(string spectrum)
    {
        // c_spot = cos²θ inside 30°: ∫ c dΩ = 2π ∫_{cos 30°}^1 μ² dμ = 2π (1 − cos³30°)/3, by the closed form here.
        double c = Math.Cos(Math.PI / 6), omega = 2 * Math.PI * (1 - c * c * c) / 3;
        double l = Luminance(Scene($$"""
            { "type": "spot", "position": [0, 0, 2], "direction": [0, 0, -1], "cutoff": 30, "exponent": 2,
              "spectrum": "{{spectrum}}", "luminous_flux": 1000 }
            """));
        Check($"{spectrum} spot 1000 lm, illuminance on axis at 2 m (lx)", Math.PI * l, 1000 / omega / 4);
    }

    [Fact]
    public void Render_json_records_the_photometric_value_and_the_radiometric_scale_it_gave()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene("""{ "type": "point", "position": [0, 0, 2], "spectrum": "A", "luminous_flux": 1200 }"""));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.True(code == 0, err);
        var light = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "out", "render.json")))!["lights"]![0]!;
        var ph = light["photometric"]!;
        Assert.Equal("luminous_flux", (string?)ph["quantity"]);
        Assert.Equal(1200, (double)ph["value"]!);
        Assert.Equal("lm", (string?)ph["unit"]);
        double expected = 1200 / (4 * Math.PI * Luminous("A"));
        Assert.True(Math.Abs((double)ph["radiometric_scale"]! - expected) / expected <= 1e-5, $"{ph["radiometric_scale"]} vs {expected}");
        Assert.True(Math.Abs((double)light["intensity"]! - expected) / expected <= 1e-5, "the light's intensity is the scale");
    }

    [Fact]
    public void Relighting_with_a_new_spectrum_keeps_the_candela_and_a_new_intensity_replaces_them()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene,
            Scene("""{ "type": "point", "name": "key", "position": [0, 0, 2], "spectrum": "D65", "luminous_intensity": 1000 }"""));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "npy,lights");
        Assert.True(code == 0, err);
        JsonNode Light(string folder) => JsonNode.Parse(File.ReadAllText(Path.Combine(dir, folder, "render.json")))!["lights"]![0]!;
        // Under A: still 1000 cd, so the scale is 1000 / (683 ∫V·A) and the diffuser's luminance stays 250/π.
        (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "-o", Path.Combine(dir, "a"), "--quiet", "--light", "key=A");
        Assert.True(code == 0, err);
        var ph = Light("a")["photometric"]!;
        Assert.Equal(1000, (double)ph["value"]!);
        double expected = 1000 / Luminous("A");
        Assert.True(Math.Abs((double)ph["radiometric_scale"]! - expected) / expected <= 1e-5, $"{ph["radiometric_scale"]} vs {expected}");
        // A new intensity is radiometric: the photometric value is gone.
        (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "-o", Path.Combine(dir, "i"), "--quiet", "--intensity", "key=2");
        Assert.True(code == 0, err);
        Assert.Null(Light("i")["photometric"]);
        Assert.Equal(2, (double)Light("i")["intensity"]!);
    }

    [Theory]
    [InlineData("\"radiometry\": \"physical\", ", "", "luminous_intensity needs physical radiometry", "\"radiometry\": \"physical\"")]
    [InlineData("\"luminous_intensity\": 1000", "\"luminous_intensity\": 1000, \"intensity\": 2", "both intensity and luminous_intensity",
        "give one")]
    [InlineData("\"luminous_intensity\": 1000", "\"illuminance\": 1000", "a point light takes no illuminance",
        "luminous_intensity (cd) or luminous_flux (lm)")]
    [InlineData("\"luminous_intensity\": 1000", "\"luminous_intensity\": 10, \"luminous_flux\": 1",
        "gives both luminous_flux and luminous_intensity", "one")]
    [InlineData("\"luminous_intensity\": 1000", "\"luminous_intensity\": -1", "$.lights[0].luminous_intensity", "")]
    public void A_bad_photometric_key_is_one_line_with_a_hint_and_exit_2(string from, string to, string what, string hint)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene,
            Scene("""{ "type": "point", "position": [0, 0, 2], "spectrum": "D65", "luminous_intensity": 1000 }""").Replace(from, to));
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd().Split('\n'));
        Assert.Contains("scene.json:", err);
        Assert.Contains(what, err);
        Assert.Contains(hint, err);
    }
}
