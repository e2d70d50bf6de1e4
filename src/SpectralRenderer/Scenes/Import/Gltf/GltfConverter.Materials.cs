using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;

namespace SpectralRenderer.Scenes.Import.Gltf;

// glTF's metallic-roughness material (glTF 2.0 Appendix B) as our material models (docs/import.md "glTF 2.0"):
//   transmissionFactor t > 0 (KHR_materials_transmission), not metallic → a Fresnel glass (eq2: mirror 1, transmit t × base
//     colour, fresnel, the KHR_materials_ior index; with KHR_materials_dispersion a Cauchy index from the Abbe number);
//   metallicFactor ≥ 0.5 → "conductor": GGX α = roughness², its normal-incidence reflectance F0 the base colour (uplifted), as
//     the index n(λ) = (1 + √F0)/(1 − √F0) with k = 0, whose Fresnel rises from F0 to 1 at grazing as glTF's Schlick term;
//   a dielectric with F0 = 0 (KHR_materials_specular's specularFactor 0, or ior 1) → "lambertian", f = base colour/π, glTF's
//     diffuse term exactly;
//   any other dielectric → "plastic" (a Lambertian base under a dielectric coat of the ior, α = roughness²): glTF's
//     fresnel_mix of the diffuse base and the GGX specular layer, energy-conserving where glTF's mix is not;
//   a textured base colour → eq2 (our coated model takes no texture): the texture as the diffuse lobe and, for a
//     dielectric, a Blinn–Phong lobe of m_spec = F0 and shininess 2/α² − 2.
// Base colours go through the sigmoid uplift as { "rgb": … } (a grey as its constant); emissiveFactor × emissive_strength is
// a luminance in cd/m² (glTF 2.0 §3.9.3's unit when physical units are needed).
sealed partial class GltfConverter
{
    static readonly Lazy<SigmoidUplift> Uplift = new(() => new SigmoidUplift());
    readonly Dictionary<int, string> _materialNames = [];
    string? _defaultMaterial;

    /// <summary>Fraunhofer lines of the Abbe number V_d = (n_d − 1)/(n_F − n_C): helium d, hydrogen F and C (nm).</summary>
    const double LambdaD = 587.56, LambdaF = 486.13, LambdaC = 656.27;

    /// <summary>Whether glTF material <paramref name="m"/> cuts away all of its primitives: alpha mode MASK, no base colour
    /// texture and a base colour factor's alpha below alphaCutoff (glTF 2.0 §3.9.4).</summary>
    bool CutOut(int m)
    {
        var path = $"$.materials[{m}]";
        var mat = doc.Item("materials", m);
        if ((doc.String(mat, "alphaMode", path) ?? "OPAQUE") != "MASK") return false;
        double cutoff = doc.Number(mat, "alphaCutoff", path, 0.5, 0);
        if (!GltfDocument.Has(mat, "pbrMetallicRoughness", out var pbr)) return 1 < cutoff;
        if (GltfDocument.Has(pbr, "baseColorTexture", out _)) return false;
        var factor = doc.Numbers(pbr, "baseColorFactor", $"{path}.pbrMetallicRoughness", [1, 1, 1, 1], 0, 1);
        return factor[3] < cutoff;
    }

    /// <summary>Our material's name for glTF material <paramref name="m"/>, converted on first use.</summary>
    string Material(int m)
    {
        if (_materialNames.TryGetValue(m, out var name)) return name;
        var path = $"$.materials[{m}]";
        var mat = doc.Item("materials", m);
        name = UniqueMaterial(SafeName(doc.String(mat, "name", path) ?? $"material{m}"));
        _materials[name] = MaterialJson(mat, path, name);
        _materialNames[m] = name;
        return name;
    }

    /// <summary>glTF's default material (§3.9.6: white, metallic 1, roughness 1) for primitives that name none.</summary>
    string DefaultMaterial()
    {
        if (_defaultMaterial is not null) return _defaultMaterial;
        _defaultMaterial = UniqueMaterial("gltf-default");
        using var empty = JsonDocument.Parse("{}");
        _materials[_defaultMaterial] = MaterialJson(empty.RootElement.Clone(), "$.meshes", _defaultMaterial);
        return _defaultMaterial;
    }

