using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// The tool's own 1 nm colorimetry (CIE 015:2018 §7): X = Σ x̄(λ)E(λ)R(λ) / Σ ȳ(λ)E_white(λ) over whole
/// nanometres λ ∈ [start, end], spectra linearly interpolated to 1 nm. The yardstick the band
/// schemes are measured against (and how data/reference was computed).
/// </summary>
public sealed class ReferenceColorimeter
{
    readonly double[] _xbar, _ybar, _zbar, _e;
    readonly double _norm;
    readonly int _first;

    public ReferenceColorimeter(Observer observer, TabulatedSpectrum light, double start = 380, double end = 780)
    {
        _first = (int)Math.Ceiling(start);
        int last = (int)Math.Floor(end);
        int n = last - _first + 1;
        _xbar = new double[n]; _ybar = new double[n]; _zbar = new double[n]; _e = new double[n];
        double yw = 0;
        for (int i = 0; i < n; i++)
        {
            int l = _first + i;
            _e[i] = light.Evaluate(l);
            _xbar[i] = observer.XBar.Evaluate(l);
            _ybar[i] = observer.YBar.Evaluate(l);
            _zbar[i] = observer.ZBar.Evaluate(l);
            yw += _ybar[i] * _e[i];
        }
        _norm = 1 / yw;
        White = Sum(i => _e[i]);
    }

    public Xyz White { get; }

    Xyz Sum(Func<int, double> stimulus)
    {
        double x = 0, y = 0, z = 0;
        for (int i = 0; i < _e.Length; i++)
        {
            double s = stimulus(i);
            x += _xbar[i] * s; y += _ybar[i] * s; z += _zbar[i] * s;
        }
        return new Xyz(x * _norm, y * _norm, z * _norm);
    }

    /// <summary>XYZ of a reflectance lit head-on by the reference light.</summary>
    public Xyz OfReflectance(TabulatedSpectrum reflectance) => Sum(i => _e[i] * reflectance.Evaluate(_first + i));

    /// <summary>
    /// XYZ of a reflectance lit head-on by another light (an irradiance in the units of the reference light, which keeps
    /// fixing the normalisation): X = Σ x̄·E·R / Σ ȳ·E_white.
    /// </summary>
    public Xyz OfReflectance(TabulatedSpectrum reflectance, TabulatedSpectrum light) =>
        Sum(i => light.Evaluate(_first + i) * reflectance.Evaluate(_first + i));
}
