using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;

namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// The preview of an imported scene as its own renderer displays it. Our physical scenes are spectral radiance in
/// W·m⁻²·sr⁻¹·nm⁻¹; with relative scaling (κ from a D65 white of values near 100) a Mitsuba or pbrt scene's preview comes out
/// about a hundred times too dark. Mitsuba 3 shows Y = ∫ȳ·L dλ / ∫ȳ dλ (MI_CIE_Y_NORMALIZATION: a unit spectrum has
/// luminance 1), pbrt-v4's default "cie1931" sensor Y = imagingRatio·∫ȳ·L dλ (film.h PixelSensor::ToSensorRGB, imagingRatio =
/// exposure time × ISO/100, 1 by default). So an imported scene gets <c>"scaling": "absolute"</c> (Y = K_m∫ȳ·L dλ in cd/m²) and
/// the preview's fixed exposure Y_native/Y_ours: the same pixels as the other renderer's sRGB output (docs/import.md).
/// </summary>
public static class ImportDisplay
{
    /// <summary>∫ȳ dλ of the CIE 1931 observer's table (nm): Mitsuba's normalisation of Y.</summary>
    public static double YBarIntegral
    {
        get
        {
            var y = Observer.Cie1931.YBar;
            return y.Integrate(y.First, y.Last);
        }
    }

    /// <summary>
    /// Sets <paramref name="scene"/>'s scaling to absolute and its preview's exposure so that its Y is
    /// <paramref name="yPerLuminanceIntegral"/> × ∫ȳ·L dλ (Mitsuba: 1/∫ȳ dλ; pbrt: its imaging ratio).
    /// </summary>
    public static void Native(JsonObject scene, double yPerLuminanceIntegral)
    {
        scene["scaling"] = "absolute";
        var exposure = (yPerLuminanceIntegral / Colorimeter.Km).ToString("G9", CultureInfo.InvariantCulture);
        scene["output"] = new JsonObject { ["exposure"] = double.Parse(exposure, CultureInfo.InvariantCulture) };
    }
}
