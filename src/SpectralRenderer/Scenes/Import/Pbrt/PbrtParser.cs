using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>
/// Reads a pbrt-v4 scene file (pbrt.org/fileformat-v4) into a <see cref="PbrtDocument"/>: the directives in order, the
/// graphics state (the current transformation matrix, `AttributeBegin`/`End`, `ReverseOrientation`, the material and
/// area light in force), `Include`/`Import` (relative to the including file), named coordinate systems, and object
/// instancing (each `ObjectInstance` lists the object's shapes under the instance's transformation; the converter makes
/// the meshes among them instances of one prototype each).
/// What it reads but does not keep is passed to its <see cref="Note"/> (kind, where, element, action).
/// </summary>
public sealed class PbrtParser
{
    /// <summary>Include depth beyond which a file is taken to include itself.</summary>
    const int MaxIncludeDepth = 32;

    /// <summary>The most shapes instancing may produce (copies of an object's shapes), so a small file cannot explode.</summary>
    public const int MaxShapes = 1_000_000;

    public delegate void Note(string kind, string where, string element, string action);

    sealed class State
    {
        public PbrtTransform Ctm = PbrtTransform.Identity;
        public bool Reverse;
        public PbrtMaterialRef Material = PbrtMaterialRef.Default;
        public PbrtEntity? AreaLight;

        public State Copy() => (State)MemberwiseClone();
    }

    readonly PbrtDocument _doc = new();
    readonly Note _note;
    readonly Dictionary<string, PbrtTransform> _coordinateSystems = new(StringComparer.Ordinal);
    readonly Dictionary<string, List<PbrtShape>> _objects = new(StringComparer.Ordinal);
    readonly Stack<(State State, PbrtToken Token)> _stack = new();
    State _state = new();
    string? _object;
    List<PbrtShape>? _objectShapes;
    bool _world;
    int _copies;

    PbrtParser(Note note) => _note = note;

    public static PbrtDocument Parse(string path, Note note)
    {
        var parser = new PbrtParser(note);
        parser.ParseFile(path, null, 0);
        if (parser._object is not null)
            throw new InputException(path, $"ObjectBegin \"{parser._object}\" is not closed by ObjectEnd", "add ObjectEnd");
        if (parser._stack.Count > 0)
            throw new InputException(parser._stack.Peek().Token.Where, "AttributeBegin is not closed by AttributeEnd",
                "add AttributeEnd");
        return parser._doc;
    }

    /// <summary>Parses pbrt text from memory (tests, the fuzz target): includes resolve against <paramref name="path"/>'s folder.</summary>
    public static PbrtDocument ParseText(string text, string path, Note note)
    {
        var parser = new PbrtParser(note);
        parser.ParseTokens(PbrtTokenizer.Tokenize(text, Path.GetFileName(path)), path, 0);
        if (parser._object is not null)
            throw new InputException(path, $"ObjectBegin \"{parser._object}\" is not closed by ObjectEnd", "add ObjectEnd");
        if (parser._stack.Count > 0)
            throw new InputException(parser._stack.Peek().Token.Where, "AttributeBegin is not closed by AttributeEnd",
                "add AttributeEnd");
        return parser._doc;
    }

    void ParseFile(string path, PbrtToken? from, int depth)
    {
        if (depth > MaxIncludeDepth)
            throw new InputException(from!.Value.Where, $"includes nest deeper than {MaxIncludeDepth} files",
                "does a file include itself?");
        string text;
        try
        {
            text = InputFile.ReadAllText(path);
        }
        catch (InputException e) when (from is { } f)
        {
            throw new InputException(f.Where, $"{f.Text} {MessageText.Quote(Path.GetFileName(path))}: {e.What}", e.Hint)
            {
                Problem = e.Problem,
            };
        }
        ParseTokens(PbrtTokenizer.Tokenize(text, Path.GetFileName(path)), path, depth);
    }

