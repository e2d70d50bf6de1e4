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
                if (p.String("filename") is { } image) InfiniteImage(e, label, scale, image, m);
                else Infinite(e, label, scale);
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
        var s = Spectrum(e, "L", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
        if (p.Find("portal") is { } portal)
            _report.Add("ignored", Place(portal.Token), $"{label} \"portal\"", "portals only guide pbrt's sampling");
        double k = scale / Photometric(s, e, label);
        // pbrt: a uniform sky of luminance L lights an upward surface with π·L, so "illuminance" E sets L = E/π.
        if (illuminance > 0) k *= illuminance / Math.PI;
        var value = Scaled(s.Node, k);
        if (_sky is not null)
        {
            Note("approximated", e, label,
                "a uniform infinite light beside an image one: left out (our sky is one image or one background)");
            return;
        }
        _background = _background is null ? value : Sum(_background, value, e);
    }

    /// <summary>
    /// An image infinite light: our "sky": { "type": "envmap", "mapping": "equal-area" } on the same file — pbrt-v4's
    /// equal-area octahedral square (Scenes/EqualAreaSquare.cs), nearest pixel, in the light's frame (+z at the square's
    /// centre) turned by its transformation. pbrt's radiance of pixel rgb is scale·RGBIlluminantSpectrum(rgb)/Σȳ·D65 (the
    /// colour space's illuminant, lights.cpp), ours s·sigmoid·D65/Ȳ_D65 × our "scale" (Mitsuba's srgb_d65), so our scale is
    /// pbrt's / CIE_Y_integral (the 1 nm sum and the integral of ȳ·D65 differ by &lt; 1e-4). "illuminance" E: pbrt scales by
    /// E/k_e, k_e = 2π/N² Σ lum(rgb)·cos θ over the pixels whose centre is above the horizon (z > 0); kept as pbrt has it.
    /// </summary>
    void InfiniteImage(PbrtEntity e, string label, double scale, string file, PbrtTransform m)
    {
        var p = e.Parameters;
        if (p.Find("L") is not null)
            throw new InputException(e.Where, $"{label}: both \"L\" and \"filename\"", "give one (pbrt refuses both, too)");
        if (p.Find("portal") is { } portal)
            _report.Add("ignored", Place(portal.Token), $"{label} \"portal\"", "portals only guide pbrt's sampling");
        string ext = Path.GetExtension(file).ToLowerInvariant();
        if (ext is not (".exr" or ".pfm" or ".hdr" or ".pic"))
        {
            Refuse(e.Where, $"{label} \"filename\"", $"'{Path.GetFileName(file)}': an environment image must be OpenEXR, PFM or "
                + "Radiance .hdr here (convert it, e.g. with imgtool convert)");
            return;
        }
        var full = Path.Combine(_dir, file);
        if (!File.Exists(full))
            throw new InputException(e.Where, $"{label}: environment image {MessageText.Quote(file)} not found",
                "the path is relative to the scene file")
            { Problem = InputProblem.MissingFile };
        var image = Imaging.RgbImage.Read(full);
        if (image.Width != image.Height)
            throw new InputException(e.Where, $"{label}: '{Path.GetFileName(file)}' is {image.Width} × {image.Height} pixels",
                "pbrt-v4's infinite light takes an equal-area square (N × N); convert a lat-long map with pbrt's imgtool makeequiarea");
        double k = scale / PbrtNamedSpectra.CieYIntegral;
        double illuminance = p.Float("illuminance", -1);
        if (illuminance > 0)
        {
            double ke = 0;
            int n = image.Width;
            for (int y = 0; y < n; y++)
                for (int x = 0; x < n; x++)
                {
                    var w = EqualAreaSquare.ToSphere((x + 0.5) / n, (y + 0.5) / n);
                    if (w.Z <= 0) continue;
                    int o = 3 * (y * n + x);
                    ke += (0.2126 * image.Rgb[o] + 0.7152 * image.Rgb[o + 1] + 0.0722 * image.Rgb[o + 2]) * w.Z;
                }
            ke *= 2 * Math.PI / ((double)n * n);
            if (ke > 0) k *= illuminance / ke;
            Note("converted", e, $"{label} \"illuminance\"", $"scaled by E/k_e = {Round(ke > 0 ? illuminance / ke : 1)} as pbrt-v4 "
                + "does (k_e = 2π/N² Σ lum·cos θ over the upper hemisphere's pixels: an upward surface then receives 2E)");
        }
        if (_sky is not null || _background is not null)
            Note("approximated", e, label, "a second infinite light: only the image is kept (our sky is one image or one background)");
        _background = null;
        _sky = new JsonObject
        {
            ["type"] = "envmap",
            ["file"] = file.Replace('\\', '/'),
            ["mapping"] = "equal-area",
            ["scale"] = Round(k),
            ["transform"] = Matrix(m),
        };
        Note("converted", e, $"{label} \"filename\"", $"the equal-area image {Path.GetFileName(file)}: our envmap sky with "
            + "\"mapping\": \"equal-area\" (pbrt's layout and nearest-pixel lookup, D65 illuminant uplift), scale/CIE_Y_integral");
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
