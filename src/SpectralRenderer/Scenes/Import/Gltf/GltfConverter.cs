using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Gltf;

/// <summary>
/// A glTF 2.0 asset as our scene (docs/import.md "glTF 2.0"): the default scene's node hierarchy walked from its roots, each
/// node's world matrix the product of its ancestors' local matrices (a node's "matrix", or T·R·S from "translation",
/// "rotation" and "scale", §3.5.3); each triangle primitive of a node's mesh one of our mesh objects (inline, in the
/// mesh's own coordinates, placed by "transform": { "matrix" }; a mesh used by several nodes a prototype and an instance
/// per node); the first perspective camera met; KHR_lights_punctual
/// lights in candela and lux; materials in GltfConverter.Materials.cs. glTF is in metres, +Y up, right-handed, a camera
/// looking down its −Z: our scene's own conventions, so coordinates are taken as they are.
/// </summary>
sealed partial class GltfConverter(GltfDocument doc, ImportOptions options)
{
    /// <summary>The bands of an imported scene (5 nm, as the Mitsuba importer's).</summary>
    const string Bands = "380:780:80";
    const int DefaultHeight = 480;

    readonly ImportReport _report = new(doc.Path, "gltf");
    readonly JsonObject _materials = [];
    readonly JsonArray _lights = [];
    readonly JsonArray _objects = [];
    readonly List<ImportedMesh> _meshes = [];
    readonly HashSet<string> _names = new(StringComparer.Ordinal);
    readonly HashSet<int> _visited = [];
    JsonObject? _camera;
    string? _cameraPath;
    double[]? _boundsMin, _boundsMax;

    public ImportedScene Convert()
    {
        var root = doc.Root;
        Asset();
        Extensions();
        int sceneCount = doc.Count("scenes");
        if (sceneCount == 0)
            throw doc.Error("$", "the asset has no \"scenes\": nothing to render",
                "export the scene (not only its meshes or materials) to glTF");
        int scene = GltfDocument.Has(root, "scene", out _) ? doc.Index(root, "scene", "$", "scenes") : 0;
        if (sceneCount > 1)
            Note("ignored", "$.scenes", "scenes",
                $"{sceneCount - 1} scene(s) other than the default scene {scene} are not converted");
        var s = doc.Item("scenes", scene);
        var nodes = doc.Array(s, "nodes", $"$.scenes[{scene}]");
        if (nodes.ValueKind == JsonValueKind.Array)
            for (int i = 0; i < nodes.GetArrayLength(); i++)
            {
                var at = $"$.scenes[{scene}].nodes[{i}]";
                if (nodes[i].ValueKind != JsonValueKind.Number || !nodes[i].TryGetInt32(out int n) || n < 0 || n >= doc.Count("nodes"))
                    throw doc.Error(at, $"{nodes[i].GetRawText()} is not an index into \"nodes\" ({doc.Count("nodes")} elements)",
                        "a scene lists its root nodes by index");
                Node(n, Affine.Identity, at);
            }
        if (_objects.Count == 0)
            throw doc.Error($"$.scenes[{scene}]", "the scene holds no triangle mesh",
                "export the geometry with the scene (mesh primitives in triangle mode)");
        var camera = _camera ?? DefaultCamera();
        var result = new JsonObject
        {
            ["name"] = Path.GetFileName(doc.Path),
            ["description"] = $"imported from glTF 2.0 by spectral import ({Path.GetFileName(doc.Path)})",
            ["bands"] = Bands,
            ["radiometry"] = "physical",
            ["integrator"] = "path",
            // glTF's lights are photometric (cd, lx, cd/m²): Y in cd/m² (κ = 683 lm/W), the preview exposed automatically.
            ["scaling"] = "absolute",
            ["output"] = new JsonObject { ["exposure"] = "auto" },
            ["camera"] = camera,
            ["materials"] = _materials,
            ["lights"] = _lights,
            ["objects"] = _objects,
        };
        if (_prototypes.Count > 0) result.Insert(result.Count - 1, "prototypes", _prototypes);
        foreach (var n in _notes.Select((n, i) => (n, i)).OrderBy(x => x.n.Path, new DocumentOrder(doc.Root)).ThenBy(x => x.i))
            _report.Add(n.n.Kind, doc.Where(n.n.Path), n.n.Element, n.n.Action);
        return new ImportedScene(result, _report, _meshes);
    }

