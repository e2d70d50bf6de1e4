using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

// Materials and textures: diffuse → lambertian-like eq2, conductor → conductor, dielectric → Fresnel glass, coateddiffuse
// → plastic; diffusetransmission, mix and the rest approximated (docs/import.md "pbrt-v4").
public sealed partial class PbrtConverter
{
    readonly Dictionary<string, string?> _materialNames = new(StringComparer.Ordinal);
    readonly Dictionary<string, JsonNode> _textures = new(StringComparer.Ordinal);
    readonly HashSet<string> _resolvingMaterials = new(StringComparer.Ordinal);

    /// <summary>Our material name for a shape's material, or null for pbrt's "interface" (no surface).</summary>
    string? MaterialName(PbrtMaterialRef r)
    {
        string key = r.Named is not null ? "named:" + r.Named : "anonymous:" + r.Anonymous;
        if (_materialNames.TryGetValue(key, out var known)) return known;
        PbrtEntity? e;
        string wanted;
        if (r.Named is not null)
        {
            if (!_doc.NamedMaterials.TryGetValue(r.Named, out e))
                throw new InputException(r.Token!.Value.Where, $"NamedMaterial \"{MessageText.Escape(r.Named)}\" is not defined",
                    InputException.DidYouMean(r.Named, _doc.NamedMaterials.Keys)
                        ?? "define it with MakeNamedMaterial before the shapes that use it");
            wanted = r.Named;
        }
        else
        {
            e = r.Anonymous >= 0 ? _doc.Materials[r.Anonymous] : null;
            wanted = e is null ? "default" : $"{e.Type}-{r.Anonymous + 1}";
        }
        JsonObject? m = e is null ? new JsonObject { ["diffuse"] = 0.5 } : Material(e, r.Named);
        string? name = m is null ? null : UniqueName(wanted);
        if (m is not null) _materials[name!] = m;
        _materialNames[key] = name;
        return name;
    }

    /// <summary>A named material's entity by name (for "mix").</summary>
    PbrtEntity? Named(string name, PbrtEntity from)
    {
        if (_doc.NamedMaterials.TryGetValue(name, out var e)) return e;
        throw new InputException(from.Where, $"the material \"{MessageText.Escape(name)}\" is not defined",
            InputException.DidYouMean(name, _doc.NamedMaterials.Keys) ?? "define it with MakeNamedMaterial");
    }

