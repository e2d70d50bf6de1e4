using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

// The watertight test (TriangleIntersection, Woop et al. 2013) for the lanes of a ray packet at once: the
// same single-precision operations in the same order as for one ray, so every lane's t, u and v are the bits
// a single ray gets. Each lane carries its own shear (RayPacket rows), so any rays can share a packet.
public partial struct TriangleSet
{
    /// <summary>Closest hit of every active lane of the packet (at the machine's SIMD width); returns the lanes that hit.</summary>
    public uint Intersect(ref RayPacket packet)
    {
        var self = this;
        return PacketLanes.Width switch
        {
            16 => Bvh.Intersect<Lanes512, TriangleSet>(ref self, ref packet),
            8 => Bvh.Intersect<Lanes256, TriangleSet>(ref self, ref packet),
            4 => Bvh.Intersect<Lanes128, TriangleSet>(ref self, ref packet),
            _ => Bvh.Intersect<Lanes1, TriangleSet>(ref self, ref packet),
        };
    }

    /// <summary>The active lanes of the packet whose rays hit a triangle in (0, TMax).</summary>
    public uint Occluded(ref RayPacket packet)
    {
        var self = this;
        return PacketLanes.Width switch
        {
            16 => Bvh.Occluded<Lanes512, TriangleSet>(ref self, ref packet),
            8 => Bvh.Occluded<Lanes256, TriangleSet>(ref self, ref packet),
            4 => Bvh.Occluded<Lanes128, TriangleSet>(ref self, ref packet),
            _ => Bvh.Occluded<Lanes1, TriangleSet>(ref self, ref packet),
        };
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void IPacketIntersector.Intersect<TLanes>(int k, ref RayPacket p, uint lanes)
    {
        uint chunkMask = TLanes.Count >= 32 ? uint.MaxValue : (1u << TLanes.Count) - 1;
        for (int c = 0; c < RayPacket.Size; c += TLanes.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m != 0) Test<TLanes, RecordHits>(k, ref p, c, m);
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    uint IPacketIntersector.Occluded<TLanes>(int k, ref RayPacket p, uint lanes)
    {
        uint chunkMask = TLanes.Count >= 32 ? uint.MaxValue : (1u << TLanes.Count) - 1;
        uint blocked = 0;
        for (int c = 0; c < RayPacket.Size; c += TLanes.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m != 0) blocked |= Test<TLanes, AnyHit>(k, ref p, c, m) << c;
        }
        return blocked;
    }

    /// <summary>What a triangle test does with its hits: record them in the packet (closest hit) or only report them (any hit).</summary>
    interface IHitMode { static abstract bool Records { get; } }
    struct RecordHits : IHitMode { public static bool Records => true; }
    struct AnyHit : IHitMode { public static bool Records => false; }

    /// <summary>
    /// TriangleIntersection.Intersect for lanes c … c + Count − 1 (those in m) against triangle k: the lanes hit, and with
    /// <typeparamref name="TMode"/> = <see cref="RecordHits"/> their t, b1, b2 and k stored in the packet here. (Too large to be
    /// inlined, it once handed t, b1, b2 back through stack slots that the caller read at once: whether those loads split a
    /// cache line, and so missed the store forwarding, depended on the stack's depth, and the camera rays' traversal ran up
    /// to 2× slower from one build to the next with the same machine code.)
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    readonly uint Test<L, TMode>(int k, ref RayPacket p, int c, uint m) where L : struct, ILanes<L> where TMode : struct, IHitMode
    {
        ref Vector3 corner = ref _corners[3 * k];
        Vector3 p0 = corner, p1 = Unsafe.Add(ref corner, 1), p2 = Unsafe.Add(ref corner, 2);
        var ox = L.Load(ref p.OriginX[c]); var oy = L.Load(ref p.OriginY[c]); var oz = L.Load(ref p.OriginZ[c]);
        // Vertices relative to the origin (A = p − o), then sheared: x = RowX·A, y = RowY·A, z = RowZ·A.
        var a0 = L.Splat(p0.X) - ox; var a1 = L.Splat(p0.Y) - oy; var a2 = L.Splat(p0.Z) - oz;
        var b0_ = L.Splat(p1.X) - ox; var b1_ = L.Splat(p1.Y) - oy; var b2_ = L.Splat(p1.Z) - oz;
        var c0 = L.Splat(p2.X) - ox; var c1 = L.Splat(p2.Y) - oy; var c2 = L.Splat(p2.Z) - oz;
        var rxx = L.Load(ref p.RowXx[c]); var rxy = L.Load(ref p.RowXy[c]); var rxz = L.Load(ref p.RowXz[c]);
        var ryx = L.Load(ref p.RowYx[c]); var ryy = L.Load(ref p.RowYy[c]); var ryz = L.Load(ref p.RowYz[c]);
        var ax = rxx * a0 + rxy * a1 + rxz * a2; var ay = ryx * a0 + ryy * a1 + ryz * a2;
        var bx = rxx * b0_ + rxy * b1_ + rxz * b2_; var by = ryx * b0_ + ryy * b1_ + ryz * b2_;
        var cx = rxx * c0 + rxy * c1 + rxz * c2; var cy = ryx * c0 + ryy * c1 + ryz * c2;

        // Scaled barycentrics: the 2D edge functions; an exact zero is recomputed in double, lane by lane.
        var u = cx * by - cy * bx;
        var v = ax * cy - ay * cx;
        var w = bx * ay - by * ax;
        var zero = L.Splat(0);
        uint onEdge = L.Bits(L.Or(L.Or(L.Equal(u, zero), L.Equal(v, zero)), L.Equal(w, zero))) & m;
        if (onEdge != 0) EdgesInDouble(onEdge, ax, ay, bx, by, cx, cy, ref u, ref v, ref w);
        var outside = L.And(L.Or(L.Or(L.Less(u, zero), L.Less(v, zero)), L.Less(w, zero)),
                            L.Or(L.Or(L.Greater(u, zero), L.Greater(v, zero)), L.Greater(w, zero)));
        var det = u + v + w;
        uint inside = m & ~L.Bits(L.Or(outside, L.Equal(det, zero)));
        if (inside == 0) return 0;   // most tests end here: the rays pass beside the triangle

        // Scaled hit distance: behind the origin when its sign is not det's (t = tScaled / det).
        var rzx = L.Load(ref p.RowZx[c]); var rzy = L.Load(ref p.RowZy[c]); var rzz = L.Load(ref p.RowZz[c]);
        var az = rzx * a0 + rzy * a1 + rzz * a2;
        var bz = rzx * b0_ + rzy * b1_ + rzz * b2_;
        var cz = rzx * c0 + rzy * c1 + rzz * c2;
        var tScaled = u * az + v * bz + w * cz;
        var behind = L.Select(L.Less(det, zero),
            L.Or(L.Greater(tScaled, zero), L.Equal(tScaled, zero)),    // tScaled ≥ 0
            L.Or(L.Less(tScaled, zero), L.Equal(tScaled, zero)));      // tScaled ≤ 0
        // Clearly beyond the closest hit so far (tScaled past tMax·det·(1 + 2⁻²⁰)): no division. The margin is far above the
        // rounding of the bound and of t = tScaled·(1/det) (a few 2⁻²⁴), so a lane whose t ≤ tMax always reaches the tests
        // below (ties at t = tMax go to the index rule); a bound that is not a normal float (underflow) is not used.
        var tMax = L.Load(ref p.TMax[c]);
        var bound = tMax * det * L.Splat(1 + 1f / (1 << 20));
        var far = L.And(L.Select(L.Less(det, zero), L.Less(tScaled, bound), L.Greater(tScaled, bound)),
                        L.Greater(L.Max(bound, L.Negate(bound)), L.Splat(1.17549435e-38f)));   // FLT_MIN
        uint candidates = inside & ~L.Bits(L.Or(behind, far));
        if (candidates == 0) return 0;

        var inv = L.Splat(1) / det;
        var t = tScaled * inv;
        uint ahead = candidates & L.Bits(L.Greater(t, zero));   // an underflow of the division
        uint hit = ahead & L.Bits(L.Less(t, tMax));
        if (!TMode.Records) return hit;
        // As TriangleSet.Intersect for one ray: at t = TMax the smaller index wins (Primitive is −1 before a first hit).
        for (uint tie = ahead & L.Bits(L.Equal(t, tMax)); tie != 0; tie &= tie - 1)
        {
            int lane = BitOperations.TrailingZeroCount(tie);
            if (k < p.Primitive[c + lane]) hit |= 1u << lane;
        }
        if (hit == 0) return 0;
        var mask = L.FromBits(hit);
        L.Store(L.Select(mask, t, tMax), ref p.TMax[c]);
        L.Store(L.Select(mask, v * inv, L.Load(ref p.U[c])), ref p.U[c]);   // b1
        L.Store(L.Select(mask, w * inv, L.Load(ref p.V[c])), ref p.V[c]);   // b2
        for (uint h = hit; h != 0; h &= h - 1) p.Primitive[c + BitOperations.TrailingZeroCount(h)] = k;
        return hit;
    }

    /// <summary>The edge functions of the given lanes recomputed in double (Woop et al. §3.3), as TriangleIntersection does.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    static void EdgesInDouble<L>(uint lanes, L ax, L ay, L bx, L by, L cx, L cy, ref L u, ref L v, ref L w) where L : struct, ILanes<L>
    {
        PacketFloats fax =
            default, fay = default, fbx = default, fby = default, fcx = default, fcy = default, fu = default, fv = default, fw = default;
        L.Store(ax, ref fax[0]); L.Store(ay, ref fay[0]); L.Store(bx, ref fbx[0]); L.Store(by, ref fby[0]);
        L.Store(cx, ref fcx[0]); L.Store(cy, ref fcy[0]); L.Store(u, ref fu[0]); L.Store(v, ref fv[0]); L.Store(w, ref fw[0]);
        for (; lanes != 0; lanes &= lanes - 1)
        {
            int i = BitOperations.TrailingZeroCount(lanes);
            fu[i] = (float)((double)fcx[i] * fby[i] - (double)fcy[i] * fbx[i]);
            fv[i] = (float)((double)fax[i] * fcy[i] - (double)fay[i] * fcx[i]);
            fw[i] = (float)((double)fbx[i] * fay[i] - (double)fby[i] * fax[i]);
        }
        u = L.Load(ref fu[0]); v = L.Load(ref fv[0]); w = L.Load(ref fw[0]);
    }
}
