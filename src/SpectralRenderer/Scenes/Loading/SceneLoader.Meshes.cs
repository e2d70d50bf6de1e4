using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Scenes.Loading;

// Meshes: OBJ/PLY files found on the model search path, read on the thread pool from the start, fitted and placed.
public sealed partial class SceneLoader
{
    readonly Dictionary<string, Task<TriangleMesh>> _meshReads = new(StringComparer.Ordinal);

    static TriangleMesh ReadMesh(string full) =>
        Path.GetExtension(full).Equals(".obj", StringComparison.OrdinalIgnoreCase) ? ObjReader.Read(full) : PlyReader.Read(full);

    /// <summary>
    /// Starts reading every mesh file the objects name on the thread pool, so parsing (the bulk of a large
    /// scene's load) overlaps the spectra, colorimetry, camera and materials, which the main thread resolves
    /// first. Only files that are found and are .obj or .ply are started; everything else is reported by
    /// <see cref="MeshObject"/> in document order, as before.
    /// </summary>
    void StartMeshReads(JsonElement root)
    {
        if (!_overrides.LoadMeshes) return;
        var meshes = new List<JsonElement>();
        if (TryGet(root, "prototypes", out var prototypes) && prototypes.ValueKind == JsonValueKind.Object)
            foreach (var p in prototypes.EnumerateObject()) meshes.Add(p.Value);
        if (TryGet(root, "objects", out var objects) && objects.ValueKind == JsonValueKind.Array)
            foreach (var o in objects.EnumerateArray())
                if (o.ValueKind == JsonValueKind.Object && o.TryGetProperty("type", out var type) && type.ValueKind == JsonValueKind.String
                    && type.GetString()!.Equals("mesh", StringComparison.OrdinalIgnoreCase)) meshes.Add(o);
        foreach (var o in meshes)
        {
            if (o.ValueKind != JsonValueKind.Object || !o.TryGetProperty("file", out var f) || f.ValueKind != JsonValueKind.String)
                continue;
            var full = ModelSearch.Find(f.GetString()!, _dir, _overrides.ModelDirectories);
            if (full is null || _meshReads.ContainsKey(full) || Path.GetExtension(full).ToLowerInvariant() is not (".obj" or ".ply"))
                continue;
            _meshReads[full] = Task.Run(() => ReadMesh(full));
        }
    }

    /// <summary>
    /// Reads that were started but not used because the load stopped at an error: they finish in the
    /// background, and a read that failed too is observed here so it is not reported a second time.
    /// </summary>
    void AbandonMeshReads()
    {
        foreach (var read in _meshReads.Values)
            read.ContinueWith(static t => _ = t.Exception, CancellationToken.None,
                TaskContinuationOptions.OnlyOnFaulted | TaskContinuationOptions.ExecuteSynchronously, TaskScheduler.Default);
        _meshReads.Clear();
    }

    /// <summary>A triangle mesh from an OBJ or PLY file found along the model search path, fitted and transformed.</summary>
    SceneObject MeshObject(JsonElement e, string path, string name, Matrix4x4 user, int material)
    {
        bool inline = TryGet(e, "inline", out var inlineBlock);
        if (inline && TryGet(e, "file", out _))
            throw Error($"{path}.inline", "a mesh gives either \"file\" or \"inline\", not both", "drop one of them");
        var file = inline ? $"inline mesh {MessageText.Quote(name)}" : String(Required(e, "file", path), $"{path}.file");
        var source = inline ? $"{path}.inline" : $"{path}.file";
        if (!_overrides.LoadMeshes) return new SceneObject { Name = name, Material = material };
        TriangleMesh mesh;
        if (inline) mesh = InlineMesh(inlineBlock, source, name);
        else
        {
            var full = ModelSearch.Find(file, _dir, _overrides.ModelDirectories)
                ?? throw Error(source, $"mesh '{file}' not found in {ModelSearch.Describe(_dir, _overrides.ModelDirectories)}",
                    "get the meshes (README, 'Meshes'); pass --models DIR or set SPECTRAL_MODELS", InputProblem.MissingFile);
            var ext = Path.GetExtension(full).ToLowerInvariant();
            if (ext is not (".obj" or ".ply"))
                throw Error(source, $"'{file}' is neither .obj nor .ply", "meshes are Wavefront .obj or Stanford .ply files");
            // The read started with the scene (StartMeshReads); a second object on the same file reads it again,
            // since fitting and transforming change the mesh. Its errors surface here, as if read in place.
            mesh = _meshReads.Remove(full, out var read) ? read.GetAwaiter().GetResult() : ReadMesh(full);
        }
        var extent = mesh.Bounds.Extent;
        if (!(float.IsFinite(extent.X) && float.IsFinite(extent.Y) && float.IsFinite(extent.Z)))
            throw Error(source,
                $"the vertices of {MessageText.Quote(file)} span more than single precision holds (coordinates near ±3.4e38)",
                "check the mesh for stray vertices, or scale it down in a modelling tool");
        if (TryGet(e, "fit", out var fit))
        {
            Object(fit, $"{path}.fit");
            Keys(fit, $"{path}.fit", "min", "max");
            var lo = Vec3(Required(fit, "min", $"{path}.fit"), $"{path}.fit.min");
            var hi = Vec3(Required(fit, "max", $"{path}.fit"), $"{path}.fit.max");
            if (hi.X < lo.X || hi.Y < lo.Y || hi.Z < lo.Z)
                throw Error($"{path}.fit", "max is below min on some axis", "give fit.min below fit.max on every axis");
            // The transform orients the mesh, then fit places it: the rotated (scaled, mirrored) mesh is what fills
            // the box, so a rotation never moves it out. A translation would be undone by the fit.
            if (TryGet(e, "transform", out var t) && TryGet(t, "translate", out _))
                throw Error($"{path}.transform.translate", "has no effect with fit (the fit box places the mesh)",
                    "move fit.min and fit.max instead, or drop fit");
            if (!user.IsIdentity) mesh.Transform(user);
            mesh.Fit(lo, hi);
        }
        else if (!user.IsIdentity) mesh.Transform(user);
        var placed = mesh.Bounds;
        if (!(Within(placed.Min) && Within(placed.Max)))
            throw Error(TryGet(e, "fit", out _) ? $"{path}.fit" : source,
                $"the placed mesh reaches [{placed.Min.X:g3}, {placed.Min.Y:g3}, {placed.Min.Z:g3}]–[{placed.Max.X:g3}, {placed.Max.Y:g3}, "
                    + $"{placed.Max.Z:g3}], outside ±{MaxCoordinate:g}",
                "use \"fit\" to place the mesh in a box, or a smaller \"transform\" scale");
        bool smooth = true;
        if (TryGet(e, "shading", out var sh))
            smooth = String(sh, $"{path}.shading").ToLowerInvariant() switch
            {
                "smooth" => true,
                "flat" => false,
                var other => throw Error($"{path}.shading", $"unknown shading '{other}'", "use smooth or flat"),
            };
        bool recompute = TryGet(e, "normals", out var nm) && String(nm, $"{path}.normals").ToLowerInvariant() switch
        {
            "file" => false,
            "computed" or "angle" => true,
            var other => throw Error($"{path}.normals", $"unknown normals '{other}'", "use file or computed"),
        };
        if (smooth && (mesh.Normals is null || recompute)) mesh.ComputeVertexNormals();
        if (mesh.TriangleCount == 0)
            throw Error(source, $"'{file}' has no triangles left after dropping {mesh.DegenerateCount} degenerate ones",
                "check the mesh: every triangle has zero area");
        return new SceneObject { Name = name, Material = material, Mesh = mesh, Smooth = smooth };
    }

