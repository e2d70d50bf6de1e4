using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Watertight ray–triangle intersection (Woop, Benthin &amp; Wald, "Watertight Ray/Triangle Intersection",
/// JCGT 2(1), 2013): the ray is sheared so it runs along +z through the origin, and the 2D edge functions of the
/// projected vertices decide the hit. Edges shared by two triangles are never missed by both; when an edge
/// function is exactly zero it is recomputed in double, as the paper does. No back-face culling.
/// </summary>
public static class TriangleIntersection
{
    /// <summary>
    /// The hit of <paramref name="ray"/> with triangle (p0, p1, p2) at t in (0, ray.TMax), or false.
    /// (b1, b2) are the barycentric weights of p1 and p2: the point is (1 − b1 − b2)·p0 + b1·p1 + b2·p2.
    /// Rays leaving a surface should start slightly off it (no epsilon is applied here).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool Intersect(in Ray ray, Vector3 p0, Vector3 p1, Vector3 p2, out float t, out float b1, out float b2)
    {
        t = b1 = b2 = 0;
        // The ray's dominant axis becomes z; x, y follow cyclically, swapped when d.z < 0 to keep the winding.
        var ad = Vector3.Abs(ray.Direction);
        int kz = ad.X > ad.Y ? (ad.X > ad.Z ? 0 : 2) : (ad.Y > ad.Z ? 1 : 2);
        int permutation = 2 * kz + (ray.Direction[kz] < 0 ? 1 : 0);
        var d = Permute(ray.Direction, permutation);
        float sz = 1 / d.Z;
        var shear = new Vector3(d.X * sz, d.Y * sz, 0);

        // Vertices relative to the origin, permuted and sheared so the ray is the +z axis: (x, y) = A.xy − S·A.z.
        var a = Permute(p0 - ray.Origin, permutation);
        var b = Permute(p1 - ray.Origin, permutation);
        var c = Permute(p2 - ray.Origin, permutation);
        float az = a.Z, bz = b.Z, cz = c.Z;
        a -= shear * az; b -= shear * bz; c -= shear * cz;
        float ax = a.X, ay = a.Y, bx = b.X, by = b.Y, cx = c.X, cy = c.Y;

        // Scaled barycentrics: the 2D edge functions.
        float u = cx * by - cy * bx;
        float v = ax * cy - ay * cx;
        float w = bx * ay - by * ax;
        if (u == 0 || v == 0 || w == 0)
        {
            u = (float)((double)cx * by - (double)cy * bx);
            v = (float)((double)ax * cy - (double)ay * cx);
            w = (float)((double)bx * ay - (double)by * ax);
        }
        if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
        float det = u + v + w;
        if (det == 0) return false;

        // Scaled hit distance, compared against the scaled interval before the one division.
        float tScaled = sz * (u * az + v * bz + w * cz);
        if (det < 0 ? (tScaled >= 0 || tScaled < ray.TMax * det) : (tScaled <= 0 || tScaled > ray.TMax * det)) return false;

        float inv = 1 / det;
        t = tScaled * inv;
        if (!(t < ray.TMax) || !(t > 0)) return false; // rounding of the division
        b1 = v * inv;
        b2 = w * inv;
        return true;
    }

    /// <summary>(v[kx], v[ky], v[kz]) for permutation = 2·kz + (swap x and y ? 1 : 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector3 Permute(Vector3 v, int permutation) => permutation switch
    {
        0 => new(v.Y, v.Z, v.X),
        1 => new(v.Z, v.Y, v.X),
        2 => new(v.Z, v.X, v.Y),
        3 => new(v.X, v.Z, v.Y),
        4 => v,
        _ => new(v.Y, v.X, v.Z),
    };
}