    readonly List<(string Kind, string Path, string Element, string Action)> _notes = [];

    /// <summary>A report entry at a JSON path; the report lists them in document order (Convert sorts them at the end).</summary>
    void Note(string kind, string where, string element, string action) => _notes.Add((kind, where, element, action));

    /// <summary>JSON paths in the order of the file: top-level keys as the file lists them, then each step by its index or
    /// name (a path before the paths below it).</summary>
    sealed class DocumentOrder(JsonElement root) : IComparer<string>
    {
        readonly List<string> _keys = root.EnumerateObject().Select(p => p.Name).ToList();

        static List<string> Steps(string path) =>
            [.. path.TrimStart('$').Replace("[", ".[", StringComparison.Ordinal).Split('.', StringSplitOptions.RemoveEmptyEntries)];

        public int Compare(string? a, string? b)
        {
            var x = Steps(a ?? "");
            var y = Steps(b ?? "");
            for (int i = 0; i < Math.Min(x.Count, y.Count); i++)
            {
                int c = i == 0 ? _keys.IndexOf(x[i]).CompareTo(_keys.IndexOf(y[i])) : Step(x[i], y[i]);
                if (c != 0) return c;
            }
            return x.Count.CompareTo(y.Count);
        }

        static int Step(string a, string b) =>
            a.StartsWith('[') && b.StartsWith('[') && int.TryParse(a.AsSpan(1, a.Length - 2), out int i)
                && int.TryParse(b.AsSpan(1, b.Length - 2), out int j)
                ? i.CompareTo(j)
                : string.CompareOrdinal(a, b);
    }

    void Asset()
    {
        if (!GltfDocument.Has(doc.Root, "asset", out var asset))
            throw doc.Error("$", "missing \"asset\"", "every glTF file has \"asset\": { \"version\": \"2.0\" }");
        doc.Object(asset, "$.asset");
        var version = doc.String(asset, "version", "$.asset") ?? throw doc.Error("$.asset", "missing \"version\"", "\"version\": \"2.0\"");
        var min = doc.String(asset, "minVersion", "$.asset");
        if (!version.StartsWith("2.", StringComparison.Ordinal) || (min is not null && min != "2.0"))
            throw doc.Error("$.asset.version", $"glTF version {MessageText.Quote(min ?? version)} is not supported",
                "export as glTF 2.0 (glTF 1.0 files need converting first)");
    }

    /// <summary>The extensions we read (docs/import.md); any other in "extensionsUsed" is reported, in "extensionsRequired"
    /// an error (the file says it cannot be shown without it) unless --lenient.</summary>
    static readonly string[] Supported =
    [
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission",
        "KHR_materials_dispersion", "KHR_materials_specular", "KHR_materials_volume", "KHR_texture_transform",
    ];

    void Extensions()
    {
        var required = doc.Array(doc.Root, "extensionsRequired", "$");
        var requiredNames = new HashSet<string>(StringComparer.Ordinal);
        if (required.ValueKind == JsonValueKind.Array)
            for (int i = 0; i < required.GetArrayLength(); i++)
            {
                var name = required[i].ValueKind == JsonValueKind.String ? required[i].GetString()! : required[i].GetRawText();
                requiredNames.Add(name);
                if (Array.IndexOf(Supported, name) < 0)
                    Fail($"$.extensionsRequired[{i}]", $"extension {name}",
                        $"the file requires the extension {name}, which we do not read");
            }
        var used = doc.Array(doc.Root, "extensionsUsed", "$");
        if (used.ValueKind == JsonValueKind.Array)
            for (int i = 0; i < used.GetArrayLength(); i++)
            {
                var name = used[i].ValueKind == JsonValueKind.String ? used[i].GetString()! : used[i].GetRawText();
                if (Array.IndexOf(Supported, name) < 0 && !requiredNames.Contains(name))
                    Note("ignored", $"$.extensionsUsed[{i}]", $"extension {name}",
                        "not read: what it adds is not converted");
            }
    }

