using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using static SpectralRenderer.Scenes.Import.Mitsuba.MitsubaTransform;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

// Shapes: Mitsuba's canonical shapes placed by to_world, written as our objects with a "transform": { "matrix" }.
public sealed partial class MitsubaConverter
{
    // A shapegroup's members are converted where an instance names it, under the instance's to_world (_outer): an obj or ply
    // member once as a prototype (with its own to_world) and per instance an "instance" object of it (docs/scene-format.md,
    // "Instancing"); any other member (a sphere, a rectangle: a few numbers) is copied under the composed transformation.
    readonly Dictionary<MitsubaElement, string> _prototypeOf = [];
    readonly JsonObject _prototypes = [];
    double[]? _outer;
    string? _instanceName;

    void Shape(MitsubaElement e)
    {
        var type = e.Attr("type");
        var m = Prop(e, "to_world") is { } t ? Transform(t) : Identity;
        if (_outer is { } outer) m = Multiply(outer, m);
        var name = UniqueName(_instanceName is null ? e.Attr("id") ?? type ?? "shape" : $"{_instanceName}-{e.Attr("id") ?? type}");
        var o = new JsonObject { ["type"] = "", ["name"] = name };
        bool repeated = false;   // an instanced member: its notes and unused properties were reported with its prototype
        switch (type)
        {
            case "obj" or "ply" when _outer is not null:
                {
                    if (!_prototypeOf.TryGetValue(e, out var prototype))
                    {
                        var saved = (_outer, _instanceName);
                        (_outer, _instanceName) = (null, null);
                        int before = _objects.Count;
                        Shape(e);   // the member on its own, as a mesh object: its keys become the prototype's
                        (_outer, _instanceName) = saved;
                        if (_objects.Count == before) return;
                        prototype = Prototypes.TakeLast(_objects, _prototypes);
                        _prototypeOf[e] = prototype;
                    }
                    repeated = true;
                    o["type"] = "instance";
                    o["prototype"] = prototype;
                    Place(o, _outer);
                    break;
                }
            case "obj" or "ply":
                {
                    var file = String(e, "filename") ?? throw new InputException(e.Where, $"a {type} shape without filename",
                        "give <string name=\"filename\" value=\"mesh.ply\"/>");
                    if (!File.Exists(Path.Combine(_dir, file)) && !_options.ModelDirectories.Any(d => File.Exists(Path.Combine(d, file))))
                        throw new InputException(e.Where, $"mesh {MessageText.Quote(file)} not found",
                            "the path is relative to the scene file; or pass --models DIR")
                        { Problem = InputProblem.MissingFile };
                    o["type"] = "mesh";
                    o["file"] = file.Replace('\\', '/');
                    if (Boolean(e, "face_normals", false)) o["shading"] = "flat";
                    if (Boolean(e, "flip_normals", false))
                        Note("ignored", e, "flip_normals: the mesh's winding is kept (it matters for an emitting mesh)");
                    if (Boolean(e, "flip_tex_coords", true) is false)
                        Note("approximated", e, "flip_tex_coords false: texture coordinates are read as the file has them");
                    Place(o, m);
                    break;
                }
            case "rectangle":
                o["type"] = "quad";
                Place(o, Multiply(m, Scale(2, 2, 1)));   // Mitsuba's [−1, 1]², ours [−½, ½]²
                break;
            case "disk":
                o["type"] = "disk";
                Place(o, m);
                break;
            case "cube":
                o["type"] = "box";
                Place(o, Multiply(m, Scale(2, 2, 2)));   // Mitsuba's [−1, 1]³, ours [−½, ½]³
                break;
            case "sphere":
                {
                    var c = Point(e, "center") ?? [0, 0, 0];
                    double r = Float(e, "radius", 1);
                    if (!(r > 0)) throw new InputException(e.Where, $"sphere radius {r} is not positive", "give a radius above 0");
                    var placed = Multiply(m, Multiply(Translation(c), Scale(r, r, r)));
                    o["type"] = "sphere";
                    if (Similarity(placed) is { } s)
                    {
                        o["center"] = Array3(Apply(placed, [0, 0, 0], 1));
                        o["radius"] = Round(s);
                    }
                    else Place(o, placed);
                    break;
                }
            case "cylinder":
                {
                    var p0 = Point(e, "p0") ?? [0, 0, 0];
                    var p1 = Point(e, "p1") ?? [0, 0, 1];
                    double r = Float(e, "radius", 1);
                    o["type"] = "cylinder";
                    o["p0"] = Array3(p0);
                    o["p1"] = Array3(p1);
                    o["radius"] = Round(r);
                    Place(o, m);
                    break;
                }
            case "serialized":
                Refuse(e, "a serialized mesh (Mitsuba's compressed format) is not read here; re-export it as PLY "
                    + "(Mitsuba: mi.load_dict({'type': 'serialized', …}).write_ply('mesh.ply'), or Blender's PLY export)");
                return;
            case "shapegroup":
                if (_outer is not null) Refuse(e, "a shapegroup inside a shapegroup (Mitsuba does not nest them)");
                return;   // declared: its members are converted where an instance names it
            case "instance":
                Instance(e, m, name);
                return;
            default:
                Refuse(e, $"the shape '{type}' has no counterpart");
                return;
        }
        MitsubaElement? bsdf = null, emitter = null;
        foreach (var c in e.Children)
        {
            if (c.Tag is not ("bsdf" or "emitter" or "medium" or "ref")) continue;
            var target = Resolve(c);
            _used.Add(c);
            switch (target.Tag)
            {
                case "bsdf": bsdf = target; break;
                case "emitter": emitter = target; break;
                case "medium": Refuse(c, "a participating medium has no counterpart yet (issue 41)"); break;
                default:
                    throw new InputException(c.Where, $"a <{target.Tag}> inside a shape",
                        "a shape holds a bsdf, an emitter and its to_world");
            }
        }
        var material = bsdf is null ? DefaultMaterial() : Material(bsdf);
        if (emitter is not null)
        {
            _used.Add(emitter);
            if (emitter.Attr("type") != "area")
                Refuse(emitter, $"a '{emitter.Attr("type")}' emitter inside a shape: only area emitters are");
            else
            {
                var radiance = Spectrum(emitter, "radiance", 1.0, true)!;
                ReportUnused(emitter);
                // Emission belongs to our material: the shape's BSDF and this radiance, one material per emitting shape.
                var emitting = (JsonObject)_materials[material]!.DeepClone();
                emitting["emission"] = new JsonObject { ["spectrum"] = radiance, ["radiance"] = 1 };
                material = UniqueName($"{name}-emitter");
                _materials[material] = emitting;
                Note("converted", emitter, "an area emitter: the shape's material emits radiance × 1 W·m⁻²·sr⁻¹·nm⁻¹ on its front side");
            }
        }
        o["material"] = material;
        if (!repeated) ReportUnused(e);
        _objects.Add((JsonNode)o);
    }