    void ParseTokens(List<PbrtToken> tokens, string path, int depth)
    {
        int i = 0;
        while (i < tokens.Count)
        {
            var t = tokens[i++];
            if (t.Kind != PbrtTokenKind.Word || t.IsNumber)
                throw new InputException(t.Where, $"expected a directive, found {t.Quoted}",
                    "a statement starts with a directive such as Shape, Material or AttributeBegin");
            switch (t.Text)
            {
                case "Include":
                case "Import":
                    {
                        string file = StringArg(tokens, ref i, t);
                        string full =
                            Path.IsPathRooted(file) ? file : Path.Combine(Path.GetDirectoryName(Path.GetFullPath(path)) ?? ".", file);
                        ParseFile(full, t, depth + 1);
                        break;
                    }
                case "Identity": Apply(t, PbrtTransform.Identity, replace: true); break;
                case "Translate":
                    {
                        var v = Numbers(tokens, ref i, t, 3);
                        Apply(t, PbrtTransform.Translate(v[0], v[1], v[2]));
                        break;
                    }
                case "Scale":
                    {
                        var v = Numbers(tokens, ref i, t, 3);
                        Apply(t, PbrtTransform.Scale(v[0], v[1], v[2]));
                        break;
                    }
                case "Rotate":
                    {
                        var v = Numbers(tokens, ref i, t, 4);
                        Apply(t, PbrtTransform.Rotate(v[0], v[1], v[2], v[3]));
                        break;
                    }
                case "LookAt":
                    {
                        var v = Numbers(tokens, ref i, t, 9);
                        var m = PbrtTransform.LookAt(v.AsSpan(0, 3), v.AsSpan(3, 3), v.AsSpan(6, 3))
                            ?? throw new InputException(t.Where, "LookAt: the eye is the look-at point or the up vector is along the view",
                                "give an eye point, a different point to look at, and an up vector not parallel to the view");
                        Apply(t, m);
                        break;
                    }
                case "Transform":
                case "ConcatTransform":
                    {
                        var v = Numbers(tokens, ref i, t, 16);
                        var m = PbrtTransform.FromPbrtList(v);
                        if (!m.IsAffine)
                            throw new InputException(t.Where, $"{t.Text}: a projective matrix (its last column is not 0 0 0 1)",
                                "give an affine transformation: rotation, scale, shear and translation");
                        if (m.Inverse() is null)
                            throw new InputException(t.Where, $"{t.Text}: the matrix is singular", "give an invertible 4 × 4 matrix");
                        Apply(t, m, replace: t.Text == "Transform");
                        break;
                    }
                case "CoordinateSystem":
                    _coordinateSystems[StringArg(tokens, ref i, t)] = _state.Ctm;
                    break;
                case "CoordSysTransform":
                    {
                        string name = StringArg(tokens, ref i, t);
                        if (!_coordinateSystems.TryGetValue(name, out var m))
                            throw new InputException(t.Where,
                                $"CoordSysTransform: unknown coordinate system \"{MessageText.Escape(name)}\"",
                                InputException.DidYouMean(name, _coordinateSystems.Keys)
                                    ?? "name it first with CoordinateSystem (or use \"camera\" after Camera)");
                        _state.Ctm = m;
                        break;
                    }
                case "TransformBegin":
                    _note("ignored", t.Where, "TransformBegin", "deprecated in pbrt-v4; read as AttributeBegin");
                    _stack.Push((_state.Copy(), t));
                    break;
                case "TransformEnd":
                case "AttributeEnd":
                    if (_stack.Count == 0)
                        throw new InputException(t.Where, $"{t.Text} without a matching begin", "remove it or add AttributeBegin before");
                    var restored = _stack.Pop().State;
                    if (t.Text == "TransformEnd") _state.Ctm = restored.Ctm;
                    else _state = restored;
                    break;
                case "AttributeBegin":
                    _stack.Push((_state.Copy(), t));
                    break;
                case "ReverseOrientation": _state.Reverse = !_state.Reverse; break;
                case "ActiveTransform":
                    {
                        var w = Next(tokens, ref i, t, "All, StartTime or EndTime");
                        if (w.Text != "All")
                            _note("ignored", t.Where, $"ActiveTransform {w.Text}",
                                "motion blur is not rendered; the transformations apply at all times");
                        break;
                    }
                case "TransformTimes":
                    Numbers(tokens, ref i, t, 2);
                    _note("ignored", t.Where, "TransformTimes", "motion blur is not rendered");
                    break;
                case "WorldBegin":
                    if (_world) throw new InputException(t.Where, "a second WorldBegin", "a file has one WorldBegin");
                    _world = true;
                    _state.Ctm = PbrtTransform.Identity;
                    _coordinateSystems["world"] = PbrtTransform.Identity;
                    break;
                case "WorldEnd":
                    _note("ignored", t.Where, "WorldEnd", "pbrt-v3 syntax, not needed in pbrt-v4");
                    break;
                case "Camera":
                    {
                        var e = Entity(tokens, ref i, t);
                        if (_world) throw new InputException(t.Where, "Camera after WorldBegin", "declare the camera before WorldBegin");
                        _doc.Camera = e;
                        _doc.CameraFromWorld = _state.Ctm;
                        _coordinateSystems["camera"] = _state.Ctm.Inverse()
                            ?? throw new InputException(t.Where, "the camera's transformation is singular",
                                "check the Scale before Camera");
                        break;
                    }
                case "Film": _doc.Film = Options(tokens, ref i, t); break;
                case "Sampler": _doc.Sampler = Options(tokens, ref i, t); break;
                case "Integrator": _doc.Integrator = Options(tokens, ref i, t); break;
                case "PixelFilter":
                case "Accelerator":
                case "ColorSpace":
                    {
                        var e = Options(tokens, ref i, t);
                        _note("ignored", t.Where, $"{t.Text} \"{e.Type}\"", t.Text switch
                        {
                            "PixelFilter" => "our film uses a box filter over each pixel",
                            "Accelerator" => "our BVH is built its own way",
                            _ => "colours are read as linear sRGB (pbrt's default colour space)",
                        });
                        break;
                    }
                case "Option":
                    {
                        var p = ParameterList(tokens, ref i);
                        foreach (var o in p.All) _note("ignored", o.Where, $"Option \"{o.Name}\"", "a pbrt rendering option");
                        break;
                    }
                case "Attribute":
                    {
                        StringArg(tokens, ref i, t);
                        var p = ParameterList(tokens, ref i);
                        if (p.All.Count > 0)
                            _note("ignored", t.Where, "Attribute",
                                "default parameters by Attribute are not applied; give them on each directive");
                        break;
                    }
                case "Material":
                    {
                        var e = Entity(tokens, ref i, t);
                        _doc.Materials.Add(e);
                        _state.Material = new(_doc.Materials.Count - 1, null, t);
                        break;
                    }
                case "MakeNamedMaterial":
                    {
                        string name = StringArg(tokens, ref i, t);
                        var p = ParameterList(tokens, ref i);
                        var type = p.String("type")
                            ?? throw new InputException(t.Where, $"MakeNamedMaterial \"{MessageText.Escape(name)}\" has no \"string type\"",
                                "add e.g. \"string type\" \"diffuse\"");
                        if (_doc.NamedMaterials.ContainsKey(name))
                            throw new InputException(t.Where, $"the material \"{MessageText.Escape(name)}\" is defined twice",
                                "give each named material its own name");
                        _doc.NamedMaterials[name] = new(type, p, t);
                        break;
                    }
                case "NamedMaterial":
                    _state.Material = new(-1, StringArg(tokens, ref i, t), t);
                    break;
                case "Texture":
                    {
                        string name = StringArg(tokens, ref i, t);
                        string valueType = StringArg(tokens, ref i, t);
                        var e = Entity(tokens, ref i, t);
                        if (valueType is not ("spectrum" or "float"))
                            throw new InputException(t.Where, $"texture \"{MessageText.Escape(name)}\" has the value type "
                                + $"\"{MessageText.Escape(valueType)}\"", "pbrt-v4 textures are \"spectrum\" or \"float\"");
                        if (_doc.Textures.ContainsKey(name))
                            throw new InputException(t.Where, $"the texture \"{MessageText.Escape(name)}\" is defined twice",
                                "give each texture its own name");
                        _doc.Textures[name] = new(name, valueType, e);
                        break;
                    }
                case "LightSource":
                    _doc.Lights.Add(new(Entity(tokens, ref i, t), _state.Ctm));
                    break;
                case "AreaLightSource":
                    _state.AreaLight = Entity(tokens, ref i, t);
                    break;
                case "Shape":
                    {
                        var e = Entity(tokens, ref i, t);
                        var shape = new PbrtShape(e, _state.Ctm, _state.Material, _state.AreaLight, _state.Reverse, null, 0);
                        if (_objectShapes is not null)
                        {
                            if (_state.AreaLight is not null)
                                _note("ignored", t.Where, "AreaLightSource in ObjectBegin", "pbrt-v4 does not make instanced shapes emit");
                            _objectShapes.Add(shape with { AreaLight = null });
                        }
                        else Add(shape);
                        break;
                    }
                case "ObjectBegin":
                    {
                        string name = StringArg(tokens, ref i, t);
                        if (_object is not null)
                            throw new InputException(t.Where,
                                $"ObjectBegin \"{MessageText.Escape(name)}\" inside ObjectBegin \"{_object}\"",
                                "close the first object with ObjectEnd");
                        if (_objects.ContainsKey(name))
                            throw new InputException(t.Where, $"the object \"{MessageText.Escape(name)}\" is defined twice",
                                "give each object its own name");
                        _object = name;
                        _objectShapes = [];
                        _objects[name] = _objectShapes;
                        _stack.Push((_state.Copy(), t));
                        break;
                    }
                case "ObjectEnd":
                    if (_object is null) throw new InputException(t.Where, "ObjectEnd without ObjectBegin", "remove it");
                    _object = null;
                    _objectShapes = null;
                    _state = _stack.Pop().State;
                    break;
                case "ObjectInstance":
                    {
                        string name = StringArg(tokens, ref i, t);
                        if (!_objects.TryGetValue(name, out var shapes) || _object == name)
                            throw new InputException(t.Where, $"ObjectInstance of an unknown object \"{MessageText.Escape(name)}\"",
                                InputException.DidYouMean(name, _objects.Keys) ?? "define it first with ObjectBegin … ObjectEnd");
                        if (_object is not null)
                            throw new InputException(t.Where, "ObjectInstance inside ObjectBegin", "pbrt-v4 does not nest instances");
                        _copies++;
                        _doc.InstancedObjects.Add(name);
                        foreach (var s in shapes)
                            Add(s with { WorldFromObject = _state.Ctm * s.WorldFromObject, Instance = name, InstanceCopy = _copies });
                        break;
                    }
                case "MakeNamedMedium":
                    {
                        string name = StringArg(tokens, ref i, t);
                        ParameterList(tokens, ref i);
                        _note("error", t.Where, $"MakeNamedMedium \"{name}\"",
                            "participating media are not imported (the engine registers no medium type yet)");
                        break;
                    }
                case "MediumInterface":
                    {
                        var a = StringArg(tokens, ref i, t);
                        string b = a;
                        if (i < tokens.Count && tokens[i].Kind == PbrtTokenKind.String) b = tokens[i++].Text;
                        if (a.Length > 0 || b.Length > 0)
                            _note("ignored", t.Where, "MediumInterface", "no media are imported; the surface is a plain boundary");
                        break;
                    }
                default:
                    throw new InputException(t.Where, $"unknown directive {t.Quoted}",
                        InputException.DidYouMean(t.Text, Directives) ?? "see pbrt.org/fileformat-v4");
            }
        }
    }

