using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

// Spectra and textures: Mitsuba's spectrum properties written as our spectrum values (docs/scene-format.md "Spectrum values").
public sealed partial class MitsubaConverter
{
    /// <summary>Mitsuba's D65 is the CIE table times this (MI_CIE_D65_NORMALIZATION): luminance factor 1.</summary>
    public const double D65Normalization = 1 / 98.99741751876255;

    /// <summary>The second radiation constant c₂ (m·K), as our blackbody:T uses it, and the first for radiance, c₁L = 2hc²
    /// (W·m²·sr⁻¹).</summary>
    const double C2 = 1.438776877e-2, C1L = 1.191042972e-16;

    /// <summary>
    /// The spectrum property <paramref name="name"/> of <paramref name="e"/> as our spectrum value, or <paramref name="fallback"/>
    /// when absent. <paramref name="emission"/>: an rgb is an illuminant uplift (times D65 normalised, as Mitsuba's srgb_d65),
    /// else a reflectance (the sigmoid uplift).
    /// </summary>
    JsonNode? Spectrum(MitsubaElement e, string name, JsonNode? fallback, bool emission)
    {
        if (Prop(e, name) is not { } p) return fallback;
        return SpectrumValue(p, emission, $"{e.Label} {name}");
    }

    JsonNode SpectrumValue(MitsubaElement p, bool emission, string what)
    {
        p = Resolve(p);
        _used.Add(p);
        switch (p.Tag)
        {
            case "float" or "integer":
                return NonNegative(Number(Value(p), p.Where, what), p);
            case "rgb":
                {
                    var v = MitsubaXml.Numbers(Value(p), p.Where, what);
                    if (v.Length == 1) v = [v[0], v[0], v[0]];
                    if (v.Length != 3)
                        throw new InputException(p.Where, $"{what}: rgb has {v.Length} values, expected 3", "e.g. value=\"0.8, 0.2, 0.1\"");
                    foreach (var x in v)
                        if (x < 0)
                            throw new InputException(p.Where, $"{what}: negative rgb value {x}", "rgb values are linear and non-negative");
                    if (!emission && v.Any(x => x > 1))
                    {
                        _report.Add("approximated", p.Place, what,
                            "an rgb reflectance above 1 clamped to 1 (a reflectance cannot exceed 1)");
                        v = [.. v.Select(x => Math.Min(1, x))];
                    }
                    var rgb = new JsonArray(v.Select(x => (JsonNode)JsonValue.Create(Round(x))).ToArray());
                    if (v[0] == v[1] && v[1] == v[2] && !emission) return JsonValue.Create(Round(v[0]))!;   // grey: a constant
                    _report.Add("uplifted", p.Place, what, emission
                        ? "linear sRGB radiance uplifted: sigmoid reflectance × D65 normalised to luminance factor 1 (Mitsuba's srgb_d65)"
                        : "linear sRGB reflectance uplifted by the sigmoid polynomial (Jakob & Hanika 2019)");
                    return emission ? new JsonObject { ["rgb"] = rgb, ["illuminant"] = "D65" } : new JsonObject { ["rgb"] = rgb };
                }
            case "spectrum":
                return SpectrumElement(p, emission, what);
            case "texture":
                return Texture(p, emission, what);
            default:
                throw new InputException(p.Where, $"{what}: a <{p.Tag}> where a spectrum is expected",
                    "give <spectrum>, <rgb>, <float> or <texture>");
        }
    }