    string UniqueMaterial(string name)
    {
        var n = name;
        for (int i = 2; _materials.ContainsKey(n); i++) n = $"{name}-{i}";
        return n;
    }

    JsonObject MaterialJson(JsonElement mat, string path, string name)
    {
        var where = path;
        var pbrPath = $"{path}.pbrMetallicRoughness";
        var pbr = GltfDocument.Has(mat, "pbrMetallicRoughness", out var p) ? doc.Object(p, pbrPath) : default;
        var baseColor = doc.Numbers(pbr, "baseColorFactor", pbrPath, [1, 1, 1, 1], 0, 1);
        double metallic = doc.Number(pbr, "metallicFactor", pbrPath, 1, 0, 1);
        double roughness = doc.Number(pbr, "roughnessFactor", pbrPath, 1, 0, 1);
        double alpha = roughness * roughness;
        double[] rgb = [baseColor[0], baseColor[1], baseColor[2]];
        var ext = GltfDocument.Has(mat, "extensions", out var e) ? doc.Object(e, $"{path}.extensions") : default;
        var extPath = $"{path}.extensions";
        double ior = Extension(ext, "KHR_materials_ior", extPath, "ior", 1.5, 1, 100);
        double transmission = Extension(ext, "KHR_materials_transmission", extPath, "transmissionFactor", 0, 0, 1);
        double dispersion = Extension(ext, "KHR_materials_dispersion", extPath, "dispersion", 0, 0, 1e3);
        double specular = Extension(ext, "KHR_materials_specular", extPath, "specularFactor", 1, 0, 1);
        double strength = Extension(ext, "KHR_materials_emissive_strength", extPath, "emissiveStrength", 1, 0, 1e30);
        ReportExtensions(ext, extPath, name);
        ReportIgnoredTextures(mat, pbr, path, pbrPath, ext, extPath);
        var mode = doc.String(mat, "alphaMode", path) ?? "OPAQUE";
        double cutoff = doc.Number(mat, "alphaCutoff", path, 0.5, 0);
        bool textured = GltfDocument.Has(pbr, "baseColorTexture", out _);
        // glTF 2.0 §3.9.4: OPAQUE ignores alpha; MASK shows a point where alpha (factor × texel) ≥ alphaCutoff; BLEND composites.
        if (mode == "MASK" && textured)
            Note("approximated", $"{path}.alphaMode", $"material {name} alpha",
                $"alpha mode MASK, cutoff {Round(cutoff)}: rendered opaque: our surfaces have no alpha test, so texels whose alpha is "
                + "below the cutoff are solid");
        else if (mode == "BLEND")
            Note("approximated", $"{path}.alphaMode", $"material {name} alpha",
                $"alpha mode BLEND, base alpha {Round(baseColor[3])}: rendered opaque (no alpha compositing)");
        else if (mode == "OPAQUE" && baseColor[3] < 1)
            Note("ignored", $"{path}.baseColorFactor", $"material {name} alpha",
                $"base alpha {Round(baseColor[3])} with alpha mode OPAQUE: ignored, as glTF asks");
        var texture = BaseColorTexture(pbr, pbrPath, rgb, name);
        double f0 = Math.Pow((ior - 1) / (ior + 1), 2) * specular;

        JsonObject o;
        if (transmission > 0 && metallic < 0.5)
        {
            o = new JsonObject
            {
                ["diffuse"] = transmission < 1 ? Reflectance(Scaled(rgb, 1 - transmission), where, name) : 0,
                ["mirror"] = 1,
                ["transmit"] = Reflectance(Scaled(rgb, transmission), where, name),
                ["fresnel"] = true,
                ["ior"] = Ior(ior, dispersion, ext, extPath, name),
            };
            Note("converted", where, $"material {name}",
                $"transmission {Round(transmission)}: a smooth Fresnel glass of ior {Round(ior)} (eq2: mirror 1, transmit "
                + $"{Round(transmission)} × base colour{(transmission < 1 ? ", the rest diffuse" : "")})");
            if (alpha > 0)
                Note("approximated", $"{pbrPath}.roughnessFactor", $"material {name} roughness",
                    $"a rough transmitting surface (α = {Round(alpha)}) is rendered smooth: we have no rough glass");
            if (!GltfDocument.Has(ext, "KHR_materials_volume", out _))
                Note("approximated", extPath, $"material {name} thin walls",
                    "glTF transmission without KHR_materials_volume is thin-walled (no refraction); ours is a solid glass that refracts");
            if (texture is not null)
                Note("approximated", $"{pbrPath}.baseColorTexture", $"material {name} texture",
                    "a transmitting material takes the base colour factor only; its texture is not applied");
        }
        else if (metallic >= 0.5)
        {
            o = new JsonObject { ["type"] = "conductor", ["conductor"] = Conductor(rgb), ["roughness"] = Round(alpha) };
            Note("converted", where, $"material {name}",
                $"metallic {Round(metallic)}: a GGX conductor of α = roughness² = {Round(alpha)} whose normal-incidence reflectance "
                + "is the base colour (n = (1 + √F0)/(1 − √F0), k = 0)");
            if (metallic < 1)
                Note("approximated", $"{pbrPath}.metallicFactor", $"material {name} metallic",
                    $"metallic {Round(metallic)} is rendered as a metal (no mix of metal and dielectric)");
            if (texture is not null)
                Note("approximated", $"{pbrPath}.baseColorTexture", $"material {name} texture",
                    "our conductor takes no texture: the base colour factor alone gives F0");
            if (transmission > 0)
                Note("ignored", extPath, $"material {name} transmission",
                    "a metal does not transmit (glTF's mix says so too)");
        }
        else
        {
            if (metallic > 0)
                Note("approximated", $"{pbrPath}.metallicFactor", $"material {name} metallic",
                    $"metallic {Round(metallic)} is rendered as a dielectric (no mix of metal and dielectric)");
            if (texture is not null)
            {
                o = new JsonObject { ["diffuse"] = texture };
                if (f0 > 0)
                {
                    o["specular"] = Round(f0);
                    o["shininess"] = Round(Math.Min(1e4, 2 / Math.Max(alpha * alpha, 2e-4) - 2));
                    Note("approximated", where, $"material {name}",
                        $"a textured dielectric: eq2's Lambertian texture with a Blinn–Phong lobe of m_spec = F0 = {Round(f0)} and "
                        + "shininess 2/α² − 2 (our coated model takes no texture)");
                }
                else Note("converted", where, $"material {name}", "F0 = 0: the texture as a Lambertian diffuse lobe");
            }
            else if (f0 == 0)
            {
                o = new JsonObject { ["type"] = "lambertian", ["reflectance"] = Reflectance(rgb, where, name) };
                Note("converted", where, $"material {name}",
                    "a dielectric without specular reflection (F0 = 0): Lambertian, f = base colour/π");
            }
            else
            {
                double coat = Math.Min(ior, 4);
                if (coat != ior)
                    Note("approximated", $"{extPath}.KHR_materials_ior.ior", $"material {name} ior",
                        $"our coat's index is at most 4: {Round(ior)} rendered as 4");
                if (specular < 1)
                    Note("approximated", $"{extPath}.KHR_materials_specular", $"material {name} specular",
                        $"specularFactor {Round(specular)}: our coat reflects the Fresnel of its index, unscaled");
                o = new JsonObject
                {
                    ["type"] = "plastic",
                    ["diffuse"] = Reflectance(rgb, where, name),
                    ["ior"] = Round(coat),
                    ["roughness"] = Round(alpha),
                };
                Note("converted", where, $"material {name}",
                    $"a dielectric: our plastic, a Lambertian base under a coat of ior {Round(coat)} with GGX "
                        + $"α = roughness² = {Round(alpha)}");
            }
        }
        Emission(mat, path, o, strength, name);
        return o;
    }