    static readonly string[] Directives =
    [
        "Include", "Import", "Identity", "Translate", "Scale", "Rotate", "LookAt", "Transform", "ConcatTransform",
        "CoordinateSystem", "CoordSysTransform", "TransformBegin", "TransformEnd", "AttributeBegin", "AttributeEnd",
        "ReverseOrientation", "ActiveTransform", "TransformTimes", "WorldBegin", "WorldEnd", "Camera", "Film", "Sampler",
        "Integrator", "PixelFilter", "Accelerator", "ColorSpace", "Option", "Attribute", "Material", "MakeNamedMaterial",
        "NamedMaterial", "Texture", "LightSource", "AreaLightSource", "Shape", "ObjectBegin", "ObjectEnd", "ObjectInstance",
        "MakeNamedMedium", "MediumInterface",
    ];

    void Add(PbrtShape shape)
    {
        if (_doc.Shapes.Count >= MaxShapes)
            throw new InputException(shape.Entity.Where, $"more than {MaxShapes} shapes after instancing",
                "each instance adds its object's shapes to the scene (meshes as instances, not copies); use fewer instances");
        _doc.Shapes.Add(shape);
    }

    void Apply(PbrtToken t, PbrtTransform m, bool replace = false)
    {
        _state.Ctm = replace ? m : _state.Ctm * m;
        if (!IsFinite(_state.Ctm))
            throw new InputException(t.Where, $"{t.Text}: the transformation is no longer finite", "check the numbers");
    }

