using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

// Ray queries for a packet of rays: the mesh triangles (most of a scene's work) as a packet through their
// BVH, then, lane by lane and in the single-ray order, the instanced meshes, the analytic shapes and the planes with each
// lane's shortened TMax, so every lane's answer is the one its ray gets from Intersect / Occluded. (Instances are met ray by
// ray: each lane's ray goes into its own object space.)
public sealed partial class SceneGeometry
{
    /// <summary>
    /// Closest hits of the packet's active lanes: bit i of the result set when lane i hits, with its record in lane i of
    /// <paramref name="hits"/> (what <see cref="Intersect(ref Ray, out SurfaceHit)"/> records for the lane's ray, bit for
    /// bit). The packet's TMax holds each lane's hit distance afterwards.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    internal uint Intersect(ref RayPacket packet, ref HitLanes hits)
    {
        uint triangles = _hasTriangles ? _triangles.Intersect(ref packet) : 0;
        uint instanced = 0;
        Span<Hit> instanceHits = stackalloc Hit[RayPacket.Size];
        if (_hasInstances)
            for (uint m = packet.Active; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                var ray = packet.Ray(lane);
                var s = _instances;
                instanceHits[lane] = new Hit();
                if (s.Bvh.Intersect(ref s, ref ray, ref instanceHits[lane]))
                {
                    instanced |= 1u << lane;
                    packet.TMax[lane] = ray.TMax;
                }
            }
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
                if (_analyticBvh.Intersect(ref a, ref ray, ref analyticHits[lane]))
                {
                    analytic |= 1u << lane;
                    packet.TMax[lane] = ray.TMax;
                }
            }
        // The planes' lanes and the corners on cache-line boundaries (LaneMemory), not zeroed: each lane used is filled.
        Span<byte> laneMemory = stackalloc byte[LaneMemory.Bytes<RecordLanes>()];
        ref var work = ref LaneMemory.At<RecordLanes>(laneMemory);
        ref var plane = ref work.Plane;
        uint planes = _planes.Length > 0 ? LaneGeometry.Planes(_planes, ref packet, packet.Active, ref plane) : 0;
        uint found = triangles | instanced | analytic | planes;
        if (found == 0) return 0;
        // Per lane, what its record is made from: the triangle's corners and vertex normals, or the shape's or plane's normal.
        uint mesh = triangles & ~instanced & ~analytic & ~planes, smooth = 0;
        ref var corners = ref work.Corners;
        for (uint m = found; m != 0; m &= m - 1)
        {
            int lane = BitOperations.TrailingZeroCount(m);
            if ((planes >> lane & 1) != 0)
            {
                var n = _planes[plane[lane]].Normal;
                hits.SetNormals(lane, n, n);
                hits.Object[lane] = _planeObject[plane[lane]];
            }
            else if ((analytic >> lane & 1) != 0)
            {
                Record(2, packet.Ray(lane), default, analyticHits[lane], -1, out var h);
                hits.SetNormals(lane, h.GeometricNormal, h.Normal);
                hits.Object[lane] = h.Object;
            }
            else if ((instanced >> lane & 1) != 0)
            {
                var h = new SurfaceHit();
                RecordInstance(instanceHits[lane], ref h);
                hits.SetNormals(lane, h.GeometricNormal, h.Normal);
                hits.Object[lane] = h.Object;
            }
            else
            {
                int k = packet.Primitive[lane];
                int meshIndex = _triangles.MeshOf[k];
                var (p0, p1, p2) = _triangles.Corners(k);
                corners.SetCorners(lane, p0, p1, p2);
                var mm = _meshes[meshIndex];
                if (_meshSmooth[meshIndex] && mm.Normals is { } normals)
                {
                    int tri = _triangles.TriangleOf[k];
                    var idx = mm.Indices;
                    corners.SetNormals(lane, normals[idx[3 * tri]], normals[idx[3 * tri + 1]], normals[idx[3 * tri + 2]]);
                    smooth |= 1u << lane;
                }
                hits.Object[lane] = _meshObject[meshIndex];
            }
        }
        switch (PacketLanes.Width)
        {
            case 16: LaneGeometry.Records<Lanes512>(ref packet, mesh, smooth, in corners, ref hits); break;
            case 8: LaneGeometry.Records<Lanes256>(ref packet, mesh, smooth, in corners, ref hits); break;
            case 4: LaneGeometry.Records<Lanes128>(ref packet, mesh, smooth, in corners, ref hits); break;
            default: LaneGeometry.Records<Lanes1>(ref packet, mesh, smooth, in corners, ref hits); break;
        }
        return found;
    }

    /// <summary>The active lanes of the packet whose rays are blocked in (0, TMax).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public uint Occluded(ref RayPacket packet)
    {
        uint blocked = _hasTriangles ? _triangles.Occluded(ref packet) : 0;
        if (_hasInstances)
            for (uint m = packet.Active & ~blocked; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                if (_instances.Occluded(packet.Ray(lane))) blocked |= 1u << lane;
            }
        if (_analyticBvh is not null)
            for (uint m = packet.Active & ~blocked; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                var a = _analytic;
                if (_analyticBvh.Occluded(ref a, packet.Ray(lane))) blocked |= 1u << lane;
            }
        uint open = packet.Active & ~blocked;
        if (_planes.Length > 0 && open != 0) blocked |= LaneGeometry.PlanesBlock(_planes, ref packet, open);
        return blocked;
    }

    /// <summary>The plane index per lane and the triangle corners of a packet's records, on cache-line boundaries.</summary>
    struct RecordLanes
    {
        public TriangleLanes Corners;
        public PacketInts Plane;
    }
}
