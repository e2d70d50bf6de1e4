using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Objects: analytic shapes, the ColorChecker chart, transforms and orientation bases.
public sealed partial class SceneLoader
{
    static readonly string[] ObjectTypes = ["sphere", "plane", "quad", "box", "mesh", "instance", "colorchecker"];

    /// <summary>The window portals among the objects (quads with "portal": true), kept apart: they are no objects.</summary>
    readonly List<Portal> _portals = [];

    void ParseObject(JsonElement e, string path, int index, List<SceneObject> objects, List<Material> materials,
        Dictionary<string, int> materialIndex)
    {
        Object(e, path);
        var type = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        var registered = ShapeTypes.ByName;
        if (Array.IndexOf(ObjectTypes, type) < 0 && !registered.ContainsKey(type))
        {
            string[] types = [.. ObjectTypes, .. registered.Keys.Order(StringComparer.Ordinal)];
            throw Error($"{path}.type", $"unknown object type '{type}'",
                InputException.DidYouMean(type, types) ?? $"types: {string.Join(", ", types)}");
        }
        string[] common = ["type", "name", "material", "transform", "portal"];
        bool portal = Bool(e, "portal", path, false);
        if (portal && type != "quad")
            throw Error($"{path}.portal", $"a portal must be a quad, found a {type}",
                "give the window's opening as a quad (its normal into the room) with \"portal\": true, apart from the wall");
        if (registered.TryGetValue(type, out var shapeType))
        {
            Keys(e, path, [.. common, .. shapeType.Keys, "medium"]);   // "medium": its interior (SceneLoader.Media.cs)
            var shapeName = TryGet(e, "name", out var sn) ? String(sn, $"{path}.name") : $"{type}-{index}";
            var transform = TryGet(e, "transform", out var st) ? Transform(st, $"{path}.transform") : Matrix4x4.Identity;
            int shapeMaterial = MaterialOf(e, path, materials, materialIndex);
            var placed = shapeType.Place(new ShapeSource(this, e, path)) * transform;
            objects.Add(new SceneObject { Name = shapeName, Material = shapeMaterial, Shape = new AnalyticShape(shapeType.Shape, placed) });
            return;
        }
        string[] specific = type switch
        {
            "sphere" => ["center", "radius"],
            "plane" => ["point", "normal"],
            "quad" => ["center", "size", "normal", "up"],
            "box" => ["center", "size", "min", "max"],
            "mesh" => ["file", "inline", "fit", "shading", "normals"],
            "instance" => ["prototype"],
            _ => ["center", "normal", "up", "patch_size", "gap", "frame"],
        };
        Keys(e, path, [.. common, .. specific, "medium"]);
        var name = TryGet(e, "name", out var n) ? String(n, $"{path}.name") : type == "colorchecker" ? "patch" : $"{type}-{index}";
        var user = TryGet(e, "transform", out var t) ? Transform(t, $"{path}.transform") : Matrix4x4.Identity;

        if (type == "colorchecker") { ColorCheckerChart(e, path, name, user, objects, materials); return; }
        if (type == "mesh") { objects.Add(MeshObject(e, path, name, user, MaterialOf(e, path, materials, materialIndex))); return; }
        if (type == "instance") { objects.Add(InstanceObject(e, path, name, user, MaterialOf(e, path, materials, materialIndex))); return; }

        if (portal) { Portal(e, path, name, user, materials, materialIndex); return; }
        int material = MaterialOf(e, path, materials, materialIndex);
        Matrix4x4 local;
        ShapeKind kind;
        switch (type)
        {
            case "sphere":
                {
                    float r = (float)Number(e, "radius", path, 1, MinSize, MaxCoordinate);
                    local = Matrix4x4.CreateScale(r) * Matrix4x4.CreateTranslation(Vec3(e, "center", path, Vector3.Zero));
                    kind = ShapeKind.Sphere;
                    break;
                }
            case "plane":
                {
                    var normal = TryGet(e, "normal", out var nn) ? Direction(nn, $"{path}.normal") : Vector3.UnitY;
                    local = Basis(normal, Vector3.UnitY, axisIsY: true) * Matrix4x4.CreateTranslation(Vec3(e, "point", path, Vector3.Zero));
                    kind = ShapeKind.Plane;
                    break;
                }
            case "quad":
                local = QuadPlacement(e, path);
                kind = ShapeKind.Quad;
                break;
            default:
                {
                    Vector3 centre, size;
                    if (TryGet(e, "min", out var mn) || TryGet(e, "max", out _))
                    {
                        var lo = Vec3(Required(e, "min", path), $"{path}.min");
                        var hi = Vec3(Required(e, "max", path), $"{path}.max");
                        centre = 0.5f * (lo + hi);
                        size = hi - lo;
                        _ = mn;
                    }
                    else
                    {
                        centre = Vec3(e, "center", path, Vector3.Zero);
                        size = Vec3(e, "size", path, Vector3.One);
                    }
                    if (!(size.X >= MinSize && size.Y >= MinSize && size.Z >= MinSize))
                        throw Error($"{path}.size",
                            $"a box needs a size of at least {MinSize} on every axis, found [{size.X}, {size.Y}, {size.Z}]",
                            "give size as [x, y, z] of positive numbers, or max above min");
                    local = Matrix4x4.CreateScale(size) * Matrix4x4.CreateTranslation(centre);
                    kind = ShapeKind.Box;
                    break;
                }
        }
        objects.Add(new SceneObject { Name = name, Material = material, Shape = new AnalyticShape(kind, local * user) });
    }

