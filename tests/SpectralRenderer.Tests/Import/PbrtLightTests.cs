using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Pbrt;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// pbrt-v4's light normalisation (lights.cpp: scale /= SpectrumToPhotometric(L), then power) against the analytic value:
/// a blackbody area light seen head-on has ∫ȳ·L dλ = scale·∫ȳB/Σȳ B (Σ over the integers 360…830 nm, pbrt's
/// InnerProduct), whatever B's own normalisation, so its luminance is 683·that cd/m²; with "power" P on a one-sided disk of
/// area A, scale·P/(π·A) in place of scale. B is Planck's law and ȳ the CIE 1931 table, both evaluated here.
/// </summary>
public class PbrtLightTests
{
    static readonly SortedDictionary<int, double> Ybar = new(File.ReadAllLines(Repo.PathOf("data", "cie1931-2deg-cmf.csv")).Skip(1)
        .Where(l => l.Length > 0).Select(l => l.Split(','))
        .ToDictionary(c => (int)double.Parse(c[0], CultureInfo.InvariantCulture), c => double.Parse(c[2], CultureInfo.InvariantCulture)));

    /// <summary>Planck's law up to a constant, λ in nm (c₂ = 1.438776877e7 nm·K).</summary>
    static double Planck(double nm, double kelvin) => Math.Pow(nm, -5) / (Math.Exp(1.438776877e7 / (nm * kelvin)) - 1);

    static double YbarAt(double nm)
    {
        int l = (int)Math.Floor(nm);
        if (l < 360 || l >= 830) return l == 830 ? Ybar[830] : 0;
        return Ybar[l] + (nm - l) * (Ybar[l + 1] - Ybar[l]);
    }

    /// <summary>∫ȳ·B dλ / Σ ȳ·B: the integral by the trapezoid rule on 0.01 nm steps over the CMF's 360–830 nm.</summary>
    static double IntegralOverSum(double kelvin)
    {
        double sum = 0, integral = 0;
        for (int l = 360; l <= 830; l++) sum += Ybar[l] * Planck(l, kelvin);
        const double h = 0.01;
        for (int i = 0; i < 47000; i++)
        {
            double a = 360 + i * h, b = a + h;
            integral += 0.5 * h * (YbarAt(a) * Planck(a, kelvin) + YbarAt(b) * Planck(b, kelvin));
        }
        return integral / sum;
    }

