using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using static SpectralRenderer.Scenes.Import.Mitsuba.MitsubaTransform;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

// Emitters: point, spot and directional lights, the constant sky as our background, an environment map as our envmap sky.
public sealed partial class MitsubaConverter
{
    void Emitter(MitsubaElement e)
    {
        var type = e.Attr("type");
        var m = Prop(e, "to_world") is { } t ? Transform(t) : Identity;
        switch (type)
        {
            case "point":
                {
                    var position = Point(e, "position") ?? Apply(m, [0, 0, 0], 1);
                    var intensity = Spectrum(e, "intensity", 1.0, true)!;
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "point",
                        ["name"] = UniqueName(e.Attr("id") ?? "point"),
                        ["position"] = Array3(position),
                        ["spectrum"] = intensity,
                        ["intensity"] = 1,
                    });
                    break;
                }
            case "spot":
                {
                    var position = Apply(m, [0, 0, 0], 1);
                    var direction = Normalize(Apply(m, [0, 0, 1], 0), e, "to_world flattens the direction");
                    var intensity = Spectrum(e, "intensity", 1.0, true)!;
                    double cutoff = Float(e, "cutoff_angle", 20), beam = Float(e, "beam_width", cutoff * 3 / 4);
                    if (Prop(e, "texture") is { } tex)
                        Note("ignored", tex, "a projected texture: the spot's intensity is uniform in its cone");
                    Note("approximated", e,
                        $"a spot with a smooth falloff from {beam:0.##}° to {cutoff:0.##}°: our spot is full "
                            + $"intensity to its cutoff {cutoff:0.##}°");
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "spot",
                        ["name"] = UniqueName(e.Attr("id") ?? "spot"),
                        ["position"] = Array3(position),
                        ["direction"] =
                            Array3(direction),
                        ["cutoff"] = Round(cutoff),
                        ["exponent"] = 0,
                        ["spectrum"] = intensity,
                        ["intensity"] = 1,
                    });
                    break;
                }
            case "directional":
                {
                    var direction = Point(e, "direction") ?? Apply(m, [0, 0, 1], 0);
                    direction = Normalize(direction, e, "the direction is zero");
                    var irradiance = Spectrum(e, "irradiance", 1.0, true)!;
                    _lights.Add((JsonNode)new JsonObject
                    {
                        ["type"] = "directional",
                        ["name"] = UniqueName(e.Attr("id") ?? "directional"),
                        ["direction"] = Array3(direction),
                        ["spectrum"] = irradiance,
                        ["intensity"] = 1,
                    });
                    break;
                }
            case "constant":
                if (_background is not null || _sky is not null)
                    Note("approximated", e, "a second sky: the skies' radiances are not added; the last one counts");
                _sky = null;
                _background = Spectrum(e, "radiance", 1.0, true);
                Note("converted", e, "a constant environment: our background, a uniform sky of that radiance");
                break;
            case "envmap":
                Envmap(e, m);
                break;
            case "area":
                throw new InputException(e.Where, "an area emitter outside a shape",
                    "nest <emitter type=\"area\"> inside the <shape> that emits");
            default:
                Refuse(e, $"the emitter '{type}' has no counterpart");
                return;
        }
        ReportUnused(e);
    }

    /// <summary>
    /// A lat-long environment map: our "sky": { "type": "envmap" } with the same file, scale and to_world (its linear part), in
    /// Mitsuba's conventions (Scenes/EnvironmentMap.cs); the file is read when the scene loads. Its filter_type is reported:
    /// we interpolate bilinearly, as Mitsuba's default.
    /// </summary>
    void Envmap(MitsubaElement e, double[] toWorld)
    {
        var file = String(e, "filename")
            ?? throw new InputException(e.Where, "an envmap without filename", "give <string name=\"filename\" value=\"sky.exr\"/>");
        double scale = Float(e, "scale", 1);
        if (String(e, "filter_type") is { } filter && filter != "bilinear")
            Note("approximated", e, $"filter_type '{filter}': the map is interpolated bilinearly");
        if (!File.Exists(Path.Combine(_dir, file)))
            throw new InputException(e.Where, $"environment map {MessageText.Quote(file)} not found",
                "the path is relative to the scene file")
            { Problem = InputProblem.MissingFile };
        if (_background is not null || _sky is not null)
            Note("approximated", e, "a second sky: the skies' radiances are not added; the last one counts");
        _background = null;
        _sky = new JsonObject { ["type"] = "envmap", ["file"] = file.Replace('\\', '/') };
        if (scale != 1) _sky["scale"] = Round(scale);
        Place(_sky, toWorld);
        Note("converted", e, $"the environment map {file}: our envmap sky (Mitsuba's lat-long convention, D65 illuminant uplift)");
    }
}
