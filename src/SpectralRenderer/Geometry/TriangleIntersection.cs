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
    public static bool Intersect(in Ray ray, Vector3 p0, Vector3 p1, Vector3 p2, out float t, out float b1, out float b2) =>
        Intersect(new ShearedRay(ray), p0, p1, p2, ray.TMax, out t, out b1, out b2);

    /// <summary>As above with the ray's shear computed once (<see cref="ShearedRay"/>), for testing many triangles.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool Intersect(in ShearedRay ray, Vector3 p0, Vector3 p1, Vector3 p2, float tMax, out float t, out float b1,
        out float b2) =>
        Distance(ray, p0, p1, p2, out t, out b1, out b2) && t < tMax;

    /// <summary>
    /// The hit at any t &gt; 0, whatever the ray's interval: the caller compares t itself (a closest-hit query keeps a hit at
    /// t = TMax when its primitive index is smaller, so the winner does not depend on the order triangles are met in).
    /// Whether a triangle is hit is decided on t alone: no test against a scaled bound tMax·det beforehand, whose rounding
    /// could reject a triangle whose t is below the bound.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool Distance(in ShearedRay ray, Vector3 p0, Vector3 p1, Vector3 p2, out float t, out float b1, out float b2)
    {
        t = b1 = b2 = 0;
        // Vertices relative to the origin, sheared so the ray is the +z axis: (x, y) = A.xy − S·A.z, z = S_z·A.z.
        var a = p0 - ray.Origin;
        var b = p1 - ray.Origin;
        var c = p2 - ray.Origin;
        float ax = Vector3.Dot(ray.RowX, a), ay = Vector3.Dot(ray.RowY, a);
        float bx = Vector3.Dot(ray.RowX, b), by = Vector3.Dot(ray.RowY, b);
        float cx = Vector3.Dot(ray.RowX, c), cy = Vector3.Dot(ray.RowY, c);

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

        // Scaled hit distance: behind the origin when its sign is not det's (t = tScaled / det).
        float az = Vector3.Dot(ray.RowZ, a), bz = Vector3.Dot(ray.RowZ, b), cz = Vector3.Dot(ray.RowZ, c);
        float tScaled = u * az + v * bz + w * cz;
        if (det < 0 ? tScaled >= 0 : tScaled <= 0) return false;

        float inv = 1 / det;
        t = tScaled * inv;
        if (!(t > 0)) return false; // an underflow of the division
        b1 = v * inv;
        b2 = w * inv;
        return true;
    }
}

/// <summary>
/// A ray prepared for the watertight test (Woop et al. 2013 §3): its dominant axis k_z, the other two
/// k_x, k_y (swapped when d[k_z] &lt; 0 to keep the winding) and the shear S = (d[k_x]/d[k_z], d[k_y]/d[k_z],
/// 1/d[k_z]), folded into three rows so a vertex A relative to the origin maps to
/// x = A[k_x] − S_x·A[k_z], y = A[k_y] − S_y·A[k_z], z = S_z·A[k_z] (the zero terms add exactly).
/// </summary>
public readonly struct ShearedRay
{
    public readonly Vector3 Origin;
    public readonly Vector3 RowX, RowY, RowZ;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public ShearedRay(in Ray ray)
    {
        Origin = ray.Origin;
        var d = ray.Direction;
        var ad = Vector3.Abs(d);
        int kz = ad.X > ad.Y ? (ad.X > ad.Z ? 0 : 2) : (ad.Y > ad.Z ? 1 : 2);
        int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
        if (d[kz] < 0) (kx, ky) = (ky, kx);
        float sz = 1 / d[kz];
        float sx = d[kx] * sz, sy = d[ky] * sz;
        RowX = Unit(kx) - sx * Unit(kz);
        RowY = Unit(ky) - sy * Unit(kz);
        RowZ = sz * Unit(kz);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector3 Unit(int axis) => axis == 0 ? Vector3.UnitX : axis == 1 ? Vector3.UnitY : Vector3.UnitZ;
}
