using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

// BSDFs: Mitsuba's models written as our material models (lambertian, conductor, plastic, eq. 2 Fresnel glass).
public sealed partial class MitsubaConverter
{
    /// <summary>Mitsuba's named indices of refraction (its ior.h table, at the sodium D line).</summary>
    static readonly Dictionary<string, double> NamedIor = new(StringComparer.Ordinal)
    {
        ["vacuum"] = 1.0,
        ["helium"] = 1.000036,
        ["hydrogen"] = 1.000132,
        ["air"] = 1.000277,
        ["carbon dioxide"] = 1.00045,
        ["water"] = 1.3330,
        ["acetone"] = 1.36,
        ["ethanol"] = 1.361,
        ["carbon tetrachloride"] = 1.461,
        ["glycerol"] = 1.4729,
        ["benzene"] = 1.501,
        ["silicone oil"] = 1.52045,
        ["bromine"] = 1.661,
        ["water ice"] = 1.31,
        ["fused quartz"] = 1.458,
        ["pyrex"] = 1.470,
        ["acrylic glass"] = 1.49,
        ["polypropylene"] = 1.49,
        ["bk7"] = 1.5046,
        ["sodium chloride"] = 1.544,
        ["amber"] = 1.55,
        ["pet"] = 1.5750,
        ["diamond"] = 2.419,
    };

    /// <summary>Mitsuba's conductor names that we have as built-in metals (data/: Johnson &amp; Christy, Rakić).</summary>
    static readonly Dictionary<string, string> NamedMetals = new(StringComparer.Ordinal)
    {
        ["Au"] = "Au",
        ["Ag"] = "Ag",
        ["Cu"] = "Cu",
        ["Al"] = "Al",
    };

    /// <summary>The name of our material for a BSDF element (converted once per element, named by its id).</summary>
    string Material(MitsubaElement bsdf)
    {
        bsdf = Resolve(bsdf);
        if (_materialNames.TryGetValue(bsdf, out var known)) return known;
        var json = Bsdf(bsdf, false);
        var name = UniqueName(bsdf.Attr("id") ?? $"{bsdf.Attr("type") ?? "bsdf"}");
        _materials[name] = json;
        _materialNames[bsdf] = name;
        return name;
    }

    /// <summary>Mitsuba's default BSDF (a shape without one): diffuse, reflectance 0.5.</summary>
    string DefaultMaterial()
    {
        const string name = "mitsuba-default-diffuse";
        if (_materials.ContainsKey(name)) return name;
        _names.Add(name);
        _materials[name] = new JsonObject { ["type"] = "lambertian", ["reflectance"] = 0.5 };
        return name;
    }

