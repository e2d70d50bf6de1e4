using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Import.Pbrt;

// Spectrum parameters: named spectra, λ–value pairs, .spd files, rgb, blackbody, constants; and pbrt's photometric
// normalisation of a light's spectrum (SpectrumToPhotometric).
public sealed partial class PbrtConverter
{
    /// <summary>What a spectrum parameter is read as: pbrt's SpectrumType (albedo, unbounded, illuminant).</summary>
    enum SpectrumUse { Reflectance, Unbounded, Illuminant }

    /// <summary>A spectrum value of our scene format and, for a light, pbrt's SpectrumToPhotometric of it (Σ ȳ·S, 1 nm).</summary>
    readonly record struct SpectrumValue(JsonNode Node, double Photometric);

    /// <summary>The colour space's illuminant (sRGB: pbrt's stdillum-D65), lights' default spectrum.</summary>
    SpectrumValue DefaultIlluminant() => new(NamedSpectrum("stdillum-D65"), PbrtNamedSpectra.CieYIntegral);

    /// <summary>
    /// The spectrum parameter <paramref name="name"/> of <paramref name="e"/> as a spectrum value, or null when absent.
    /// Textures are left to <see cref="Texture"/> (the caller asks for them first).
    /// </summary>
    SpectrumValue? Spectrum(PbrtEntity e, string name, SpectrumUse use, string label)
    {
        var p = e.Parameters.Find(name);
        if (p is null) return null;
        switch (p.Type)
        {
            case "float":
                if (p.Numbers.Length != 1)
                    throw new InputException(p.Where, $"\"float {name}\" should be one number", $"e.g. \"float {name}\" 0.5");
                return Constant(p, p.Numbers[0], use);
            case "spectrum" when p.Strings.Length > 0:
                {
                    if (p.Strings.Length != 1)
                        throw new InputException(p.Where, $"\"spectrum {name}\" should be one name or file",
                            "e.g. \"spectrum eta\" \"metal-Au-eta\"");
                    string s = p.Strings[0];
                    if (PbrtNamedSpectra.TryGet(s, out var table, out _))
                        return new(NamedSpectrum(s), PbrtNamedSpectra.YInnerProduct(table) * PbrtNamedSpectra.Normalisation(s));
                    return SpdFile(p, s);
                }
            case "spectrum":
                {
                    var v = p.Numbers;
                    if (v.Length < 4 || v.Length % 2 != 0)
                        throw new InputException(p.Where, $"\"spectrum {name}\" should be pairs of wavelength (nm) and value",
                            "e.g. \"spectrum reflectance\" [ 400 0.2 700 0.8 ]");
                    // pbrt's PiecewiseLinearSpectrum from pairs is zero outside its wavelengths.
                    return Pairs(p, v, Extrapolation.Zero);
                }
            case "rgb":
                {
                    if (p.Numbers.Length != 3)
                        throw new InputException(p.Where, $"\"rgb {name}\" should be three numbers", "e.g. [ 0.5 0.5 0.5 ]");
                    return Rgb(p, p.Numbers, use, label);
                }
            case "blackbody":
                {
                    if (p.Numbers.Length != 1)
                        throw new InputException(p.Where, $"\"blackbody {name}\" should be one temperature in kelvin",
                            "e.g. \"blackbody L\" 3000");
                    double t = p.Numbers[0];
                    if (!(t >= 100 && t <= 1e6))
                        throw new InputException(p.Where, $"blackbody temperature {t} K", "give a temperature between 100 and 1000000 K");
                    var b = Planck.Spectrum(t);
                    string kelvin = t.ToString("R", CultureInfo.InvariantCulture);
                    if (use == SpectrumUse.Illuminant)
                        return new(JsonValue.Create($"blackbody:{kelvin}")!, PbrtNamedSpectra.YInnerProduct(b));
                    // Elsewhere pbrt's BlackbodySpectrum is normalised to 1 at its peak (Wien's λ_max = 2.8977721e-3 m·K / T).
                    double peak = b.WithExtrapolation(Extrapolation.Clamp).Evaluate(2.8977721e6 / t);
                    return new(new JsonObject { ["name"] = $"blackbody:{kelvin}", ["scale"] = 1 / peak }, 0);
                }
            default:
                throw new InputException(p.Where, $"\"{p.Type} {name}\" is not a spectrum",
                    $"give \"spectrum {name}\", \"rgb {name}\", \"blackbody {name}\" or a texture");
        }
    }

    SpectrumValue Constant(PbrtParameter p, double v, SpectrumUse use)
    {
        if (v < 0) throw new InputException(p.Where, $"\"{p.Name}\" is negative ({v})", "spectra are not negative");
        if (use == SpectrumUse.Reflectance && v > 1)
        {
            _report.Add("approximated", Place(p.Token), $"\"{p.Type} {p.Name}\"", $"a reflectance of {Round(v)} is clamped to 1");
            v = 1;
        }
        var ybar = Observer.Cie1931.YBar;
        double ysum = 0;
        for (int l = 360; l <= 830; l++) ysum += ybar.Evaluate(l);
        return new(JsonValue.Create(Round(v))!, v * ysum);
    }

    /// <summary>A named spectrum of pbrt-v4, added to the scene's "spectra" (its table, and pbrt's scale for an illuminant).</summary>
    JsonNode NamedSpectrum(string name)
    {
        if (!_spectra.ContainsKey(name))
        {
            PbrtNamedSpectra.TryGet(name, out var table, out bool illuminant);
            var o = new JsonObject { ["values"] = PairsJson(table.Wavelengths, table.Values), ["extrapolate"] = "clamp" };
            if (illuminant) o["scale"] = PbrtNamedSpectra.Normalisation(name);
            _spectra[name] = o;
        }
        return JsonValue.Create(name)!;
    }

