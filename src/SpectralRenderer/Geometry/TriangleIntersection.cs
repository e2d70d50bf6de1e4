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
        var d = ray.Direction;
        // kz: the dimension where |d| is largest; kx, ky follow cyclically, swapped if d[kz] < 0 to keep the winding.
        var ad = Vector3.Abs(d);
        int kz = ad.X > ad.Y ? (ad.X > ad.Z ? 0 : 2) : (ad.Y > ad.Z ? 1 : 2);
        int kx = kz == 2 ? 0 : kz + 1;
        int ky = kx == 2 ? 0 : kx + 1;
        float dz = d[kz];
        if (dz < 0) (kx, ky) = (ky, kx);
        float sx = d[kx] / dz, sy = d[ky] / dz, sz = 1 / dz;

        // Vertices relative to the origin, sheared and scaled so the ray is the +z axis.
        var a = p0 - ray.Origin;
        var b = p1 - ray.Origin;
        var c = p2 - ray.Origin;
        float az = a[kz], bz = b[kz], cz = c[kz];
        float ax = a[kx] - sx * az, ay = a[ky] - sy * az;
        float bx = b[kx] - sx * bz, by = b[ky] - sy * bz;
        float cx = c[kx] - sx * cz, cy = c[ky] - sy * cz;

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
}
