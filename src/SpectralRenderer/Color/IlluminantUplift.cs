using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// The illuminant uplift of an emitted linear sRGB colour (Mitsuba 3's <c>srgb_d65</c> and pbrt-v4's <c>RGBIlluminantSpectrum</c>):
/// S(λ) = s·r(λ)·I(λ)/Ȳ_I, where s = 2·max(r, g, b), r(λ) the sigmoid reflectance (<see cref="SigmoidUplift"/>) of rgb/s (at
/// most ½, away from the sigmoid's ends) and Ȳ_I = ∫ȳ·I dλ / ∫ȳ dλ (CIE 1931), so a white [1, 1, 1] is I scaled to luminance
/// factor Y = 1 (Mitsuba's MI_CIE_D65_NORMALIZATION is 1/Ȳ of D65).
/// </summary>
public static class IlluminantUplift
{
    /// <summary>Ȳ_I of <paramref name="illuminant"/> (0 when it has no visible light); one without data past ȳ's range is 0
    /// there.</summary>
    public static double LuminanceFactor(ref TabulatedSpectrum illuminant)
    {
        var ybar = Observer.Cie1931.YBar;
        double lo = ybar.First, hi = ybar.Last;
        if (!illuminant.Covers(lo, hi)) illuminant = illuminant.WithExtrapolation(Extrapolation.Zero);
        return TabulatedSpectrum.IntegrateProduct(ybar, illuminant, lo, hi) / ybar.Integrate(lo, hi);
    }

    /// <summary>
    /// scale·r(λ)·I(λ)/Ȳ_I tabulated at the union of r's (<see cref="SigmoidUplift.Wavelengths"/>) and I's knots, for the
    /// reflectance <paramref name="reflectance"/> at SigmoidUplift.Wavelengths and an illuminant of factor
    /// <paramref name="luminanceFactor"/> (<see cref="LuminanceFactor"/>, with the extrapolation it chose).
    /// </summary>
    public static TabulatedSpectrum Product(string name, double[] reflectance, double scale, TabulatedSpectrum illuminant,
        double luminanceFactor)
    {
        var r = new TabulatedSpectrum("uplift", SigmoidUplift.Wavelengths, reflectance, Extrapolation.Clamp);
        var knots = new SortedSet<double>(SigmoidUplift.Wavelengths);
        foreach (var w in illuminant.Wavelengths) knots.Add(w);
        var wl = knots.Where(w => illuminant.Covers(w, w) || illuminant.Extrapolation != Extrapolation.Error).ToArray();
        var v = wl.Select(w => scale * r.Evaluate(w) * illuminant.Evaluate(w) / luminanceFactor).ToArray();
        return new TabulatedSpectrum(name, wl, v, illuminant.Extrapolation);
    }

    /// <summary>The sigmoid reflectance (at <see cref="SigmoidUplift.Wavelengths"/>) of a linear sRGB colour (IEC 61966-2-1's
    /// matrix), each component in [0, 1].</summary>
    public static double[] Reflectance(double r, double g, double b) => Shared.Value.Spectrum(new Xyz(
        0.4124 * r + 0.3576 * g + 0.1805 * b,
        0.2126 * r + 0.7152 * g + 0.0722 * b,
        0.0193 * r + 0.1192 * g + 0.9505 * b), out _);

    static readonly Lazy<SigmoidUplift> Shared = new(() => new SigmoidUplift());
}