    static JsonArray PairsJson(ReadOnlySpan<double> wavelengths, ReadOnlySpan<double> values)
    {
        var a = new JsonArray();
        for (int i = 0; i < wavelengths.Length; i++) a.Add((JsonNode)new JsonArray(wavelengths[i], values[i]));
        return a;
    }

    SpectrumValue Pairs(PbrtParameter p, double[] v, Extrapolation outside)
    {
        int n = v.Length / 2;
        var wl = new double[n];
        var values = new double[n];
        for (int i = 0; i < n; i++)
        {
            wl[i] = v[2 * i];
            values[i] = v[2 * i + 1];
            if (!(wl[i] > 0) || (i > 0 && wl[i] <= wl[i - 1]))
                throw new InputException(p.Where, $"\"{p.Type} {p.Name}\": wavelength {Round(wl[i])} nm is not positive and ascending",
                    "list pairs of wavelength and value in ascending wavelength");
            if (values[i] < 0)
                throw new InputException(p.Where, $"\"{p.Type} {p.Name}\": value {Round(values[i])} at {Round(wl[i])} nm is negative",
                    "spectra are not negative");
        }
        var table = new TabulatedSpectrum(p.Name, wl, values, outside);
        var ybar = Observer.Cie1931.YBar;
        double ysum = 0;
        for (int l = 360; l <= 830; l++) ysum += ybar.Evaluate(l) * table.Evaluate(l);
        string policy = outside == Extrapolation.Zero ? "zero" : "clamp";
        return new(new JsonObject { ["values"] = PairsJson(wl, values), ["extrapolate"] = policy }, ysum);
    }

    /// <summary>A spectrum file (pbrt's .spd: wavelength–value pairs, # comments), read inline; pbrt holds its end values.</summary>
    SpectrumValue SpdFile(PbrtParameter p, string file)
    {
        var full = Path.IsPathRooted(file) ? file : Path.Combine(_dir, file);
        if (!File.Exists(full))
            throw new InputException(p.Where, $"unknown named spectrum or missing file {MessageText.Quote(file)}",
                InputException.DidYouMean(file, PbrtNamedSpectra.Names)
                    ?? "pbrt-v4's named spectra are listed in data/pbrt-v4/README.md; a file is relative to the scene")
            { Problem = InputProblem.MissingFile };
        var text = InputFile.ReadAllText(full);
        var numbers = new List<double>();
        int line = 0;
        foreach (var raw in text.Split('\n'))
        {
            line++;
            int hash = raw.IndexOf('#');
            var content = hash >= 0 ? raw[..hash] : raw;
            foreach (var cell in content.Split([' ', '\t', '\r', ','], StringSplitOptions.RemoveEmptyEntries))
            {
                if (!double.TryParse(cell, NumberStyles.Float, CultureInfo.InvariantCulture, out double v) || !double.IsFinite(v))
                    throw new InputException($"{Path.GetFileName(full)}:{line}", $"{MessageText.Quote(cell)} is not a number",
                        "a spectrum file lists wavelength (nm) and value pairs");
                numbers.Add(v);
            }
        }
        if (numbers.Count < 4 || numbers.Count % 2 != 0)
            throw new InputException(Path.GetFileName(full), $"{numbers.Count} numbers: not pairs of wavelength and value",
                "a spectrum file lists at least two wavelength (nm) and value pairs");
        return Pairs(p, [.. numbers], Extrapolation.Clamp);
    }

    SpectrumValue Rgb(PbrtParameter p, double[] rgb, SpectrumUse use, string label)
    {
        foreach (double c in rgb)
            if (c < 0) throw new InputException(p.Where, $"\"rgb {p.Name}\" has a negative component", "give r, g, b ≥ 0");
        var values = new JsonArray(Round(rgb[0]), Round(rgb[1]), Round(rgb[2]));
        string where = Place(p.Token);
        switch (use)
        {
            case SpectrumUse.Illuminant:
                _report.Add("uplifted", where, $"{label} \"rgb {p.Name}\"",
                    "an RGB emission: the sigmoid uplift times pbrt's D65 (stdillum-D65), as pbrt's RGBIlluminantSpectrum");
                return new(new JsonObject { ["rgb"] = values, ["illuminant"] = NamedSpectrum("stdillum-D65") },
                    PbrtNamedSpectra.CieYIntegral);
            case SpectrumUse.Reflectance:
                {
                    double max = rgb.Max();
                    if (max > 1)
                    {
                        _report.Add("approximated", where, $"{label} \"rgb {p.Name}\"",
                            "a reflectance above 1 is scaled to a maximum of 1");
                        values = new JsonArray(Round(rgb[0] / max), Round(rgb[1] / max), Round(rgb[2] / max));
                    }
                    else
                        _report.Add("uplifted", where, $"{label} \"rgb {p.Name}\"",
                            "an RGB reflectance through the sigmoid uplift (Jakob & Hanika 2019)");
                    return new(new JsonObject { ["rgb"] = values }, 0);
                }
            default:
                {
                    double max = rgb.Max();
                    if (!(max > 0)) return new(JsonValue.Create(0.0)!, 0);
                    _report.Add("approximated", where, $"{label} \"rgb {p.Name}\"",
                        "an unbounded RGB spectrum: the sigmoid uplift of rgb / max times max (pbrt scales by 2·max around ½)");
                    return new(new JsonObject
                    {
                        ["rgb"] = new JsonArray(Round(rgb[0] / max), Round(rgb[1] / max), Round(rgb[2] / max)),
                        ["scale"] = Round(max)
                    }, 0);
                }
        }
    }
}