    /// <summary>A quad's placement: the unit square scaled to its "size", turned to its "normal" and "up", at its "center".</summary>
    Matrix4x4 QuadPlacement(JsonElement e, string path)
    {
        var size = Size2(e, path);
        var normal = TryGet(e, "normal", out var nn) ? Direction(nn, $"{path}.normal") : Vector3.UnitZ;
        var up = TryGet(e, "up", out var u) ? Direction(u, $"{path}.up") : Vector3.UnitY;
        return Matrix4x4.CreateScale(size.X, size.Y, 1) * Basis(normal, up, axisIsY: false, path: $"{path}.up")
            * Matrix4x4.CreateTranslation(Vec3(e, "center", path, Vector3.Zero));
    }

    /// <summary>
    /// A window portal: a quad with "portal": true, its normal into the room (<see cref="Scenes.Portal"/>); it needs no material,
    /// and one that emits is refused (a portal is no surface: it would emit from nowhere).
    /// </summary>
    void Portal(JsonElement e, string path, string name, Matrix4x4 user, List<Material> materials, Dictionary<string, int> materialIndex)
    {
        if (TryGet(e, "material", out _) && materials[MaterialOf(e, path, materials, materialIndex)].Emission is not null)
            throw Error($"{path}.portal", $"portal '{name}' has an emitting material",
                "a portal is an opening, not a light: drop its \"material\" (or make the emitter a separate quad)");
        var shape = new AnalyticShape(ShapeKind.Quad, QuadPlacement(e, path) * user);
        var m = shape.ObjectToWorld;
        var corner = Vector3.Transform(new Vector3(-0.5f, -0.5f, 0), m);
        _portals.Add(new Portal(name, corner, Vector3.Transform(new Vector3(0.5f, -0.5f, 0), m) - corner,
            Vector3.Transform(new Vector3(-0.5f, 0.5f, 0), m) - corner, shape.FlatNormal!.Value));
    }