    /// <summary>&lt;shape type="instance"&gt; with a reference to a shapegroup and its to_world: the group's members placed by
    /// it.</summary>
    void Instance(MitsubaElement e, double[] m, string name)
    {
        if (_outer is not null) { Refuse(e, "an instance inside a shapegroup (Mitsuba does not nest them)"); return; }
        MitsubaElement? group = null;
        foreach (var c in e.Children)
            if (c.Tag is "ref" or "shape")
            {
                var target = Resolve(c);
                _used.Add(c);
                if (target.Tag != "shape" || target.Attr("type") != "shapegroup")
                    throw new InputException(c.Where, $"an instance of a <{target.Tag} type=\"{target.Attr("type")}\">",
                        "an instance refers to a <shape type=\"shapegroup\" id=\"…\"> by <ref id=\"…\"/>");
                group = target;
            }
        if (group is null)
            throw new InputException(e.Where, "an instance without a shapegroup", "add <ref id=\"GROUP\"/> naming a shapegroup");
        ReportUnused(e);
        (_outer, _instanceName) = (m, name);
        try
        {
            foreach (var member in group.Children)
                if (member.Tag == "shape") { _used.Add(member); Shape(member); }
        }
        finally { (_outer, _instanceName) = (null, null); }
    }

    /// <summary>The object's "transform": { "matrix" } unless the identity.</summary>
    static void Place(JsonObject o, double[] m)
    {
        bool identity = true;
        var id = Identity;
        for (int i = 0; i < 16; i++) identity &= Math.Abs(m[i] - id[i]) < 1e-12;
        if (identity) return;
        o["transform"] = new JsonObject { ["matrix"] = new JsonArray([.. m.Select(v => (JsonNode)JsonValue.Create(Round(v)))]) };
    }

    /// <summary>The common scale of a similarity (orthogonal columns of equal length), or null.</summary>
    static double? Similarity(double[] m)
    {
        double[] a = [m[0], m[4], m[8]], b = [m[1], m[5], m[9]], c = [m[2], m[6], m[10]];
        double la = Math.Sqrt(Dot(a, a)), lb = Math.Sqrt(Dot(b, b)), lc = Math.Sqrt(Dot(c, c));
        double tol = 1e-9 * la;
        if (Math.Abs(la - lb) > tol || Math.Abs(la - lc) > tol) return null;
        if (Math.Abs(Dot(a, b)) > tol * la || Math.Abs(Dot(a, c)) > tol * la || Math.Abs(Dot(b, c)) > tol * la) return null;
        return la;
    }

    static double[] Scale(double x, double y, double z) => [x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0, 0, 0, 0, 1];
    static double[] Translation(double[] t) => [1, 0, 0, t[0], 0, 1, 0, t[1], 0, 0, 1, t[2], 0, 0, 0, 1];
}