    JsonObject? Material(PbrtEntity e, string? named)
    {
        string label = named is null ? $"Material \"{e.Type}\"" : $"MakeNamedMaterial \"{named}\"";
        var p = e.Parameters;
        foreach (var ignored in new[] { "normalmap", "displacement" })
            if (p.Find(ignored) is { } q)
                _report.Add("ignored", Place(q.Token), $"{label} \"{q.Name}\"", $"{q.Name} is not rendered: the surface is smooth");
        JsonObject? m;
        switch (e.Type)
        {
            case "diffuse":
                m = new JsonObject { ["diffuse"] = Reflectance(e, "reflectance", 0.5, label) };
                break;
            case "conductor":
                m = Conductor(e, label);
                break;
            case "dielectric":
            case "thindielectric":
                m = Dielectric(e, label);
                break;
            case "coateddiffuse":
                {
                    var diffuse = Reflectance(e, "reflectance", 0.5, label);
                    double alpha = Alpha(e, label);
                    double ior = ConstantIor(e, label);
                    foreach (var q in new[] { "thickness", "albedo", "g", "maxdepth", "nsamples" }) p.Find(q);
                    Note("approximated", e, label,
                        "our coated plastic (a Fresnel coat over a Lambertian base, internal reflections summed) with "
                        + "the same base, coat index and roughness; pbrt's stochastic layer (thickness, albedo, g) is not modelled");
                    if (diffuse is JsonObject { } tex && tex["texture"] is not null)
                    {
                        Note("approximated", e, label,
                            "a textured base: our plastic takes no texture, so a diffuse material with the texture");
                        m = new JsonObject { ["diffuse"] = diffuse };
                        break;
                    }
                    m = new JsonObject { ["type"] = "plastic", ["diffuse"] = diffuse, ["ior"] = Round(Math.Clamp(ior, 1.0001, 4)) };
                    if (alpha > 0) m["roughness"] = Round(alpha);
                    break;
                }
            case "coatedconductor":
                {
                    Note("approximated", e, label,
                        "the conductor base only (conductor.eta, conductor.k, conductor.roughness): the dielectric "
                        + "coat is not modelled");
                    m = Conductor(e, label, "conductor.");
                    foreach (var q in new[] { "interface.roughness", "interface.eta", "thickness", "albedo", "g", "maxdepth", "nsamples" })
                        p.Find(q);
                    break;
                }
            case "diffusetransmission":
                {
                    var diffuse = Reflectance(e, "reflectance", 0.25, label);
                    p.Find("transmittance");
                    Note("approximated", e, label, "its diffuse reflection only: light transmitted through the surface is dropped");
                    m = new JsonObject { ["diffuse"] = diffuse };
                    break;
                }
            case "mix":
                {
                    var names = p.Find("materials");
                    if (names is null || names.Type != "string" || names.Strings.Length != 2)
                        throw new InputException(e.Where, $"{label} needs \"string materials\" [ \"a\" \"b\" ]",
                            "name the two materials it mixes");
                    double amount = p.Find("amount") is { Type: "float", Numbers.Length: 1 } a ? a.Numbers[0] : 0.5;
                    string chosen = names.Strings[amount > 0.5 ? 1 : 0];
                    Note("approximated", e, label,
                        $"the material chosen more often (\"{chosen}\", amount {Round(amount)}): our materials do "
                        + "not mix");
                    if (!_resolvingMaterials.Add(chosen))
                        throw new InputException(e.Where, $"{label} mixes itself (\"{MessageText.Escape(chosen)}\")",
                            "mix two other materials");
                    try { m = Material(Named(chosen, e)!, chosen); }
                    finally { _resolvingMaterials.Remove(chosen); }
                    break;
                }
            case "interface":
                Note("ignored", e, label, "a medium boundary without a surface: its shapes are left out");
                m = null;
                break;
            case "measured":
            case "hair":
            case "subsurface":
                Refuse(e.Where, label, $"pbrt's {e.Type} material has no counterpart; rendered as a 0.5 diffuse material");
                m = new JsonObject { ["diffuse"] = 0.5 };
                foreach (var q in p.All) q.Used = true;
                break;
            default:
                throw new InputException(e.Where, $"unknown material type \"{MessageText.Escape(e.Type)}\"",
                    InputException.DidYouMean(e.Type, MaterialTypes) ?? "see pbrt.org/fileformat-v4");
        }
        ReportUnused(e, label);
        return m;
    }

    static readonly string[] MaterialTypes =
        ["diffuse", "conductor", "dielectric", "thindielectric", "coateddiffuse", "coatedconductor", "diffusetransmission", "mix",
            "interface", "measured", "hair", "subsurface"];

    JsonObject Conductor(PbrtEntity e, string label, string prefix = "")
    {
        var p = e.Parameters;
        double alpha = Alpha(e, label, prefix);
        JsonObject m;
        if (p.Has(prefix + "reflectance"))
        {
            var r = Reflectance(e, prefix + "reflectance", 1, label);
            p.Find(prefix + "eta");
            p.Find(prefix + "k");
            Note("approximated", e, label, "a conductor given by its reflectance: a mirror of that reflectance at every angle (no Fresnel "
                + "fall-off)" + (alpha > 0 ? "; its roughness is not kept" : ""));
            return new JsonObject { ["diffuse"] = 0, ["mirror"] = r };
        }
        var eta = Spectrum(e, prefix + "eta", SpectrumUse.Unbounded, label)?.Node ?? NamedSpectrum("metal-Cu-eta");
        var k = Spectrum(e, prefix + "k", SpectrumUse.Unbounded, label)?.Node ?? NamedSpectrum("metal-Cu-k");
        m = new JsonObject { ["type"] = "conductor", ["conductor"] = new JsonObject { ["n"] = eta, ["k"] = k } };
        if (alpha > 0) m["roughness"] = Round(alpha);
        return m;
    }