    static bool IsFinite(PbrtTransform m)
    {
        foreach (double v in m.RowMajor)
            if (!double.IsFinite(v)) return false;
        return true;
    }

    PbrtEntity Options(List<PbrtToken> tokens, ref int i, PbrtToken t) => Entity(tokens, ref i, t);

    PbrtEntity Entity(List<PbrtToken> tokens, ref int i, PbrtToken t)
    {
        string type = StringArg(tokens, ref i, t);
        return new(type, ParameterList(tokens, ref i), t);
    }

    static PbrtToken Next(List<PbrtToken> tokens, ref int i, PbrtToken directive, string expected)
    {
        if (i >= tokens.Count)
            throw new InputException(directive.Where, $"{directive.Text} ends the file before its {expected}", $"add the {expected}");
        return tokens[i++];
    }

    static string StringArg(List<PbrtToken> tokens, ref int i, PbrtToken directive)
    {
        var t = Next(tokens, ref i, directive, "quoted name");
        if (t.Kind != PbrtTokenKind.String)
            throw new InputException(t.Where, $"{directive.Text} expects a quoted name, found {t.Quoted}",
                $"e.g. {directive.Text} \"name\"");
        return t.Text;
    }

    static double[] Numbers(List<PbrtToken> tokens, ref int i, PbrtToken directive, int count)
    {
        bool bracket = i < tokens.Count && tokens[i].Kind == PbrtTokenKind.OpenBracket;
        if (bracket) i++;
        var v = new double[count];
        for (int k = 0; k < count; k++)
        {
            var t = Next(tokens, ref i, directive, $"{count} numbers");
            if (!t.TryNumber(out v[k]))
                throw new InputException(t.Where, $"{directive.Text} expects {count} numbers, found {t.Quoted} as number {k + 1}",
                    $"{directive.Text} takes exactly {count} numbers");
        }
        if (bracket && Next(tokens, ref i, directive, "closing bracket").Kind != PbrtTokenKind.CloseBracket)
            throw new InputException(tokens[i - 1].Where, $"{directive.Text} expects {count} numbers and then ']'",
                $"{directive.Text} takes exactly {count} numbers");
        return v;
    }

