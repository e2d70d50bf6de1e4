using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

// Lights. pbrt-v4 divides every light's spectrum by SpectrumToPhotometric(S) = Σ ȳ(λ)·S(λ) (1 nm, 360–830 nm), so
// "scale" sets ∫ȳ·L (pbrt-v4 lights.cpp, "scale so that radiance is equivalent to 1 nit"); "power" then sets the
// emitted ȳ-weighted power and "illuminance" the ȳ-weighted irradiance. Our radiance is pbrt's numbers read as
// W·m⁻²·sr⁻¹·nm⁻¹ (docs/import.md "pbrt-v4").
public sealed partial class PbrtConverter
{
    void Light(PbrtLight light)
    {
        var e = light.Entity;
        var p = e.Parameters;
        var m = _world * light.WorldFromLight;
        string label = $"LightSource \"{e.Type}\"";
        double scale = p.Float("scale", 1);
        if (scale < 0) throw new InputException(e.Where, $"{label}: scale {scale}", "give a scale ≥ 0");
        switch (e.Type)
        {
            case "point":
                {
                    var s = Spectrum(e, "I", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
                    double k = scale / Photometric(s, e, label);
                    double power = p.Float("power", -1);
                    if (power > 0) k *= power / (4 * Math.PI);
                    var from = p.Numbers("from", 3, "point3") ?? [0, 0, 0];
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "point",
                        ["name"] = UniqueName("point"),
                        ["position"] = Array3(m.Point(from[0], from[1], from[2])),
                        ["spectrum"] = s.Node,
                        ["intensity"] = Round(k),
                    });
                    break;
                }
            case "spot":
                {
                    var s = Spectrum(e, "I", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
                    double k = scale / Photometric(s, e, label);
                    double cone = p.Float("coneangle", 30), delta = p.Float("conedeltaangle", 5);
                    if (!(cone > 0 && cone <= 180 && delta >= 0 && delta <= cone))
                        throw new InputException(e.Where, $"{label}: coneangle {cone}, conedeltaangle {delta}",
                            "give 0 < coneangle ≤ 180 and 0 ≤ conedeltaangle ≤ coneangle (degrees)");
                    double cosEnd = Math.Cos(cone * Math.PI / 180), cosStart = Math.Cos((cone - delta) * Math.PI / 180);
                    // A hard cone of the same ∫ of pbrt's smoothstep fall-off: 1 − cos θc = (1 − cosStart) + (cosStart − cosEnd)/2.
                    double cutoff = Math.Acos(0.5 * (cosStart + cosEnd)) * 180 / Math.PI;
                    double power = p.Float("power", -1);
                    if (power > 0) k *= power / (2 * Math.PI * ((1 - cosStart) + (cosStart - cosEnd) / 2));
                    var from = p.Numbers("from", 3, "point3") ?? [0, 0, 0];
                    var to = p.Numbers("to", 3, "point3") ?? [0, 0, 1];
                    var direction = PbrtTransform.Normalize(m.Vector(to[0] - from[0], to[1] - from[1], to[2] - from[2]));
                    if (direction.Length == 0)
                        throw new InputException(e.Where, $"{label}: from and to are the same point", "give a direction");
                    if (delta > 0)
                        Note("approximated", e, label, $"pbrt's smooth fall-off over the last {Round(delta)}° replaced by a hard cone of "
                            + $"{Round(cutoff)}° holding the same power");
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "spot",
                        ["name"] = UniqueName("spot"),
                        ["position"] = Array3(m.Point(from[0], from[1], from[2])),
                        ["direction"] = Array3(direction),
                        ["cutoff"] = Round(cutoff),
                        ["exponent"] = 0,
                        ["spectrum"] = s.Node,
                        ["intensity"] = Round(k),
                    });
                    break;
                }
            case "distant":
                {
                    var s = Spectrum(e, "L", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
                    double k = scale / Photometric(s, e, label);
                    double illuminance = p.Float("illuminance", -1);
                    if (illuminance > 0) k *= illuminance;
                    var from = p.Numbers("from", 3, "point3") ?? [0, 0, 0];
                    var to = p.Numbers("to", 3, "point3") ?? [0, 0, 1];
                    var direction = PbrtTransform.Normalize(m.Vector(to[0] - from[0], to[1] - from[1], to[2] - from[2]));
                    if (direction.Length == 0)
                        throw new InputException(e.Where, $"{label}: from and to are the same point", "give a direction");
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "directional",
                        ["name"] = UniqueName("distant"),
                        ["direction"] = Array3(direction),
                        ["spectrum"] = s.Node,
                        ["intensity"] = Round(k),
                    });
                    break;
                }
            case "infinite":
                Infinite(e, label, scale);
                break;
            case "goniometric":
            case "projection":
                foreach (var q in p.All) q.Used = true;
                Refuse(e.Where, label, $"a {e.Type} light (an image of intensities) has no counterpart");
                break;
            default:
                throw new InputException(e.Where, $"unknown light type \"{MessageText.Escape(e.Type)}\"",
                    InputException.DidYouMean(e.Type, ["point", "spot", "distant", "infinite", "goniometric", "projection"])
                        ?? "see pbrt.org/fileformat-v4");
        }
        ReportUnused(e, label);
    }

    void Infinite(PbrtEntity e, string label, double scale)
    {
        var p = e.Parameters;
        if (_background is not null)
            Note("approximated", e, label, "a second infinite light: added to the first (our sky is one uniform background)");
        double illuminance = p.Float("illuminance", -1);
        SpectrumValue s;
        if (p.String("filename") is { } file)
        {
            Refuse(e.Where, $"{label} \"filename\"", $"an environment image ('{Path.GetFileName(file)}') has no counterpart yet; "
                + "rendered as a uniform sky of pbrt's default illuminant at the given scale");
            s = DefaultIlluminant();
        }
        else s = Spectrum(e, "L", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
        if (p.Find("portal") is { } portal)
            _report.Add("ignored", Place(portal.Token), $"{label} \"portal\"", "portals only guide pbrt's sampling");
        double k = scale / Photometric(s, e, label);
        // pbrt: a uniform sky of luminance L lights an upward surface with π·L, so "illuminance" E sets L = E/π.
        if (illuminance > 0) k *= illuminance / Math.PI;
        var value = Scaled(s.Node, k);
        _background = _background is null ? value : Sum(_background, value, e);
    }

    JsonNode Sum(JsonNode a, JsonNode b, PbrtEntity e)
    {
        if (a is JsonValue x && b is JsonValue y && x.TryGetValue<double>(out var u) && y.TryGetValue<double>(out var v))
            return Round(u + v);
        Note("approximated", e, "LightSource \"infinite\"", "two infinite lights of different spectra: the last one kept");
        return b;
    }

    /// <summary>pbrt's SpectrumToPhotometric, refused when zero (a light pbrt would divide by zero).</summary>
    static double Photometric(SpectrumValue s, PbrtEntity e, string label) =>
        s.Photometric > 0 ? s.Photometric
            : throw new InputException(e.Where, $"{label}: the spectrum has no luminance (Σ ȳ·S = 0)",
                "pbrt divides a light's spectrum by its luminance; give a spectrum with visible light");

    /// <summary>A spectrum value times <paramref name="k"/>: a number multiplied, a name or object given a "scale".</summary>
    static JsonNode Scaled(JsonNode s, double k)
    {
        switch (s)
        {
            case JsonValue v when v.TryGetValue<double>(out var c): return Round(c * k);
            case JsonValue v when v.TryGetValue<string>(out var name): return new JsonObject { ["name"] = name, ["scale"] = Round(k) };
            case JsonObject o:
                {
                    var copy = (JsonObject)o.DeepClone();
                    copy["scale"] = Round(k * (copy["scale"]?.GetValue<double>() ?? 1));
                    return copy;
                }
            default: return new JsonObject { ["values"] = s.DeepClone(), ["scale"] = Round(k) };
        }
    }
}
