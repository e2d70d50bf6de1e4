using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Ray queries against every object of a scene: all mesh triangles in one SAH BVH (walked 8-wide by single rays, binary by
/// packets), instanced meshes in a two-level <see cref="InstanceSet"/> (SceneGeometry.Instances.cs), the finite analytic
/// shapes in another, infinite planes tested directly. Closest hit for camera and secondary rays,
/// any hit (early exit) for shadow rays.
/// </summary>
public sealed partial class SceneGeometry
{
    readonly TriangleSet _triangles;
    readonly bool _hasTriangles;
    readonly int[] _meshObject;
    readonly TriangleMesh[] _meshes;
    readonly bool[] _meshSmooth;
    readonly AnalyticSet _analytic;
    readonly Bvh? _analyticBvh;
    readonly int[] _analyticObject;
    readonly FlatFaces? _faces;   // the finite shapes as flat faces, when they are few quads and boxes (IntersectScattered)
    readonly (Vector3 Normal, float Offset)[] _planes;   // n·x = offset, world space
    readonly int[] _planeObject;

    /// <param name="cache">Where a BVH built for the same triangles by an earlier scene can be found (and this one's kept); null: built
    /// here.</param>
    public SceneGeometry(Scene scene, GeometryCache? cache = null)
    {
        var meshes = new List<TriangleMesh>();
        var meshObject = new List<int>();
        var finite = new List<(AnalyticShape Shape, int Object)>();
        var planes = new List<(AnalyticShape Shape, int Object)>();
        var instances = new List<int>();
        for (int i = 0; i < scene.Objects.Count; i++)
        {
            var o = scene.Objects[i];
            if (o.Mesh is { TriangleCount: > 0 } && o.InstanceTransform is not null) instances.Add(i);
            else if (o.Mesh is { } m) { meshes.Add(m); meshObject.Add(i); }
            else if (o.Shape is { IsInfinite: true } p) planes.Add((p, i));
            else if (o.Shape is { } s) finite.Add((s, i));
        }
        _meshes = meshes.ToArray();
        _meshObject = meshObject.ToArray();
        _meshSmooth = meshObject.Select(i => scene.Objects[i].Smooth).ToArray();
        _hasTriangles = meshes.Count > 0 && meshes.Sum(m => m.TriangleCount) > 0;
        _triangles = !_hasTriangles ? default : cache is null ? TriangleSet.Build(_meshes) : cache.Triangles(_meshes);
        (_instances, _hasInstances) = BuildInstances(scene, instances);
        TriangleCount = (_hasTriangles ? _triangles.Count : 0) + InstancedTriangleCount;

        if (finite.Count > 0)
        {
            _analyticBvh = Bvh.Build(finite.Select(f => f.Shape.Bounds).ToArray(), 2);
            var order = _analyticBvh.PrimitiveOrder;
            _analytic = new AnalyticSet(order.Select(k => finite[k].Shape).ToArray());
            _analyticObject = order.Select(k => finite[k].Object).ToArray();
            _faces = FlatFaces.TryBuild(order.Select(k => finite[k].Shape).ToArray());
        }
        else _analyticObject = [];
        // Planes are tested directly in world space (an affine map keeps a plane a plane).
        _planes = planes.Select(p =>
        {
            var n = Vector3.Normalize(Vector3.TransformNormal(Vector3.UnitY, p.Shape.NormalToWorld));
            return (n, Vector3.Dot(n, Vector3.Transform(Vector3.Zero, p.Shape.ObjectToWorld)));
        }).ToArray();
        _planeObject = planes.Select(p => p.Object).ToArray();
        _planeShapes = planes.Select(p => p.Shape).ToArray();

        var b = Bounds3.Empty;
        if (_hasTriangles) b.Include(_triangles.Bvh.Bounds);
        if (_hasInstances) b.Include(_instances.Bvh.Bounds);
        if (_analyticBvh is not null) b.Include(_analyticBvh.Bounds);
        float extent = b.IsEmpty ? 1 : Math.Max(b.Extent.Length(), Vector3.Max(Vector3.Abs(b.Min), Vector3.Abs(b.Max)).Length());
        Epsilon = 1e-5f * Math.Max(1f, extent);
        BoundingRadius = b.IsEmpty ? 0 : b.Extent.Length() / 2;
        BoundingCentre = b.IsEmpty ? Vector3.Zero : (b.Min + b.Max) / 2;
    }

    /// <summary>The centre of the finite geometry's bounding box (the origin without finite geometry).</summary>
    public Vector3 BoundingCentre { get; }

    /// <summary>The radius of the sphere about the finite geometry's bounding box (half its diagonal; 0 without finite
    /// geometry): what a light at infinity shines through (its power, <c>EmitterSet.Power</c>).</summary>
    public float BoundingRadius { get; }

    /// <summary>Offset for secondary-ray origins, scaled to the scene's size.</summary>
    public float Epsilon { get; }
    /// <summary>Triangles seen: the meshes' in world space and every instance's prototype triangles.</summary>
    public int TriangleCount { get; }
    /// <summary>Bytes the triangle structures hold per triangle (<see cref="TriangleSet.BytesPerTriangle"/>; 0 without
    /// triangles).</summary>
    public double TriangleBytesPerTriangle => _hasTriangles ? _triangles.BytesPerTriangle : 0;

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Intersect(ref Ray ray, out SurfaceHit hit)
    {
        hit = default;
        var h = new Hit();
        int kind = 0; // 1 triangle, 2 analytic, 3 plane
        if (_hasTriangles)
        {
            var t = _triangles;
            if (t.Wide.Intersect(ref t, ref ray, ref h)) kind = 1;
        }
        if (_hasInstances)
        {
            var s = _instances;
            if (s.Bvh.Intersect(ref s, ref ray, ref h)) kind = 4;
        }
        var ah = new Hit();
        if (_analyticBvh is not null)
        {
            var a = _analytic;
            if (_analyticBvh.Intersect(ref a, ref ray, ref ah)) kind = 2;
        }
        int plane = -1;
        for (int i = 0; i < _planes.Length; i++)
            if (HitPlane(i, ray, out float tp)) { ray.TMax = tp; plane = i; kind = 3; }
        if (kind == 0) return false;
        Record(kind, ray, h, ah, plane, out hit);
        return true;
    }

    /// <summary>
    /// As <see cref="Intersect(ref Ray, out SurfaceHit)"/>, for rays scattered in every direction one at a time (the path integrator's): a
    /// scene's few quads and boxes are met as <see cref="FlatFaces"/> all at once instead of through their BVH. The hit agrees with
    /// <see cref="Intersect(ref Ray, out SurfaceHit)"/>'s to float rounding (world-space instead of object-space distances), not bit for
    /// bit, so the whitted integrator keeps <see cref="Intersect(ref Ray, out SurfaceHit)"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool IntersectScattered(ref Ray ray, out SurfaceHit hit)
    {
        if (_faces is not { } faces) return Intersect(ref ray, out hit);
        var h = new Hit();
        int kind = 0;
        if (_hasTriangles)
        {
            var t = _triangles;
            if (t.Wide.Intersect(ref t, ref ray, ref h)) kind = 1;
        }
        if (_hasInstances)
        {
            var s = _instances;
            if (s.Bvh.Intersect(ref s, ref ray, ref h)) kind = 4;
        }
        int face = faces.Intersect(ref ray);
        if (face >= 0) kind = 2;
        int plane = -1;
        for (int i = 0; i < _planes.Length; i++)
            if (HitPlane(i, ray, out float tp)) { ray.TMax = tp; plane = i; kind = 3; }
        if (kind != 2)
        {
            if (kind == 0) { hit = default; return false; }
            Record(kind, ray, h, default, plane, out hit);
            return true;
        }
        hit = default;
        hit.T = ray.TMax;
        hit.Position = ray.At(ray.TMax);
        hit.Kind = 2;
        hit.Normal = hit.GeometricNormal = faces.Normal(face);
        int shape = faces.ShapeOf(face);
        hit.Object = _analyticObject[shape];
        hit.Primitive = shape;
        return true;
    }

    /// <summary>As <see cref="Occluded(in Ray)"/>, with the flat faces of <see cref="IntersectScattered"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool OccludedScattered(in Ray ray)
    {
        if (_faces is not { } faces) return Occluded(ray);
        if (_hasTriangles)
        {
            var t = _triangles;
            if (t.Wide.Occluded(ref t, ray)) return true;
        }
        if (_hasInstances && _instances.Occluded(ray)) return true;
        if (faces.Occluded(ray)) return true;
        for (int i = 0; i < _planes.Length; i++)
            if (HitPlane(i, ray, out _)) return true;
        return false;
    }

    /// <summary>The surface record of a closest hit found by kind (1 triangle h, 2 analytic shape ah, 3 plane, 4 instanced
    /// triangle h) at ray.TMax.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void Record(int kind, in Ray ray, in Hit h, in Hit ah, int plane, out SurfaceHit hit)
    {
        hit = default;
        hit.T = ray.TMax;
        hit.Position = ray.At(ray.TMax);
        hit.Kind = kind;
        switch (kind)
        {
            case 1:
                {
                    int k = h.Primitive;
                    int mesh = _triangles.MeshOf[k];
                    var (p0, p1, p2) = _triangles.Corners(k);
                    var ng = Vector3.Normalize(Vector3.Cross(p1 - p0, p2 - p0));
                    hit.GeometricNormal = ng;
                    hit.Normal = ng;
                    var m = _meshes[mesh];
                    if (_meshSmooth[mesh] && m.Normals is { } normals)
                    {
                        int tri = _triangles.TriangleOf[k];
                        var idx = m.Indices;
                        var n = (1 - h.U - h.V) * normals[idx[3 * tri]] + h.U * normals[idx[3 * tri + 1]] + h.V * normals[idx[3 * tri + 2]];
                        if (n.LengthSquared() > 0) hit.Normal = Vector3.Normalize(n);
                    }
                    hit.Object = _meshObject[mesh];
                    hit.Primitive = k; hit.B1 = h.U; hit.B2 = h.V;
                    break;
                }
            case 2:
                {
                    // A flat shape's normal is one vector; a curved or many-faced one's winning shape is re-intersected for
                    // it (cheaper than carrying normals through the BVH).
                    var shape = _analytic[ah.Primitive];
                    Vector3 na;
                    if (shape.FlatNormal is { } flat) na = flat;
                    else shape.Intersect(new Ray(ray.Origin, ray.Direction, float.PositiveInfinity), 0, out _, out na);
                    hit.Normal = hit.GeometricNormal = na;
                }
                hit.Object = _analyticObject[ah.Primitive];
                hit.Primitive = ah.Primitive;
                break;
            case 4:
                RecordInstance(h, ref hit);
                break;
            default:
                hit.Normal = hit.GeometricNormal = _planes[plane].Normal;
                hit.Object = _planeObject[plane];
                hit.Primitive = plane;
                break;
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Occluded(in Ray ray)
    {
        if (_hasTriangles)
        {
            var t = _triangles;
            if (t.Wide.Occluded(ref t, ray)) return true;
        }
        if (_hasInstances && _instances.Occluded(ray)) return true;
        if (_analyticBvh is not null)
        {
            var a = _analytic;
            if (_analyticBvh.Occluded(ref a, ray)) return true;
        }
        for (int i = 0; i < _planes.Length; i++)
            if (HitPlane(i, ray, out _)) return true;
        return false;
    }

    /// <summary>The ray meets plane i at t in (0, TMax).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    bool HitPlane(int i, in Ray ray, out float t)
    {
        var (n, offset) = _planes[i];
        float denominator = Vector3.Dot(n, ray.Direction);
        t = (offset - Vector3.Dot(n, ray.Origin)) / denominator;
        return denominator != 0 && t > 0 && t < ray.TMax;
    }
}
