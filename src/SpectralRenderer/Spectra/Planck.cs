using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// A Planckian (blackbody) radiator, the spectrum <c>blackbody:T</c>: Planck's law
/// M(λ, T) = c₁ λ⁻⁵ / (exp(c₂ / λT) − 1) (CIE 015:2018 §4, eq. 4.1), as a <b>relative</b> spectral power
/// distribution normalised to 100 at 560 nm, like the CIE A and D tables in data/illuminants.csv.
/// c₂ = hc/k = 1.438776877 × 10⁻² m·K (exact SI 2019 constants; CIE 015:2018 uses the same value).
/// The table is sampled at 1 nm over 300–830 nm (the range of the CIE daylight components; linear
/// interpolation between the 1 nm samples is within 1e-4 relative of Planck's law above 2000 K).
/// </summary>
public static class Planck
{
    /// <summary>Second radiation constant c₂ = hc/k in nm·K.</summary>
    public const double C2 = 1.438776877e7;
    public const double First = 300, Last = 830;

    /// <summary>Planck's law up to the constant c₁: λ⁻⁵ / (exp(c₂ / λT) − 1), λ in nm.</summary>
    public static double Relative(double wavelengthNm, double kelvin) =>
        Math.Pow(wavelengthNm, -5) / double.ExpM1(C2 / (wavelengthNm * kelvin));

    /// <summary>The relative SPD at temperature <paramref name="kelvin"/>, 100 at 560 nm.</summary>
    public static TabulatedSpectrum Spectrum(double kelvin, string? name = null)
    {
        if (!double.IsFinite(kelvin) || kelvin < 100 || kelvin > 1e6)
            throw new ArgumentOutOfRangeException(nameof(kelvin), "a blackbody temperature must be 100–1,000,000 K");
        int n = (int)(Last - First) + 1;
        var w = new double[n];
        var v = new double[n];
        double norm = 100 / Relative(560, kelvin);
        for (int i = 0; i < n; i++)
        {
            w[i] = First + i;
            v[i] = Relative(w[i], kelvin) * norm;
        }
        return new TabulatedSpectrum(name ?? $"blackbody:{kelvin:0.###}", w, v);
    }

    /// <summary>Parses the T of <c>blackbody:T</c> (kelvin), with a clear error.</summary>
    public static TabulatedSpectrum Parse(string name, string text, string where)
    {
        if (!double.TryParse(text.Trim().TrimEnd('K', 'k'), System.Globalization.NumberStyles.Float,
                System.Globalization.CultureInfo.InvariantCulture, out double t) || !double.IsFinite(t) || t < 100 || t > 1e6)
            throw new InputException(where, $"'{name}' needs a temperature in kelvin between 100 and 1000000 after 'blackbody:'",
                "e.g. blackbody:3000");
        return Spectrum(t, name);
    }
}