    /// <summary>
    /// "inline": { "positions": [x, y, z, …], "indices": [i, j, k, …], "normals": [x, y, z, …]?, "uvs": [u, v, …]? } — a mesh
    /// held in the scene (an imported scene's, so a render needs no file): three indices per triangle, one normal and one uv
    /// pair per position.
    /// </summary>
    TriangleMesh InlineMesh(JsonElement e, string path, string name)
    {
        Object(e, path);
        Keys(e, path, "positions", "indices", "normals", "uvs");
        var p = Floats(Required(e, "positions", path), $"{path}.positions", 3, -MaxCoordinate, MaxCoordinate);
        int vertices = p.Length / 3;
        var positions = new Vector3[vertices];
        for (int i = 0; i < vertices; i++) positions[i] = new Vector3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
        var ie = Required(e, "indices", path);
        var f = Floats(ie, $"{path}.indices", 3, 0, Math.Max(0, vertices - 1));
        var indices = new int[f.Length];
        for (int i = 0; i < f.Length; i++)
        {
            if (f[i] != MathF.Floor(f[i]))
                throw Error($"{path}.indices[{i}]", $"index {f[i]} is not a whole number", "indices count positions from 0");
            indices[i] = (int)f[i];
        }
        if (indices.Length == 0) throw Error($"{path}.indices", "no triangles", "give three indices per triangle");
        Vector3[]? normals = null;
        if (TryGet(e, "normals", out var ne))
        {
            var n = Floats(ne, $"{path}.normals", 3, -MaxCoordinate, MaxCoordinate);
            if (n.Length != p.Length)
                throw Error($"{path}.normals", $"{n.Length / 3} normals for {vertices} positions", "give one normal per position");
            normals = new Vector3[vertices];
            for (int i = 0; i < vertices; i++)
            {
                var v = new Vector3(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
                normals[i] = v.LengthSquared() > 0 ? Vector3.Normalize(v) : Vector3.UnitZ;
            }
        }
        Vector2[]? corners = null;
        if (TryGet(e, "uvs", out var ue))
        {
            var uv = Floats(ue, $"{path}.uvs", 2, -MaxCoordinate, MaxCoordinate);
            if (uv.Length != 2 * vertices)
                throw Error($"{path}.uvs", $"{uv.Length / 2} uv pairs for {vertices} positions", "give one [u, v] pair per position");
            corners = new Vector2[indices.Length];   // the mesh keeps uvs per triangle corner
            for (int i = 0; i < indices.Length; i++) corners[i] = new Vector2(uv[2 * indices[i]], uv[2 * indices[i] + 1]);
        }
        return new TriangleMesh(positions, indices, indices.Length, normals, $"inline:{name}", corners);
    }

    /// <summary>A flat array of numbers in [min, max] whose length is a positive multiple of <paramref name="group"/>.</summary>
    float[] Floats(JsonElement e, string path, int group, double min, double max)
    {
        if (e.ValueKind != JsonValueKind.Array || e.GetArrayLength() == 0 || e.GetArrayLength() % group != 0)
            throw Error(path, $"expected a flat array of numbers, {group} per entry, found {Kind(e)}"
                + (e.ValueKind == JsonValueKind.Array ? $" of length {e.GetArrayLength()}" : ""),
                    $"e.g. [{string.Join(", ", Enumerable.Range(0, group))}]");
        var a = new float[e.GetArrayLength()];
        int i = 0;
        foreach (var x in e.EnumerateArray())
        {
            a[i] = (float)Number(x, $"{path}[{i}]", min, max);
            i++;
        }
        return a;
    }
}
