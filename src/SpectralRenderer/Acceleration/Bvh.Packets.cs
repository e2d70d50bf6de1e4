using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>What a <see cref="Bvh"/> leaf asks of its primitives for a <see cref="RayPacket"/>: the lanes given are those whose rays enter
/// the leaf's box.</summary>
internal interface IPacketIntersector
{
    /// <summary>Closest hit of primitive k for the given lanes: where it is hit at t in (0, TMax), sets TMax = t, Primitive = k, U,
    /// V.</summary>
    void Intersect<TLanes>(int k, ref RayPacket packet, uint lanes) where TLanes : struct, ILanes<TLanes>;

    /// <summary>The lanes (of those given) whose rays hit primitive k at t in (0, TMax).</summary>
    uint Occluded<TLanes>(int k, ref RayPacket packet, uint lanes) where TLanes : struct, ILanes<TLanes>;
}

// Packet traversal: one stack for the whole packet, each entry carrying the lanes that entered the parent's
// box, so a lane that leaves the packet (misses a box) is not tested further down while the others go on
// together. A node's box is tested for its lanes when it is visited (the same slab arithmetic as SlabRay,
// lane by lane); of two children, the one most lanes reach first (by the sign of their direction on the
// split axis) is visited first.
public sealed partial class Bvh
{
    /// <summary>Closest hit for every active lane; returns the lanes that hit something (their TMax, Primitive, U, V are set).</summary>
    internal uint Intersect<TLanes, TPrims>(ref TPrims prims, ref RayPacket packet)
        where TLanes : struct, ILanes<TLanes> where TPrims : struct, IPacketIntersector
    {
        if (_nodes.Length == 0 || packet.Active == 0) return 0;
        packet.Prepare<TLanes>();
        return IntersectCore<TLanes, TPrims>(ref prims, ref packet);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    uint IntersectCore<TLanes, TPrims>(ref TPrims prims, ref RayPacket packet)
        where TLanes : struct, ILanes<TLanes> where TPrims : struct, IPacketIntersector
    {
        Span<int> stack = stackalloc int[StackSize];
        Span<uint> stackLanes = stackalloc uint[StackSize];
        ref BvhNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        int negative = packet.NegativeAxes();
        int sp = 0, current = 0;
        uint lanes = packet.Active, hits = 0;
        while (true)
        {
            ref BvhNode node = ref Unsafe.Add(ref root, current);
            uint entered = EnterBox<TLanes>(in node, ref packet, lanes);
            if (entered != 0)
            {
                if (node.Count > 0)
                {
                    int last = node.Offset + node.Count;
                    for (int k = node.Offset; k < last; k++) prims.Intersect<TLanes>(k, ref packet, entered);
                }
                else
                {
                    int near = current + 1, far = node.Offset;
                    if (((negative >> node.Axis) & 1) != 0) (near, far) = (far, near);
                    stack[sp] = far; stackLanes[sp] = entered; sp++;
                    current = near; lanes = entered;
                    continue;
                }
            }
            if (sp == 0) break;
            sp--;
            current = stack[sp]; lanes = stackLanes[sp];
        }
        for (uint m = packet.Active; m != 0; m &= m - 1)
        {
            int lane = BitOperations.TrailingZeroCount(m);
            if (packet.Primitive[lane] >= 0) hits |= 1u << lane;
        }
        return hits;
    }

    /// <summary>The active lanes whose rays hit something in (0, TMax); stops as soon as every lane is blocked.</summary>
    internal uint Occluded<TLanes, TPrims>(ref TPrims prims, ref RayPacket packet)
        where TLanes : struct, ILanes<TLanes> where TPrims : struct, IPacketIntersector
    {
        if (_nodes.Length == 0 || packet.Active == 0) return 0;
        packet.Prepare<TLanes>();
        return OccludedCore<TLanes, TPrims>(ref prims, ref packet);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    uint OccludedCore<TLanes, TPrims>(ref TPrims prims, ref RayPacket packet)
        where TLanes : struct, ILanes<TLanes> where TPrims : struct, IPacketIntersector
    {
        Span<int> stack = stackalloc int[StackSize];
        Span<uint> stackLanes = stackalloc uint[StackSize];
        ref BvhNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        int negative = packet.NegativeAxes();
        int sp = 0, current = 0;
        uint open = packet.Active;          // lanes not yet blocked
        uint lanes = open;
        while (true)
        {
            ref BvhNode node = ref Unsafe.Add(ref root, current);
            uint entered = EnterBox<TLanes>(in node, ref packet, lanes & open);
            if (entered != 0)
            {
                if (node.Count > 0)
                {
                    int last = node.Offset + node.Count;
                    for (int k = node.Offset; k < last && entered != 0; k++)
                    {
                        uint blocked = prims.Occluded<TLanes>(k, ref packet, entered);
                        entered &= ~blocked;
                        open &= ~blocked;
                    }
                    if (open == 0) break;
                }
                else
                {
                    int near = current + 1, far = node.Offset;
                    if (((negative >> node.Axis) & 1) != 0) (near, far) = (far, near);
                    stack[sp] = far; stackLanes[sp] = entered; sp++;
                    current = near; lanes = entered;
                    continue;
                }
            }
            if (sp == 0) break;
            sp--;
            current = stack[sp]; lanes = stackLanes[sp];
        }
        return packet.Active & ~open;
    }

    /// <summary>
    /// The lanes (of <paramref name="lanes"/>) whose interval [0, TMax] overlaps the node's box: SlabRay.Hits
    /// lane by lane — near and far slab distances chosen by the direction's sign, the exit widened by
    /// SlabRay.ExitScale, NaN slabs (origin in a face's plane, zero direction) dropping out.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint EnterBox<TLanes>(in BvhNode node, ref RayPacket p, uint lanes) where TLanes : struct, ILanes<TLanes>
    {
        var minX = TLanes.Splat(node.Min.X); var minY = TLanes.Splat(node.Min.Y); var minZ = TLanes.Splat(node.Min.Z);
        var maxX = TLanes.Splat(node.Max.X); var maxY = TLanes.Splat(node.Max.Y); var maxZ = TLanes.Splat(node.Max.Z);
        var scale = TLanes.Splat(SlabRay.ExitScale);
        var zero = TLanes.Splat(0);
        uint entered = 0;
        uint chunkMask = TLanes.Count >= 32 ? uint.MaxValue : (1u << TLanes.Count) - 1;
        for (int c = 0; c < RayPacket.Size; c += TLanes.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m == 0) continue;
            var ox = TLanes.Load(ref p.OriginX[c]); var ix = TLanes.Load(ref p.InverseX[c]); var nx = TLanes.Load(ref p.NegativeX[c]);
            var oy = TLanes.Load(ref p.OriginY[c]); var iy = TLanes.Load(ref p.InverseY[c]); var ny = TLanes.Load(ref p.NegativeY[c]);
            var oz = TLanes.Load(ref p.OriginZ[c]); var iz = TLanes.Load(ref p.InverseZ[c]); var nz = TLanes.Load(ref p.NegativeZ[c]);
            var entry = TLanes.Max((TLanes.Select(nx, maxX, minX) - ox) * ix, zero);
            entry = TLanes.Max((TLanes.Select(ny, maxY, minY) - oy) * iy, entry);
            entry = TLanes.Max((TLanes.Select(nz, maxZ, minZ) - oz) * iz, entry);
            var exit = TLanes.Min((TLanes.Select(nx, minX, maxX) - ox) * ix * scale, TLanes.Load(ref p.TMax[c]));
            exit = TLanes.Min((TLanes.Select(ny, minY, maxY) - oy) * iy * scale, exit);
            exit = TLanes.Min((TLanes.Select(nz, minZ, maxZ) - oz) * iz * scale, exit);
            entered |= (TLanes.Bits(TLanes.LessOrEqual(entry, exit)) & m) << c;
        }
        return entered;
    }
}
