using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// A bounding volume hierarchy over primitives given by their bounds, in an array of 32-byte nodes in
/// depth-first order, each interior node's first child right after it (see <see cref="BvhBuilder"/> for the
/// binned-SAH build; compacted after it to the nodes in use). Traversal is
/// front-to-back with a fixed stack and allocates nothing; the primitives are tested through a struct
/// <see cref="IPrimitiveIntersector"/> that receives positions in <see cref="PrimitiveOrder"/>.
/// </summary>
[SkipLocalsInit]
public sealed partial class Bvh
{
    const int StackSize = 128;

    readonly BvhNode[] _nodes;

    Bvh(BvhNode[] nodes, int[] order, int maxDepth)
    {
        if (maxDepth > StackSize) throw new InvalidOperationException($"BVH depth {maxDepth} exceeds the traversal stack ({StackSize})");
        _nodes = nodes;
        PrimitiveOrder = order;
        MaxDepth = maxDepth;
    }

    /// <summary>Builds the hierarchy (in parallel on large inputs; the result does not depend on the thread count).</summary>
    /// <param name="maxLeafSize">Most primitives in one leaf; smaller leaves are made when the SAH prefers them.</param>
    public static Bvh Build(ReadOnlySpan<Bounds3> primitiveBounds, int maxLeafSize = 4) =>
        Build(primitiveBounds, maxLeafSize, parallel: true);

    /// <summary>As <see cref="Build(ReadOnlySpan{Bounds3}, int)"/>, optionally on the calling thread only.</summary>
    public static Bvh Build(ReadOnlySpan<Bounds3> primitiveBounds, int maxLeafSize, bool parallel)
    {
        var (nodes, order, depth) = BvhBuilder.Build(primitiveBounds, maxLeafSize, parallel);
        return new Bvh(nodes, order, depth);
    }

    /// <summary>As <see cref="Build(ReadOnlySpan{Bounds3}, int, bool)"/> from boxes the caller made for it, which the builder takes
    /// as its own (permutes, then lets go).</summary>
    internal static Bvh Build(BvhBuilder.Box[] boxes, int maxLeafSize, bool parallel)
    {
        var (nodes, order, depth) = BvhBuilder.Build(boxes, maxLeafSize, parallel);
        return new Bvh(nodes, order, depth);
    }

    /// <summary>k → original primitive index: traversal hands k to the intersector, so store primitive data permuted by this.</summary>
    public int[] PrimitiveOrder { get; }
    /// <summary>Nodes in the node array (at most 2n − 1 for n primitives).</summary>
    public int NodeCount => _nodes.Length;
    public int MaxDepth { get; }
    public ReadOnlySpan<BvhNode> Nodes => _nodes;
    public Bounds3 Bounds => _nodes.Length == 0 ? Bounds3.Empty : new Bounds3(_nodes[0].Min, _nodes[0].Max);

    /// <summary>
    /// Closest hit: shortens ray.TMax to each hit found. At an interior node both children's boxes are
    /// tested; the nearer (by entry distance) is visited first and the farther pushed with its distance,
    /// to be skipped when popped if a closer hit was found meanwhile.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Intersect<T>(ref T prims, ref Ray ray, ref Hit hit) where T : struct, IPrimitiveIntersector
    {
        if (_nodes.Length == 0) return false;
        var slabs = new SlabRay(ray);
        ref BvhNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        if (!slabs.Hits(in root, ray.TMax)) return false;
        prims.Prepare(ray);
        Span<int> stack = stackalloc int[StackSize];
        Span<float> entries = stackalloc float[StackSize];
        int sp = 0, current = 0;
        bool found = false;
        while (true)
        {
            ref BvhNode node = ref Unsafe.Add(ref root, current);
            if (node.Count > 0)
            {
                int last = node.Offset + node.Count;
                for (int k = node.Offset; k < last; k++)
                    if (prims.Intersect(k, ref ray, ref hit)) found = true;
            }
            else
            {
                int left = current + 1, right = node.Offset;
                bool hitLeft = slabs.Hits(in Unsafe.Add(ref root, left), ray.TMax, out float tLeft);
                bool hitRight = slabs.Hits(in Unsafe.Add(ref root, right), ray.TMax, out float tRight);
                if (hitLeft && hitRight)
                {
                    if (tRight < tLeft) { (left, right) = (right, left); tRight = tLeft; }
                    stack[sp] = right; entries[sp] = tRight; sp++;
                    current = left;
                    continue;
                }
                if (hitLeft) { current = left; continue; }
                if (hitRight) { current = right; continue; }
            }
            while (true)
            {
                if (sp == 0) return found;
                sp--;
                if (entries[sp] <= ray.TMax) { current = stack[sp]; break; }
            }
        }
    }

    /// <summary>Whether anything is hit in (0, ray.TMax); stops at the first hit.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Occluded<T>(ref T prims, in Ray ray) where T : struct, IPrimitiveIntersector
    {
        if (_nodes.Length == 0) return false;
        var slabs = new SlabRay(ray);
        prims.Prepare(ray);
        int negative = slabs.NegativeAxes;
        Span<int> stack = stackalloc int[StackSize];
        ref BvhNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        int sp = 0, current = 0;
        while (true)
        {
            ref BvhNode node = ref Unsafe.Add(ref root, current);
            if (slabs.Hits(in node, ray.TMax))
            {
                if (node.Count > 0)
                {
                    int last = node.Offset + node.Count;
                    for (int k = node.Offset; k < last; k++)
                        if (prims.Occluded(k, in ray)) return true;
                }
                else if (((negative >> node.Axis) & 1) != 0)
                {
                    stack[sp++] = current + 1;
                    current = node.Offset;
                    continue;
                }
                else
                {
                    stack[sp++] = node.Offset;
                    current++;
                    continue;
                }
            }
            if (sp == 0) return false;
            current = stack[--sp];
        }
    }

}
