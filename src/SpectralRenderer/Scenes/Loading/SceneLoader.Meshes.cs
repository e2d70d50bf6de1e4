using System.Numerics;
using System.Runtime.CompilerServices;
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
    [MethodImpl(MethodImplOptions.NoOptimization)]
    void StartMeshReads(JsonElement root)
    {
        if (!_overrides.LoadMeshes || !TryGet(root, "objects", out var objects) || objects.ValueKind != JsonValueKind.Array) return;
        foreach (var o in objects.EnumerateArray())
        {
            if (o.ValueKind != JsonValueKind.Object || !o.TryGetProperty("type", out var type) || type.ValueKind != JsonValueKind.String ||
                !type.GetString()!.Equals("mesh", StringComparison.OrdinalIgnoreCase) ||
                !o.TryGetProperty("file", out var f) || f.ValueKind != JsonValueKind.String) continue;
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
    [MethodImpl(MethodImplOptions.NoOptimization)]
    SceneObject MeshObject(JsonElement e, string path, string name, Matrix4x4 user, int material)
    {
        var file = String(Required(e, "file", path), $"{path}.file");
        if (!_overrides.LoadMeshes) return new SceneObject { Name = name, Material = material };
        var full = ModelSearch.Find(file, _dir, _overrides.ModelDirectories)
            ?? throw Error($"{path}.file", $"mesh '{file}' not found in {ModelSearch.Describe(_dir, _overrides.ModelDirectories)}",
                "get the meshes (README, 'Meshes'); pass --models DIR or set SPECTRAL_MODELS", InputProblem.MissingFile);
        var ext = Path.GetExtension(full).ToLowerInvariant();
        if (ext is not (".obj" or ".ply"))
            throw Error($"{path}.file", $"'{file}' is neither .obj nor .ply", "meshes are Wavefront .obj or Stanford .ply files");
        // The read started with the scene (StartMeshReads); a second object on the same file reads it again,
        // since fitting and transforming change the mesh. Its errors surface here, as if read in place.
        TriangleMesh mesh = _meshReads.Remove(full, out var read) ? read.GetAwaiter().GetResult() : ReadMesh(full);
        var extent = mesh.Bounds.Extent;
        if (!(float.IsFinite(extent.X) && float.IsFinite(extent.Y) && float.IsFinite(extent.Z)))
            throw Error($"{path}.file",
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
            throw Error(TryGet(e, "fit", out _) ? $"{path}.fit" : $"{path}.file",
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
            throw Error($"{path}.file", $"'{file}' has no triangles left after dropping {mesh.DegenerateCount} degenerate ones",
                "check the mesh: every triangle has zero area");
        return new SceneObject { Name = name, Material = material, Mesh = mesh, Smooth = smooth };
    }
}
