using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

// Ray queries for a packet of rays: the mesh triangles (most of a scene's work) as a packet through their
// BVH, then, lane by lane and in the single-ray order, the analytic shapes and the planes with each lane's
// shortened TMax, so every lane's answer is the one its ray gets from Intersect / Occluded.
public sealed partial class SceneGeometry
{
    /// <summary>
    /// Closest hits of the packet's active lanes: bit i of the result set when lane i hits, with its record in
    /// <paramref name="hits"/>[i]. The packet's TMax holds each lane's hit distance afterwards.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    public uint Intersect(ref RayPacket packet, Span<SurfaceHit> hits)
    {
        uint triangles = _hasTriangles ? _triangles.Intersect(ref packet) : 0;
        // The analytic shapes lane by lane with each lane's TMax, then the planes for all lanes at once: the single-ray order.
        uint analytic = 0;
        Span<Hit> analyticHits = stackalloc Hit[RayPacket.Size];
        if (_analyticBvh is not null)
            for (uint m = packet.Active; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                var ray = packet.Ray(lane);
                var a = _analytic;
                analyticHits[lane] = new Hit();
                if (_analyticBvh.Intersect(ref a, ref ray, ref analyticHits[lane])) { analytic |= 1u << lane; packet.TMax[lane] = ray.TMax; }
            }
        Unsafe.SkipInit(out PacketInts plane);
        uint planes = _planes.Length > 0 ? LaneGeometry.Planes(_planes, ref packet, packet.Active, ref plane) : 0;
        uint found = triangles | analytic | planes;
        for (uint m = found; m != 0; m &= m - 1)
        {
            int lane = BitOperations.TrailingZeroCount(m);
            var h = new Hit();
            int kind = 1;
            if ((planes >> lane & 1) != 0) kind = 3;
            else if ((analytic >> lane & 1) != 0) kind = 2;
            else { h.Primitive = packet.Primitive[lane]; h.U = packet.U[lane]; h.V = packet.V[lane]; }
            Record(kind, packet.Ray(lane), h, kind == 2 ? analyticHits[lane] : default, kind == 3 ? plane[lane] : -1, out hits[lane]);
        }
        return found;
    }

    /// <summary>The active lanes of the packet whose rays are blocked in (0, TMax).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public uint Occluded(ref RayPacket packet)
    {
        uint blocked = _hasTriangles ? _triangles.Occluded(ref packet) : 0;
        if (_analyticBvh is null && _planes.Length == 0) return blocked;
        for (uint m = packet.Active & ~blocked; m != 0; m &= m - 1)
        {
            int lane = BitOperations.TrailingZeroCount(m);
            var ray = packet.Ray(lane);
            bool hit = false;
            if (_analyticBvh is not null)
            {
                var a = _analytic;
                hit = _analyticBvh.Occluded(ref a, ray);
            }
            for (int i = 0; i < _planes.Length && !hit; i++) hit = HitPlane(i, ray, out _);
            if (hit) blocked |= 1u << lane;
        }
        return blocked;
    }
}
