using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Distributed;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 27's one scale for built-in lights (docs/scene-format.md, "Spectrum values"): the smooth CIE illuminants 100 at
/// 560 nm as published, the fluorescent ones, LEDs and measured sources with D65's luminous flux (∫V·S computed here by a
/// midpoint sum on the 1 nm CIE table and on the CSV column read here); swapping D65 for any of them at the same
/// photometric value, or — for the luminous-scaled ones — at the same intensity, gives a white diffuser the same luminance.
/// </summary>
public class BuiltinLightScaleTests(Xunit.Abstractions.ITestOutputHelper output)
{
    public static TheoryData<string, string, string, bool> Builtins => new()
    {
        { "D65", "illuminants.csv", "D65", false }, { "A", "illuminants.csv", "A", false }, { "D50", "illuminants.csv", "D50", false },
        { "E", "illuminants.csv", "E", false }, { "FL2", "illuminants.csv", "FL2", true }, { "FL11", "illuminants.csv", "FL11", true },
        { "led-blue", "leds.csv", "blue_465nm", true }, { "led-green", "leds.csv", "green_525nm", true },
        { "led-rgb", "light-sources.csv", "3-LED-1 (457/540/605)", true }, { "led-yag", "light-sources.csv", "Phosphor LED YAG", true },
    };

    /// <summary>The CSV column as the file has it, parsed here: (λ, value) rows.</summary>
    static (double[] L, double[] V) Column(string file, string column)
    {
        var lines = File.ReadAllLines(Repo.PathOf("data", file));
        int c = Array.IndexOf(lines[0].Split(','), column);
        var rows = lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')).ToArray();
        return (rows.Select(r => double.Parse(r[0], System.Globalization.CultureInfo.InvariantCulture)).ToArray(),
                rows.Select(r => double.Parse(r[c], System.Globalization.CultureInfo.InvariantCulture)).ToArray());
    }

    static double Lerp((double[] L, double[] V) t, double l)
    {
        int i = Array.FindLastIndex(t.L, x => x <= l);
        if (i < 0 || i >= t.L.Length - 1) return i == t.L.Length - 1 && l == t.L[^1] ? t.V[^1] : 0;
        return t.V[i] + (l - t.L[i]) / (t.L[i + 1] - t.L[i]) * (t.V[i + 1] - t.V[i]);
    }

    /// <summary>∫V·S dλ by a 0.05 nm midpoint sum over the table's range (within 360–830 nm).</summary>
    static double LuminousIntegral((double[] L, double[] V) s)
    {
        var v = Column("cie1931-2deg-cmf.csv", "ybar");
        double lo = Math.Max(s.L[0], 360), hi = Math.Min(s.L[^1], 830);
        int n = (int)Math.Round((hi - lo) / 0.05);
        double sum = 0;
        for (int i = 0; i < n; i++) { double l = lo + (i + 0.5) * (hi - lo) / n; sum += Lerp(v, l) * Lerp(s, l); }
        return sum * (hi - lo) / n;
    }

    [Theory, MemberData(nameof(Builtins))]
    public void Each_built_in_light_is_on_its_documented_scale(string name, string file, string column, bool luminous)
    {
        var s = SpectrumLibrary.Resolve(name);
        Assert.Equal(luminous, SpectrumLibrary.IsLuminousNormalised(name));
        var table = Column(file, column);
        double d65 = LuminousIntegral(Column("illuminants.csv", "D65"));
        // The resolved spectrum is the table times one factor.
        double factor = s.Evaluate(table.L[table.V.ToList().IndexOf(table.V.Max())]) / table.V.Max();
        if (luminous)
        {
            double expected = d65 / LuminousIntegral(table);
            output.WriteLine($"{name}: × {factor:G6} (expected {expected:G6}) so that ∫V·S = D65's {d65:G6}");
            Assert.True(Math.Abs(factor - expected) / expected <= 1e-4, $"{name}: factor {factor} vs {expected}");
        }
        else
        {
            Assert.Equal(1.0, factor, 12);
            Assert.Equal(100.0, s.Evaluate(560), 9);
        }
    }

    static string Diffuser(string spectrum, string strength) => $$"""
        { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:40",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 1, "width": 1, "height": 1 },
          "materials": { "white": { "diffuse": 1 } },
          "lights": [ { "type": "point", "position": [0, 0, 2], "spectrum": "{{spectrum}}", {{strength}} } ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "white" } ] }
        """;

