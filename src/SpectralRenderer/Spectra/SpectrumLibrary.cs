using System.Collections.Concurrent;
using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// Resolves spectrum names (see docs/scene-format.md): the CIE illuminants <c>D65 A D50 E FL2 FL11</c>,
/// the modelled LEDs <c>led-blue led-green</c>, the NIST sources <c>led-rgb led-yag</c>,
/// ColorChecker patches <c>colorchecker:14</c> / <c>colorchecker:green</c> (Ohta),
/// <c>constant:0.5</c>, a Planckian radiator <c>blackbody:3000</c> (<see cref="Planck"/>), CIE daylight
/// <c>daylight:5000</c> (<see cref="CieDaylight"/>), and any CSV file with a column: <c>file.csv:column</c>.
/// </summary>
public static class SpectrumLibrary
{
    static readonly ConcurrentDictionary<string, SpectralTable> Tables = new(StringComparer.Ordinal);

    /// <summary>
    /// The built-in lights and their one scale (docs/scene-format.md, "Spectrum values"): the CIE illuminants with a
    /// smooth spectrum are 100 at 560 nm as published (A, D65, D50, E; so are blackbody:T and daylight:T); the
    /// fluorescent illuminants, the LEDs and the measured sources (a line spectrum has no meaningful value at 560 nm) are
    /// scaled by luminous flux: ∫V(λ)·S(λ) dλ equals D65's, so at the same intensity they give the same lux as D65.
    /// </summary>
    static readonly (string Name, string File, string Column, bool Luminous)[] Builtins =
    [
        // A, D65, D50 and E from 300 nm (their UV part; 380–780 nm the same values as illuminants.csv).
        ("D65", "illuminants-300-780.csv", "D65", false), ("A", "illuminants-300-780.csv", "A", false),
        ("D50", "illuminants-300-780.csv", "D50", false), ("E", "illuminants-300-780.csv", "E", false),
        ("FL2", "illuminants.csv", "FL2", true), ("FL11", "illuminants.csv", "FL11", true),
        ("led-blue", "leds.csv", "blue_465nm", true), ("led-green", "leds.csv", "green_525nm", true),
        ("led-rgb", "light-sources.csv", "3-LED-1 (457/540/605)", true), ("led-yag", "light-sources.csv", "Phosphor LED YAG", true),
    ];

    /// <summary>
    /// The built-in coefficient spectra, per metre as published (docs/scene-format.md, "Participating media"; data/README.md):
    /// the absorption coefficient of pure water, Pope &amp; Fry (1997) from 380 to 727.5 nm and Smith &amp; Baker (1981) from
    /// 730 to 800 nm (<c>water</c>), and Smith &amp; Baker's alone from 200 to 800 nm (<c>water-smith-baker</c>).
    /// </summary>
    static readonly (string Name, string File, string Column)[] Coefficients =
    [
        ("water", "water-absorption.csv", "a_w_per_m"), ("water-smith-baker", "water-smith-baker-1981.csv", "a_w_per_m"),
    ];

    /// <summary>Whether the built-in light <paramref name="name"/> is scaled by luminous flux (else 100 at 560 nm); null if none.</summary>
    public static bool? IsLuminousNormalised(string name)
    {
        foreach (var b in Builtins)
            if (string.Equals(b.Name, name, StringComparison.OrdinalIgnoreCase)) return b.Luminous;
        return null;
    }

    static readonly ConcurrentDictionary<string, TabulatedSpectrum> Normalised = new(StringComparer.Ordinal);

    /// <summary>
    /// The table scaled so that ∫V·S dλ = ∫V·D65 dλ: V(λ) = ȳ of data/cie1931-2deg-cmf.csv (CIE 1924 photopic), each
    /// integral exact on the tables over the spectrum's own range.
    /// </summary>
    static TabulatedSpectrum LuminousNormalised(string name, TabulatedSpectrum s) => Normalised.GetOrAdd(name, _ => OnLightScale(s, name));

    /// <summary>
    /// <paramref name="s"/> on the built-in lights' scale (a spectrum object's <c>"scale": "luminous"</c>): scaled so that
    /// ∫V·S dλ = ∫V·D65 dλ, as the built-in line and narrow-band lights are; refused when ∫V·S is 0 (no visible light).
    /// </summary>
    public static TabulatedSpectrum OnLightScale(TabulatedSpectrum s, string? name = null, string where = "spectrum")
    {
        var v = DataTable("cie1931-2deg-cmf.csv")["ybar"];
        var d65 = DataTable("illuminants.csv")["D65"];
        static double Luminous(TabulatedSpectrum v, TabulatedSpectrum s) =>
            s.Last <= v.First || s.First >= v.Last ? 0
                : TabulatedSpectrum.IntegrateProduct(v, s, Math.Max(v.First, s.First), Math.Min(v.Last, s.Last));
        double flux = Luminous(v, s);
        if (!(flux > 0))
            throw new InputException(where, "\"scale\": \"luminous\" needs a spectrum with visible light (∫V·S dλ is 0)",
                "give a light's spectrum, or a number as the scale");
        return s.Scaled(Luminous(v, d65) / flux, name ?? s.Name);
    }