    JsonObject Dielectric(PbrtEntity e, string label)
    {
        var p = e.Parameters;
        double alpha = Alpha(e, label);
        if (alpha > 0)
            Note("approximated", e, label, $"a rough dielectric (α = {Round(alpha)}) rendered smooth: our Fresnel glass has no roughness");
        if (e.Type == "thindielectric")
            Note("approximated", e, label, "a thin dielectric rendered as a solid Fresnel glass (refraction offsets the light)");
        JsonNode ior;
        var eta = p.Find("eta");
        if (eta is null) ior = 1.5;
        else if (eta.Type is "float" && eta.Numbers.Length == 1)
        {
            if (!(eta.Numbers[0] > 0)) throw new InputException(eta.Where, $"eta {eta.Numbers[0]}", "give an index of refraction above 0");
            ior = Round(eta.Numbers[0]);
        }
        else
        {
            eta.Used = false;
            var s = Spectrum(e, "eta", SpectrumUse.Unbounded, label)!.Value.Node;
            // A spectrally varying index: our glass takes it at each band centre and refracts each band on its own ray.
            ior = new JsonObject { ["spectrum"] = s };
            _report.Add("converted", Place(eta.Token), $"{label} \"eta\"",
                "a dispersive index: taken at each band centre, each band refracted on its own ray");
        }
        return new JsonObject { ["diffuse"] = 0, ["mirror"] = 1, ["transmit"] = 1, ["fresnel"] = true, ["ior"] = ior };
    }

    /// <summary>A coat's index as one number (our plastic's coat is not dispersive): a spectrum is taken at 550 nm.</summary>
    double ConstantIor(PbrtEntity e, string label)
    {
        var eta = e.Parameters.Find("eta");
        if (eta is null) return 1.5;
        if (eta.Type == "float" && eta.Numbers.Length == 1) return eta.Numbers[0];
        if (eta.Type == "spectrum" && eta.Strings.Length == 1 && PbrtNamedSpectra.TryGet(eta.Strings[0], out var t, out _))
        {
            _report.Add("approximated", Place(eta.Token), $"{label} \"eta\"",
                "the coat's index taken at 550 nm (our coat is not dispersive)");
            return t.Evaluate(550);
        }
        _report.Add("approximated", Place(eta.Token), $"{label} \"eta\"", "the coat's index is not a number: 1.5 used");
        return 1.5;
    }

    /// <summary>GGX α from pbrt's roughness (or the mean of u and v roughness): √r when remaproughness (the default).</summary>
    double Alpha(PbrtEntity e, string label, string prefix = "")
    {
        var p = e.Parameters;
        double r = 0;
        var rough = p.Find(prefix + "roughness");
        var u = p.Find(prefix + "uroughness");
        var v = p.Find(prefix + "vroughness");
        double Value(PbrtParameter? q)
        {
            if (q is null) return 0;
            if (q.Type == "float" && q.Numbers.Length == 1 && q.Numbers[0] >= 0) return q.Numbers[0];
            if (q.Type == "texture")
            {
                _report.Add("approximated", Place(q.Token), $"{label} \"{q.Name}\"", "a roughness texture: 0 (smooth) used");
                return 0;
            }
            throw new InputException(q.Where, $"\"{q.Type} {q.Name}\" should be one number ≥ 0", $"e.g. \"float {q.Name}\" 0.1");
        }
        if (u is not null || v is not null)
        {
            double ru = Value(u ?? rough), rv = Value(v ?? rough);
            r = 0.5 * (ru + rv);
            if (ru != rv)
                _report.Add("approximated", Place((u ?? v)!.Token), $"{label} anisotropic roughness",
                    "our microfacet model is isotropic: the mean of uroughness and vroughness");
        }
        else r = Value(rough);
        bool remap = p.Bool("remaproughness", true);
        double alpha = remap ? Math.Sqrt(r) : r;
        if (alpha > 1)
        {
            _report.Add("approximated", Place(e.Token), $"{label} roughness", $"α = {Round(alpha)} clamped to 1");
            alpha = 1;
        }
        return alpha;
    }

    /// <summary>A reflectance parameter (spectrum, rgb, float or texture) as our spectrum or texture value.</summary>
    JsonNode Reflectance(PbrtEntity e, string name, double fallback, string label)
    {
        var p = e.Parameters.Find(name);
        if (p is null) return fallback;
        if (p.Type == "texture")
        {
            if (p.Strings.Length != 1)
                throw new InputException(p.Where, $"\"texture {name}\" should name one texture", "e.g. \"texture reflectance\" \"wood\"");
            return Texture(p.Strings[0], p, label);
        }
        p.Used = false;
        return Spectrum(e, name, SpectrumUse.Reflectance, label)!.Value.Node;
    }

