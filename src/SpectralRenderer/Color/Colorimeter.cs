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

    /// <param name="whiteRadiance">The radiance of a perfect white diffuser per unit irradiance head-on: 1 in the paper's
    /// radiometry (eq. 2 without units), 1/π in physical radiometry — so that relative κ gives that diffuser Y = 1 in both.</param>
    public Colorimeter(BandGrid grid, Observer observer, TabulatedSpectrum referenceLight,
        BandIntegration scheme = BandIntegration.Exact, bool absolute = false, double whiteRadiance = 1.0)
    {
        WhiteRadiance = whiteRadiance;
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
            // Prefiltered weights: the CMF averaged under the reference light within each band, Σ_b x̄E / ∫_b E dλ, the
            // numerator CIE 015's 1 nm sum (CieSummation, as OfProduct), the denominator the band integral the band values
            // are means of — so the weights applied to the light's band means give its 1 nm sum exactly.
            double peak = 0;
            var e = new double[n];
            for (int b = 0; b < n; b++) { e[b] = referenceLight.Integrate(grid.Lower(b), grid.Upper(b)); peak = Math.Max(peak, e[b]); }
            for (int b = 0; b < n; b++)
            {
                double lo = grid.Lower(b), hi = grid.Upper(b);
                if (e[b] > 1e-12 * peak)
                {
                    Wx[b] = CieSummation.Product(observer.XBar, referenceLight, lo, hi) / e[b] * dl;
                    Wy[b] = CieSummation.Product(observer.YBar, referenceLight, lo, hi) / e[b] * dl;
                    Wz[b] = CieSummation.Product(observer.ZBar, referenceLight, lo, hi) / e[b] * dl;
                }
                else
                {   // The reference light is dark here: fall back to the plain CMF band integral.
                    Wx[b] = CieSummation.Product(observer.XBar, null, lo, hi);
                    Wy[b] = CieSummation.Product(observer.YBar, null, lo, hi);
                    Wz[b] = CieSummation.Product(observer.ZBar, null, lo, hi);
                }
            }
        }

        var light = Project(referenceLight);
        for (int b = 0; b < n; b++) light[b] *= whiteRadiance;
        double yWhite = 0;
        for (int b = 0; b < n; b++) yWhite += Wy[b] * light[b];
        Kappa = absolute ? Km : 1.0 / yWhite;
        for (int b = 0; b < n; b++) { Wx[b] *= Kappa; Wy[b] *= Kappa; Wz[b] *= Kappa; }
        White = scheme == BandIntegration.Exact ? OfProduct(referenceLight, null) * whiteRadiance : ToXyz(light);
    }

    /// <summary>1 (paper radiometry) or 1/π (physical): the white diffuser's radiance per unit irradiance.</summary>
    public double WhiteRadiance { get; }

    /// <summary>
    /// κ·Σ x̄·a·b (and ȳ, z̄) over the band range, CIE 015:2018 §7.1's 1 nm sum of the tables' interpolants
    /// (<see cref="CieSummation"/>): the colour of the radiance a·b (a light on a material component; b null for a radiance
    /// a alone) at full resolution, whatever the bands.
    /// </summary>
    public Xyz OfProduct(TabulatedSpectrum a, TabulatedSpectrum? b)
    {
        double lo = Grid.Start, hi = Grid.End;
        return new Xyz(
            Kappa * CieSummation.Product(Observer.XBar, a, b, lo, hi),
            Kappa * CieSummation.Product(Observer.YBar, a, b, lo, hi),
            Kappa * CieSummation.Product(Observer.ZBar, a, b, lo, hi));
    }

    /// <summary>
    /// The band values of the radiance a·b as this scheme defines them: the exact band means of the product
    /// (<see cref="BandIntegration.Exact"/>) or the product of the factors' band values (weighted, paper).
    /// </summary>
    public double[] ProjectProduct(TabulatedSpectrum a, TabulatedSpectrum b)
    {
        if (Scheme == BandIntegration.Exact) return BandProjection.MeansOfProduct(a, b, Grid);
        var pa = Project(a);
        var pb = Project(b);
        for (int i = 0; i < pa.Length; i++) pa[i] *= pb[i];
        return pa;
    }

    /// <summary>
    /// The colour of the radiance a·b as this scheme defines it: exact (<see cref="OfProduct"/>) or eq. 3 on its
    /// band values.
    /// </summary>
    public Xyz XyzOfProduct(TabulatedSpectrum a, TabulatedSpectrum b) =>
        Scheme == BandIntegration.Exact ? OfProduct(a, b) : ToXyz(ProjectProduct(a, b));

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
    public static Xyz ToXyz<T>(ReadOnlySpan<double> wx, ReadOnlySpan<double> wy, ReadOnlySpan<double> wz,
        ReadOnlySpan<T> bands) where T : struct,
        INumberBase<T>
    {
        double x = 0, y = 0, z = 0;
        for (int b = 0; b < wx.Length; b++)
        {
            double v = double.CreateTruncating(bands[b]);
            x += wx[b] * v; y += wy[b] * v; z += wz[b] * v;
        }
        return new Xyz(x, y, z);
    }

    /// <summary>XYZ of a reflectance lit head-on by the reference light at unit intensity (the white diffuser's radiance factor
    /// included).</summary>
    public Xyz OfReflectance(TabulatedSpectrum reflectance) => OfReflectance(reflectance, ReferenceLight);

    /// <summary>XYZ of a reflectance lit head-on by <paramref name="light"/> (an irradiance; radiance = light · R ·
    /// <see cref="WhiteRadiance"/>).</summary>
    public Xyz OfReflectance(TabulatedSpectrum reflectance, TabulatedSpectrum light) =>
        XyzOfProduct(light, reflectance) * WhiteRadiance;
}
