using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Scenes.Import.Pbrt;

// Shapes: trianglemesh, bilinearmesh and loopsubdiv inline (in world space, their winding set to pbrt's orientation),
// plymesh by path with the transformation as a matrix, sphere, disk, cylinder; and the diffuse area light a shape carries.
public sealed partial class PbrtConverter
{
    readonly Dictionary<string, string> _emitting = new(StringComparer.Ordinal);

    // ObjectInstance copies of a mesh shape: the shape converted once, in its own space, as a prototype, and each copy an
    // "instance" object of it under the copy's transformation (docs/scene-format.md, "Instancing").
    readonly Dictionary<PbrtEntity, string> _prototypeOf = new(ReferenceEqualityComparer.Instance);
    readonly JsonObject _prototypes = [];
    static readonly string[] MeshShapes = ["trianglemesh", "bilinearmesh", "loopsubdiv", "plymesh"];

    void Shape(PbrtShape s)
    {
        var e = s.Entity;
        var p = e.Parameters;
        string label = $"Shape \"{e.Type}\"";
        var m = _world * s.WorldFromObject;
        bool instanced = s.Instance is not null && Array.IndexOf(MeshShapes, e.Type) >= 0;
        if (instanced && MaterialName(s.Material) is { } instanceMaterial)
        {
            if (!_prototypeOf.TryGetValue(e, out var prototype))
            {
                // The shape in its own space (pbrt's winding rules then see the identity; the instance's transform, applied
                // by the inverse transpose to normals, keeps its side as pbrt's flip for a mirroring transform does).
                int before = _objects.Count;
                Shape(s with { Instance = null, WorldFromObject = _world.Inverse() ?? PbrtTransform.Identity });
                if (_objects.Count == before) return;
                prototype = Prototypes.TakeLast(_objects, _prototypes);
                _prototypeOf[e] = prototype;
            }
            _objects.Add((JsonNode)new JsonObject
            {
                ["type"] = "instance",
                ["name"] = UniqueName($"{s.Instance}-{s.InstanceCopy}"),
                ["prototype"] = prototype,
                ["material"] = instanceMaterial,
                ["transform"] = Matrix(m),
            });
            return;
        }
        if (p.Find("alpha") is { } alpha)
            _report.Add("ignored", Place(alpha.Token), $"{label} \"alpha\"", "alpha cut-outs are not rendered: the shape is opaque");
        foreach (var q in new[] { "emissionfilename", "displacement", "edgelength" }) p.Find(q);
        string? material = MaterialName(s.Material);
        if (material is null)
        {
            foreach (var q in p.All) q.Used = true;
            Note("ignored", e, label, "its material is \"interface\" (a medium boundary): left out");
            return;
        }
        JsonObject? obj;
        double area;
        bool flippedFile = false;
        switch (e.Type)
        {
            case "trianglemesh":
            case "loopsubdiv":
                {
                    var positions = p.Numbers("P", 3, "point3")
                        ?? throw new InputException(e.Where, $"{label} has no \"point3 P\"", "give the vertex positions");
                    int[] indices;
                    var idx = p.Numbers("indices", 3, "integer");
                    if (idx is null)
                    {
                        if (positions.Length != 9)
                            throw new InputException(e.Where, $"{label} without \"integer indices\" has {positions.Length / 3} points",
                                "give indices, three per triangle (only a single triangle may leave them out)");
                        indices = [0, 1, 2];
                    }
                    else indices = Indices(idx, positions.Length / 3, e);
                    var normals = e.Type == "trianglemesh" ? p.Numbers("N", 3, "normal") : null;
                    var uvs = e.Type == "trianglemesh" ? p.Numbers("uv", 2, "point2") : null;
                    if (normals is not null && normals.Length != positions.Length)
                        throw new InputException(e.Where, $"{label}: {normals.Length / 3} normals for {positions.Length / 3} points",
                            "give one normal per point");
                    if (uvs is not null && uvs.Length / 2 != positions.Length / 3)
                        throw new InputException(e.Where, $"{label}: {uvs.Length / 2} uv pairs for {positions.Length / 3} points",
                            "give one uv per point");
                    if (e.Type == "loopsubdiv")
                    {
                        p.Find("levels");
                        Note("approximated", e, label, "the control mesh itself: Loop subdivision is not applied");
                    }
                    p.Find("S");
                    p.Find("faceIndices");
                    (obj, area) = Mesh(s, m, positions, indices, normals, uvs, label);
                    break;
                }
            case "bilinearmesh":
                {
                    var positions = p.Numbers("P", 3, "point3")
                        ?? throw new InputException(e.Where, $"{label} has no \"point3 P\"", "give the vertex positions");
                    var idx = p.Numbers("indices", 4, "integer");
                    int[] quads = idx is null
                        ? positions.Length == 12 ? [0, 1, 2, 3]
                            : throw new InputException(e.Where, $"{label} without \"integer indices\" has {positions.Length / 3} points",
                                "give indices, four per patch (only a single patch may leave them out)")
                        : Indices(idx, positions.Length / 3, e);
                    // A patch (p00, p10, p01, p11) as the triangles (p00, p10, p11) and (p00, p11, p01): pbrt's orientation.
                    var indices = new int[quads.Length / 4 * 6];
                    for (int q = 0, t = 0; q < quads.Length; q += 4)
                    {
                        indices[t++] = quads[q];
                        indices[t++] = quads[q + 1];
                        indices[t++] = quads[q + 3];
                        indices[t++] = quads[q];
                        indices[t++] = quads[q + 3];
                        indices[t++] = quads[q + 2];
                    }
                    var normals = p.Numbers("N", 3, "normal");
                    var uvs = p.Numbers("uv", 2, "point2");
                    if (normals is not null && normals.Length != positions.Length)
                        throw new InputException(e.Where, $"{label}: {normals.Length / 3} normals for {positions.Length / 3} points",
                            "give one normal per point");
                    if (uvs is not null && uvs.Length / 2 != positions.Length / 3)
                        throw new InputException(e.Where, $"{label}: {uvs.Length / 2} uv pairs for {positions.Length / 3} points",
                            "give one uv per point");
                    Note("approximated", e, label, "each bilinear patch split into two triangles (a curved patch is flattened)");
                    (obj, area) = Mesh(s, m, positions, indices, normals, uvs, label);
                    break;
                }
            case "plymesh":
                {
                    var file =
                        p.String("filename")
                            ?? throw new InputException(e.Where, $"{label} has no \"string filename\"", "name the .ply file");
                    var full = Path.IsPathRooted(file) ? file : Path.Combine(_dir, file);
                    obj = new JsonObject
                    {
                        ["type"] = "mesh",
                        ["name"] = UniqueName(Path.GetFileNameWithoutExtension(file)),
                        ["file"] = file,
                        ["material"] = material,
                        ["transform"] = Matrix(m),
                    };
                    // pbrt orients a mesh without normals by its winding, flipped by ReverseOrientation or a mirroring transform.
                    flippedFile = s.ReverseOrientation ^ (m.Determinant3 < 0);
                    area = s.AreaLight is not null && s.AreaLight.Parameters.Has("power") ? PlyArea(full, m, e) : 0;
                    break;
                }
            case "sphere":
                {
                    double r = p.Float("radius", 1);
                    if (!(r > 0)) throw new InputException(e.Where, $"{label}: radius {r}", "give a radius above 0");
                    double zmin = p.Float("zmin", -r), zmax = p.Float("zmax", r), phimax = p.Float("phimax", 360);
                    if (zmin > -r || zmax < r || phimax < 360)
                        Note("approximated", e, label, "a partial sphere (zmin, zmax or phimax) rendered whole");
                    if (s.ReverseOrientation && s.AreaLight is not null)
                        Note("approximated", e, label, "a sphere light facing inwards (ReverseOrientation): ours emits outwards");
                    if (Similarity(m) is { } scale)
                    {
                        obj = new JsonObject
                        {
                            ["type"] = "sphere",
                            ["name"] = UniqueName("sphere"),
                            ["center"] = Array3(m.Point(0, 0, 0)),
                            ["radius"] = Round(r * scale),
                            ["material"] = material,
                        };
                        area = 4 * Math.PI * r * r * scale * scale;
                    }
                    else
                    {
                        Note("approximated", e, label, "a sphere under a non-uniform scale (an ellipsoid): a mesh of 64 × 32 quads");
                        var (positions, indices, normals) = Ellipsoid(r);
                        (obj, area) = Mesh(s, m, positions, indices, normals, null, label);
                    }
                    break;
                }
            case "disk":
                {
                    double r =
                        p.Float("radius", 1), h = p.Float("height", 0), inner = p.Float("innerradius", 0), phimax = p.Float("phimax", 360);
                    if (!(r > 0)) throw new InputException(e.Where, $"{label}: radius {r}", "give a radius above 0");
                    if (inner > 0 || phimax < 360)
                        Note("approximated", e, label, "an annulus or a sector (innerradius, phimax) rendered whole");
                    // pbrt's disk faces +z; ReverseOrientation or a mirroring transform turns it (pbrt-v4 shapes.h, flipNormal).
                    double side = s.ReverseOrientation ^ (s.WorldFromObject.Determinant3 < 0) ? -1 : 1;
                    obj = new JsonObject
                    {
                        ["type"] = "disk",
                        ["name"] = UniqueName("disk"),
                        ["center"] = new JsonArray(0, 0, Round(h)),
                        ["radius"] = Round(r),
                        ["normal"] = new JsonArray(0, 0, side),
                        ["up"] = new JsonArray(0, 1, 0),
                        ["material"] = material,
                        ["transform"] = Matrix(m),
                    };
                    var ax = m.Vector(1, 0, 0);
                    var ay = m.Vector(0, 1, 0);
                    var c = PbrtTransform.Cross(ax, ay);
                    area = Math.PI * r * r * Math.Sqrt(PbrtTransform.Dot(c, c));
                    break;
                }
            case "cylinder":
                {
                    double r = p.Float("radius", 1), zmin = p.Float("zmin", -1), zmax = p.Float("zmax", 1), phimax = p.Float("phimax", 360);
                    if (!(r > 0) || !(zmax > zmin))
                        throw new InputException(e.Where, $"{label}: radius {r}, z {zmin}…{zmax}", "give r > 0, zmin < zmax");
                    if (phimax < 360) Note("approximated", e, label, "a partial cylinder (phimax) rendered whole");
                    obj = new JsonObject
                    {
                        ["type"] = "cylinder",
                        ["name"] = UniqueName("cylinder"),
                        ["p0"] = new JsonArray(0, 0, Round(zmin)),
                        ["p1"] = new JsonArray(0, 0, Round(zmax)),
                        ["radius"] = Round(r),
                        ["material"] = material,
                        ["transform"] = Matrix(m),
                    };
                    double scale = Similarity(m) ?? 1;
                    area = 2 * Math.PI * r * (zmax - zmin) * scale * scale;
                    break;
                }
            case "curve":
                foreach (var q in p.All) q.Used = true;
                Refuse(e.Where, label, "curves (hair, fur) have no counterpart");
                return;
            default:
                throw new InputException(e.Where, $"unknown shape type \"{MessageText.Escape(e.Type)}\"",
                    InputException.DidYouMean(e.Type, ShapeTypes) ?? "see pbrt.org/fileformat-v4");
        }
        ReportUnused(e, label);
        if (s.AreaLight is { } light) obj["material"] = EmittingMaterial(material, light, area, flippedFile, e);
        _objects.Add((JsonNode)obj);
    }

