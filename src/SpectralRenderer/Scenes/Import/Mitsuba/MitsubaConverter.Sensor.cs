using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using static SpectralRenderer.Scenes.Import.Mitsuba.MitsubaTransform;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

// The sensor (perspective camera, film size, sample count) and the integrator.
public sealed partial class MitsubaConverter
{
    void Sensor(MitsubaElement e)
    {
        if (_camera is not null) { Note("ignored", e, "a second sensor: our scene has one camera, the first sensor's"); return; }
        var type = e.Attr("type");
        if (type is not ("perspective" or "thinlens"))
        {
            Refuse(e, $"the sensor type '{type}' has no counterpart (our camera is a pinhole)");
            return;
        }
        if (type == "thinlens") Note("approximated", e, "a thin-lens camera rendered as a pinhole (no depth of field)");
        var m = Prop(e, "to_world") is { } t ? Transform(t) : Identity;
        if (Determinant(m) < 0) Note("approximated", e, "the camera's to_world mirrors the image; rendered unmirrored");
        var position = Apply(m, [0, 0, 0], 1);
        var forward = Apply(m, [0, 0, 1], 0);
        var up = Apply(m, [0, 1, 0], 0);
        double fov = Float(e, "fov", double.NaN);
        string axis = String(e, "fov_axis") ?? "x";
        if (double.IsNaN(fov))
        {
            // Mitsuba's alternative: a 35 mm equivalent focal length ("50mm" by default) on the 36 × 24 mm frame's diagonal.
            var focal = String(e, "focal_length") ?? "50mm";
            double f = Number(focal.EndsWith("mm", StringComparison.Ordinal) ? focal[..^2] : focal, e.Where, "focal_length");
            fov = 2 * Math.Atan(Math.Sqrt(36 * 36 + 24 * 24) / (2 * f)) * 180 / Math.PI;
            axis = "diagonal";
        }
        int width = 768, height = 576, spp = 4;
        foreach (var c in e.Children)
        {
            if (c.Tag == "film")
            {
                _used.Add(c);
                if (c.Attr("type") is not ("hdrfilm" or "specfilm"))
                    Note("approximated", c, $"film '{c.Attr("type")}': our render writes its own outputs (spectral cube, preview)");
                width = (int)Float(c, "width", 768);
                height = (int)Float(c, "height", 576);
                if (width < 1 || height < 1 || width > 65536 || height > 65536)
                    throw new InputException(c.Where, $"film size {width}×{height} is out of range", "give width and height of 1 to 65536");
                if (Prop(c, "rfilter") is { } rf)
                    Note("approximated", rf, "the reconstruction filter: our film is a box filter over each pixel");
                foreach (var f in c.Children)
                    if (f.Tag == "rfilter")
                    {
                        _used.Add(f);
                        if (f.Attr("type") != "box")
                            Note("approximated", f, $"rfilter '{f.Attr("type")}': our film is a box filter over each pixel");
                    }
                Prop(c, "pixel_format");
                Prop(c, "component_format");
                Prop(c, "file_format");
                ReportUnused(c);
            }
            else if (c.Tag == "sampler")
            {
                _used.Add(c);
                spp = (int)Float(c, "sample_count", 4);
                if (spp < 1) throw new InputException(c.Where, $"sample_count {spp} is below 1", "give at least one sample per pixel");
                if (c.Attr("type") is not ("independent" or "stratified" or "multijitter" or "ldsampler" or "orthogonal"))
                    Note("approximated", c, $"sampler '{c.Attr("type")}': ours is Owen-scrambled Sobol (path) with the same sample count");
                Prop(c, "seed");
                ReportUnused(c);
            }
        }
        double vertical = FovAxis(axis, fov, e, width, height);
        Prop(e, "near_clip");
        Prop(e, "far_clip");
        Prop(e, "aperture_radius");
        Prop(e, "focus_distance");
        if (Prop(e, "principal_point_offset_x") is { } px) Note("ignored", px, "a principal point offset: our camera is centred");
        if (Prop(e, "principal_point_offset_y") is { } py) Note("ignored", py, "a principal point offset: our camera is centred");
        ReportUnused(e);
        _camera = new JsonObject
        {
            ["position"] = Array3(position),
            ["look_at"] = Array3([position[0] + forward[0], position[1] + forward[1], position[2] + forward[2]]),
            ["up"] = Array3(up),
            ["fov"] = Round(vertical),
            ["width"] = width,
            ["height"] = height,
            ["spp"] = spp,
        };
    }

