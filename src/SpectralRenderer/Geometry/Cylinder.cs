using System.Numerics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// The open tube x² + y² = 1, 0 ≤ z ≤ 1 (no caps, as Mitsuba's and pbrt's cylinder; close it with disks), normal
/// outward (x, y, 0). Texture coordinates as pbrt's and Mitsuba's: u = φ/2π, φ = atan2(y, x) ∈ [0, 2π), v = z.
/// Sampled uniformly by area: z = u₁, φ = 2π·u₂.
/// </summary>
public sealed class Cylinder : CanonicalShape
{
    public override bool Intersect(Vector3 o, Vector3 d, float tMin, float tMax, out float t, out Vector3 normal)
    {
        // (o_x + t d_x)² + (o_y + t d_y)² = 1, in double with the stable root pair (as the sphere's).
        t = 0;
        normal = default;
        double a = (double)d.X * d.X + (double)d.Y * d.Y;
        if (a == 0) return false;   // along the axis: never meets the tube's side
        double b = (double)o.X * d.X + (double)o.Y * d.Y, c = (double)o.X * o.X + (double)o.Y * o.Y - 1;
        double disc = b * b - a * c;
        if (disc < 0) return false;
        double sq = Math.Sqrt(disc);
        double q = b > 0 ? -(b + sq) : -(b - sq);
        double t0 = q / a, t1 = c / q;
        if (t0 > t1) (t0, t1) = (t1, t0);
        for (int i = 0; i < 2; i++)
        {
            double th = i == 0 ? t0 : t1;
            if (!(th > tMin && th < tMax)) continue;
            float z = o.Z + (float)th * d.Z;
            if (z < 0 || z > 1) continue;   // the ray passes above or below the tube here: the far wall may still be hit
            t = (float)th;
            normal = new Vector3(o.X + t * d.X, o.Y + t * d.Y, 0);
            return true;
        }
        return false;
    }

    public override Bounds3 Bounds => new(new Vector3(-1, -1, 0), new Vector3(1, 1, 1));
    public override float Area => 2 * MathF.PI;

    public override Vector3 SampleArea(Vector2 u, out Vector3 normal)
    {
        float phi = 2 * MathF.PI * u.Y;
        normal = new Vector3(MathF.Cos(phi), MathF.Sin(phi), 0);
        return new Vector3(normal.X, normal.Y, u.X);
    }

    public override Vector2 TexCoord(Vector3 p)
    {
        float phi = MathF.Atan2(p.Y, p.X);
        if (phi < 0) phi += 2 * MathF.PI;
        return new Vector2(phi / (2 * MathF.PI), p.Z);
    }

    public override float TexCoordArea => 1;
}
