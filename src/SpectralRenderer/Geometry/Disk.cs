using System.Numerics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// The unit disk x² + y² ≤ 1 in the plane z = 0, normal +z (one-sided like the quad: emission leaves on +z unless
/// two-sided). Texture coordinates are planar, the disk inscribed in [0, 1]²: u = (x + 1)/2, v = (y + 1)/2.
/// Sampled uniformly by area: r = √u₁, φ = 2π·u₂ (pbrt-v4 §A.5.1).
/// </summary>
public sealed class Disk : CanonicalShape
{
    public override bool Intersect(Vector3 o, Vector3 d, float tMin, float tMax, out float t, out Vector3 normal)
    {
        normal = Vector3.UnitZ;
        t = 0;
        if (d.Z == 0) return false;
        t = -o.Z / d.Z;
        if (!(t > tMin && t < tMax)) return false;
        var p = o + t * d;
        return p.X * p.X + p.Y * p.Y <= 1;
    }

    public override Bounds3 Bounds => new(new Vector3(-1, -1, 0), new Vector3(1, 1, 0));
    public override Vector3? FlatNormal => Vector3.UnitZ;
    public override float Area => MathF.PI;

    public override Vector3 SampleArea(Vector2 u, out Vector3 normal)
    {
        normal = Vector3.UnitZ;
        float r = MathF.Sqrt(u.X), phi = 2 * MathF.PI * u.Y;
        return new Vector3(r * MathF.Cos(phi), r * MathF.Sin(phi), 0);
    }

    public override Vector2 TexCoord(Vector3 p) => new(0.5f * (p.X + 1), 0.5f * (p.Y + 1));
    public override float TexCoordArea => MathF.PI / 4;
}
