using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests;

/// <summary>
/// The CIE 015:2018 §7 summation at 1 nm, written out here independently of the engine's colorimeters:
/// X = Σ_λ x̄(λ)·E(λ)·R(λ) / Σ_λ ȳ(λ)·E_white(λ) over whole nanometres 380…780, each table read at λ
/// by linear interpolation. Several lights add their spectra (each with its intensity).
/// </summary>
static class Cie015
{
    public static Xyz Of(TabulatedSpectrum reflectance, (TabulatedSpectrum Spd, double Intensity)[] lights, TabulatedSpectrum white,
        Observer? observer = null, int first = 380, int last = 780)
    {
        observer ??= Observer.Cie1931;
        double x = 0, y = 0, z = 0, yw = 0;
        for (int l = first; l <= last; l++)
        {
            double e = 0;
            foreach (var (spd, k) in lights) e += k * At(spd, l);
            double r = reflectance is null ? 1 : At(reflectance, l);
            x += At(observer.XBar, l) * e * r;
            y += At(observer.YBar, l) * e * r;
            z += At(observer.ZBar, l) * e * r;
            yw += At(observer.YBar, l) * At(white, l);
        }
        return new Xyz(x / yw, y / yw, z / yw);
    }

    /// <summary>
    /// Σ f(λ)·1 nm over whole nanometres first…last with the two ends at half weight: §7.1's 1 nm sum in its trapezoidal form
    /// (the engine's one summation rule for colour and camera signals), f built from the tables' interpolants by the caller.
    /// </summary>
    public static double Sum(Func<int, double> f, int first = 380, int last = 780)
    {
        double s = 0.5 * (f(first) + f(last));
        for (int l = first + 1; l < last; l++) s += f(l);
        return s;
    }

    /// <summary>XYZ of the perfect white diffuser under the white itself (Y = 1).</summary>
    public static Xyz White(TabulatedSpectrum white, Observer? observer = null) =>
        Of(TabulatedSpectrum.Constant(1), [(white, 1)], white, observer);

    /// <summary>The table's linear interpolant at whole nanometre l (its end value outside the table).</summary>
    static double At(TabulatedSpectrum s, int l)
    {
        var w = s.Wavelengths; var v = s.Values;
        if (l <= w[0]) return v[0];
        if (l >= w[^1]) return v[^1];
        int i = 0;
        while (w[i + 1] < l) i++;
        double t = (l - w[i]) / (w[i + 1] - w[i]);
        return v[i] + t * (v[i + 1] - v[i]);
    }
}