    double Extension(JsonElement ext, string extension, string extPath, string key, double fallback, double min, double max) =>
        GltfDocument.Has(ext, extension, out var x)
            ? doc.Number(doc.Object(x, $"{extPath}.{extension}"), key, $"{extPath}.{extension}", fallback, min, max)
            : fallback;

    /// <summary>Material extensions we do not read, reported per material.</summary>
    void ReportExtensions(JsonElement ext, string extPath, string name)
    {
        if (ext.ValueKind != JsonValueKind.Object) return;
        foreach (var x in ext.EnumerateObject())
            if (Array.IndexOf(Supported, x.Name) < 0)
                Note("ignored", $"{extPath}.{x.Name}", $"material {name} {x.Name}",
                    "not read: what it adds is not converted");
        if (GltfDocument.Has(ext, "KHR_materials_volume", out var v) && GltfDocument.Has(v, "attenuationDistance", out _))
            Note("ignored", $"{extPath}.KHR_materials_volume.attenuationDistance", $"material {name} attenuation",
                "absorption inside the volume is not modelled (the glass is clear)");
        if (GltfDocument.Has(ext, "KHR_materials_specular", out var s) && GltfDocument.Has(s, "specularColorFactor", out _))
            Note("ignored", $"{extPath}.KHR_materials_specular.specularColorFactor", $"material {name} specular colour",
                "the coat's reflection is not tinted");
    }

