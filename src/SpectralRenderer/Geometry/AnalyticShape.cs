using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Geometry;

/// <summary>The analytic primitives, each a canonical shape in its object space.</summary>
public enum ShapeKind
{
    /// <summary>Unit sphere at the origin.</summary>
    Sphere,
    /// <summary>The plane y = 0, normal +y (infinite).</summary>
    Plane,
    /// <summary>The square [−½, ½]² in the plane z = 0, normal +z.</summary>
    Quad,
    /// <summary>The cube [−½, ½]³.</summary>
    Box,
}

/// <summary>
/// An analytic shape placed by an object-to-world transform. Rays are intersected in object space
/// (o' = M⁻¹o, d' = M⁻¹d keeps the ray parameter t); normals go back with the inverse transpose.
/// </summary>
public sealed class AnalyticShape
{
    public AnalyticShape(ShapeKind kind, Matrix4x4 objectToWorld)
    {
        Kind = kind;
        ObjectToWorld = objectToWorld;
        if (!Matrix4x4.Invert(objectToWorld, out var inv))
            throw new ArgumentException("the object's transform is singular (a zero scale?)");
        WorldToObject = inv;
        NormalToWorld = Matrix4x4.Transpose(inv);
        Bounds = ComputeBounds();
        if (kind is ShapeKind.Quad or ShapeKind.Plane)
            FlatNormal = Vector3.Normalize(Vector3.TransformNormal(kind == ShapeKind.Quad ? Vector3.UnitZ : Vector3.UnitY, NormalToWorld));
    }

    /// <summary>A quad's or plane's world-space unit normal, the one <see cref="Intersect"/> returns at every hit; null for the other kinds.</summary>
    public Vector3? FlatNormal { get; }

    public ShapeKind Kind { get; }
    public Matrix4x4 ObjectToWorld { get; }
    public Matrix4x4 WorldToObject { get; }
    public Matrix4x4 NormalToWorld { get; }
    public bool IsInfinite => Kind == ShapeKind.Plane;
    public Bounds3 Bounds { get; }

    /// <summary>Closest hit in (tMin, ray.TMax); on a hit returns t and the world-space unit normal.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Intersect(in Ray ray, float tMin, out float t, out Vector3 normal)
    {
        var o = Vector3.Transform(ray.Origin, WorldToObject);
        var d = Vector3.TransformNormal(ray.Direction, WorldToObject);
        Vector3 n = default;
        t = 0;
        switch (Kind)
        {
            case ShapeKind.Sphere:
                {
                    // |o + t d|² = 1, solved in double for a stable discriminant.
                    double a = Vector3.Dot(d, d), b = Vector3.Dot(o, d), c = Vector3.Dot(o, o) - 1.0;
                    double disc = b * b - a * c;
                    if (disc < 0) { normal = default; return false; }
                    double sq = Math.Sqrt(disc);
                    double q = b > 0 ? -(b + sq) : -(b - sq);
                    double t0 = q / a, t1 = c / q;
                    if (t0 > t1) (t0, t1) = (t1, t0);
                    double th = t0 > tMin ? t0 : t1;
                    if (!(th > tMin && th < ray.TMax)) { normal = default; return false; }
                    t = (float)th;
                    n = o + t * d;
                    break;
                }
            case ShapeKind.Plane:
                {
                    if (d.Y == 0) { normal = default; return false; }
                    t = -o.Y / d.Y;
                    if (!(t > tMin && t < ray.TMax)) { normal = default; return false; }
                    n = Vector3.UnitY;
                    break;
                }
            case ShapeKind.Quad:
                {
                    if (d.Z == 0) { normal = default; return false; }
                    t = -o.Z / d.Z;
                    if (!(t > tMin && t < ray.TMax)) { normal = default; return false; }
                    var p = o + t * d;
                    if (Math.Abs(p.X) > 0.5f || Math.Abs(p.Y) > 0.5f) { normal = default; return false; }
                    n = Vector3.UnitZ;
                    break;
                }
            case ShapeKind.Box:
                {
                    float tNear = float.NegativeInfinity, tFar = float.PositiveInfinity;
                    int axisNear = 0, axisFar = 0;
                    for (int i = 0; i < 3; i++)
                    {
                        float oi = Component(o, i), di = Component(d, i);
                        float inv = 1f / di;
                        float ta = (-0.5f - oi) * inv, tb = (0.5f - oi) * inv;
                        if (ta > tb) (ta, tb) = (tb, ta);
                        if (ta > tNear) { tNear = ta; axisNear = i; }
                        if (tb < tFar) { tFar = tb; axisFar = i; }
                    }
                    if (tNear > tFar) { normal = default; return false; }
                    int axis;
                    if (tNear > tMin) { t = tNear; axis = axisNear; }
                    else { t = tFar; axis = axisFar; }
                    if (!(t > tMin && t < ray.TMax)) { normal = default; return false; }
                    var p = o + t * d;
                    n = axis switch
                    {
                        0 => new Vector3(Math.Sign(p.X), 0, 0),
                        1 => new Vector3(0, Math.Sign(p.Y), 0),
                        _ => new Vector3(0, 0, Math.Sign(p.Z)),
                    };
                    break;
                }
        }
        normal = Vector3.Normalize(Vector3.TransformNormal(n, NormalToWorld));
        return true;
    }

    static float Component(Vector3 v, int i) => i == 0 ? v.X : i == 1 ? v.Y : v.Z;

    Bounds3 ComputeBounds()
    {
        if (Kind == ShapeKind.Plane) return new Bounds3(new Vector3(float.NegativeInfinity), new Vector3(float.PositiveInfinity));
        var b = Bounds3.Empty;
        float zr = Kind == ShapeKind.Quad ? 0 : Kind == ShapeKind.Sphere ? 1 : 0.5f;
        float r = Kind == ShapeKind.Sphere ? 1 : 0.5f;
        for (int i = 0; i < 8; i++)
        {
            var c = new Vector3((i & 1) == 0 ? -r : r, (i & 2) == 0 ? -r : r, (i & 4) == 0 ? -zr : zr);
            b.Include(Vector3.Transform(c, ObjectToWorld));
        }
        return b;
    }
}
