using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>
/// How close an estimated spectrum is to a true one (band by band, same grid): RMSE, the goodness-of-fit
/// coefficient GFC (Romero, García-Beltrán &amp; Hernández-Andrés 1997; Hernández-Andrés et al. 2001), and the
/// least-squares scale c with the residual after scaling — the paper's §3.4 finding that a shadowed pixel's
/// reconstruction is the truth times a factor.
/// </summary>
public static class SpectralMetrics
{
    /// <summary>Root-mean-square difference sqrt(Σ (a − b)² / N).</summary>
    public static double Rmse(ReadOnlySpan<double> a, ReadOnlySpan<double> b)
    {
        Check(a, b);
        double s = 0;
        for (int i = 0; i < a.Length; i++) { double d = a[i] - b[i]; s += d * d; }
        return a.Length == 0 ? 0 : Math.Sqrt(s / a.Length);
    }

    /// <summary>
    /// GFC = |Σ a·b| / sqrt(Σ a² · Σ b²), 1 for proportional spectra. Two all-zero spectra give 1, one all-zero
    /// spectrum gives 0. GFC ≥ 0.999 is "good", ≥ 0.9999 "excellent" (Hernández-Andrés et al. 2001).
    /// </summary>
    public static double Gfc(ReadOnlySpan<double> a, ReadOnlySpan<double> b)
    {
        Check(a, b);
        double ab = 0, aa = 0, bb = 0;
        for (int i = 0; i < a.Length; i++) { ab += a[i] * b[i]; aa += a[i] * a[i]; bb += b[i] * b[i]; }
        if (aa == 0 && bb == 0) return 1;
        if (aa == 0 || bb == 0) return 0;
        return Math.Min(1, Math.Abs(ab) / Math.Sqrt(aa * bb));
    }

    /// <summary>
    /// The c minimising |c·truth − estimate|², c = Σ estimate·truth / Σ truth² (0 when truth is all zero),
    /// and the RMSE between c·truth and the estimate.
    /// </summary>
    public static (double Scale, double Residual) Scale(ReadOnlySpan<double> truth, ReadOnlySpan<double> estimate)
    {
        Check(truth, estimate);
        double et = 0, tt = 0;
        for (int i = 0; i < truth.Length; i++) { et += estimate[i] * truth[i]; tt += truth[i] * truth[i]; }
        double c = tt > 0 ? et / tt : 0;
        var scaled = new double[truth.Length];
        for (int i = 0; i < scaled.Length; i++) scaled[i] = c * truth[i];
        return (c, Rmse(scaled, estimate));
    }

    static void Check(ReadOnlySpan<double> a, ReadOnlySpan<double> b)
    {
        if (a.Length != b.Length) throw new ArgumentException($"spectra of {a.Length} and {b.Length} bands");
    }
}

/// <summary>
/// CIEDE2000 between two reflectances (band values) seen under D65: XYZ = eq. 3 of E_b·R_b with E = D65's band
/// values, CIELAB relative to the colorimeter's white (the perfect diffuser under D65).
/// </summary>
public sealed class ReflectanceDifference
{
    readonly Colorimeter _colorimeter;
    readonly double[] _light;

    public ReflectanceDifference(Colorimeter colorimeter)
    {
        _colorimeter = colorimeter;
        _light = colorimeter.Project(colorimeter.ReferenceLight);
    }

    /// <summary>D65 on <paramref name="grid"/> with the CIE 1931 (or 1964) observer and the given band scheme.</summary>
    public static ReflectanceDifference UnderD65(BandGrid grid, BandIntegration scheme = BandIntegration.Weighted,
        int observerDegrees = 2) =>
        new(new Colorimeter(grid, observerDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931, SpectrumLibrary.Resolve("D65"), scheme));

    public Colorimeter Colorimeter => _colorimeter;

    public Lab LabOf(ReadOnlySpan<double> reflectance)
    {
        if (reflectance.Length != _light.Length)
            throw new ArgumentException($"reflectance of {reflectance.Length} bands on a {_light.Length}-band grid");
        Span<double> l = stackalloc double[_light.Length];
        for (int b = 0; b < l.Length; b++) l[b] = _light[b] * reflectance[b];
        return Lab.FromXyz(_colorimeter.ToXyz(l), _colorimeter.White);
    }

    public double DeltaE00(ReadOnlySpan<double> a, ReadOnlySpan<double> b) => DeltaE2000.Between(LabOf(a), LabOf(b));
}