    [Theory, MemberData(nameof(Builtins))]
    public void Swapping_D65_for_a_built_in_light_at_the_same_photometric_value_keeps_the_luminance(string name, string file, string column,
        bool luminous)
    {
        _ = (file, column);
        double d65 = SceneText.Render(Diffuser("D65", "\"luminous_intensity\": 800")).Xyz![1];
        double other = SceneText.Render(Diffuser(name, "\"luminous_intensity\": 800")).Xyz![1];
        Assert.True(Math.Abs(other / d65 - 1) <= 1e-3, $"{name}: {other} vs D65 {d65} cd/m²");
        Assert.True(Math.Abs(d65 - 200 / Math.PI) / (200 / Math.PI) <= 1e-3, $"D65 {d65} vs 800/4/π");
        // At the same intensity, the luminous-scaled lights give D65's luminance too.
        double d65i = SceneText.Render(Diffuser("D65", "\"intensity\": 3")).Xyz![1];
        double otheri = SceneText.Render(Diffuser(name, "\"intensity\": 3")).Xyz![1];
        output.WriteLine($"{name}: same intensity, luminance {otheri / d65i:F4} × D65's");
        if (luminous) Assert.True(Math.Abs(otheri / d65i - 1) <= 1e-3, $"{name}: {otheri} vs D65 {d65i} cd/m² at intensity 3");
    }

    /// <summary>
    /// Issue 42: a spectrum object's <c>"scale": "luminous"</c> puts a light's own shape (here a Gaussian of peak 1 at 450 nm, the
    /// README's LED) on the built-in lights' scale — at the same intensity a white diffuser has D65's luminance — while the same
    /// shape as given is ∫V·G / ∫V·D65 of it (both integrals by this class's midpoint sum).
    /// </summary>
    [Fact]
    public void A_spectrum_objects_luminous_scale_gives_D65s_luminance_at_the_same_intensity()
    {
        var l = Enumerable.Range(0, 81).Select(i => 380.0 + 5 * i).ToArray();
        var g = l.Select(x => Math.Exp(-0.5 * ((x - 450) / 12) * ((x - 450) / 12))).ToArray();
        string pairs =
            string.Join(", ", l.Zip(g, (a, b) => string.Create(System.Globalization.CultureInfo.InvariantCulture, $"[{a}, {b:R}]")));
        string Scene(string spectrum) =>
            Diffuser("D65", "\"intensity\": 3").Replace("\"D65\", \"intensity\"", $"{spectrum}, \"intensity\"");
        double d65 = SceneText.Render(Diffuser("D65", "\"intensity\": 3")).Xyz![1];
        double scaled = SceneText.Render(Scene($"{{ \"values\": [{pairs}], \"scale\": \"luminous\" }}")).Xyz![1];
        double given = SceneText.Render(Scene($"[{pairs}]")).Xyz![1];
        double expected = LuminousIntegral((l, g)) / LuminousIntegral(Column("illuminants.csv", "D65"));
        output.WriteLine($"scaled {scaled / d65:F5} × D65's luminance; as given {given / d65:G5} (expected {expected:G5})");
        Assert.True(Math.Abs(scaled / d65 - 1) <= 1e-3, $"scaled: {scaled} vs D65 {d65}");
        Assert.True(Math.Abs(given / d65 / expected - 1) <= 1e-3, $"as given: {given / d65} vs {expected}");
    }

    /// <summary>
    /// The example sweep's LED jobs are lit: on the floor, the brightest lit pixel over the darkest shadowed one (both Y),
    /// within 10 % of the D65 job's, at equal photometric value (the LEDs now carry D65's luminous flux per unit).
    /// </summary>
    [SkippableFact]
    public void The_example_sweeps_LED_jobs_have_the_D65_jobs_lit_to_shadow_ratio()
    {
        var bunny = ModelFiles.Find("stanford-bunny.obj", out var reason);
        Skip.If(bunny is null, reason);
        var plan = SweepPlan.Load(Repo.PathOf("sweeps", "bunny-colorchecker-lights.json"));
        double Ratio(string light)
        {
            var job = plan.Jobs.First(j => j.Parameters.Contains(("patch", "colorchecker:19")) && j.Parameters.Contains(("light", light)));
            var scene = plan.SceneFor(job);
            scene["camera"]!["width"] = 64;
            scene["camera"]!["height"] = 48;
            scene["camera"]!["spp"] = 1;
            var s = SceneLoader.Parse(System.Text.Encoding.UTF8.GetBytes(scene.ToJsonString()), Repo.PathOf("sweeps", "job.json"),
                new SceneOverrides { ModelDirectories = [Path.GetDirectoryName(bunny)!] });
            var r = SpectralRenderer.Rendering.Registry.Integrators.Render(s);
            int floor = s.Objects.FindIndex(o => o.Name == "floor");   // ids: object index, −1 background
            double lit = 0, shadow = double.MaxValue;
            for (int i = 0; i < r.ObjectIds.Length; i++)
            {
                if (r.ObjectIds[i] != floor) continue;
                double y = r.Xyz![3 * i + 1];
                lit = Math.Max(lit, y);
                shadow = Math.Min(shadow, y);
            }
            output.WriteLine($"{light}: floor lit {lit:G4} / shadow {shadow:G4} = {lit / shadow:F3}");
            return lit / shadow;
        }
        double d65 = Ratio("D65");
        Assert.True(d65 > 3, $"D65 ratio {d65}");
        foreach (var led in new[] { "led-blue", "led-green" })
        {
            double ratio = Ratio(led);
            Assert.True(Math.Abs(ratio / d65 - 1) <= 0.10, $"{led}: lit-to-shadow {ratio:F3} vs D65's {d65:F3}");
        }
    }
}