    /// <summary>A render with the integrator the scene names (the imported scene's path tracer).</summary>
    internal static RenderResult Render(SpectralRenderer.Scenes.Scene scene, int threads) =>
        Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), scene.Integrator!.Name), threads);

    /// <summary>A disk light of radius 0.5 facing the camera 3 m away, filling the centre pixels, converted and rendered.</summary>
    static (double Luminance, RenderResult Result, SpectralRenderer.Scenes.Scene Scene) RenderLight(string light, bool twoSided = false)
    {
        var path = Path.Combine(Path.GetTempPath(), "light.pbrt");
        var text = "Scale -1 1 1\nLookAt 0 0 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 5\nFilm "
            + "\"rgb\" \"integer xresolution\" 8 "
            + "\"integer yresolution\" 8\nSampler \"sobol\" \"integer pixelsamples\" 1\nWorldBegin\nAttributeBegin\n"
            + $"AreaLightSource \"diffuse\" {light}{(twoSided ? " \"bool twosided\" true" : "")}\nShape \"disk\" "
                + $"\"float radius\" 0.5\nAttributeEnd\n";
        var imported = new PbrtConverter(path, new ImportOptions()).ConvertText(text);
        imported.Scene["scaling"] = "absolute";
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        var result = Render(scene, 1);
        int centre = (4 * 8 + 4) * 3;
        return (result.Xyz![centre + 1], result, scene);
    }

    [Fact]
    public void A_blackbody_area_light_has_pbrts_luminance_683_times_scale()
    {
        var (luminance, result, scene) = RenderLight("\"blackbody L\" 3200 \"float scale\" 2.5");
        double expected = 683 * 2.5 * IntegralOverSum(3200);
        Assert.True(Math.Abs(luminance - expected) <= 2e-4 * expected, $"{luminance} cd/m² instead of {expected}");
        Assert.True(Math.Abs(expected / (683 * 2.5) - 1) < 1e-3);   // pbrt's sum and the integral agree closely

        // Each band: the band mean of scale·B(λ)/Σȳ·B, B from Planck's law here.
        double sum = 0;
        for (int l = 360; l <= 830; l++) sum += Ybar[l] * Planck(l, 3200);
        for (int b = 0; b < scene.Bands; b++)
        {
            double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b), mean = 0;
            for (int i = 0; i < 1000; i++) mean += Planck(lo + (i + 0.5) * (hi - lo) / 1000, 3200) / 1000;
            double band = 2.5 * mean / sum;
            Assert.True(Math.Abs(result.Image[4, 4, b] - band) <= 2e-4 * band, $"band {b}: {result.Image[4, 4, b]} instead of {band}");
        }
    }

    [Fact]
    public void Power_sets_the_luminance_to_scale_times_power_over_pi_area_per_side()
    {
        // 10 W (ȳ-weighted) from a one-sided disk of area π/4: ∫ȳL = 10/(π·π/4); two-sided, half of it.
        double area = Math.PI * 0.25;
        var (one, _, _) = RenderLight("\"blackbody L\" 5000 \"float power\" 10");
        double expected = 683 * 10 / (Math.PI * area) * IntegralOverSum(5000);
        Assert.True(Math.Abs(one - expected) <= 2e-4 * expected, $"{one} cd/m² instead of {expected}");
        var (two, _, _) = RenderLight("\"blackbody L\" 5000 \"float power\" 10", twoSided: true);
        Assert.True(Math.Abs(two - expected / 2) <= 2e-4 * expected, $"two-sided: {two} cd/m² instead of {expected / 2}");
    }

    [Fact]
    public void Point_spot_and_distant_lights_take_pbrts_power_and_illuminance()
    {
        // intensity × Σȳ·S = scale × (power/4π | power/(2π(1 − cos θ_start) + π(cos θ_start − cos θ_end)) | illuminance).
        var path = Path.Combine(Path.GetTempPath(), "lights.pbrt");
        var imported = new PbrtConverter(path, new ImportOptions()).ConvertText("Camera \"perspective\"\nWorldBegin\n"
            + "LightSource \"point\" \"blackbody I\" 4000 \"float power\" 100 \"float scale\" 2\n"
            + "LightSource \"spot\" \"blackbody I\" 4000 \"float power\" 100 \"float coneangle\" 30 \"float conedeltaangle\" 10\n"
            + "LightSource \"distant\" \"blackbody L\" 4000 \"float illuminance\" 7\nShape \"sphere\"");
        var lights = imported.Scene["lights"]!.AsArray();
        double sum = 0;
        var bb = SpectralRenderer.Spectra.Planck.Spectrum(4000);
        for (int l = 360; l <= 830; l++) sum += Ybar[l] * bb.Evaluate(l);   // the exported spectrum is blackbody:4000, 100 at 560 nm
        Assert.Equal("blackbody:4000", lights[0]!["spectrum"]!.GetValue<string>());
        Assert.Equal(2 * 100 / (4 * Math.PI), lights[0]!["intensity"]!.GetValue<double>() * sum, 1e-6 * 100);
        double cosEnd = Math.Cos(30 * Math.PI / 180), cosStart = Math.Cos(20 * Math.PI / 180);
        Assert.Equal(100 / (2 * Math.PI * (1 - cosStart) + Math.PI * (cosStart - cosEnd)),
            lights[1]!["intensity"]!.GetValue<double>() * sum, 1e-4);
        Assert.Equal(Math.Acos((cosStart + cosEnd) / 2) * 180 / Math.PI, lights[1]!["cutoff"]!.GetValue<double>(), 1e-6);
        Assert.Equal(7, lights[2]!["intensity"]!.GetValue<double>() * sum, 1e-6);
        // The distant light shines from "from" (0,0,0) to "to" (0,0,1), mirrored with the world: towards +z still.
        Assert.Equal(1, lights[2]!["direction"]![2]!.GetValue<double>(), 9);
    }
}