    /// <summary>A named texture as our texture or spectrum value: a PNG image map, a constant, a scaled texture; others
    /// approximated.</summary>
    JsonNode Texture(string name, PbrtParameter from, string label)
    {
        if (_textures.TryGetValue(name, out var done)) return done.DeepClone();
        if (!_doc.Textures.TryGetValue(name, out var t))
            throw new InputException(from.Where, $"unknown texture \"{MessageText.Escape(name)}\"",
                InputException.DidYouMean(name, _doc.Textures.Keys) ?? "define it with Texture before");
        if (!_resolvingMaterials.Add("texture:" + name))
            throw new InputException(t.Entity.Where, $"the texture \"{MessageText.Escape(name)}\" refers to itself", "break the cycle");
        JsonNode value;
        try { value = TextureValue(t); }
        finally { _resolvingMaterials.Remove("texture:" + name); }
        ReportUnused(t.Entity, $"Texture \"{name}\"");
        _textures[name] = value;
        return value.DeepClone();
    }

    JsonNode TextureValue(PbrtTexture t)
    {
        var e = t.Entity;
        var p = e.Parameters;
        string label = $"Texture \"{t.Name}\" \"{e.Type}\"";
        switch (e.Type)
        {
            case "imagemap":
                {
                    var file =
                        p.String("filename") ?? throw new InputException(e.Where, $"{label} has no \"string filename\"", "name the image");
                    if (!file.EndsWith(".png", StringComparison.OrdinalIgnoreCase))
                    {
                        Note("approximated", e, label, $"only PNG image maps are read: '{Path.GetFileName(file)}' replaced by a 0.5 grey");
                        return 0.5;
                    }
                    var o = new JsonObject { ["texture"] = file };
                    double scale = p.Float("scale", 1);
                    if (scale != 1) o["scale"] = Round(scale);
                    double su = p.Float("uscale", 1), sv = p.Float("vscale", 1), du = p.Float("udelta", 0), dv = p.Float("vdelta", 0);
                    if (su != 1 || sv != 1 || du != 0 || dv != 0)
                        o["uv_transform"] = new JsonObject
                        {
                            ["scale"] = new JsonArray(Round(su), Round(sv)),
                            ["offset"] = new JsonArray(Round(du), Round(dv))
                        };
                    var encoding = p.String("encoding") ?? "sRGB";
                    if (encoding != "sRGB")
                        Note("approximated", e, label, $"encoding '{encoding}': our PNG textures are decoded as sRGB");
                    if (p.Bool("invert", false)) Note("ignored", e, label, "invert is not applied");
                    foreach (var q in new[] { "filter", "maxanisotropy", "wrap", "mapping" }) p.Find(q);
                    Note("uplifted", e, label, "an sRGB PNG texture: each texel uplifted to a reflectance (sigmoid, Jakob & Hanika 2019)");
                    return o;
                }
            case "constant":
                return Reflectance(e, "value", 1, label);
            case "scale":
                {
                    var inner = Reflectance(e, "tex", 1, label);
                    var sp = p.Find("scale");
                    double s = 1;
                    if (sp is not null && sp.Type == "float" && sp.Numbers.Length == 1) s = sp.Numbers[0];
                    else if (sp is not null) Note("approximated", e, label, "a scale that is not a number is left out");
                    if (s == 1) return inner;
                    if (inner is JsonValue v && v.TryGetValue<double>(out double c)) return Round(Math.Clamp(c * s, 0, 1));
                    if (inner is JsonObject io && io["texture"] is not null)
                    {
                        io["scale"] = Round(s * (io["scale"]?.GetValue<double>() ?? 1));
                        return io;
                    }
                    if (inner is JsonObject so && so["scale"] is null) { so["scale"] = Round(s); return so; }
                    return new JsonObject { ["name"] = inner, ["scale"] = Round(s) };
                }
            case "checkerboard":
            case "mix":
            case "directionmix":
                {
                    bool checker = e.Type == "checkerboard";
                    var a = Reflectance(e, "tex1", checker ? 1 : 0, label);
                    var b = Reflectance(e, "tex2", checker ? 0 : 1, label);
                    foreach (var q in new[] { "uscale", "vscale", "udelta", "vdelta", "dimension", "amount", "dir", "mapping" }) p.Find(q);
                    Note("approximated", e, label,
                        $"a {e.Type} texture: our engine has no procedural textures; the mean of its two values");
                    if (a is JsonValue x && b is JsonValue y && x.TryGetValue<double>(out var xa) && y.TryGetValue<double>(out var yb))
                        return Round(0.5 * (xa + yb));
                    return a;
                }
            default:
                foreach (var q in p.All) q.Used = true;
                Note("approximated", e, label, $"the {e.Type} texture has no counterpart: a 0.5 grey");
                return 0.5;
        }
    }
}