    /// <summary>An element that would change the picture materially and has no counterpart: an error (one line, exit 2)
    /// unless --lenient, when it is reported and skipped.</summary>
    void Fail(string path, string element, string what)
    {
        if (!options.Lenient)
            throw doc.Error(path, what, "convert it in the authoring tool, or import with --lenient to skip it (reported)");
        Note("error", path, element, $"{what}; skipped (--lenient)");
    }

    // ---- the node hierarchy ----

    void Node(int n, double[] parent, string at)
    {
        var path = $"$.nodes[{n}]";
        if (!_visited.Add(n))
            throw doc.Error(at, $"node {n} appears twice in the hierarchy (or in a cycle)",
                "in glTF each node has at most one parent (§3.5.1)");
        var node = doc.Item("nodes", n);
        var world = Affine.Multiply(parent, LocalMatrix(node, path));
        int mesh = doc.Index(node, "mesh", path, "meshes");
        if (mesh >= 0) Mesh(mesh, world, path, doc.String(node, "name", path));
        int camera = doc.Index(node, "camera", path, "cameras");
        if (camera >= 0) Camera(camera, world, path);
        if (GltfDocument.Has(node, "extensions", out var ext) && GltfDocument.Has(ext, "KHR_lights_punctual", out var lp))
        {
            var lightPath = $"{path}.extensions.KHR_lights_punctual";
            Light(LightIndex(doc.Object(lp, lightPath), lightPath), world, lightPath);
        }
        if (GltfDocument.Has(node, "skin", out _))
            Note("ignored", $"{path}.skin", "skin", "the mesh is converted in its bind pose; skinning is not applied");
        if (GltfDocument.Has(node, "weights", out _))
            Note("ignored", $"{path}.weights", "morph weights", "the mesh is converted without its morph targets");
        var children = doc.Array(node, "children", path);
        if (children.ValueKind == JsonValueKind.Array)
            for (int i = 0; i < children.GetArrayLength(); i++)
            {
                var c = children[i];
                if (c.ValueKind != JsonValueKind.Number || !c.TryGetInt32(out int child) || child < 0 || child >= doc.Count("nodes"))
                    throw doc.Error($"{path}.children[{i}]",
                        $"{c.GetRawText()} is not an index into \"nodes\" ({doc.Count("nodes")} elements)",
                        "a node lists its children by index");
                Node(child, world, $"{path}.children[{i}]");
            }
    }

    /// <summary>The node's local matrix: "matrix" (16 numbers, column-major) or T·R·S (§3.5.3).</summary>
    double[] LocalMatrix(JsonElement node, string path)
    {
        bool trs = GltfDocument.Has(node, "translation", out _) || GltfDocument.Has(node, "rotation", out _)
            || GltfDocument.Has(node, "scale", out _);
        if (GltfDocument.Has(node, "matrix", out _))
        {
            if (trs) throw doc.Error(path, "a node has both \"matrix\" and translation/rotation/scale", "give one or the other (§3.5.3)");
            var c = doc.Numbers(node, "matrix", path, new double[16], -1e7, 1e7);
            var m = new double[16];
            for (int row = 0; row < 4; row++)
                for (int col = 0; col < 4; col++) m[4 * row + col] = c[4 * col + row];
            if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
                throw doc.Error($"{path}.matrix", "the matrix is not affine (its last row is not 0, 0, 0, 1)",
                    "glTF node matrices are affine transforms (§3.5.3)");
            return m;
        }
        var t = doc.Numbers(node, "translation", path, [0, 0, 0], -1e7, 1e7);
        var q = doc.Numbers(node, "rotation", path, [0, 0, 0, 1], -1, 1);
        var s = doc.Numbers(node, "scale", path, [1, 1, 1], -1e7, 1e7);
        double norm = Math.Sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (norm < 1e-6) throw doc.Error($"{path}.rotation", "the rotation quaternion has length 0", "a unit quaternion [x, y, z, w]");
        return Affine.Trs(t, [q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm], s);
    }

