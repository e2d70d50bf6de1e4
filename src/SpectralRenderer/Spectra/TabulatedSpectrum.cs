using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// A spectrum given as a table (λ_i, v_i), taken to be the piecewise-linear interpolant of
/// its samples. Band values are exact integrals of that interpolant (not point samples).
/// </summary>
public sealed class TabulatedSpectrum
{
    readonly double[] _wavelengths;
    readonly double[] _values;

    public TabulatedSpectrum(string name, double[] wavelengths, double[] values,
        Extrapolation extrapolation = Extrapolation.Error)
    {
        if (wavelengths.Length != values.Length || wavelengths.Length == 0)
            throw new ArgumentException("a spectrum needs as many values as wavelengths, at least one");
        for (int i = 1; i < wavelengths.Length; i++)
            if (!(wavelengths[i] > wavelengths[i - 1]))
                throw new ArgumentException($"{name}: wavelengths must be strictly ascending");
        Name = name;
        _wavelengths = wavelengths;
        _values = values;
        Extrapolation = extrapolation;
    }

    /// <summary>A constant spectrum over all wavelengths.</summary>
    public static TabulatedSpectrum Constant(double value, string? name = null) =>
        new(name ?? $"constant:{value}", [1.0, 1e5], [value, value], Extrapolation.Clamp);

    public string Name { get; }
    public Extrapolation Extrapolation { get; }
    public ReadOnlySpan<double> Wavelengths => _wavelengths;
    public ReadOnlySpan<double> Values => _values;
    public double First => _wavelengths[0];
    public double Last => _wavelengths[^1];

    public TabulatedSpectrum WithExtrapolation(Extrapolation e) => new(Name, _wavelengths, _values, e);
    public TabulatedSpectrum Scaled(double s, string? name = null)
    {
        var v = new double[_values.Length];
        for (int i = 0; i < v.Length; i++) v[i] = _values[i] * s;
        return new TabulatedSpectrum(name ?? Name, _wavelengths, v, Extrapolation);
    }

    /// <summary>Does the table cover [lo, hi], or does the extrapolation policy allow it?</summary>
    public bool Covers(double lo, double hi) =>
        Extrapolation != Extrapolation.Error || (lo >= First - 1e-9 && hi <= Last + 1e-9);

    /// <summary>Throws a clear error when [lo, hi] is not covered.</summary>
    public void RequireCoverage(double lo, double hi, string where)
    {
        if (!Covers(lo, hi))
            throw new InputException(where,
                $"spectrum '{Name}' covers {First:0.###}–{Last:0.###} nm but the bands need {lo:0.###}–{hi:0.###} nm",
                "choose bands inside its range or set an extrapolation policy (\"extrapolate\": \"clamp\" or \"zero\")");
    }

    /// <summary>The value of the linear interpolant at λ.</summary>
    public double Evaluate(double wavelength)
    {
        var w = _wavelengths;
        if (wavelength <= w[0] || wavelength >= w[^1])
        {
            bool inside = wavelength == w[0] || wavelength == w[^1];
            if (!inside && Extrapolation == Extrapolation.Zero) return 0;
            if (!inside && Extrapolation == Extrapolation.Error)
                throw new InvalidOperationException($"{Name} is not defined at {wavelength} nm");
            return wavelength <= w[0] ? _values[0] : _values[^1];
        }
        int i = Segment(wavelength);
        double t = (wavelength - w[i]) / (w[i + 1] - w[i]);
        return _values[i] + t * (_values[i + 1] - _values[i]);
    }

    /// <summary>∫_lo^hi S(λ) dλ of the linear interpolant, exactly.</summary>
    public double Integrate(double lo, double hi) => IntegrateProduct(this, null, lo, hi);

    /// <summary>The band mean: ∫_lo^hi S dλ / (hi − lo) (the guide §2: band value = mean over the band).</summary>
    public double Mean(double lo, double hi) => Integrate(lo, hi) / (hi - lo);

    /// <summary>
    /// ∫_lo^hi a(λ)·b(λ) dλ of two piecewise-linear spectra, exactly (see the three-factor overload).
    /// With <paramref name="b"/> null the integral of <paramref name="a"/> alone.
    /// </summary>
    public static double IntegrateProduct(TabulatedSpectrum a, TabulatedSpectrum? b, double lo, double hi) =>
        IntegrateProduct(a, b, null, lo, hi);