    static readonly string[] ShapeTypes = ["trianglemesh", "bilinearmesh", "loopsubdiv", "plymesh", "sphere", "disk", "cylinder", "curve"];

    static int[] Indices(double[] v, int vertices, PbrtEntity e)
    {
        var a = new int[v.Length];
        for (int i = 0; i < v.Length; i++)
        {
            if (v[i] != Math.Floor(v[i]) || v[i] < 0 || v[i] >= vertices)
                throw new InputException(e.Where, $"index {v[i]} is not a vertex (the shape has {vertices} points)",
                    "indices count the points from 0");
            a[i] = (int)v[i];
        }
        return a;
    }

    /// <summary>The uniform scale of a similarity transform, or null when it stretches unevenly or shears.</summary>
    static double? Similarity(PbrtTransform m)
    {
        var c = new[] { m.Vector(1, 0, 0), m.Vector(0, 1, 0), m.Vector(0, 0, 1) };
        double l = Math.Sqrt(PbrtTransform.Dot(c[0], c[0]));
        for (int i = 0; i < 3; i++)
        {
            if (Math.Abs(Math.Sqrt(PbrtTransform.Dot(c[i], c[i])) - l) > 1e-6 * l) return null;
            for (int j = i + 1; j < 3; j++)
                if (Math.Abs(PbrtTransform.Dot(c[i], c[j])) > 1e-6 * l * l) return null;
        }
        return l;
    }