    JsonObject Bsdf(MitsubaElement e, bool twoSided)
    {
        _used.Add(e);
        var type = e.Attr("type");
        JsonObject m;
        switch (type)
        {
            case "twosided":
                {
                    var nested = e.Children.Where(c => c.Tag is "bsdf" or "ref").ToList();
                    if (nested.Count == 0)
                        throw new InputException(e.Where, "a twosided BSDF without a nested BSDF", "nest the BSDF inside it");
                    if (nested.Count > 1)
                        Note("approximated", e, "a twosided BSDF with a different back side: both sides get the front BSDF");
                    foreach (var n in nested) _used.Add(n);
                    return Bsdf(Resolve(nested[0]), true);
                }
            case "diffuse":
                m = new JsonObject { ["type"] = "lambertian", ["reflectance"] = Spectrum(e, "reflectance", 0.5, false) };
                break;
            case "conductor" or "roughconductor":
                m = Conductor(e, type == "roughconductor");
                break;
            case "dielectric" or "roughdielectric":
                {
                    double ior = Ior(e);
                    if (type == "roughdielectric")
                        Note("approximated", e, string.Create(CultureInfo.InvariantCulture,
                            $"a rough dielectric (alpha {Alpha(e, 0.1):0.###}) rendered as smooth Fresnel glass (our rough "
                                + $"glass is not a scene material yet)"));
                    Prop(e, "distribution");
                    Prop(e, "sample_visible");
                    SpecularWeights(e);
                    m = new JsonObject { ["diffuse"] = 0, ["mirror"] = 1, ["transmit"] = 1, ["fresnel"] = true, ["ior"] = Round(ior) };
                    break;
                }
            case "thindielectric":
                {
                    double ior = Ior(e);
                    // A thin slab's reflectance at normal incidence, the inter-reflections summed: R' = R + T²R/(1 − R²) = 2R/(1 + R).
                    double r = Math.Pow((ior - 1) / (ior + 1), 2), slab = 2 * r / (1 + r);
                    SpecularWeights(e);
                    Note("approximated", e, string.Create(CultureInfo.InvariantCulture,
                        $"a thin dielectric as a constant mirror {slab:0.####} and straight transmission {1 - slab:0.####} (its "
                            + $"normal-incidence values; Mitsuba's vary with angle)"));
                    m = new JsonObject { ["diffuse"] = 0, ["mirror"] = Round(slab), ["transmit"] = Round(1 - slab), ["ior"] = 1 };
                    break;
                }
            case "plastic" or "roughplastic":
                {
                    double ior = Ior(e);
                    if (ior <= 1) throw new InputException(e.Where, $"a plastic coat of index {ior} ≤ 1", "give int_ior above ext_ior");
                    var diffuse = Spectrum(e, "diffuse_reflectance", 0.5, false);
                    double alpha = type == "roughplastic" ? Alpha(e, 0.1) : 0;
                    Prop(e, "distribution");
                    Prop(e, "sample_visible");
                    bool nonlinear = Boolean(e, "nonlinear", false);
                    if (Prop(e, "specular_reflectance") is { } sr && !IsOne(sr))
                        Note("ignored", sr, "specular_reflectance: our coat reflects its Fresnel reflectance, uncoloured");
                    Note("approximated", e,
                        "our coated plastic: a Lambertian base under a clear Fresnel coat, ρ_eff = ρ(1 − F_int)/(1 − ρF_int) "
                        + "leaving in proportion to 1 − E(θo); Mitsuba's plastic weights the base by (1 − F(θi))(1 − F(θo))/η² and "
                        + (nonlinear ? "the same internal sum" : "a linear internal-scattering term")
                        + (alpha > 0 ? " and samples Beckmann/GGX as given (ours GGX)" : ""));
                    m = new JsonObject { ["type"] = "plastic", ["diffuse"] = diffuse, ["ior"] = Round(Math.Min(ior, 4)) };
                    if (alpha > 0) m["roughness"] = Round(Math.Min(1, alpha));
                    break;
                }
            case "principled" or "principledthin":
                {
                    var baseColour = Spectrum(e, "base_color", 0.5, false);
                    double metallic = Float(e, "metallic", 0), roughness = Float(e, "roughness", 0.5);
                    foreach (var c in e.Children) _used.Add(c);
                    Note("approximated", e, string.Create(CultureInfo.InvariantCulture,
                        $"principled (metallic {metallic:0.##}, roughness {roughness:0.##}) as our coated plastic with "
                            + $"base_color and GGX α = roughness²")
                        + " (metallic, specular, sheen, clearcoat and transmission not converted)");
                    m = new JsonObject { ["type"] = "plastic", ["diffuse"] = baseColour, ["ior"] = 1.5 };
                    if (roughness > 0) m["roughness"] = Round(Math.Min(1, roughness * roughness));
                    break;
                }
            case "mask" or "bumpmap" or "normalmap":
                {
                    var nested = e.Children.FirstOrDefault(c => c.Tag is "bsdf" or "ref")
                        ?? throw new InputException(e.Where, $"a {type} BSDF without a nested BSDF", "nest the BSDF inside it");
                    Note("approximated", e, type == "mask" ? "the opacity mask is not converted: the surface is opaque"
                        : $"the {type} is not converted: the nested BSDF on the geometric surface");
                    foreach (var c in e.Children) _used.Add(c);
                    return Bsdf(Resolve(nested), twoSided);
                }
            case "blendbsdf":
                {
                    var nested = e.Children.Where(c => c.Tag is "bsdf" or "ref").ToList();
                    if (nested.Count == 0)
                        throw new InputException(e.Where, "a blendbsdf without nested BSDFs", "nest two BSDFs inside it");
                    Note("approximated", e, "a blend of two BSDFs: the first one alone (our materials do not mix)");
                    foreach (var c in e.Children) _used.Add(c);
                    return Bsdf(Resolve(nested[0]), twoSided);
                }
            default:
                Refuse(e, $"the BSDF '{type}' has no counterpart in our materials");
                return new JsonObject { ["type"] = "lambertian", ["reflectance"] = 0.5 };
        }
        if (!twoSided && type is "diffuse" or "plastic" or "roughplastic" or "conductor" or "roughconductor")
            Note("approximated", e, "a one-sided BSDF (black from behind in Mitsuba): our surfaces reflect on both sides");
        ReportUnused(e);
        return m;
    }

