using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Generated texture coordinates (u, v) of the analytic shapes, v up (texel row 0 of an image is v = 1), and the
/// density of the mapping (uv units per world length, the square root of uv area over world area) that sets the
/// mip level of a lookup. Quad: u = x + ½, v = y + ½ over [−½, ½]². Sphere: u = ½ + atan2(x, z)/2π (longitude),
/// v = 1 − acos(y)/π (0 at the south pole). Box: each face holds the whole [0, 1]² (the face's own right and up
/// axes, seen from outside). Plane: u = x, v = −z in object space (repeats with the texture's wrap). A registered kind
/// (disk, cylinder, …): its <see cref="CanonicalShape.TexCoord"/>, at the density of its uv area over its world area.
/// </summary>
public static class TextureCoordinates
{
    /// <summary>The (u, v) at world point <paramref name="p"/> on <paramref name="shape"/>, and uv units per world length there.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static Vector2 OfShape(AnalyticShape shape, Vector3 p, out float uvPerLength)
    {
        var o = Vector3.Transform(p, shape.WorldToObject);
        var m = shape.ObjectToWorld;
        var ax = new Vector3(m.M11, m.M12, m.M13);   // the object's axes in world space (row-vector convention)
        var ay = new Vector3(m.M21, m.M22, m.M23);
        var az = new Vector3(m.M31, m.M32, m.M33);
        switch (shape.Kind)
        {
            case ShapeKind.Quad:
                uvPerLength = Density(Vector3.Cross(ax, ay).Length());
                return new Vector2(o.X + 0.5f, o.Y + 0.5f);
            case ShapeKind.Plane:
                uvPerLength = Density(Vector3.Cross(ax, az).Length());
                return new Vector2(o.X, -o.Z);
            case ShapeKind.Sphere:
                {
                    var d = o.LengthSquared() > 0 ? Vector3.Normalize(o) : Vector3.UnitY;
                    // Area of the (possibly scaled) sphere ~ 4π times the mean product of its semi-axes.
                    float area = 4 * MathF.PI * (ax.Length() * ay.Length() + ay.Length() * az.Length() + az.Length() * ax.Length()) / 3;
                    uvPerLength = Density(area);
                    return new Vector2(0.5f + MathF.Atan2(d.X, d.Z) / (2 * MathF.PI), 1 - MathF.Acos(Math.Clamp(d.Y, -1f, 1f)) / MathF.PI);
                }
            case ShapeKind.Registered:
                {
                    var canonical = shape.Canonical!;
                    uvPerLength = shape.Area > 0 ? MathF.Sqrt(canonical.TexCoordArea / shape.Area) : 0;
                    return canonical.TexCoord(o);
                }
            default:
                {
                    float x = MathF.Abs(o.X), y = MathF.Abs(o.Y), z = MathF.Abs(o.Z);
                    if (z >= x && z >= y)
                    {
                        uvPerLength = Density(Vector3.Cross(ax, ay).Length());
                        return new Vector2(0.5f + MathF.CopySign(1, o.Z) * o.X, o.Y + 0.5f);
                    }
                    if (x >= y)
                    {
                        uvPerLength = Density(Vector3.Cross(ay, az).Length());
                        return new Vector2(0.5f - MathF.CopySign(1, o.X) * o.Z, o.Y + 0.5f);
                    }
                    uvPerLength = Density(Vector3.Cross(ax, az).Length());
                    return new Vector2(o.X + 0.5f, 0.5f - MathF.CopySign(1, o.Y) * o.Z);
                }
        }
    }

    /// <summary>(u, v) interpolated over a triangle with barycentrics (b1, b2) from its corners' coordinates, and the density.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector2 OfTriangle(Vector2 t0, Vector2 t1, Vector2 t2, float b1, float b2, Vector3 p0, Vector3 p1, Vector3 p2,
        out float uvPerLength)
    {
        var e1 = t1 - t0;
        var e2 = t2 - t0;
        float uvArea = MathF.Abs(e1.X * e2.Y - e1.Y * e2.X);
        float worldArea = Vector3.Cross(p1 - p0, p2 - p0).Length();
        uvPerLength = worldArea > 0 ? MathF.Sqrt(uvArea / worldArea) : 0;
        return (1 - b1 - b2) * t0 + b1 * t1 + b2 * t2;
    }

    static float Density(float area) => area > 0 ? 1 / MathF.Sqrt(area) : 0;
}
