using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// The tool's own 1 nm colorimetry (CIE 015:2018 §7): X = Σ x̄(λ)E(λ)R(λ) / Σ ȳ(λ)E(λ) over whole
/// nanometres λ ∈ [start, end], spectra linearly interpolated to 1 nm. The yardstick the band
/// schemes are measured against (and how data/reference was computed).
/// </summary>
public sealed class ReferenceColorimeter
{
    readonly double[] _x, _y, _z, _e;
    readonly int _first;

    public ReferenceColorimeter(Observer observer, TabulatedSpectrum light, double start = 380, double end = 780)
    {
        _first = (int)Math.Ceiling(start);
        int last = (int)Math.Floor(end);
        int n = last - _first + 1;
        _x = new double[n]; _y = new double[n]; _z = new double[n]; _e = new double[n];
        double yw = 0;
        for (int i = 0; i < n; i++)
        {
            int l = _first + i;
            _e[i] = light.Evaluate(l);
            _x[i] = observer.XBar.Evaluate(l) * _e[i];
            _y[i] = observer.YBar.Evaluate(l) * _e[i];
            _z[i] = observer.ZBar.Evaluate(l) * _e[i];
            yw += _y[i];
        }
        for (int i = 0; i < n; i++) { _x[i] /= yw; _y[i] /= yw; _z[i] /= yw; }
        double xw = 0, zw = 0;
        for (int i = 0; i < n; i++) { xw += _x[i]; zw += _z[i]; }
        White = new Xyz(xw, 1.0, zw);
    }

    public Xyz White { get; }

    public Xyz OfReflectance(TabulatedSpectrum reflectance)
    {
        double x = 0, y = 0, z = 0;
        for (int i = 0; i < _x.Length; i++)
        {
            double r = reflectance.Evaluate(_first + i);
            x += _x[i] * r; y += _y[i] * r; z += _z[i] * r;
        }
        return new Xyz(x, y, z);
    }
}