    void ReportIgnoredTextures(JsonElement mat, JsonElement pbr, string path, string pbrPath, JsonElement ext, string extPath)
    {
        foreach (var (parent, at, key, what) in new[]
        {
            (pbr, pbrPath, "metallicRoughnessTexture", "metallic and roughness are their factors, uniform"),
            (mat, path, "normalTexture", "normal mapping is not applied"),
            (mat, path, "occlusionTexture", "ambient occlusion is computed by the path tracer, not read"),
            (mat, path, "emissiveTexture", "emission is the emissive factor, uniform"),
        })
            if (GltfDocument.Has(parent, key, out _)) Note(key == "occlusionTexture" ? "ignored" : "approximated",
                $"{at}.{key}", key, what);
        foreach (var (extension, key) in new[]
        {
            ("KHR_materials_transmission", "transmissionTexture"), ("KHR_materials_specular", "specularTexture"),
            ("KHR_materials_specular", "specularColorTexture"), ("KHR_materials_volume", "thicknessTexture"),
        })
            if (GltfDocument.Has(ext, extension, out var x) && GltfDocument.Has(x, key, out _))
                Note("approximated", $"{extPath}.{extension}.{key}", key, "the factor alone is used, uniform");
    }

    /// <summary>A reflectance spectrum value for a linear sRGB colour: a grey as its constant (the flat spectrum the uplift
    /// converges to), any other as { "rgb": … } through the sigmoid uplift (reported).</summary>
    JsonNode Reflectance(double[] rgb, string where, string name)
    {
        if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) return Round(rgb[0]);
        Note("uplifted", where, $"material {name} colour",
            $"linear sRGB ({Round(rgb[0])}, {Round(rgb[1])}, {Round(rgb[2])}) through the sigmoid uplift (Jakob & Hanika 2019)");
        return new JsonObject { ["rgb"] = Vector(rgb) };
    }

    static double[] Scaled(double[] rgb, double s) => [rgb[0] * s, rgb[1] * s, rgb[2] * s];

    /// <summary>{ "n": …, "k": 0 } whose normal-incidence Fresnel reflectance ((n − 1)/(n + 1))² is the uplifted base colour F0
    /// (capped at 0.999, n ≈ 4000).</summary>
    static JsonObject Conductor(double[] rgb)
    {
        static double N(double f0)
        {
            double r = Math.Sqrt(Math.Clamp(f0, 0, 0.999));
            return (1 + r) / (1 - r);
        }
        JsonNode n;
        if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) n = Round(N(rgb[0]));
        else
        {
            var f0 = Uplift.Value.Spectrum(new Xyz(
                0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2],
                0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2],
                0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2]), out _);
            var pairs = new JsonArray();
            for (int i = 0; i < f0.Length; i++)
                pairs.Add((JsonNode)new JsonArray(JsonValue.Create(SigmoidUplift.Wavelengths[i]), JsonValue.Create(Round(N(f0[i])))));
            n = pairs;
        }
        return new JsonObject { ["n"] = n, ["k"] = 0 };
    }

    /// <summary>The index: a number, or with KHR_materials_dispersion a Cauchy n(λ) = A + B/λ² whose n_d is the ior and whose
    /// Abbe number V_d = (n_d − 1)/(n_F − n_C) is 20/dispersion: B = (n_d − 1)/(V_d (λ_F⁻² − λ_C⁻²)), A = n_d − B/λ_d².</summary>
    JsonNode Ior(double ior, double dispersion, JsonElement ext, string extPath, string name)
    {
        if (dispersion == 0) return Round(ior);
        double abbe = 20 / dispersion;
        double b = (ior - 1) / (abbe * (1 / (LambdaF * LambdaF) - 1 / (LambdaC * LambdaC)));
        double a = ior - b / (LambdaD * LambdaD);
        Note("converted", $"{extPath}.KHR_materials_dispersion", $"material {name} dispersion",
            $"Abbe number V_d = 20/{Round(dispersion)} = {Round(abbe)} with n_d = {Round(ior)}: Cauchy A = {Round(a)}, B = {Round(b)} nm²");
        _ = ext;
        return new JsonObject { ["cauchy"] = new JsonArray(JsonValue.Create(Round(a)), JsonValue.Create(Round(b))) };
    }

    /// <summary>emissiveFactor × emissiveStrength as a luminance (cd/m²: its Y) with the colour's chromaticity.</summary>
    void Emission(JsonElement mat, string path, JsonObject o, double strength, string name)
    {
        var factor = doc.Numbers(mat, "emissiveFactor", path, [0, 0, 0], 0, 1);
        double[] e = [factor[0] * strength, factor[1] * strength, factor[2] * strength];
        double luminance = Luminance(e);
        if (luminance <= 0) return;
        var emission = new JsonObject { ["spectrum"] = EmissionSpectrum(e), ["luminance"] = Round(luminance) };
        if (doc.Bool(mat, "doubleSided", path, false)) emission["two_sided"] = true;
        o["emission"] = emission;
        Note("converted", $"{path}.emissiveFactor", $"material {name} emission",
            $"emissive ({Round(e[0])}, {Round(e[1])}, {Round(e[2])}) read as cd/m² (glTF 2.0 §3.9.3): luminance {Round(luminance)} cd/m²");
    }

    /// <summary>The base colour texture as our texture object: the image's file (relative to the asset) or a data: URI, the
    /// factor as its scale, the sampler's wrap; null when there is none or it cannot be read.</summary>
    JsonObject? BaseColorTexture(JsonElement pbr, string pbrPath, double[] factor, string name)
    {
        if (!GltfDocument.Has(pbr, "baseColorTexture", out var info)) return null;
        var infoPath = $"{pbrPath}.baseColorTexture";
        doc.Object(info, infoPath);
        int t = doc.Index(info, "index", infoPath, "textures", required: true);
        double texCoord = doc.Number(info, "texCoord", infoPath, 0, 0, 64);
        JsonObject? uvTransform = null;
        if (GltfDocument.Has(info, "extensions", out var ie) && GltfDocument.Has(ie, "KHR_texture_transform", out var tt))
        {
            var ttPath = $"{infoPath}.extensions.KHR_texture_transform";
            doc.Object(tt, ttPath);
            texCoord = doc.Number(tt, "texCoord", ttPath, texCoord, 0, 64);   // overrides the textureInfo's
            uvTransform = TextureTransform(tt, ttPath);
            Note("converted", ttPath, $"material {name} texture transform",
                "offset, rotation and scale as our uv_transform, carried into our v-up texture coordinates");
        }
        if (texCoord != 0)
            Note("approximated", $"{infoPath}.texCoord", "texture coordinates",
                "TEXCOORD_0 is used (our meshes keep one set)");
        var texPath = $"$.textures[{t}]";
        var texture = doc.Item("textures", t);
        int source = doc.Index(texture, "source", texPath, "images");
        if (source < 0)
        {
            Note("approximated", texPath, $"material {name} texture",
                "the texture has no PNG or JPEG source (an extension's image format): the base colour factor is used");
            return null;
        }
        var imagePath = $"$.images[{source}]";
        var image = doc.Item("images", source);
        string? reference = Image(image, imagePath);
        if (reference is null)
        {
            Note("approximated", imagePath, $"material {name} texture",
                "the image is neither PNG nor JPEG: the base colour factor is used");
            return null;
        }
        var o = new JsonObject { ["texture"] = reference };
        double y = Luminance(factor);
        if (factor[0] != 1 || factor[1] != 1 || factor[2] != 1)
        {
            o["scale"] = Round(factor[0] == factor[1] && factor[1] == factor[2] ? factor[0] : y);
            if (!(factor[0] == factor[1] && factor[1] == factor[2]))
                Note("approximated", $"{pbrPath}.baseColorFactor", $"material {name} texture factor",
                    $"a coloured factor on a texture: the texture scaled by the factor's luminance {Round(y)}");
        }
        int sampler = doc.Index(texture, "sampler", texPath, "samplers");
        if (sampler >= 0)
        {
            var sp = $"$.samplers[{sampler}]";
            var s = doc.Item("samplers", sampler);
            int ws = (int)doc.Number(s, "wrapS", sp, 10497), wt = (int)doc.Number(s, "wrapT", sp, 10497);
            if (ws != wt)
                Note("approximated", sp, "texture wrap", "one wrap mode for u and v: wrapS's");
            var wrap = ws switch { 33071 => "clamp", 33648 => "mirror", _ => "repeat" };
            if (wrap != "repeat") (uvTransform ??= [])["wrap"] = wrap;
        }
        if (uvTransform is not null) o["uv_transform"] = uvTransform;
        Note("uplifted", infoPath, $"material {name} texture", "sRGB texels through the sigmoid uplift");
        return o;
    }

    /// <summary>
    /// KHR_texture_transform as our uv_transform. glTF: t' = T·R·S·t in its v-down texture space, R = [[cos r, sin r],
    /// [−sin r, cos r]] ("counter-clockwise" on the v-down UV map: the extension's example, which takes the lower left quadrant,
    /// and KhronosGroup/glTF#1563). Our coordinates are F(t) = (u, 1 − v) (the importer flips v), so ours is F·M·F: the same
    /// scale, R conjugated by the flip — our counter-clockwise rotation by r (uv' = R(r)·(s ⊙ uv) + o) — and the offset
    /// o = (o_u + sin r·s_v, 1 − o_v − cos r·s_v).
    /// </summary>
    JsonObject TextureTransform(JsonElement tt, string path)
    {
        var offset = doc.Numbers(tt, "offset", path, [0, 0]);
        var scale = doc.Numbers(tt, "scale", path, [1, 1]);
        double r = doc.Number(tt, "rotation", path, 0, -1e6, 1e6);
        double ou = offset[0] + Math.Sin(r) * scale[1], ov = 1 - offset[1] - Math.Cos(r) * scale[1];
        return new JsonObject
        {
            ["scale"] = new JsonArray(Round(scale[0]), Round(scale[1])),
            ["offset"] = new JsonArray(Round(ou), Round(ov)),
            ["rotation"] = Round(r * 180 / Math.PI),
        };
    }

    /// <summary>An image as our texture reference: a PNG or JPEG file's path relative to the asset, or a data: URI (for a
    /// data: URI or a buffer view); null for another format.</summary>
    string? Image(JsonElement image, string path)
    {
        var uri = doc.String(image, "uri", path);
        if (uri is not null && !uri.StartsWith("data:", StringComparison.OrdinalIgnoreCase))
        {
            var full = doc.FilePath(uri, $"{path}.uri", "image");
            var ext = Path.GetExtension(full).ToLowerInvariant();
            return ext is ".png" or ".jpg" or ".jpeg" ? Uri.UnescapeDataString(uri) : null;
        }
        byte[] bytes;
        if (uri is not null) bytes = doc.UriBytes(uri, $"{path}.uri", "image");
        else
        {
            int view = doc.Index(image, "bufferView", path, "bufferViews", required: true);
            bytes = doc.BufferView(view, path).Bytes.ToArray();
        }
        string? mime = bytes.Length > 8 && bytes[0] == 0x89 && bytes[1] == (byte)'P' && bytes[2] == (byte)'N' && bytes[3] == (byte)'G'
            ? "image/png"
            : Imaging.JpegReader.IsJpeg(bytes) ? "image/jpeg" : null;
        return mime is null ? null : $"data:{mime};base64,{System.Convert.ToBase64String(bytes)}";
    }
}
