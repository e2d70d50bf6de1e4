using System.Numerics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

// Instanced meshes (SceneObject.InstanceTransform): one BVH per distinct prototype mesh and a top-level BVH over the
// instances (InstanceSet), met after the world-space triangles by every query, single rays and packets (lane by lane).
// A hit's normals go back to world space with the inverse transpose, each vertex normal on its own before they are
// interpolated, as they are for the same mesh transformed into world space: the two agree to float rounding.
public sealed partial class SceneGeometry
{
    readonly InstanceSet _instances;
    readonly bool _hasInstances;
    // Per instance, in the top-level order (k): its object, prototype mesh, smooth shading, and transforms (set by
    // BuildInstances, from the constructor).
    int[] _instanceObject = [];
    TriangleMesh[] _instanceMesh = [];
    bool[] _instanceSmooth = [];
    Matrix4x4[] _instanceToWorld = [];
    Matrix4x4[] _instanceNormalToWorld = [];

    /// <summary>Triangles of all instances (each instance counting its prototype's).</summary>
    public int InstancedTriangleCount { get; private set; }

    /// <summary>The distinct prototype meshes, each with its own BVH (what instancing saves: the memory of one copy each).</summary>
    public int PrototypeCount => _hasInstances ? _instances.Prototypes.Length : 0;

    (InstanceSet, bool) BuildInstances(Scene scene, List<int> objects)
    {
        if (objects.Count == 0) return (default, false);
        var prototypeIndex = new Dictionary<TriangleMesh, int>(ReferenceEqualityComparer.Instance);
        var prototypes = new List<TriangleSet>();
        var prototypeOf = new int[objects.Count];
        var toWorld = new Matrix4x4[objects.Count];
        for (int i = 0; i < objects.Count; i++)
        {
            var o = scene.Objects[objects[i]];
            var mesh = o.Mesh!;
            if (!prototypeIndex.TryGetValue(mesh, out int p))
            {
                prototypeIndex[mesh] = p = prototypes.Count;
                prototypes.Add(TriangleSet.Build([mesh]));
            }
            prototypeOf[i] = p;
            toWorld[i] = o.InstanceTransform!.Value;
            InstancedTriangleCount += mesh.TriangleCount;
        }
        var set = InstanceSet.Build(prototypes, prototypeOf, toWorld);
        int n = objects.Count;
        var order = set.InstanceOf;
        var objectOf = new int[n];
        var meshOf = new TriangleMesh[n];
        var smooth = new bool[n];
        var world = new Matrix4x4[n];
        var normal = new Matrix4x4[n];
        for (int k = 0; k < n; k++)
        {
            var o = scene.Objects[objects[order[k]]];
            objectOf[k] = objects[order[k]];
            meshOf[k] = o.Mesh!;
            smooth[k] = o.Smooth;
            world[k] = toWorld[order[k]];
            Matrix4x4.Invert(world[k], out var inverse);
            normal[k] = Matrix4x4.Transpose(inverse);
        }
        (_instanceObject, _instanceMesh, _instanceSmooth) = (objectOf, meshOf, smooth);
        (_instanceToWorld, _instanceNormalToWorld) = (world, normal);
        return (set, true);
    }

    /// <summary>The surface record of instanced triangle h (h.Primitive the instance k, h.Element its prototype's triangle):
    /// the face normal n·M⁻ᵀ, and for smooth shading the vertex normals, each taken to world space and normalised, then
    /// interpolated (as the mesh transformed into world space has them).</summary>
    void RecordInstance(in Hit h, ref SurfaceHit hit)
    {
        int k = h.Primitive;
        var prototype = _instances.Prototypes[_instances.PrototypeOf(k)];
        var (p0, p1, p2) = prototype.Corners(h.Element);
        var toWorld = _instanceNormalToWorld[k];
        var ng = Vector3.Normalize(Vector3.TransformNormal(Vector3.Cross(p1 - p0, p2 - p0), toWorld));
        hit.GeometricNormal = ng;
        hit.Normal = ng;
        var m = _instanceMesh[k];
        if (_instanceSmooth[k] && m.Normals is { } normals)
        {
            int tri = prototype.TriangleOf[h.Element];
            var idx = m.Indices;
            var n = (1 - h.U - h.V) * World(normals[idx[3 * tri]]) + h.U * World(normals[idx[3 * tri + 1]])
                + h.V * World(normals[idx[3 * tri + 2]]);
            if (n.LengthSquared() > 0) hit.Normal = Vector3.Normalize(n);
        }
        hit.Object = _instanceObject[k];
        hit.Primitive = k; hit.Element = h.Element; hit.B1 = h.U; hit.B2 = h.V;

        Vector3 World(Vector3 normal) => Vector3.Normalize(Vector3.TransformNormal(normal, toWorld));
    }

    /// <summary>Texture coordinates of an instanced triangle's hit (kind 4): its prototype's, the density from its world corners.</summary>
    Vector2 InstanceTexCoord(in SurfaceHit hit, out float uvPerLength)
    {
        int k = hit.Primitive;
        var prototype = _instances.Prototypes[_instances.PrototypeOf(k)];
        var (p0, p1, p2) = prototype.Corners(hit.Element);
        var m = _instanceToWorld[k];
        (p0, p1, p2) = (Vector3.Transform(p0, m), Vector3.Transform(p1, m), Vector3.Transform(p2, m));
        int tri = prototype.TriangleOf[hit.Element];
        var uvs = _instanceMesh[k].TexCoords;
        return uvs is null
            ? TextureCoordinates.OfTriangle(Vector2.Zero, Vector2.UnitX, Vector2.UnitY, hit.B1, hit.B2, p0, p1, p2, out uvPerLength)
            : TextureCoordinates.OfTriangle(uvs[3 * tri], uvs[3 * tri + 1], uvs[3 * tri + 2], hit.B1, hit.B2, p0, p1, p2,
                out uvPerLength);
    }
}