    /// <summary>
    /// Mitsuba's fov is along fov_axis (x by default; y, diagonal, smaller, larger); ours is vertical: tan(v/2) = tan(fov/2)·h/a,
    /// a the film's extent along that axis.
    /// </summary>
    static double FovAxis(string axis, double fov, MitsubaElement where, int width, int height)
    {
        double along = axis switch
        {
            "x" => width,
            "y" => height,
            "diagonal" => Math.Sqrt((double)width * width + (double)height * height),
            "smaller" => Math.Min(width, height),
            "larger" => Math.Max(width, height),
            _ => throw new InputException(where.Where, $"fov_axis {MessageText.Quote(axis)} is not x, y, diagonal, smaller or larger",
                InputException.DidYouMean(axis, ["x", "y", "diagonal", "smaller", "larger"]) ?? "use x, y, diagonal, smaller or larger"),
        };
        if (!(fov > 0 && fov < 180))
            throw new InputException(where.Where, $"fov {fov} is outside (0, 180) degrees", "give the field of view in degrees");
        return 2 * Math.Atan(Math.Tan(fov * Math.PI / 360) * height / along) * 180 / Math.PI;
    }

    double[] Transform(MitsubaElement t)
    {
        if (t.Tag != "transform")
            throw new InputException(t.Where, $"'{t.Attr("name")}' is a <{t.Tag}>, expected a <transform>",
                "e.g. <transform name=\"to_world\"> … </transform>");
        var m = MitsubaTransform.Of(t);
        if (Math.Abs(Determinant(m)) < 1e-18)
            throw new InputException(t.Where, "the transform is singular (a zero scale?)", "give a transform with three independent axes");
        return m;
    }

    void Integrator(MitsubaElement e)
    {
        var type = e.Attr("type");
        var inner = e;
        while (type is "aov" or "moment" && inner.Children.FirstOrDefault(c => c.Tag == "integrator") is { } nested)
        {
            Note("ignored", inner, $"the {type} wrapper: its nested integrator is converted");
            inner = nested;
            type = inner.Attr("type");
        }
        switch (type)
        {
            case "path" or "volpath" or "volpathmis" or "prb" or "ptracer":
                {
                    if (type != "path")
                        Note("approximated", inner, $"integrator '{type}' converted as our path tracer (unidirectional, NEE + MIS)");
                    int depth = (int)Float(inner, "max_depth", -1);
                    int rr = (int)Float(inner, "rr_depth", 5);
                    if (Boolean(inner, "hide_emitters", false)) Note("ignored", inner, "hide_emitters: emitters are seen directly");
                    var o = new JsonObject { ["type"] = "path" };
                    // Mitsuba counts the directly seen emitter as depth 1 (max_depth 2 = direct light); ours counts bounces.
                    if (depth >= 1) o["max_depth"] = depth - 1;
                    else if (depth == 0) Refuse(inner, "max_depth 0 renders nothing");
                    if (rr != 5) o["rr_depth"] = Math.Max(1, rr);
                    _integrator = o.Count == 1 ? "path" : o;
                    break;
                }
            case "direct":
                {
                    Prop(inner, "emitter_samples");
                    Prop(inner, "bsdf_samples");
                    if (Boolean(inner, "hide_emitters", false)) Note("ignored", inner, "hide_emitters: emitters are seen directly");
                    Note("converted", inner,
                        "direct illumination: our path tracer with max_depth 1 (one light sample and one BSDF sample per vertex, MIS)");
                    _integrator = new JsonObject { ["type"] = "path", ["max_depth"] = 1 };
                    break;
                }
            default:
                Note("approximated", inner, $"integrator '{type}' has no counterpart: rendered with our path tracer");
                _integrator = "path";
                return;
        }
        ReportUnused(inner);
    }
}
