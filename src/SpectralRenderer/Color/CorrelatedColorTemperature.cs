using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// Correlated colour temperature (CIE 015:2018 §9.5): the temperature of the Planckian radiator whose
/// chromaticity is nearest in the CIE 1960 UCS (u, v), with Δ_uv the signed distance (positive above the
/// locus). The locus is computed from Planck's law and the CIE 1931 2° CMFs at 1 nm over 360–830 nm, and
/// the nearest point found by golden-section search in reciprocal temperature (to better than 0.01 K), so
/// it needs neither Robertson's isotemperature table nor Ohno's interpolation, which both approximate it.
/// </summary>
public static class CorrelatedColorTemperature
{
    /// <summary>CIE 1960 UCS chromaticity u = 4X/(X + 15Y + 3Z), v = 6Y/(X + 15Y + 3Z).</summary>
    public static (double U, double V) Uv(Xyz c)
    {
        double d = c.X + 15 * c.Y + 3 * c.Z;
        return (4 * c.X / d, 6 * c.Y / d);
    }

    /// <summary>(u, v) of the Planckian radiator at <paramref name="kelvin"/> (2° observer).</summary>
    public static (double U, double V) PlanckianUv(double kelvin)
    {
        var o = Observer.Cie1931;
        double x = 0, y = 0, z = 0;
        for (int l = 360; l <= 830; l++)
        {
            double m = Planck.Relative(l, kelvin);
            x += o.XBar.Evaluate(l) * m; y += o.YBar.Evaluate(l) * m; z += o.ZBar.Evaluate(l) * m;
        }
        return Uv(new Xyz(x, y, z));
    }

    /// <summary>CCT in kelvin and Δ_uv of chromaticity (u, v), searched over 1000–100000 K.</summary>
    public static (double Kelvin, double Duv) FromUv(double u, double v)
    {
        double Distance2(double mired)
        {
            var (pu, pv) = PlanckianUv(1e6 / mired);
            return (pu - u) * (pu - u) + (pv - v) * (pv - v);
        }
        // Coarse scan in mired (10–1000), then golden section around the best sample.
        double best = 10, bestD = double.MaxValue;
        for (double m = 10; m <= 1000; m += 5)
        {
            double d = Distance2(m);
            if (d < bestD) { bestD = d; best = m; }
        }
        double a = Math.Max(10, best - 5), b = Math.Min(1000, best + 5);
        double g = (Math.Sqrt(5) - 1) / 2;
        double c1 = b - g * (b - a), c2 = a + g * (b - a), f1 = Distance2(c1), f2 = Distance2(c2);
        while (b - a > 1e-7)
        {
            if (f1 < f2) { b = c2; c2 = c1; f2 = f1; c1 = b - g * (b - a); f1 = Distance2(c1); }
            else { a = c1; c1 = c2; f1 = f2; c2 = a + g * (b - a); f2 = Distance2(c2); }
        }
        double mired = (a + b) / 2, kelvin = 1e6 / mired;
        var (lu, lv) = PlanckianUv(kelvin);
        double duv = Math.Sqrt(Distance2(mired)) * Math.Sign(v - lv);
        return (kelvin, duv);
    }

    /// <summary>CCT and Δ_uv of a light: its XYZ by 1 nm summation over 360–830 nm, 2° observer.</summary>
    public static (double Kelvin, double Duv) Of(TabulatedSpectrum light)
    {
        var o = Observer.Cie1931;
        var l = light.WithExtrapolation(Extrapolation.Zero);
        double x = 0, y = 0, z = 0;
        for (int w = 360; w <= 830; w++)
        {
            double e = l.Evaluate(w);
            x += o.XBar.Evaluate(w) * e; y += o.YBar.Evaluate(w) * e; z += o.ZBar.Evaluate(w) * e;
        }
        var (u, v) = Uv(new Xyz(x, y, z));
        return FromUv(u, v);
    }
}