    /// <summary>A registered shape type's object as its <see cref="ShapeType.Place"/> reads it: its keys, checked, with errors
    /// at their JSON path.</summary>
    public sealed class ShapeSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal ShapeSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A point [x, y, z] (scene units), or <paramref name="fallback"/> when absent.</summary>
        public Vector3 Point(string key, Vector3 fallback) => _loader.Vec3(_e, key, _path, fallback);
        /// <summary>A translation to the point <paramref name="key"/> (the origin when absent).</summary>
        public Matrix4x4 Translation(string key) => Matrix4x4.CreateTranslation(Point(key, Vector3.Zero));
        /// <summary>A length of at least <see cref="MinSize"/>, 1 when absent.</summary>
        public float Size(string key, double fallback = 1) => (float)_loader.Number(_e, key, _path, fallback, MinSize, MaxCoordinate);
        /// <summary>A number in [min, max], <paramref name="fallback"/> when absent.</summary>
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        /// <summary>The rotation taking +z to the direction <paramref name="normalKey"/> (default +z) and +y towards
        /// <paramref name="upKey"/> (default +y), as a quad's "normal" and "up".</summary>
        public Matrix4x4 Frame(string normalKey, string upKey)
        {
            var normal = TryGet(_e, normalKey, out var n) ? _loader.Direction(n, $"{_path}.{normalKey}") : Vector3.UnitZ;
            var up = TryGet(_e, upKey, out var u) ? _loader.Direction(u, $"{_path}.{upKey}") : Vector3.UnitY;
            return _loader.Basis(normal, up, axisIsY: false, path: $"{_path}.{upKey}");
        }
        /// <summary>The rotation taking +z to unit <paramref name="normal"/> and +y towards <paramref name="up"/>.</summary>
        public Matrix4x4 Frame(Vector3 normal, Vector3 up) => _loader.Basis(normal, up, axisIsY: false, path: _path);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
    }

    static bool Within(Vector3 p) => Math.Abs(p.X) <= MaxCoordinate && Math.Abs(p.Y) <= MaxCoordinate && Math.Abs(p.Z) <= MaxCoordinate;

    Vector2 Size2(JsonElement e, string path)
    {
        if (!TryGet(e, "size", out var s)) return Vector2.One;
        if (s.ValueKind == JsonValueKind.Number)
        {
            float v = (float)Number(s, $"{path}.size", MinSize, MaxCoordinate);
            return new Vector2(v, v);
        }
        if (s.ValueKind != JsonValueKind.Array || s.GetArrayLength() != 2)
            throw Error($"{path}.size", $"expected [width, height], found {Kind(s)}", "e.g. \"size\": [2, 1] or \"size\": 2");
        return new Vector2((float)Number(s[0], $"{path}.size[0]", MinSize, MaxCoordinate),
            (float)Number(s[1], $"{path}.size[1]", MinSize, MaxCoordinate));
    }

    /// <summary>The Macbeth chart as 24 quads, 4 rows × 6 columns in the standard order, on an optional black frame.</summary>
    void ColorCheckerChart(JsonElement e, string path, string name, Matrix4x4 user, List<SceneObject> objects, List<Material> materials)
    {
        if (TryGet(e, "material", out _))
            throw Error($"{path}.material", "a colorchecker chooses its own materials (the 24 Ohta reflectances)",
                "remove 'material' from the colorchecker");
        float patch = (float)Number(e, "patch_size", path, 1, MinSize, MaxCoordinate);
        float gap = (float)Number(e, "gap", path, 0.2 * patch, 0, MaxCoordinate);
        var normal = TryGet(e, "normal", out var nn) ? Direction(nn, $"{path}.normal") : Vector3.UnitZ;
        var up = TryGet(e, "up", out var u) ? Direction(u, $"{path}.up") : Vector3.UnitY;
        var centre = Vec3(e, "center", path, Vector3.Zero);
        var basis = Basis(normal, up, axisIsY: false, path: $"{path}.up");
        float pitch = patch + gap;
        for (int p = 1; p <= ColorChecker.PatchCount; p++)
        {
            int row = (p - 1) / 6, col = (p - 1) % 6;
            var offset = new Vector3((col - 2.5f) * pitch, (1.5f - row) * pitch, 0);
            var local =
                Matrix4x4.CreateScale(patch, patch, 1) * Matrix4x4.CreateTranslation(offset) * basis * Matrix4x4.CreateTranslation(centre);
            var spectrum = ColorChecker.Patch(p);
            var bands = Bands(spectrum, $"{path} (patch {p})");
            materials.Add(DiffuseMaterial($"colorchecker:{p}", bands, spectrum));
            objects.Add(new SceneObject
            {
                Name = $"{name}-{p:00}",
                Material = materials.Count - 1,
                Shape = new AnalyticShape(ShapeKind.Quad, local * user)
            });
        }
        if (TryGet(e, "frame", out var frame) && !(frame.ValueKind == JsonValueKind.False))
        {
            var spectrum =
                frame.ValueKind == JsonValueKind.True ? TabulatedSpectrum.Constant(0.03, "chart frame") : Spectrum(frame, $"{path}.frame");
            var bands = Bands(spectrum, $"{path}.frame");
            materials.Add(DiffuseMaterial($"{name}-frame", bands, spectrum));
            // Behind the patches by a hair, so the patches win at every pixel they cover.
            var local = Matrix4x4.CreateScale(6 * pitch + gap, 4 * pitch + gap, 1) * Matrix4x4.CreateTranslation(0, 0,
                -1e-3f * pitch) * basis * Matrix4x4.CreateTranslation(
                centre);
            objects.Add(new SceneObject
            {
                Name = $"{name}-frame",
                Material = materials.Count - 1,
                Shape = new AnalyticShape(ShapeKind.Quad, local * user)
            });
        }
    }

    /// <summary>A rotation taking the canonical normal (+z, or +y for planes) to <paramref name="normal"/>, with its height axis towards
    /// <paramref name="up"/>.</summary>
    Matrix4x4 Basis(Vector3 normal, Vector3 up, bool axisIsY, string? path = null)
    {
        if (axisIsY)
        {
            // any orthonormal frame with y = normal
            var helper = MathF.Abs(normal.X) < 0.9f ? Vector3.UnitX : Vector3.UnitZ;
            var z = Vector3.Normalize(Vector3.Cross(helper, normal));
            var x = Vector3.Cross(normal, z);
            return Rows(x, normal, z);
        }
        var xAxis = Vector3.Cross(up, normal);
        if (xAxis.LengthSquared() < 1e-12f)
            throw Error(path ?? "$", "up is parallel to the normal", "choose an up vector across the surface");
        xAxis = Vector3.Normalize(xAxis);
        var yAxis = Vector3.Cross(normal, xAxis);
        return Rows(xAxis, yAxis, normal);
    }

    static Matrix4x4 Rows(Vector3 x, Vector3 y, Vector3 z) => new(
        x.X, x.Y, x.Z, 0,
        y.X, y.Y, y.Z, 0,
        z.X, z.Y, z.Z, 0,
        0, 0, 0, 1);

    /// <summary>{"translate": [x,y,z], "rotate": [rx,ry,rz] degrees about x then y then z, "scale": s | [sx,sy,sz]}: scale, then rotate,
    /// then translate; or {"matrix": [16 numbers]} alone.</summary>
    Matrix4x4 Transform(JsonElement e, string path)
    {
        Object(e, path);
        Keys(e, path, "translate", "rotate", "scale", "matrix");
        if (TryGet(e, "matrix", out var mx)) return TransformMatrix(e, mx, path);
        var m = Matrix4x4.Identity;
        if (TryGet(e, "scale", out var s))
        {
            if (s.ValueKind == JsonValueKind.Number) m *= Matrix4x4.CreateScale((float)Number(s, $"{path}.scale", MinSize, 1 / MinSize));
            else
            {
                var v = Vec3(s, $"{path}.scale");
                if (!(Math.Abs(v.X) >= MinSize && Math.Abs(v.Y) >= MinSize && Math.Abs(v.Z) >= MinSize) || Math.Abs(v.X) > 1 / MinSize
                    || Math.Abs(v.Y) > 1 / MinSize || Math.Abs(v.Z) > 1 / MinSize)
                    throw Error($"{path}.scale", "a zero or extreme scale flattens or explodes the object",
                        $"use scales of magnitude {MinSize} to {1 / MinSize}");
                m *= Matrix4x4.CreateScale(v);
            }
        }
        if (TryGet(e, "rotate", out var r))
        {
            var deg = Vec3(r, $"{path}.rotate") * (MathF.PI / 180);
            m *= Matrix4x4.CreateRotationX(deg.X) * Matrix4x4.CreateRotationY(deg.Y) * Matrix4x4.CreateRotationZ(deg.Z);
        }
        if (TryGet(e, "translate", out var tr)) m *= Matrix4x4.CreateTranslation(Vec3(tr, $"{path}.translate"));
        return m;
    }

    /// <summary>
    /// "matrix": 16 numbers, a row-major 4 × 4 matrix M acting on column vectors, p' = M·p (Mitsuba's and pbrt's order): the
    /// last row must be [0, 0, 0, 1] (affine) and M invertible. System.Numerics acts on row vectors, so it holds Mᵀ.
    /// </summary>
    Matrix4x4 TransformMatrix(JsonElement e, JsonElement mx, string path)
    {
        string where = $"{path}.matrix";
        foreach (var key in new[] { "translate", "rotate", "scale" })
            if (TryGet(e, key, out _))
                throw Error($"{path}.{key}", "a transform gives either \"matrix\" or translate/rotate/scale, not both",
                    "fold the translation, rotation and scale into the matrix");
        if (mx.ValueKind != JsonValueKind.Array || mx.GetArrayLength() != 16)
            throw Error(where, $"expected 16 numbers (a row-major 4 × 4 matrix), found {Kind(mx)}",
                "e.g. [1,0,0,tx, 0,1,0,ty, 0,0,1,tz, 0,0,0,1]");
        var v = new float[16];
        int i = 0;
        foreach (var x in mx.EnumerateArray())
        {
            v[i] = (float)Number(x, $"{where}[{i}]", -MaxCoordinate, MaxCoordinate);
            i++;
        }
        if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
            throw Error(where, $"the last row is [{v[12]}, {v[13]}, {v[14]}, {v[15]}], not [0, 0, 0, 1]: a projective matrix",
                "give an affine transform (rotation, scale, shear and translation)");
        var m = new Matrix4x4(
            v[0], v[4], v[8], 0,
            v[1], v[5], v[9], 0,
            v[2], v[6], v[10], 0,
            v[3], v[7], v[11], 1);
        float det = m.GetDeterminant();
        float norm = MathF.Max(MathF.Max(new Vector3(v[0], v[4], v[8]).Length(), new Vector3(v[1], v[5], v[9]).Length()),
            new Vector3(v[2], v[6], v[10]).Length());
        if (!(MathF.Abs(det) >= (float)Math.Pow(MinSize, 3) && MathF.Abs(det) >= 1e-9f * norm * norm * norm))
            throw Error(where, $"the matrix is singular or nearly so (determinant {det:g3}): it flattens the object",
                "give a matrix with three independent columns");
        return m;
    }
}