    int LightIndex(JsonElement lp, string path)
    {
        int count = Lights().ValueKind == JsonValueKind.Array ? Lights().GetArrayLength() : 0;
        if (!GltfDocument.Has(lp, "light", out var v))
            throw doc.Error(path, "missing \"light\"", "the index of a KHR_lights_punctual light");
        if (v.ValueKind != JsonValueKind.Number || !v.TryGetInt32(out int i) || i < 0 || i >= count)
            throw doc.Error($"{path}.light", $"{v.GetRawText()} is not an index into the KHR_lights_punctual lights ({count})",
                count == 0 ? "the file defines no lights in its root \"extensions\"" : $"give 0 to {count - 1}");
        return i;
    }

    JsonElement Lights() =>
        GltfDocument.Has(doc.Root, "extensions", out var e) && GltfDocument.Has(e, "KHR_lights_punctual", out var lp)
            ? doc.Array(doc.Object(lp, "$.extensions.KHR_lights_punctual"), "lights", "$.extensions.KHR_lights_punctual")
            : default;

    // ---- meshes ----

    void Mesh(int m, double[] world, string nodePath, string? nodeName)
    {
        var mesh = doc.Item("meshes", m);
        var path = $"$.meshes[{m}]";
        var primitives = doc.Array(mesh, "primitives", path);
        if (primitives.ValueKind != JsonValueKind.Array || primitives.GetArrayLength() == 0)
            throw doc.Error(path, "a mesh without \"primitives\"", "a glTF mesh has at least one primitive (§3.7.2)");
        var baseName = SafeName(nodeName ?? doc.String(mesh, "name", path) ?? $"mesh{m}");   // the node is the object
        for (int k = 0; k < primitives.GetArrayLength(); k++)
        {
            var p = $"{path}.primitives[{k}]";
            if (_uses.TryGetValue((m, k), out var first))
            {
                Instance(first, world, nodeName is null ? first.Name : SafeName(nodeName), nodePath);
                continue;
            }
            var prim = doc.Object(primitives[k], p);
            var triangles = Primitive(prim, p);
            if (triangles is null) continue;
            if (doc.Index(prim, "material", p, "materials") is >= 0 and var cut && CutOut(cut))
            {
                Note("converted", p, "primitive of a cut-out material",
                    $"left out: material {cut}'s alpha mode MASK with a base alpha below its alphaCutoff and no texture cuts it all away");
                continue;
            }
            var name = Unique(primitives.GetArrayLength() > 1 ? $"{baseName}-{k}" : baseName);
            var (positions, indices, normals, uvs) = triangles.Value;
            _meshes.Add(new ImportedMesh(name, positions, indices, normals, uvs));
            int material = doc.Index(prim, "material", p, "materials");
            var o = new JsonObject
            {
                ["type"] = "mesh",
                ["name"] = name,
                ["material"] = material >= 0 ? Material(material) : DefaultMaterial(),
            };
            if (normals is null)
            {
                o["shading"] = "flat";
                Note("converted", $"{p}.attributes", "primitive without NORMAL",
                    "shaded flat, as glTF 2.0 §3.7.2.1 asks");
            }
            if (!Affine.IsIdentity(world)) o["transform"] = new JsonObject { ["matrix"] = Affine.Json(world) };
            if (Affine.Determinant(world) < 0)
                Note("converted", nodePath, "mirroring transform",
                    "the node's matrix has a negative determinant: its triangles' front faces are reversed (§3.7.2.1)");
            o["inline"] = _meshes[^1].InlineJson();
            _objects.Add((JsonNode)o);
            _uses[(m, k)] = new(o, name, positions);
            Grow(positions, world);
        }
    }

    // A mesh referenced by several nodes (§3.5.1): its primitives become prototypes, each node's use an instance of them
    // placed by the node's world matrix (docs/scene-format.md, "Instancing"), not copies.
    readonly Dictionary<(int Mesh, int Primitive), PrimitiveUse> _uses = [];
    readonly JsonObject _prototypes = [];

