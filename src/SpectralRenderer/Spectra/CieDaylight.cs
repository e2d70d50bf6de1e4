using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// CIE daylight illuminants of any correlated colour temperature, the spectrum <c>daylight:T</c>
/// (CIE 015:2018 §4.1.2): chromaticity x_D from T by the CIE polynomials (4000–7000 K and
/// 7000–25000 K), y_D = −3x_D² + 2.870 x_D − 0.275, then S(λ) = S₀(λ) + M₁S₁(λ) + M₂S₂(λ) with
/// M₁, M₂ rounded to three decimals as the standard prescribes. S₀, S₁, S₂ are the CIE table
/// (data/cie-daylight-components.csv, 300–830 nm at 5 nm), so S is 100 at 560 nm. T is used as given:
/// the CIE's D65 (nominally 6500 K on the old c₂) is <c>daylight:6504</c>.
/// </summary>
public static class CieDaylight
{
    public const double MinKelvin = 4000, MaxKelvin = 25000;

    static readonly Lazy<SpectralTable> Components =
        new(() => CsvSpectrumReader.ReadSigned(DataDirectory.File_("cie-daylight-components.csv")));

    /// <summary>CIE D chromaticity (x_D, y_D) at correlated colour temperature <paramref name="kelvin"/>.</summary>
    public static (double X, double Y) Chromaticity(double kelvin)
    {
        if (kelvin < MinKelvin || kelvin > MaxKelvin)
            throw new ArgumentOutOfRangeException(nameof(kelvin), "CIE daylight is defined for 4000–25000 K");
        double t = kelvin, t2 = t * t, t3 = t2 * t;
        double x = t <= 7000
            ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
            : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
        return (x, -3 * x * x + 2.870 * x - 0.275);
    }

    /// <summary>The D-series SPD of chromaticity (x, y) (CIE 015:2018 eq. 4.7–4.8).</summary>
    public static TabulatedSpectrum FromChromaticity(double x, double y, string name)
    {
        double m = 0.0241 + 0.2562 * x - 0.7341 * y;
        double m1 = Math.Round((-1.3515 - 1.7703 * x + 5.9114 * y) / m, 3, MidpointRounding.AwayFromZero);
        double m2 = Math.Round((0.0300 - 31.4424 * x + 30.0717 * y) / m, 3, MidpointRounding.AwayFromZero);
        var t = Components.Value;
        var s0 = t["S0"]; var s1 = t["S1"]; var s2 = t["S2"];
        var w = s0.Wavelengths.ToArray();
        var v = new double[w.Length];
        for (int i = 0; i < w.Length; i++) v[i] = s0.Values[i] + m1 * s1.Values[i] + m2 * s2.Values[i];
        return new TabulatedSpectrum(name, w, v);
    }

    public static TabulatedSpectrum Spectrum(double kelvin, string? name = null)
    {
        var (x, y) = Chromaticity(kelvin);
        return FromChromaticity(x, y, name ?? $"daylight:{kelvin:0.###}");
    }

    /// <summary>Parses the T of <c>daylight:T</c> (kelvin), with a clear error.</summary>
    public static TabulatedSpectrum Parse(string name, string text, string where)
    {
        if (!double.TryParse(text.Trim().TrimEnd('K', 'k'), System.Globalization.NumberStyles.Float,
                System.Globalization.CultureInfo.InvariantCulture, out double t) || !(t >= MinKelvin && t <= MaxKelvin))
            throw new InputException(where, $"'{name}' needs a correlated colour temperature between 4000 and 25000 K after 'daylight:'",
                "CIE daylight is defined there, e.g. daylight:6504 (D65); for lower temperatures use blackbody:T");
        return Spectrum(t, name);
    }
}
