using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>A CIE standard colorimetric observer: the colour-matching functions x̄, ȳ, z̄ (CIE 015:2018).</summary>
public sealed class Observer
{
    Observer(string name, TabulatedSpectrum x, TabulatedSpectrum y, TabulatedSpectrum z)
    {
        Name = name;
        XBar = x; YBar = y; ZBar = z;
    }

    public string Name { get; }
    public TabulatedSpectrum XBar { get; }
    public TabulatedSpectrum YBar { get; }
    public TabulatedSpectrum ZBar { get; }

    static Observer? _cie1931, _cie1964;

    /// <summary>CIE 1931 2° standard observer, 360–830 nm at 1 nm.</summary>
    public static Observer Cie1931 => _cie1931 ??= Load("CIE 1931 2°", "cie1931-2deg-cmf.csv");
    /// <summary>CIE 1964 10° supplementary standard observer, 360–830 nm at 1 nm.</summary>
    public static Observer Cie1964 => _cie1964 ??= Load("CIE 1964 10°", "cie1964-10deg-cmf.csv");

    /// <summary>"2" or "10" (degrees).</summary>
    public static Observer FromDegrees(string degrees, string where = "--observer") => degrees.Trim().TrimEnd('°') switch
    {
        "2" => Cie1931,
        "10" => Cie1964,
        _ => throw new InputException(where, $"unknown observer '{degrees}'", "use 2 (CIE 1931) or 10 (CIE 1964)"),
    };

    public int Degrees => ReferenceEquals(this, Cie1964) ? 10 : 2;

    static Observer Load(string name, string file)
    {
        var t = SpectrumLibrary.DataTable(file);
        // Outside 360–830 nm the CMFs are zero to within 1e-6 of their peak: zero extrapolation.
        return new Observer(name,
            t["xbar"].WithExtrapolation(Extrapolation.Zero),
            t["ybar"].WithExtrapolation(Extrapolation.Zero),
            t["zbar"].WithExtrapolation(Extrapolation.Zero));
    }
}
