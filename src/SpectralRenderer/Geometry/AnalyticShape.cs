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
    /// <summary>A registered kind (<see cref="AnalyticShape.Canonical"/>: disk, cylinder, or one added by a registration).</summary>
    Registered,
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
        if (kind == ShapeKind.Registered) throw new ArgumentException("a registered kind is placed with its canonical shape");
        Bounds = ComputeBounds();
        if (kind is ShapeKind.Quad or ShapeKind.Plane)
            FlatNormal = Vector3.Normalize(Vector3.TransformNormal(kind == ShapeKind.Quad ? Vector3.UnitZ : Vector3.UnitY, NormalToWorld));
    }

    /// <summary>A registered kind of shape (<see cref="CanonicalShape"/>) placed by <paramref name="objectToWorld"/>.</summary>
    public AnalyticShape(CanonicalShape canonical, Matrix4x4 objectToWorld)
    {
        Kind = ShapeKind.Registered;
        Canonical = canonical;
        ObjectToWorld = objectToWorld;
        if (!Matrix4x4.Invert(objectToWorld, out var inv))
            throw new ArgumentException("the object's transform is singular (a zero scale?)");
        WorldToObject = inv;
        NormalToWorld = Matrix4x4.Transpose(inv);
        Bounds = ComputeBounds();
        if (canonical.FlatNormal is { } flat) FlatNormal = Vector3.Normalize(Vector3.TransformNormal(flat, NormalToWorld));
        _determinant = MathF.Abs(objectToWorld.GetDeterminant());
        Area = canonical.Area * MeanAreaScale(canonical);
    }

    /// <summary>The shape of a <see cref="ShapeKind.Registered"/> kind, else null.</summary>
    public CanonicalShape? Canonical { get; }

    /// <summary>A registered kind's world-space area (exact for flat shapes and similarity placements, else by a 32 × 32
    /// midpoint rule over its area sampling); 0 for the built-in kinds.</summary>
    public float Area { get; }

    readonly float _determinant;

    /// <summary>J = |det L|·|L⁻ᵀ·n|: how much the placement's linear part L scales area at object normal n.</summary>
    float AreaScale(Vector3 objectNormal) => _determinant * Vector3.TransformNormal(objectNormal, NormalToWorld).Length();

    float MeanAreaScale(CanonicalShape canonical)
    {
        const int n = 32;
        double sum = 0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
            {
                canonical.SampleArea(new Vector2((i + 0.5f) / n, (j + 0.5f) / n), out var normal);
                sum += AreaScale(normal);
            }
        return (float)(sum / (n * n));
    }

    /// <summary>A registered kind's point for <paramref name="u"/> ∈ [0, 1)² (world space), its unit outward normal and the
    /// area density p_A = 1/(A_obj·J) of drawing it.</summary>
    public Vector3 SampleArea(Vector2 u, out Vector3 normal, out float pdfArea)
    {
        var canonical = Canonical!;
        var p = canonical.SampleArea(u, out var n);
        var world = Vector3.TransformNormal(n, NormalToWorld);
        float length = world.Length();
        normal = world / length;
        pdfArea = 1 / (canonical.Area * _determinant * length);
        return Vector3.Transform(p, ObjectToWorld);
    }

    /// <summary>The area density of <see cref="SampleArea"/> at a point of world normal <paramref name="normal"/>:
    /// 1/(A_obj·J) with J = |det L|/|Lᵀ·n| (the object normal is Lᵀn normalised).</summary>
    public float AreaPdf(Vector3 normal)
    {
        var m = ObjectToWorld;
        var back = new Vector3(m.M11 * normal.X + m.M12 * normal.Y + m.M13 * normal.Z,
            m.M21 * normal.X + m.M22 * normal.Y + m.M23 * normal.Z, m.M31 * normal.X + m.M32 * normal.Y + m.M33 * normal.Z);
        return back.Length() / (Canonical!.Area * _determinant);
    }

    /// <summary>A flat shape's (quad, plane, disk) world-space unit normal, the one <see cref="Intersect"/> returns at every
    /// hit; null for the other kinds.</summary>
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
            default:
                if (!Canonical!.Intersect(o, d, tMin, ray.TMax, out t, out n)) { normal = default; return false; }
                break;
        }
        normal = Vector3.Normalize(Vector3.TransformNormal(n, NormalToWorld));
        return true;
    }

    static float Component(Vector3 v, int i) => i == 0 ? v.X : i == 1 ? v.Y : v.Z;

    Bounds3 ComputeBounds()
    {
        if (Kind == ShapeKind.Plane) return new Bounds3(new Vector3(float.NegativeInfinity), new Vector3(float.PositiveInfinity));
        var b = Bounds3.Empty;
        if (Canonical is { } canonical)
        {
            var (lo, hi) = (canonical.Bounds.Min, canonical.Bounds.Max);
            for (int i = 0; i < 8; i++)
                b.Include(Vector3.Transform(new Vector3((i & 1) == 0 ? lo.X : hi.X, (i & 2) == 0 ? lo.Y : hi.Y, (i & 4) == 0 ? lo.Z : hi.Z),
                    ObjectToWorld));
            return b;
        }
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