    /// <summary>`"type name" value` pairs up to the next directive.</summary>
    static PbrtParameters ParameterList(List<PbrtToken> tokens, ref int i)
    {
        var list = new List<PbrtParameter>();
        while (i < tokens.Count && tokens[i].Kind == PbrtTokenKind.String)
        {
            var decl = tokens[i++];
            var parts = decl.Text.Split((char[]?)null, StringSplitOptions.RemoveEmptyEntries);
            if (parts.Length != 2)
                throw new InputException(decl.Where, $"a parameter should be declared as \"type name\", found {decl.Quoted}",
                    "e.g. \"float radius\" 1");
            string type =
                parts[0] switch { "point" => "point3", "vector" => "vector3", "normal3" => "normal", "color" => "rgb", _ => parts[0] };
            string name = parts[1];
            if (i >= tokens.Count)
                throw new InputException(decl.Where, $"the parameter \"{MessageText.Escape(decl.Text)}\" has no value",
                    "give its value after it");
            var values = new List<PbrtToken>();
            if (tokens[i].Kind == PbrtTokenKind.OpenBracket)
            {
                i++;
                while (true)
                {
                    if (i >= tokens.Count)
                        throw new InputException(decl.Where, $"the values of \"{MessageText.Escape(decl.Text)}\" are not closed by ']'",
                            "add ']'");
                    var v = tokens[i++];
                    if (v.Kind == PbrtTokenKind.CloseBracket) break;
                    if (v.Kind == PbrtTokenKind.OpenBracket)
                        throw new InputException(v.Where, "'[' inside a parameter's values", "close the values with ']'");
                    values.Add(v);
                }
            }
            else values.Add(tokens[i++]);
            list.Add(Parameter(type, name, decl, values));
        }
        return new PbrtParameters(list);
    }