    /// <summary>Every built-in name, for help texts and "did you mean".</summary>
    public static IEnumerable<string> KnownNames =>
        Builtins.Select(b => b.Name).Concat(Coefficients.Select(c => c.Name))
            .Concat(ColorChecker.PatchKeys.Select(k => "colorchecker:" + k)).Append("constant:<value>")
            .Append("blackbody:<K>").Append("daylight:<K>");

    public static SpectralTable Table(string path) => Tables.GetOrAdd(System.IO.Path.GetFullPath(path), CsvSpectrumReader.Read);
    public static SpectralTable DataTable(string file) => Table(DataDirectory.File_(file));

    /// <summary>Resolves a name. <paramref name="baseDirectory"/> anchors relative CSV paths; <paramref name="where"/> names the place for
    /// errors.</summary>
    public static TabulatedSpectrum Resolve(string name, string? baseDirectory = null, string where = "spectrum")
    {
        name = name.Trim();
        foreach (var b in Builtins)
            if (string.Equals(b.Name, name, StringComparison.OrdinalIgnoreCase))
                return Rename(b.Luminous ? LuminousNormalised(b.Name, DataTable(b.File)[b.Column]) : DataTable(b.File)[b.Column], b.Name);

        foreach (var c in Coefficients)
            if (string.Equals(c.Name, name, StringComparison.OrdinalIgnoreCase))
                return Rename(DataTable(c.File)[c.Column], c.Name);

        if (name.StartsWith("constant:", StringComparison.OrdinalIgnoreCase))
        {
            var v = name["constant:".Length..];
            if (!double.TryParse(v, NumberStyles.Float, CultureInfo.InvariantCulture, out double c) || !double.IsFinite(c) || c < 0)
                throw new InputException(where, $"'{name}' needs a finite non-negative number after 'constant:'", "e.g. constant:0.5");
            return TabulatedSpectrum.Constant(c, name);
        }

        if (name.StartsWith("blackbody:", StringComparison.OrdinalIgnoreCase))
            return Planck.Parse(name, name["blackbody:".Length..], where);
        if (name.StartsWith("daylight:", StringComparison.OrdinalIgnoreCase))
            return CieDaylight.Parse(name, name["daylight:".Length..], where);

        if (name.StartsWith("colorchecker:", StringComparison.OrdinalIgnoreCase))
            return ColorChecker.Patch(name["colorchecker:".Length..], where);

        int colon = name.LastIndexOf(':');
        if (colon > 0 && name[..colon].EndsWith(".csv", StringComparison.OrdinalIgnoreCase))
        {
            var file = name[..colon];
            var column = name[(colon + 1)..];
            var path = System.IO.Path.IsPathRooted(file) ? file : System.IO.Path.Combine(baseDirectory ?? ".", file);
            if (!File.Exists(path) && !Directory.Exists(path))
                throw new InputException(where, $"CSV file {MessageText.Quote(file, 80)} not found",
                    "check the name: a relative path starts at the scene's folder");
            var table = Table(path);
            if (!table.TryGet(column, out var s))
                throw new InputException(where, $"{file} has no column '{column}'",
                    InputException.DidYouMean(column, table.Columns) ?? $"its columns are: {string.Join(", ", table.Columns)}");
            return s;
        }
        if (name.EndsWith(".csv", StringComparison.OrdinalIgnoreCase))
            throw new InputException(where, $"'{name}' names a CSV file but no column", "write file.csv:column");

        throw new InputException(where, $"unknown spectrum '{name}'",
            InputException.DidYouMean(name, Builtins.Select(b => b.Name).Concat(ColorChecker.PatchKeys.Select(k => "colorchecker:" + k)))
            ?? "built-in names: D65, A, D50, E, FL2, FL11, led-blue, led-green, led-rgb, led-yag, colorchecker:1..24, constant:<v>, "
                + "blackbody:<K>, daylight:<K>, file.csv:column");
    }

    static TabulatedSpectrum Rename(TabulatedSpectrum s, string name) =>
        new(name, s.Wavelengths.ToArray(), s.Values.ToArray(), s.Extrapolation);
}
