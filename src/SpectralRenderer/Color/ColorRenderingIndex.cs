using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// CIE 13.3-1995 colour rendering index of a light source: the 14 test colour samples
/// (data/reflectances-cie13.3-tcs14.csv) under the test source and under the reference illuminant of the
/// same CCT (Planckian below 5000 K, CIE daylight from 5000 K), CIE 1931 2° observer, 1 nm summation over
/// 360–780 nm (5 nm tables interpolated to 1 nm by Sprague's method, CIE 167:2005, their end values continued outside
/// them); von Kries
/// adaptation in the CIE 1960 UCS (13.3 eq. 4–5), the CIE 1964 U*V*W* space, R_i = 100 − 4.6 ΔE_i,
/// Ra = the mean of R₁…R₈.
/// </summary>
public static class ColorRenderingIndex
{
    public sealed record Result(double Ra, double[] SpecialIndices, double Cct, double Duv, string Reference);

    const int First = 360, Last = 780;

    public static Result Of(TabulatedSpectrum source)
    {
        var (cct, duv) = CorrelatedColorTemperature.Of(source);
        var (reference, refName) = cct < 5000
            ? (Planck.Spectrum(cct), $"Planckian {cct:0} K")
            : (CieDaylight.FromChromaticity(CieDaylight.Chromaticity(Math.Min(cct, CieDaylight.MaxKelvin)).X,
                CieDaylight.Chromaticity(Math.Min(cct, CieDaylight.MaxKelvin)).Y, "D"), $"CIE daylight {cct:0} K");

        var samples = SpectrumLibrary.DataTable("reflectances-cie13.3-tcs14.csv");
        var test = Sampled(source.WithExtrapolation(Extrapolation.Clamp));
        var refr = Sampled(reference.WithExtrapolation(Extrapolation.Clamp));
        var (ut, vt) = CorrelatedColorTemperature.Uv(Tristimulus(test, null));
        var (ur, vr) = CorrelatedColorTemperature.Uv(Tristimulus(refr, null));
        double ct = C(ut, vt), dt = D(ut, vt), cr = C(ur, vr), dr = D(ur, vr);

        var r = new double[14];
        for (int i = 0; i < 14; i++)
        {
            var rho = samples.Columns[i];
            var reflect = Sampled(samples[rho]);
            var xt = Tristimulus(test, reflect);
            var xr = Tristimulus(refr, reflect);

            // Test sample adapted to the reference white (CIE 13.3 eq. 5).
            var (u, v) = CorrelatedColorTemperature.Uv(xt);
            double c = C(u, v), d = D(u, v);
            double den = 16.518 + 1.481 * cr / ct * c - dr / dt * d;
            double ua = (10.872 + 0.404 * cr / ct * c - 4 * dr / dt * d) / den;
            double va = 5.520 / den;
            var (uref, vref) = CorrelatedColorTemperature.Uv(xr);

            var (wt, ust, vst) = Uvw(xt.Y, ua, va, ur, vr);
            var (wr, usr, vsr) = Uvw(xr.Y, uref, vref, ur, vr);
            double de = Math.Sqrt((wt - wr) * (wt - wr) + (ust - usr) * (ust - usr) + (vst - vsr) * (vst - vsr));
            r[i] = 100 - 4.6 * de;
        }
        return new Result(r.Take(8).Average(), r, cct, duv, refName);
    }

    static double C(double u, double v) => (4 - u - 10 * v) / v;
    static double D(double u, double v) => (1.708 * v + 0.404 - 1.481 * u) / v;

    /// <summary>CIE 1964 W* = 25 Y^(1/3) − 17 (Y of the sample, white = 100), U* = 13 W*(u − u_w), V* = 13 W*(v − v_w).</summary>
    static (double W, double U, double V) Uvw(double y, double u, double v, double uw, double vw)
    {
        double w = 25 * Math.Cbrt(y) - 17;
        return (w, 13 * w * (u - uw), 13 * w * (v - vw));
    }

    static double[] Sampled(TabulatedSpectrum s)
    {
        // 5 nm tables to 1 nm by Sprague (CIE 167:2005), as the reference computation does.
        if (Sprague.Applies(s) && s.Wavelengths[1] - s.Wavelengths[0] > 1) return Sprague.At1nm(s, First, Last);
        var v = new double[Last - First + 1];
        for (int i = 0; i < v.Length; i++) v[i] = s.Evaluate(First + i);
        return v;
    }

    /// <summary>XYZ of a sample (or of the source itself when <paramref name="reflectance"/> is null), Y of the perfect white =
    /// 100.</summary>
    static Xyz Tristimulus(double[] light, double[]? reflectance)
    {
        var o = Observer.Cie1931;
        double x = 0, y = 0, z = 0, yw = 0;
        for (int i = 0; i < light.Length; i++)
        {
            int l = First + i;
            double e = light[i], r = reflectance?[i] ?? 1, yb = o.YBar.Evaluate(l);
            x += o.XBar.Evaluate(l) * e * r; y += yb * e * r; z += o.ZBar.Evaluate(l) * e * r;
            yw += yb * e;
        }
        double k = 100 / yw;
        return new Xyz(x * k, y * k, z * k);
    }
}