    static PbrtParameter Parameter(string type, string name, PbrtToken decl, List<PbrtToken> values)
    {
        string label = $"\"{MessageText.Escape(decl.Text)}\"";
        bool spectrumText = type == "spectrum" && values.Count > 0 && values[0].Kind == PbrtTokenKind.String;
        if (PbrtParameters.IsNumeric(type) || (type == "spectrum" && !spectrumText))
        {
            var numbers = new double[values.Count];
            for (int k = 0; k < values.Count; k++)
                if (!values[k].TryNumber(out numbers[k]))
                    throw new InputException(values[k].Where, $"{label} expects numbers, found {values[k].Quoted}",
                        "write numbers without quotes, e.g. [ 0.5 0.5 0.5 ]");
            return new() { Type = type, Name = name, Token = decl, Numbers = numbers };
        }
        if (type == "bool")
        {
            var bools = new bool[values.Count];
            for (int k = 0; k < values.Count; k++)
                bools[k] = values[k].Text switch
                {
                    "true" => true,
                    "false" => false,
                    _ => throw new InputException(values[k].Where, $"{label} expects true or false, found {values[k].Quoted}",
                        "e.g. \"bool twosided\" true"),
                };
            return new() { Type = type, Name = name, Token = decl, Bools = bools };
        }
        if (type is "string" or "texture" or "spectrum")
        {
            foreach (var v in values)
                if (v.Kind != PbrtTokenKind.String)
                    throw new InputException(v.Where, $"{label} expects quoted strings, found {v.Quoted}",
                        "put the value in double quotes");
            return new() { Type = type, Name = name, Token = decl, Strings = values.Select(v => v.Text).ToArray() };
        }
        throw new InputException(decl.Where, $"unknown parameter type \"{MessageText.Escape(type)}\"",
            InputException.DidYouMean(type, Types) ?? "see pbrt.org/fileformat-v4");
    }

    static readonly string[] Types =
        ["float", "integer", "point2", "vector2", "point3", "vector3", "normal", "rgb", "blackbody", "spectrum", "bool", "string",
            "texture"];
}
