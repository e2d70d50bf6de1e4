using System.Numerics;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// One node of the BVH's node array, 32 bytes (pbrt-v4's LinearBVHNode): its bounds; for a leaf, the first
/// primitive (in BVH order) and the count; for an interior node, the index of the second child (the first
/// child follows the node directly) and the split axis.
/// </summary>
[StructLayout(LayoutKind.Sequential)]
public readonly struct BvhNode : IEquatable<BvhNode>
{
    public readonly Vector3 Min;
    /// <summary>Leaf: first primitive. Interior: index of the second child.</summary>
    public readonly int Offset;
    public readonly Vector3 Max;
    /// <summary>Primitives in a leaf; 0 for an interior node.</summary>
    public readonly ushort Count;
    /// <summary>Split axis of an interior node (0 = x, 1 = y, 2 = z).</summary>
    public readonly byte Axis;
    readonly byte _unused;

    BvhNode(Vector3 min, Vector3 max, int offset, ushort count, byte axis)
    {
        Min = min; Max = max; Offset = offset; Count = count; Axis = axis; _unused = 0;
    }

    public static BvhNode Leaf(Vector3 min, Vector3 max, int first, int count) => new(min, max, first, checked((ushort)count), 0);
    public static BvhNode Interior(Vector3 min, Vector3 max, int secondChild, int axis) => new(min, max, secondChild, 0, (byte)axis);

    public bool IsLeaf => Count > 0;

    public bool Equals(BvhNode o) => Min == o.Min && Max == o.Max && Offset == o.Offset && Count == o.Count && Axis == o.Axis;
    public override bool Equals(object? obj) => obj is BvhNode n && Equals(n);
    public override int GetHashCode() => HashCode.Combine(Min, Max, Offset, Count, Axis);
}
