using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// Eq. 3 on a band grid: X = Σ_b W_x,b · L_b (and Y, Z), where L_b are band values of a spectral
/// radiance. The weights fold in κ and the band integration scheme; with relative scaling a perfect
/// white diffuser under the reference light has Y = 1, with absolute scaling κ = 683 lm/W.
/// </summary>
public sealed class Colorimeter
{
    /// <summary>K_m, the maximum luminous efficacy of photopic vision (CIE 015:2018).</summary>
    public const double Km = 683.0;

    public Colorimeter(BandGrid grid, Observer observer, TabulatedSpectrum referenceLight,
        BandIntegration scheme = BandIntegration.Weighted, bool absolute = false)
    {
        Grid = grid;
        Observer = observer;
        ReferenceLight = referenceLight;
        Scheme = scheme;
        Absolute = absolute;
        int n = grid.Count;
        double dl = grid.Width;
        Wx = new double[n]; Wy = new double[n]; Wz = new double[n];

        if (scheme == BandIntegration.Paper)
        {
            var x = BandProjection.SampleMeans1nm(observer.XBar, grid);
            var y = BandProjection.SampleMeans1nm(observer.YBar, grid);
            var z = BandProjection.SampleMeans1nm(observer.ZBar, grid);
            for (int b = 0; b < n; b++) { Wx[b] = x[b] * dl; Wy[b] = y[b] * dl; Wz[b] = z[b] * dl; }
        }
        else
        {
            // Prefiltered weights: the CMF averaged under the reference light within each band,
            // ∫_b x̄E dλ / ∫_b E dλ, at the data's full resolution (exact for piecewise-linear tables).
            double peak = 0;
            var e = new double[n];
            for (int b = 0; b < n; b++) { e[b] = referenceLight.Integrate(grid.Lower(b), grid.Upper(b)); peak = Math.Max(peak, e[b]); }
            for (int b = 0; b < n; b++)
            {
                double lo = grid.Lower(b), hi = grid.Upper(b);
                if (e[b] > 1e-12 * peak)
                {
                    Wx[b] = TabulatedSpectrum.IntegrateProduct(observer.XBar, referenceLight, lo, hi) / e[b] * dl;
                    Wy[b] = TabulatedSpectrum.IntegrateProduct(observer.YBar, referenceLight, lo, hi) / e[b] * dl;
                    Wz[b] = TabulatedSpectrum.IntegrateProduct(observer.ZBar, referenceLight, lo, hi) / e[b] * dl;
                }
                else
                {   // The reference light is dark here: fall back to the plain CMF band integral.
                    Wx[b] = observer.XBar.Integrate(lo, hi);
                    Wy[b] = observer.YBar.Integrate(lo, hi);
                    Wz[b] = observer.ZBar.Integrate(lo, hi);
                }
            }
        }

        var light = Project(referenceLight);
        double yWhite = 0;
        for (int b = 0; b < n; b++) yWhite += Wy[b] * light[b];
        Kappa = absolute ? Km : 1.0 / yWhite;
        for (int b = 0; b < n; b++) { Wx[b] *= Kappa; Wy[b] *= Kappa; Wz[b] *= Kappa; }
        White = ToXyz(light);
    }

    public BandGrid Grid { get; }
    public Observer Observer { get; }
    public TabulatedSpectrum ReferenceLight { get; }
    public BandIntegration Scheme { get; }
    public bool Absolute { get; }
    /// <summary>κ of eq. 3.</summary>
    public double Kappa { get; }
    /// <summary>XYZ of the perfect white diffuser under the reference light (Y = 1 when relative).</summary>
    public Xyz White { get; }
    public double[] Wx { get; }
    public double[] Wy { get; }
    public double[] Wz { get; }

    /// <summary>Band values of a spectrum as this scheme defines them.</summary>
    public double[] Project(TabulatedSpectrum s) => Scheme == BandIntegration.Paper
        ? BandProjection.SampleMeans1nm(s, Grid)
        : BandProjection.Means(s, Grid);

    /// <summary>Eq. 3: XYZ of band values.</summary>
    public Xyz ToXyz(ReadOnlySpan<double> bands) => ToXyz(Wx, Wy, Wz, bands);

    /// <summary>Eq. 3: XYZ of band values.</summary>
    public Xyz ToXyz(ReadOnlySpan<float> bands) => ToXyz<float>(Wx, Wy, Wz, bands);

    /// <summary>Eq. 3 with given weights, X = Σ_b Wx[b]·L[b] (and Y, Z), summed in double: the one XYZ sum of band values.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static Xyz ToXyz<T>(ReadOnlySpan<double> wx, ReadOnlySpan<double> wy, ReadOnlySpan<double> wz, ReadOnlySpan<T> bands) where T : struct, INumberBase<T>
    {
        double x = 0, y = 0, z = 0;
        for (int b = 0; b < wx.Length; b++)
        {
            double v = double.CreateTruncating(bands[b]);
            x += wx[b] * v; y += wy[b] * v; z += wz[b] * v;
        }
        return new Xyz(x, y, z);
    }

    /// <summary>XYZ of a reflectance lit head-on by the reference light: L_b = E_b · R_b.</summary>
    public Xyz OfReflectance(TabulatedSpectrum reflectance)
    {
        var e = Project(ReferenceLight);
        var r = Project(reflectance);
        for (int b = 0; b < e.Length; b++) e[b] *= r[b];
        return ToXyz(e);
    }
}