    /// <summary>A primitive's first object (a mesh object until a second node uses it), its mesh's name, its positions.</summary>
    sealed record PrimitiveUse(JsonObject First, string Name, float[] Positions);

    /// <summary>A further use of a converted primitive: the first use's object turned into an instance of the primitive's
    /// prototype (once), and an instance for this use.</summary>
    void Instance(PrimitiveUse use, double[] world, string baseName, string nodePath)
    {
        var first = use.First;
        if (!_prototypes.ContainsKey(use.Name))
        {
            var prototype = new JsonObject();
            if (first["shading"] is { } shading) prototype["shading"] = shading.DeepClone();
            prototype["inline"] = first["inline"]!.DeepClone();
            _prototypes[use.Name] = prototype;
            first.Remove("inline");
            first.Remove("shading");
            first["type"] = "instance";
            first["prototype"] = use.Name;
        }
        var o = new JsonObject
        {
            ["type"] = "instance",
            ["name"] = Unique(baseName),
            ["prototype"] = use.Name,
            ["material"] = first["material"]!.DeepClone(),
        };
        if (!Affine.IsIdentity(world)) o["transform"] = new JsonObject { ["matrix"] = Affine.Json(world) };
        if (Affine.Determinant(world) < 0)
            Note("converted", nodePath, "mirroring transform",
                "the node's matrix has a negative determinant: its triangles' front faces are reversed (§3.7.2.1)");
        _objects.Add((JsonNode)o);
        Grow(use.Positions, world);
    }

