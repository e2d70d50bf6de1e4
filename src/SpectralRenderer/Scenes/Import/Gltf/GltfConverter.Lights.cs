using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import.Gltf;

// KHR_lights_punctual: point and spot lights in candela (lm/sr), directional lights in lux (lm/m²), each with a linear RGB
// colour, placed by its node (a light shines down the node's −Z). Our photometric keys take the value: the colour's
// luminance Y (Rec. 709 weights of linear sRGB) times the intensity is the light's luminous intensity or illuminance, and
// the colour's chromaticity its spectrum (the illuminant uplift over D65; "D65" itself for white). Inverse-square falloff
// as glTF's; the optional "range" cut-off is not modelled.
sealed partial class GltfConverter
{
    /// <summary>The light's luminance factor of a linear sRGB colour (ITU-R BT.709 Y weights).</summary>
    static double Luminance(double[] rgb) => 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];

    /// <summary>An emission's spectrum for a linear sRGB colour: D65 for white, else the illuminant uplift of the colour scaled
    /// to a largest component of 1 (the shape only: a photometric key sets the scale).</summary>
    static JsonNode EmissionSpectrum(double[] rgb)
    {
        double max = Math.Max(rgb[0], Math.Max(rgb[1], rgb[2]));
        if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) return "D65";
        return new JsonObject { ["rgb"] = Vector([rgb[0] / max, rgb[1] / max, rgb[2] / max]), ["illuminant"] = "D65" };
    }

    void Light(int l, double[] world, string nodePath)
    {
        var path = $"$.extensions.KHR_lights_punctual.lights[{l}]";
        var light = doc.Object(Lights()[l], path);
        var type = doc.String(light, "type", path) ?? throw doc.Error(path, "missing \"type\"", "point, spot or directional");
        var color = doc.Numbers(light, "color", path, [1, 1, 1], 0, 1);
        double intensity = doc.Number(light, "intensity", path, 1, 0, 1e30);
        double value = intensity * Luminance(color);
        var label = $"{type} light {l}";
        if (value == 0)
        {
            Note("ignored", path, label, "its intensity (or its colour's luminance) is 0: it gives no light");
            return;
        }
        var o = new JsonObject
        {
            ["type"] = type,
            ["name"] = Unique(SafeName(doc.String(light, "name", path) ?? $"light{l}")),
        };
        var position = Affine.Point(world, 0, 0, 0);
        var direction = Affine.Normalized(Affine.Direction(world, 0, 0, -1));
        string unit = "cd";
        switch (type)
        {
            case "point":
                o["position"] = Vector(position);
                o["luminous_intensity"] = Round(value);
                break;
            case "spot":
                {
                    var spotPath = $"{path}.spot";
                    if (!GltfDocument.Has(light, "spot", out var spot))
                        throw doc.Error(path, "a spot light without \"spot\"", "give its cone angles");
                    doc.Object(spot, spotPath);
                    double inner = doc.Number(spot, "innerConeAngle", spotPath, 0, 0, Math.PI / 2);
                    double outer = doc.Number(spot, "outerConeAngle", spotPath, Math.PI / 4, 0, Math.PI / 2);
                    if (!(inner < outer) || outer == 0)
                        throw doc.Error(spotPath, "innerConeAngle must be below outerConeAngle, and outerConeAngle above 0",
                            "KHR_lights_punctual: 0 ≤ inner < outer ≤ π/2");
                    // glTF's falloff is t² for t = (cos θ − cos outer)/(cos inner − cos outer) between the cones; our spot is
                    // a hard cone (exponent 0): the one of the same luminous flux, 1 − cos θc = 1 − cos inner + (cos inner − cos outer)/3.
                    double ci = Math.Cos(inner), co = Math.Cos(outer);
                    double cutoff = Math.Acos(ci - (ci - co) / 3) * 180 / Math.PI;
                    o["position"] = Vector(position);
                    o["direction"] = Vector(direction);
                    o["cutoff"] = Round(cutoff);
                    o["exponent"] = 0;
                    o["luminous_intensity"] = Round(value);
                    Note("approximated", spotPath, "spot cone",
                        $"the smooth falloff from {Round(inner * 180 / Math.PI)}° to {Round(outer * 180 / Math.PI)}° is a hard cone of "
                        + $"{Round(cutoff)}° with the same luminous flux");
                    break;
                }
            case "directional":
                o["direction"] = Vector(direction);
                o["illuminance"] = Round(value);
                unit = "lx";
                break;
            default:
                Fail($"{path}.type", $"light type {type}",
                    $"light type {Diagnostics.MessageText.Quote(type)} is not one of point, spot, directional");
                return;
        }
        o["spectrum"] = EmissionSpectrum(color);
        if (GltfDocument.Has(light, "range", out _))
            Note("ignored", $"{path}.range", "light range",
                "the cut-off distance is not modelled: inverse-square everywhere");
        Note("converted", nodePath, label,
            $"{Round(intensity)} {unit} × the colour's luminance {Round(Luminance(color))} = {Round(value)} {unit} "
            + $"({(unit == "cd" ? "luminous_intensity" : "illuminance")}), spectrum "
            + (color[0] == color[1] && color[1] == color[2] ? "D65" : "the colour uplifted over D65"));
        _lights.Add((JsonNode)o);
    }
}