    static JsonObject Matrix(PbrtTransform m)
    {
        var a = new JsonArray();
        foreach (double v in m.RowMajor) a.Add((JsonNode)JsonValue.Create(Round(v)));
        return new JsonObject { ["matrix"] = a };
    }

    /// <summary>
    /// A mesh in world space, inline: positions through <paramref name="m"/>, normals through its inverse transpose (negated by
    /// ReverseOrientation), and each triangle wound so that its normal is pbrt's: towards the shading normals when given,
    /// else the winding's, flipped by ReverseOrientation or a mirroring transform (pbrt-v4 shapes.h, Triangle).
    /// </summary>
    (JsonObject Object, double Area) Mesh(PbrtShape s, PbrtTransform m, double[] p, int[] indices, double[]? n, double[]? uv, string label)
    {
        int vertices = p.Length / 3;
        var positions = new float[p.Length];
        var world = new double[p.Length];
        for (int v = 0; v < vertices; v++)
        {
            var w = m.Point(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
            for (int c = 0; c < 3; c++)
            {
                world[3 * v + c] = w[c];
                positions[3 * v + c] = (float)w[c];
                if (!float.IsFinite(positions[3 * v + c]))
                    throw new InputException(s.Entity.Where, $"{label}: point {v} lands outside single precision",
                        "check its coordinates and scale");
            }
        }
        float[]? normals = null;
        double[]? worldNormals = null;
        if (n is not null)
        {
            var inv =
                m.Inverse() ?? throw new InputException(s.Entity.Where, $"{label}: the transformation is singular", "check the Scale");
            normals = new float[n.Length];
            worldNormals = new double[n.Length];
            double sign = s.ReverseOrientation ? -1 : 1;
            for (int v = 0; v < vertices; v++)
            {
                double x = n[3 * v], y = n[3 * v + 1], z = n[3 * v + 2];
                double[] t = [inv[0, 0] * x + inv[1, 0] * y + inv[2, 0] * z, inv[0, 1] * x + inv[1, 1] * y + inv[2, 1] * z,
                    inv[0, 2] * x + inv[1, 2] * y + inv[2, 2] * z];
                var u = PbrtTransform.Normalize(t);
                if (u.Length == 0) u = [0, 0, 0];
                for (int c = 0; c < 3; c++)
                {
                    worldNormals[3 * v + c] = sign * u[c];
                    normals[3 * v + c] = (float)(sign * u[c]);
                }
            }
        }
        bool flip = s.ReverseOrientation ^ (m.Determinant3 < 0);
        var tri = (int[])indices.Clone();
        double area = 0;
        for (int t = 0; t < tri.Length; t += 3)
        {
            int a = tri[t], b = tri[t + 1], c = tri[t + 2];
            double[] e1 = [world[3 * b] - world[3 * a], world[3 * b + 1] - world[3 * a + 1], world[3 * b + 2] - world[3 * a + 2]];
            double[] e2 = [world[3 * c] - world[3 * a], world[3 * c + 1] - world[3 * a + 1], world[3 * c + 2] - world[3 * a + 2]];
            var cross = PbrtTransform.Cross(e1, e2);
            area += 0.5 * Math.Sqrt(PbrtTransform.Dot(cross, cross));
            bool swap = flip;
            if (worldNormals is not null)
            {
                double[] ns = new double[3];
                for (int k = 0; k < 3; k++) ns[k] = worldNormals[3 * a + k] + worldNormals[3 * b + k] + worldNormals[3 * c + k];
                swap = PbrtTransform.Dot(cross, ns) < 0;
            }
            if (swap) (tri[t + 1], tri[t + 2]) = (tri[t + 2], tri[t + 1]);
        }
        float[]? uvs = uv?.Select(x => (float)x).ToArray();
        string name = UniqueName(s.Instance is null ? s.Entity.Type : $"{s.Instance}-{s.InstanceCopy}");
        var mesh = new ImportedMesh(name, positions, tri, normals, uvs);
        _meshes.Add(mesh);
        var obj = new JsonObject { ["type"] = "mesh", ["name"] = name, ["inline"] = mesh.InlineJson() };
        if (normals is null) obj["shading"] = "flat";
        obj["material"] = MaterialName(s.Material);
        return (obj, area);
    }

    /// <summary>A lat-long sphere of radius r in object space (64 × 32 quads), outward normals, for an ellipsoid.</summary>
    static (double[] P, int[] Indices, double[] N) Ellipsoid(double r)
    {
        const int nu = 64, nv = 32;
        var p = new List<double>();
        var n = new List<double>();
        for (int j = 0; j <= nv; j++)
        {
            double theta = Math.PI * j / nv;
            for (int i = 0; i <= nu; i++)
            {
                double phi = 2 * Math.PI * i / nu;
                double x = Math.Sin(theta) * Math.Cos(phi), y = Math.Sin(theta) * Math.Sin(phi), z = Math.Cos(theta);
                p.AddRange([r * x, r * y, r * z]);
                n.AddRange([x, y, z]);
            }
        }
        var idx = new List<int>();
        for (int j = 0; j < nv; j++)
            for (int i = 0; i < nu; i++)
            {
                int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
                if (j > 0) idx.AddRange([a, c, b]);
                if (j < nv - 1) idx.AddRange([b, c, d]);
            }
        return ([.. p], [.. idx], [.. n]);
    }

    double PlyArea(string full, PbrtTransform m, PbrtEntity e)
    {
        TriangleMesh mesh;
        try { mesh = PlyReader.Read(full); }
        catch (InputException ex) { throw new InputException(e.Where, ex.What, ex.Hint) { Problem = ex.Problem }; }
        double area = 0;
        var idx = mesh.Indices;
        for (int t = 0; t + 2 < mesh.TriangleCount * 3; t += 3)
        {
            var a = mesh.Positions[idx[t]];
            var b = mesh.Positions[idx[t + 1]];
            var c = mesh.Positions[idx[t + 2]];
            var pa = m.Point(a.X, a.Y, a.Z);
            var pb = m.Point(b.X, b.Y, b.Z);
            var pc = m.Point(c.X, c.Y, c.Z);
            var cross = PbrtTransform.Cross([pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]], [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]]);
            area += 0.5 * Math.Sqrt(PbrtTransform.Dot(cross, cross));
        }
        return area;
    }

    /// <summary>
    /// The shape's material with the area light's emission: radiance = scale·L/Σȳ·L (pbrt's 1-nit normalisation), times
    /// power/(sides·A·π) when "power" is given (pbrt-v4 DiffuseAreaLight::Create), one- or two-sided.
    /// </summary>
    string EmittingMaterial(string material, PbrtEntity light, double area, bool flippedFile, PbrtEntity shape)
    {
        var p = light.Parameters;
        string label = $"AreaLightSource \"{light.Type}\"";
        if (light.Type != "diffuse")
        {
            Refuse(light.Where, label, "only the diffuse area light has a counterpart");
            return material;
        }
        double scale = p.Float("scale", 1);
        bool twoSided = p.Bool("twosided", false);
        SpectrumValue s;
        if (p.String("filename") is { } file)
        {
            Refuse(light.Where, $"{label} \"filename\"", $"an emission image ('{Path.GetFileName(file)}') has no counterpart; "
                + "rendered with pbrt's default illuminant");
            s = DefaultIlluminant();
        }
        else s = Spectrum(light, "L", SpectrumUse.Illuminant, label) ?? DefaultIlluminant();
        double k = scale / Photometric(s, light, label);
        double power = p.Float("power", -1);
        if (power > 0)
        {
            if (!(area > 0)) throw new InputException(shape.Where, $"{label} \"power\" on a shape of no area", "give the shape an area");
            k *= power / ((twoSided ? 2 : 1) * area * Math.PI);
        }
        if (flippedFile && !twoSided)
        {
            Note("approximated", light, label, "a PLY mesh whose orientation pbrt flips (ReverseOrientation or a mirror): made two-sided");
            twoSided = true;
        }
        ReportUnused(light, label);
        var emission = new JsonObject { ["spectrum"] = s.Node, ["radiance"] = Round(k) };
        if (twoSided) emission["two_sided"] = true;
        string key = material + "\n" + emission.ToJsonString();
        if (_emitting.TryGetValue(key, out var known)) return known;
        var m = (JsonObject)_materials[material]!.DeepClone();
        m["emission"] = emission;
        string name = UniqueName(material + "-emitting");
        _materials[name] = m;
        _emitting[key] = name;
        return name;
    }
}
