using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>
/// pbrt-v4's named spectra (`metal-Au-eta`, `glass-BK7`, `stdillum-D65`, …), read from data/pbrt-v4/*.csv: the tables of
/// pbrt-v4's src/pbrt/util/spectrum.cpp (commit 5f7a606, extracted by scripts/pbrt-named-spectra.py; data/pbrt-v4/README.md).
/// pbrt builds each with PiecewiseLinearSpectrum::FromInterleaved: linear between samples, the end values held beyond the
/// table; the illuminants (files illuminants-*.csv) are also scaled to Σ ȳ(λ)·S(λ) = CIE_Y_integral over 360…830 nm.
/// </summary>
public static class PbrtNamedSpectra
{
    /// <summary>pbrt-v4's CIE_Y_integral (spectrum.h): Σ ȳ(λ) over the integers 360…830 nm of its CIE 1931 table.</summary>
    public const double CieYIntegral = 106.856895;

    static readonly Lazy<Dictionary<string, (TabulatedSpectrum Table, bool Illuminant)>> All = new(Load);

    public static IEnumerable<string> Names => All.Value.Keys.Order(StringComparer.Ordinal);

    /// <summary>The table as pbrt-v4 lists it (before any normalisation), and whether pbrt normalises it as an illuminant.</summary>
    public static bool TryGet(string name, out TabulatedSpectrum table, out bool illuminant)
    {
        if (All.Value.TryGetValue(name, out var e))
        {
            table = e.Table;
            illuminant = e.Illuminant;
            return true;
        }
        table = null!;
        illuminant = false;
        return false;
    }

    /// <summary>
    /// The factor pbrt multiplies a named spectrum's table by: CIE_Y_integral / Σ ȳ·S for an illuminant, 1 otherwise.
    /// </summary>
    public static double Normalisation(string name) =>
        TryGet(name, out var t, out bool illuminant) && illuminant ? CieYIntegral / YInnerProduct(t) : 1;

    /// <summary>
    /// pbrt-v4's InnerProduct(&amp;Spectra::Y(), s) (spectrum.h): Σ ȳ(λ)·S(λ) over the integers λ = 360…830 nm, S evaluated
    /// as the linear interpolant with its end values held (as FromInterleaved extends a table), ȳ the CIE 1931 table.
    /// </summary>
    public static double YInnerProduct(TabulatedSpectrum s)
    {
        var ybar = Observer.Cie1931.YBar;
        var held = s.WithExtrapolation(Extrapolation.Clamp);
        double sum = 0;
        for (int l = 360; l <= 830; l++) sum += ybar.Evaluate(l) * held.Evaluate(l);
        return sum;
    }

    static Dictionary<string, (TabulatedSpectrum, bool)> Load()
    {
        var folder = Path.Combine(DataDirectory.Path, "pbrt-v4");
        var all = new Dictionary<string, (TabulatedSpectrum, bool)>(StringComparer.Ordinal);
        foreach (var file in Directory.GetFiles(folder, "*.csv").Order(StringComparer.Ordinal))
        {
            var table = CsvSpectrumReader.Read(file);
            bool illuminant = Path.GetFileName(file).StartsWith("illuminants", StringComparison.Ordinal);
            foreach (var column in table.Columns) all[column] = (table[column].WithExtrapolation(Extrapolation.Clamp), illuminant);
        }
        return all;
    }
}
