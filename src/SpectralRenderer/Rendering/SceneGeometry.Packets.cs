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
    public uint Intersect(ref RayPacket packet, Span<SurfaceHit> hits)
    {
        uint triangles = _hasTriangles ? _triangles.Intersect(ref packet) : 0;
        uint found = 0;
        for (uint m = packet.Active; m != 0; m &= m - 1)
        {
            int lane = BitOperations.TrailingZeroCount(m);
            var ray = packet.Ray(lane);
            int kind = 0;
            var h = new Hit();
            if ((triangles >> lane & 1) != 0) { kind = 1; h.Primitive = packet.Primitive[lane]; h.U = packet.U[lane]; h.V = packet.V[lane]; }
            var ah = new Hit();
            if (_analyticBvh is not null)
            {
                var a = _analytic;
                if (_analyticBvh.Intersect(ref a, ref ray, ref ah)) kind = 2;
            }
            int plane = -1;
            for (int i = 0; i < _planes.Length; i++)
                if (HitPlane(i, ray, out float tp)) { ray.TMax = tp; plane = i; kind = 3; }
            if (kind == 0) continue;
            packet.TMax[lane] = ray.TMax;
            Record(kind, ray, h, ah, plane, out hits[lane]);
            found |= 1u << lane;
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
