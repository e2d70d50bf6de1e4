using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>The reference the BVH must reproduce: every primitive tested, in order.</summary>
static class BruteForce
{
    public static bool Intersect<T>(ref T prims, int count, ref Ray ray, ref Hit hit) where T : struct, IPrimitiveIntersector
    {
        bool found = false;
        prims.Prepare(ray);
        for (int k = 0; k < count; k++) found |= prims.Intersect(k, ref ray, ref hit);
        return found;
    }

    public static bool Occluded<T>(ref T prims, int count, in Ray ray) where T : struct, IPrimitiveIntersector
    {
        prims.Prepare(ray);
        for (int k = 0; k < count; k++) if (prims.Occluded(k, ray)) return true;
        return false;
    }

    /// <summary>
    /// Compares closest hits and occlusion of the BVH with brute force on the rays (in parallel over rays).
    /// Returns (closest-hit disagreements, occlusion disagreements, hits). A different primitive at the same
    /// distance (a ray through a shared edge) is not a disagreement.
    /// </summary>
    public static (int closest, int occluded, int hits) Compare(TriangleSet set, Ray[] rays)
    {
        int closest = 0, occluded = 0, hits = 0;
        Parallel.For(0, rays.Length, () => (0, 0, 0), (i, _, acc) =>
        {
            var s = set;
            var a = rays[i]; var ha = new Hit();
            var b = rays[i]; var hb = new Hit();
            bool fa = set.Bvh.Intersect(ref s, ref a, ref ha);
            bool fb = Intersect(ref s, s.Count, ref b, ref hb);
            bool agree = fa == fb && (!fa || ha.Primitive == hb.Primitive && a.TMax == b.TMax
                                            || Math.Abs(a.TMax - b.TMax) <= 1e-5f * b.TMax
                                                && SameDistance(s, rays[i], ha.Primitive, b.TMax));
            if (!agree) acc.Item1++;
            // Occlusion up to just beyond half the closest distance, and unbounded.
            var half = rays[i]; half.TMax = fb ? 0.5f * b.TMax : rays[i].TMax;
            if (set.Bvh.Occluded(ref s, half) != Occluded(ref s, s.Count, half)) acc.Item2++;
            if (set.Bvh.Occluded(ref s, rays[i]) != fb) acc.Item2++;
            if (fb) acc.Item3++;
            return acc;
        }, acc =>
        {
            Interlocked.Add(ref closest, acc.Item1);
            Interlocked.Add(ref occluded, acc.Item2);
            Interlocked.Add(ref hits, acc.Item3);
        });
        return (closest, occluded, hits);
    }

    static bool SameDistance(TriangleSet s, Ray ray, int k, float t)
    {
        var h = new Hit();
        s.Prepare(ray);
        return s.Intersect(k, ref ray, ref h) && Math.Abs(ray.TMax - t) <= 1e-5f * t;
    }
}