    /// <summary>A primitive's triangles (positions, indices, normals, uvs with v = 1 − v_glTF), or null when it is not a surface.</summary>
    (float[], int[], float[]?, float[]?)? Primitive(JsonElement prim, string p)
    {
        int mode = (int)doc.Number(prim, "mode", p, 4, 0, 6);
        if (mode < 4)
        {
            Note("ignored", $"{p}.mode", $"primitive mode {mode}",
                $"{(mode == 0 ? "points" : "lines")} are not surfaces: not converted");
            return null;
        }
        if (GltfDocument.Has(prim, "extensions", out var ext) && ext.ValueKind == JsonValueKind.Object)
            foreach (var e in ext.EnumerateObject())
            {
                Fail($"{p}.extensions.{e.Name}", $"extension {e.Name}",
                    $"the primitive is compressed or extended by {e.Name}, which we do not read");
                return null;
            }
        if (!GltfDocument.Has(prim, "attributes", out var attributes))
            throw doc.Error(p, "missing \"attributes\"", "a primitive has at least POSITION");
        doc.Object(attributes, $"{p}.attributes");
        var a = $"{p}.attributes";
        int position = doc.Index(attributes, "POSITION", a, "accessors", required: true);
        var positions = doc.Floats(position, $"{a}.POSITION", "VEC3", [5126]);
        int vertices = positions.Length / 3;
        foreach (var v in positions)
            if (Math.Abs(v) > 1e7)
                throw doc.Error($"$.accessors[{position}]",
                    $"a position of {v.ToString("G4", CultureInfo.InvariantCulture)} m is beyond ±1e7",
                    "single-precision ray tracing keeps about 7 digits: scale the model");
        float[]? normals = null, uvs = null;
        int normal = doc.Index(attributes, "NORMAL", a, "accessors");
        if (normal >= 0)
        {
            normals = doc.Floats(normal, $"{a}.NORMAL", "VEC3", [5126]);
            if (normals.Length != positions.Length)
                throw doc.Error($"{a}.NORMAL", $"{normals.Length / 3} normals for {vertices} positions",
                    "every attribute has one element per vertex");
        }
        int uv = doc.Index(attributes, "TEXCOORD_0", a, "accessors");
        if (uv >= 0)
        {
            uvs = doc.Floats(uv, $"{a}.TEXCOORD_0", "VEC2", [5126, 5121, 5123]);
            if (uvs.Length / 2 != vertices)
                throw doc.Error($"{a}.TEXCOORD_0", $"{uvs.Length / 2} texture coordinates for {vertices} positions",
                    "every attribute has one element per vertex");
            for (int i = 1; i < uvs.Length; i += 2) uvs[i] = 1 - uvs[i];   // glTF's v runs down the image, ours up
        }
        foreach (var attribute in attributes.EnumerateObject())
            if (attribute.Name is not ("POSITION" or "NORMAL" or "TEXCOORD_0"))
                Note("ignored", $"{a}.{attribute.Name}", $"attribute {attribute.Name}",
                    attribute.Name.StartsWith("COLOR_", StringComparison.Ordinal)
                        ? "vertex colours are not applied to the base colour"
                        : "not used by our meshes");
        if (GltfDocument.Has(prim, "targets", out _))
            Note("ignored", $"{p}.targets", "morph targets", "the mesh is converted without them");
        int indexAccessor = doc.Index(prim, "indices", p, "accessors");
        int[] list = indexAccessor >= 0 ? doc.Indices(indexAccessor, $"{p}.indices", vertices) : [.. Enumerable.Range(0, vertices)];
        int[] triangles;
        switch (mode)
        {
            case 4:
                if (list.Length % 3 != 0)
                    throw doc.Error(indexAccessor >= 0 ? $"{p}.indices" : $"{a}.POSITION",
                        $"{list.Length} vertices do not make whole triangles", "triangle mode takes three indices per triangle");
                triangles = list;
                break;
            case 5:   // strip: triangle i is (i, i+1, i+2), every other one reversed to keep the winding (§3.7.2.1)
                triangles = new int[Math.Max(0, list.Length - 2) * 3];
                for (int i = 0; i + 2 < list.Length; i++)
                {
                    bool even = i % 2 == 0;
                    (triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]) =
                        even ? (list[i], list[i + 1], list[i + 2]) : (list[i + 1], list[i], list[i + 2]);
                }
                Note("converted", $"{p}.mode", "triangle strip", "converted to a list of triangles");
                break;
            default:  // fan: triangle i is (i+1, i+2, 0)
                triangles = new int[Math.Max(0, list.Length - 2) * 3];
                for (int i = 0; i + 2 < list.Length; i++)
                    (triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]) = (list[i + 1], list[i + 2], list[0]);
                Note("converted", $"{p}.mode", "triangle fan", "converted to a list of triangles");
                break;
        }
        if (triangles.Length == 0)
        {
            Note("ignored", p, "empty primitive", "it has no triangle");
            return null;
        }
        return (positions, triangles, normals, uvs);
    }

    /// <summary>Letters, digits, '-' and '_' only (a file name for the PLY written beside the scene).</summary>
    static string SafeName(string name)
    {
        var b = new StringBuilder();
        foreach (char c in name.Trim()) b.Append(char.IsAsciiLetterOrDigit(c) || c is '-' or '_' ? c : '_');
        var s = b.ToString().Trim('_');
        return s.Length == 0 ? "mesh" : s.Length > 64 ? s[..64] : s;
    }

    string Unique(string name)
    {
        var n = name;
        for (int i = 2; !_names.Add(n); i++) n = $"{name}-{i}";
        return n;
    }

    void Grow(float[] positions, double[] world)
    {
        _boundsMin ??= [double.MaxValue, double.MaxValue, double.MaxValue];
        _boundsMax ??= [double.MinValue, double.MinValue, double.MinValue];
        for (int i = 0; i < positions.Length; i += 3)
        {
            var p = Affine.Point(world, positions[i], positions[i + 1], positions[i + 2]);
            for (int c = 0; c < 3; c++)
            {
                _boundsMin[c] = Math.Min(_boundsMin[c], p[c]);
                _boundsMax[c] = Math.Max(_boundsMax[c], p[c]);
            }
        }
    }

    // ---- cameras (§3.10) ----

    void Camera(int c, double[] world, string nodePath)
    {
        var path = $"$.cameras[{c}]";
        if (_camera is not null)
        {
            Note("ignored", nodePath, $"camera {c}", $"the first camera met ({_cameraPath}) is the one rendered");
            return;
        }
        var camera = doc.Item("cameras", c);
        var type = doc.String(camera, "type", path);
        if (type != "perspective")
        {
            Fail($"{path}.type", $"{type ?? "untyped"} camera",
                $"a{(type == "orthographic" ? "n orthographic" : $" {MessageText.Quote(type ?? "missing")}")} camera has no counterpart "
                    + "(our camera is a pinhole)");
            return;
        }
        if (!GltfDocument.Has(camera, "perspective", out var p))
            throw doc.Error(path, "missing \"perspective\"", "a perspective camera gives its yfov");
        doc.Object(p, $"{path}.perspective");
        double yfov = doc.Number(p, "yfov", $"{path}.perspective", -1, 1e-6, Math.PI - 1e-6);
        if (yfov < 0) throw doc.Error($"{path}.perspective", "missing \"yfov\"", "the vertical field of view in radians");
        double aspect = doc.Number(p, "aspectRatio", $"{path}.perspective", 0, 1e-3, 1e3);
        int height = DefaultHeight, width = aspect > 0 ? Math.Max(1, (int)Math.Round(DefaultHeight * aspect)) : 640;
        if (aspect == 0)
            Note("converted", $"{path}.perspective", "camera without aspectRatio",
                "rendered at 640 × 480 (the glTF leaves the aspect ratio to the viewport)");
        if (GltfDocument.Has(p, "znear", out _) || GltfDocument.Has(p, "zfar", out _))
            Note("ignored", $"{path}.perspective", "znear/zfar", "a ray tracer has no clipping planes: not used");
        var eye = Affine.Point(world, 0, 0, 0);
        var forward = Affine.Normalized(Affine.Direction(world, 0, 0, -1));
        var up = Affine.Normalized(Affine.Direction(world, 0, 1, 0));
        _camera = new JsonObject
        {
            ["position"] = Vector(eye),
            ["look_at"] = Vector([eye[0] + forward[0], eye[1] + forward[1], eye[2] + forward[2]]),
            ["up"] = Vector(up),
            ["fov"] = Round(yfov * 180 / Math.PI),
            ["width"] = width,
            ["height"] = height,
            ["spp"] = 16,
        };
        _cameraPath = path;
        Note("converted", path, "perspective camera",
            $"yfov {Round(yfov * 180 / Math.PI)}° is our vertical fov; {width} × {height} pixels, 16 samples per pixel");
    }

    /// <summary>No camera in the scene: one on +Z of the bounds' centre, looking down −Z, far enough that the bounding sphere fits
    /// the 40° vertical field of view.</summary>
    JsonObject DefaultCamera()
    {
        var min = _boundsMin!;
        var max = _boundsMax!;
        double[] c = [(min[0] + max[0]) / 2, (min[1] + max[1]) / 2, (min[2] + max[2]) / 2];
        double r = Math.Max(1e-3, 0.5 * Math.Sqrt(Sq(max[0] - min[0]) + Sq(max[1] - min[1]) + Sq(max[2] - min[2])));
        double d = r / Math.Sin(20 * Math.PI / 180);
        Note("approximated", "$", "no camera",
            "the scene has no camera: one placed on +Z of the models' bounds looking down −Z, 40° vertical field of view");
        return new JsonObject
        {
            ["position"] = Vector([c[0], c[1], c[2] + d]),
            ["look_at"] = Vector(c),
            ["up"] = Vector([0, 1, 0]),
            ["fov"] = 40,
            ["width"] = 640,
            ["height"] = DefaultHeight,
            ["spp"] = 16,
        };
    }

    static double Sq(double x) => x * x;

    /// <summary>A number rounded to 9 significant digits, so that float noise does not reach the JSON.</summary>
    internal static double Round(double v) =>
        v == 0 ? 0 : double.Parse(v.ToString("G9", CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);

    internal static JsonArray Vector(double[] v) => [.. v.Select(x => (JsonNode)JsonValue.Create(Round(x)))];
}