    /// <summary>
    /// ∫_lo^hi a(λ)·b(λ)·c(λ) dλ of up to three piecewise-linear spectra, exactly: on each interval between
    /// the merged knots the product is a polynomial of degree ≤ 3, which Simpson's rule integrates without
    /// error. A null factor is 1. This is the band integral of a light × a reflectance (× a CMF) at the
    /// tables' full resolution.
    /// </summary>
    public static double IntegrateProduct(TabulatedSpectrum a, TabulatedSpectrum? b, TabulatedSpectrum? c, double lo, double hi)
    {
        if (hi <= lo) return 0;
        double sum = 0;
        double x0 = lo;
        int ia = a.FirstKnotAbove(lo), ib = b?.FirstKnotAbove(lo) ?? int.MaxValue, ic = c?.FirstKnotAbove(lo) ?? int.MaxValue;
        while (x0 < hi)
        {
            double na = ia < a._wavelengths.Length ? a._wavelengths[ia] : double.PositiveInfinity;
            double nb = b is not null && ib < b._wavelengths.Length ? b._wavelengths[ib] : double.PositiveInfinity;
            double nc = c is not null && ic < c._wavelengths.Length ? c._wavelengths[ic] : double.PositiveInfinity;
            double x1 = Math.Min(hi, Math.Min(na, Math.Min(nb, nc)));
            if (x1 == na) ia++;
            if (x1 == nb) ib++;
            if (x1 == nc) ic++;
            var (fa0, fa1) = a.Ends(x0, x1);
            var (fb0, fb1) = b?.Ends(x0, x1) ?? (1.0, 1.0);
            var (fc0, fc1) = c?.Ends(x0, x1) ?? (1.0, 1.0);
            // Inside one knot interval all are linear, so their midpoint values are the means of the ends.
            double fam = 0.5 * (fa0 + fa1), fbm = 0.5 * (fb0 + fb1), fcm = 0.5 * (fc0 + fc1);
            sum += (x1 - x0) / 6 * (fa0 * fb0 * fc0 + 4 * fam * fbm * fcm + fa1 * fb1 * fc1);
            x0 = x1;
        }
        return sum;
    }

    /// <summary>The band mean of a product, ∫_lo^hi a·b dλ / (hi − lo), exactly.</summary>
    public static double MeanOfProduct(TabulatedSpectrum a, TabulatedSpectrum b, double lo, double hi) =>
        IntegrateProduct(a, b, null, lo, hi) / (hi - lo);

    /// <summary>The largest and smallest value the interpolant takes on [lo, hi] (at knots inside it or at its ends).</summary>
    public (double Min, double Max) Range(double lo, double hi)
    {
        double min = double.PositiveInfinity, max = double.NegativeInfinity;
        void Take(double v) { min = Math.Min(min, v); max = Math.Max(max, v); }
        if (Covers(lo, lo)) Take(Evaluate(Math.Max(lo, Extrapolation == Extrapolation.Error ? First : lo)));
        if (Covers(hi, hi)) Take(Evaluate(Math.Min(hi, Extrapolation == Extrapolation.Error ? Last : hi)));
        for (int i = 0; i < _wavelengths.Length; i++)
            if (_wavelengths[i] >= lo && _wavelengths[i] <= hi) Take(_values[i]);
        return (min, max);
    }

    /// <summary>The interpolant's values at both ends of [x0, x1], an interval between knots (zero outside the table under
    /// <see cref="Extrapolation.Zero"/>).</summary>
    (double, double) Ends(double x0, double x1) =>
        Extrapolation == Extrapolation.Zero && (x1 <= First || x0 >= Last) ? (0, 0) : (Evaluate(x0), Evaluate(x1));

    int FirstKnotAbove(double x)
    {
        int i = Array.BinarySearch(_wavelengths, x);
        return i >= 0 ? i + 1 : ~i;
    }

    int Segment(double x)
    {
        int i = Array.BinarySearch(_wavelengths, x);
        if (i >= 0) return Math.Min(i, _wavelengths.Length - 2);
        return ~i - 1;
    }

    public override string ToString() => Name;
}