    JsonObject Conductor(MitsubaElement e, bool rough)
    {
        JsonNode metal;
        var named = String(e, "material");
        var eta = Prop(e, "eta");
        var k = Prop(e, "k");
        if (eta is not null || k is not null)
        {
            if (named is not null) Note("ignored", e, "material: eta and k are given and take its place");
            metal = new JsonObject
            {
                ["n"] = eta is null ? 0 : OpticalConstant(eta, "eta"),
                ["k"] = k is null ? 1 : OpticalConstant(k, "k"),
            };
        }
        else if ((named ?? "none") == "none")
        {
            Note("converted", e, "material 'none': a perfect mirror, n = 0, k = 1 (|r| = 1 at every angle)");
            metal = new JsonObject { ["n"] = 0, ["k"] = 1 };
        }
        else if (NamedMetals.TryGetValue(named!, out var ours))
        {
            Note("converted", e,
                $"material '{named}': our built-in {ours} (Johnson & Christy 1972 / Rakić 1995; Mitsuba's tables may differ slightly)");
            metal = ours;
        }
        else
        {
            Refuse(e, $"the metal '{named}' is not among our built-in ones (Au, Ag, Cu, Al); give its eta and k spectra");
            metal = "Al";
        }
        if (Prop(e, "specular_reflectance") is { } sr && !IsOne(sr))
            Note("ignored", sr, "specular_reflectance: our conductor reflects its Fresnel reflectance alone");
        if (Float(e, "ext_eta", 1) is var ext && Math.Abs(ext - 1) > 1e-3)
            Note("approximated", e, "ext_eta: the metal is taken as seen from vacuum");
        var m = new JsonObject { ["type"] = "conductor", ["conductor"] = metal };
        if (rough)
        {
            double alpha = Alpha(e, 0.1);
            var distribution = String(e, "distribution") ?? "beckmann";
            if (distribution != "ggx") Note("approximated", e, $"the {distribution} distribution as GGX with the same α");
            Prop(e, "sample_visible");
            m["roughness"] = Round(Math.Min(1, alpha));
        }
        return m;
    }

    /// <summary>eta or k of a conductor: a spectrum as given; an rgb has no uplift that keeps an index, so its mean.</summary>
    JsonNode OpticalConstant(MitsubaElement p, string what)
    {
        p = Resolve(p);
        if (p.Tag == "rgb")
        {
            var v = MitsubaXml.Numbers(Value(p), p.Where, what);
            _used.Add(p);
            Note("approximated", p, $"{what} given as rgb: the mean of its three values, constant over wavelength");
            return Round(v.Average());
        }
        var s = SpectrumValue(p, true, what);
        if (s is JsonObject o && o.ContainsKey("extrapolate")) o["extrapolate"] = "clamp";   // an index is not zero outside its table
        return s;
    }

    /// <summary>int_ior / ext_ior: numbers or Mitsuba's named media (bk7 and air by default).</summary>
    double Ior(MitsubaElement e)
    {
        double Named(string name, string fallback)
        {
            var p = Prop(e, name);
            var text = p is null ? fallback : Value(p);
            if (double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out var v)) return v;
            return NamedIor.TryGetValue(text, out var n) ? n
                : throw new InputException(p!.Where, $"unknown index of refraction {MessageText.Quote(text)}",
                    InputException.DidYouMean(text, NamedIor.Keys) ?? "a number or a name such as bk7, water, air");
        }
        double inner = Named("int_ior", "bk7"), outer = Named("ext_ior", "air");
        if (!(inner > 0 && outer > 0))
            throw new InputException(e.Where, "an index of refraction is not positive", "give int_ior and ext_ior above 0");
        return inner / outer;
    }

    /// <summary>A roughness α: alpha, or the mean of alpha_u and alpha_v (anisotropy approximated).</summary>
    double Alpha(MitsubaElement e, double fallback)
    {
        double a = Float(e, "alpha", double.NaN);
        if (!double.IsNaN(a)) return a;
        double u = Float(e, "alpha_u", double.NaN), v = Float(e, "alpha_v", double.NaN);
        if (double.IsNaN(u) && double.IsNaN(v)) return fallback;
        if (double.IsNaN(u) || double.IsNaN(v) || u != v)
            Note("approximated", e, "an anisotropic roughness as the mean of alpha_u and alpha_v");
        return double.IsNaN(u) ? v : double.IsNaN(v) ? u : 0.5 * (u + v);
    }

    void SpecularWeights(MitsubaElement e)
    {
        foreach (var name in new[] { "specular_reflectance", "specular_transmittance" })
            if (Prop(e, name) is { } p && !IsOne(p)) Note("ignored", p, $"{name}: our glass weights its lobes by Fresnel alone");
    }

    static bool IsOne(MitsubaElement p) =>
        p.Tag is "float" or "spectrum" && p.Attr("value") is { } v
            && double.TryParse(v, NumberStyles.Float, CultureInfo.InvariantCulture, out var x) && x == 1;
}
