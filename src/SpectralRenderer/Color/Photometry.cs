using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// Photometry (CIE 015:2018 §4, SI brochure: candela): a photometric quantity X_v = K_m ∫ V(λ) X_e,λ dλ with
/// K_m = 683 lm/W and V(λ) the CIE 1924 photopic luminous efficiency function — ȳ(λ) of the CIE 1931 observer table
/// (data/cie1931-2deg-cmf.csv), which SI photometry uses whatever observer a scene's colours are computed for.
/// </summary>
public static class Photometry
{
    /// <summary>V(λ), CIE 1924 photopic (= ȳ of CIE 1931 2°), 360–830 nm at 1 nm, zero outside.</summary>
    public static TabulatedSpectrum V => Observer.Cie1931.YBar;

    /// <summary>
    /// K_m ∫ V(λ) S(λ) dλ over the spectrum's tabulated range (within V's 360–830 nm), exactly on the tables: the
    /// lumens per watt-unit of <paramref name="spectrum"/> (lm per unit of a radiant flux whose spectral density is S,
    /// likewise cd per W·sr⁻¹, lx per W·m⁻², cd·m⁻² per W·m⁻²·sr⁻¹).
    /// </summary>
    public static double Luminous(TabulatedSpectrum spectrum)
    {
        double lo = Math.Max(spectrum.First, V.First), hi = Math.Min(spectrum.Last, V.Last);
        // A constant (or clamped) spectrum spans far beyond V: V is zero outside its table.
        if (spectrum.Extrapolation != Extrapolation.Error) { lo = V.First; hi = V.Last; }
        return hi > lo ? Colorimeter.Km * TabulatedSpectrum.IntegrateProduct(V, spectrum, lo, hi) : 0;
    }
}