    JsonNode SpectrumElement(MitsubaElement p, bool emission, string what)
    {
        if (p.Attr("filename") is { } file) return SpdFile(p, file, what);
        var type = p.Attr("type");
        if (type is null)
        {
            var text = Value(p);
            if (!text.Contains(':')) return NonNegative(Number(text.Trim(), p.Where, what), p);
            var pairs = new List<(double, double)>();
            foreach (var item in text.Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries))
            {
                var lv = item.Split(':');
                if (lv.Length != 2)
                    throw new InputException(p.Where, $"{what}: {MessageText.Quote(item, 30)} is not wavelength:value",
                        "e.g. value=\"400:0.1, 500:0.4, 600:0.8\"");
                pairs.Add((Number(lv[0].Trim(), p.Where, what), Number(lv[1].Trim(), p.Where, what)));
            }
            return Pairs(pairs, p, what);
        }
        switch (type)
        {
            case "uniform":
                return NonNegative(Float(p, "value", 1), p);
            case "d65":
                {
                    double scale = Float(p, "scale", 1);
                    ReportUnused(p);
                    return new JsonObject { ["name"] = "D65", ["scale"] = Round(scale * D65Normalization) };
                }
            case "blackbody":
                {
                    double t = Float(p, "temperature", double.NaN);
                    if (!(t >= 100 && t <= 1e6))
                        throw new InputException(p.Where, $"{what}: blackbody temperature {t} K is outside 100–10⁶ K",
                            "give <float name=\"temperature\" value=\"5000\"/>");
                    ReportUnused(p);
                    // Mitsuba's blackbody is Planck's spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹; ours is relative, 100 at 560 nm.
                    double l = 560e-9, b560 = C1L / Math.Pow(l, 5) / (Math.Exp(C2 / (l * t)) - 1) * 1e-9;
                    _report.Add("converted", p.Place, what,
                        string.Create(CultureInfo.InvariantCulture,
                            $"blackbody {t} K: Planck radiance, our blackbody:{t} × {b560 / 100:G6}"));
                    return new JsonObject
                    {
                        ["name"] = string.Create(CultureInfo.InvariantCulture, $"blackbody:{t}"),
                        ["scale"] = Round(b560 / 100)
                    };
                }
            case "regular":
                {
                    double lo = Float(p, "wavelength_min", double.NaN), hi = Float(p, "wavelength_max", double.NaN);
                    var values = MitsubaXml.Numbers(String(p, "values") ?? "", p.Where, what);
                    if (!(hi > lo) || values.Length < 2)
                        throw new InputException(p.Where,
                            $"{what}: a regular spectrum needs wavelength_min < wavelength_max and two or more values",
                            "e.g. <float name=\"wavelength_min\" value=\"400\"/> … <string name=\"values\" value=\"0.1, 0.5, 0.9\"/>");
                    ReportUnused(p);
                    return Pairs([.. values.Select((v, i) => (lo + (hi - lo) * i / (values.Length - 1), v))], p, what);
                }
            case "irregular":
                {
                    var wl = MitsubaXml.Numbers(String(p, "wavelengths") ?? "", p.Where, what);
                    var values = MitsubaXml.Numbers(String(p, "values") ?? "", p.Where, what);
                    if (wl.Length != values.Length)
                        throw new InputException(p.Where, $"{what}: {wl.Length} wavelengths for {values.Length} values",
                            "give one value per wavelength");
                    ReportUnused(p);
                    return Pairs([.. wl.Zip(values)], p, what);
                }
            case "srgb" or "srgb_d65":
                {
                    var c = Prop(p, "color")
                        ?? throw new InputException(p.Where, $"{what}: an srgb spectrum without color",
                            "give <rgb name=\"color\" value=\"…\"/>");
                    ReportUnused(p);
                    return SpectrumValue(c, emission || type == "srgb_d65", what);
                }
            default:
                throw new InputException(p.Where, $"{what}: spectrum type {MessageText.Quote(type)} is not one we convert",
                    "use wavelength:value lists, regular, irregular, blackbody, d65, uniform, srgb or a .spd file");
        }
    }

    /// <summary>A .spd file: one "wavelength value" pair per line, '#' comments (Mitsuba's spectrum_from_file).</summary>
    JsonNode SpdFile(MitsubaElement p, string file, string what)
    {
        var full = Path.Combine(Path.GetDirectoryName(Path.GetFullPath(p.File))!, file);
        if (!File.Exists(full))
            throw new InputException(p.Where, $"{what}: spectrum file {MessageText.Quote(file)} not found",
                "the path is relative to the scene file")
            { Problem = InputProblem.MissingFile };
        var pairs = new List<(double, double)>();
        int line = 0;
        foreach (var raw in File.ReadAllLines(full))
        {
            line++;
            var text = raw.Trim();
            if (text.Length == 0 || text[0] == '#') continue;
            var n = MitsubaXml.Numbers(text, $"{file}:{line}", "a spectrum line");
            if (n.Length != 2)
                throw new InputException($"{file}:{line}", $"expected 'wavelength value', found {n.Length} numbers", "one pair per line");
            pairs.Add((n[0], n[1]));
        }
        _report.Add("converted", p.Place, what, $"the spectrum file {file} written inline ({pairs.Count} pairs)");
        return Pairs(pairs, p, what);
    }

    /// <summary>
    /// Tabulated pairs as our { "values": [[λ, v], …], "extrapolate": "zero" }: zero outside the table, as Mitsuba's regular and
    /// irregular spectra are.
    /// </summary>
    static JsonObject Pairs(List<(double Wavelength, double Value)> pairs, MitsubaElement p, string what)
    {
        if (pairs.Count < 2)
            throw new InputException(p.Where, $"{what}: a tabulated spectrum needs two or more pairs", "e.g. value=\"400:0.1, 700:0.9\"");
        var a = new JsonArray();
        for (int i = 0; i < pairs.Count; i++)
        {
            var (l, v) = pairs[i];
            if (i > 0 && l <= pairs[i - 1].Wavelength)
                throw new InputException(p.Where, $"{what}: wavelength {l} does not follow {pairs[i - 1].Wavelength}",
                    "list the wavelengths in ascending order");
            if (l <= 0) throw new InputException(p.Where, $"{what}: wavelength {l} nm is not positive", "wavelengths are in nm");
            if (v < 0)
                throw new InputException(p.Where, $"{what}: negative value {v} at {l} nm", "spectra here are reflectances or radiances");
            a.Add((JsonNode)new JsonArray(JsonValue.Create(Round(l)), JsonValue.Create(Round(v))));
        }
        return new JsonObject { ["values"] = a, ["extrapolate"] = "zero" };
    }

    static JsonNode NonNegative(double v, MitsubaElement p)
    {
        if (v < 0) throw new InputException(p.Where, $"negative value {v}", "spectra here are reflectances or radiances, not negative");
        return JsonValue.Create(Round(v))!;
    }

    /// <summary>
    /// A texture: a PNG bitmap becomes our sRGB PNG texture (uplifted per texel); a checkerboard, which our engine does not
    /// have, its two colours' mean (approximated).
    /// </summary>
    JsonNode Texture(MitsubaElement t, bool emission, string what)
    {
        _used.Add(t);
        switch (t.Attr("type"))
        {
            case "bitmap":
                {
                    var file = String(t, "filename")
                        ?? throw new InputException(t.Where, "a bitmap texture without filename",
                            "give <string name=\"filename\" value=\"…\"/>");
                    var ext = Path.GetExtension(file).ToLowerInvariant();
                    if (emission || ext != ".png")
                    {
                        Refuse(t, emission ? "an emission texture from an RGB image: our emission textures are spectral images"
                            : $"a {ext} bitmap: our RGB textures are 8- or 16-bit sRGB PNG (convert it, e.g. oiiotool in{ext} -o out.png)");
                        return 0.5;
                    }
                    if (!File.Exists(Path.Combine(_dir, file)))
                        throw new InputException(t.Where, $"texture {MessageText.Quote(file)} not found",
                            "the path is relative to the scene file")
                        { Problem = InputProblem.MissingFile };
                    if (Boolean(t, "raw", false))
                        Note("approximated", t, "raw=true (linear values): read as sRGB-encoded as our PNG textures are");
                    var o = new JsonObject { ["texture"] = file };
                    var wrap = String(t, "wrap_mode") ?? "repeat";
                    if (wrap != "repeat") o["uv_transform"] = new JsonObject { ["wrap"] = wrap == "mirror" ? "mirror" : "clamp" };
                    Prop(t, "filter_type");
                    if (Prop(t, "to_uv") is { } uv) Note("ignored", uv, "the texture's to_uv transform (not converted)");
                    _report.Add("uplifted", t.Place, what, $"the sRGB texture {file}: each texel by the sigmoid uplift");
                    ReportUnused(t);
                    return o;
                }
            case "checkerboard":
                {
                    var c0 = Spectrum(t, "color0", 0.4, emission);
                    var c1 = Spectrum(t, "color1", 0.2, emission);
                    Prop(t, "to_uv");
                    ReportUnused(t);
                    Note("approximated", t, "a checkerboard: our engine has no procedural textures; the mean of its two colours");
                    if (c0 is JsonValue a && c1 is JsonValue b && a.TryGetValue<double>(out var x) && b.TryGetValue<double>(out var y))
                        return JsonValue.Create(Round(0.5 * (x + y)))!;
                    return c0 ?? 0.3;
                }
            default:
                Refuse(t, $"texture type '{t.Attr("type")}' has no counterpart");
                return 0.5;
        }
    }
}
