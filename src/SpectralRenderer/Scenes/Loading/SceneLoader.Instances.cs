using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Loading;

// Instancing: "prototypes" names meshes (as a mesh object gives them: file or inline, transform, fit, shading, normals) that
// "instance" objects place by their own transform, sharing the one mesh and its BVH (SceneGeometry's two levels).
public sealed partial class SceneLoader
{
    static readonly string[] PrototypeKeys = ["file", "inline", "transform", "fit", "shading", "normals"];
    readonly Dictionary<string, SceneObject> _prototypes = new(StringComparer.Ordinal);

    /// <summary>Reads "prototypes": { "NAME": { mesh keys }, … }, each mesh once, in object space.</summary>
    void ParsePrototypes(JsonElement root)
    {
        if (!TryGet(root, "prototypes", out var block)) return;
        foreach (var p in Object(block, "$.prototypes").EnumerateObject())
        {
            string path = $"$.prototypes.{p.Name}";
            Object(p.Value, path);
            Keys(p.Value, path, PrototypeKeys);
            var user = TryGet(p.Value, "transform", out var t) ? Transform(t, $"{path}.transform") : Matrix4x4.Identity;
            _prototypes[p.Name] = MeshObject(p.Value, path, p.Name, user, 0);
        }
    }

    /// <summary>{ "type": "instance", "prototype": "NAME", "material", "transform" }: the prototype's mesh placed by the
    /// transform, not copied.</summary>
    SceneObject InstanceObject(JsonElement e, string path, string name, Matrix4x4 transform, int material)
    {
        var reference = String(Required(e, "prototype", path), $"{path}.prototype");
        if (!_prototypes.TryGetValue(reference, out var prototype))
            throw Error($"{path}.prototype", $"no prototype named {MessageText.Quote(reference)}",
                InputException.DidYouMean(reference, _prototypes.Keys)
                ?? (_prototypes.Count == 0 ? "define it under the top-level \"prototypes\"" :
                    $"prototypes: {string.Join(", ", _prototypes.Keys.Order(StringComparer.Ordinal))}"));
        if (prototype.Mesh is { } mesh)
        {
            var placed = mesh.Bounds.Transformed(transform);
            if (!(Within(placed.Min) && Within(placed.Max)))
                throw Error($"{path}.transform",
                    $"the instance reaches [{placed.Min.X:g3}, {placed.Min.Y:g3}, {placed.Min.Z:g3}]–[{placed.Max.X:g3}, "
                        + $"{placed.Max.Y:g3}, {placed.Max.Z:g3}], outside ±{MaxCoordinate:g}",
                    "use a smaller transform scale or translation");
        }
        return new SceneObject
        {
            Name = name,
            Material = material,
            Mesh = prototype.Mesh,
            Smooth = prototype.Smooth,
            InstanceTransform = transform,
        };
    }

    /// <summary>
    /// Instances whose material emits become world-space copies of their prototype: an area emitter samples its triangles in
    /// world space (and a luminous flux needs their world area), so emitting instances are supported by copying them.
    /// </summary>
    void CopyEmittingInstances(List<SceneObject> objects, List<Material> materials, Dictionary<string, int> materialIndex)
    {
        var flux = new HashSet<int>();
        foreach (var f in _fluxEmissions)
            if (f.Path.StartsWith("$.materials.", StringComparison.Ordinal)
                && materialIndex.TryGetValue(f.Path["$.materials.".Length..], out int m)) flux.Add(m);
        for (int i = 0; i < objects.Count; i++)
        {
            var o = objects[i];
            if (o.InstanceTransform is null || o.Mesh is null) continue;
            if (materials[o.Material].Emission is null && !flux.Contains(o.Material)) continue;
            objects[i] =
                new SceneObject { Name = o.Name, Material = o.Material, Mesh = o.WorldMesh(), Smooth = o.Smooth, Medium = o.Medium };
        }
    }
}
