using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// Top-down BVH construction with the binned surface area heuristic (Wald, "On fast Construction of SAH-based
/// Bounding Volume Hierarchies", 2007; pbrt-v4 §7.3.2): at each node the primitive centroids are binned into
/// 16 buckets along each axis, and the split plane between buckets minimising
/// 1/2 + (N_left·A_left + N_right·A_right) / A_node is chosen, or a leaf when that is not cheaper than N.
/// Subtrees over many primitives are built in parallel; each subtree's result depends only on its primitives,
/// and the tree is flattened depth-first afterwards, so the node array is the same for any thread count.
/// </summary>
sealed class BvhBuilder
{
    const int Bins = 16;
    const int ParallelThreshold = 8192;
    /// <summary>Below this depth the SAH may cut off single primitives; deeper, the median is taken, which bounds the depth.</summary>
    const int SahDepthLimit = 40;
    const float TraversalCost = 0.5f;

    readonly Bounds3[] _bounds;
    readonly Vector3[] _centroids;
    readonly int[] _order;
    readonly int _maxLeafSize;
    readonly bool _parallel;
    int _nodeCount;

    sealed class Node
    {
        public Bounds3 Bounds;
        public Node? Left, Right;
        public int Start, Count, Axis;
    }

    BvhBuilder(ReadOnlySpan<Bounds3> bounds, int maxLeafSize, bool parallel)
    {
        _bounds = bounds.ToArray();
        _centroids = new Vector3[bounds.Length];
        for (int i = 0; i < bounds.Length; i++) _centroids[i] = bounds[i].Centre;
        _order = new int[bounds.Length];
        for (int i = 0; i < _order.Length; i++) _order[i] = i;
        _maxLeafSize = maxLeafSize;
        _parallel = parallel;
    }

    public static (BvhNode[] nodes, int[] order, int maxDepth) Build(ReadOnlySpan<Bounds3> bounds, int maxLeafSize, bool parallel)
    {
        if (maxLeafSize < 1 || maxLeafSize > ushort.MaxValue) throw new ArgumentOutOfRangeException(nameof(maxLeafSize));
        if (bounds.Length == 0) return ([], [], 0);
        var builder = new BvhBuilder(bounds, maxLeafSize, parallel);
        var root = builder.Subtree(0, bounds.Length, 0);
        var nodes = new BvhNode[builder._nodeCount];
        int next = 0, maxDepth = 0;
        Flatten(root, nodes, ref next, 1, ref maxDepth);
        return (nodes, builder._order, maxDepth);
    }

    static int Flatten(Node n, BvhNode[] nodes, ref int next, int depth, ref int maxDepth)
    {
        int index = next++;
        maxDepth = Math.Max(maxDepth, depth);
        if (n.Left is null)
        {
            nodes[index] = BvhNode.Leaf(n.Bounds.Min, n.Bounds.Max, n.Start, n.Count);
            return index;
        }
        Flatten(n.Left, nodes, ref next, depth + 1, ref maxDepth);
        int second = Flatten(n.Right!, nodes, ref next, depth + 1, ref maxDepth);
        nodes[index] = BvhNode.Interior(n.Bounds.Min, n.Bounds.Max, second, n.Axis);
        return index;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    Node Subtree(int start, int end, int depth)
    {
        Interlocked.Increment(ref _nodeCount);
        var node = new Node { Start = start, Count = end - start };
        var bounds = Bounds3.Empty;
        var centroidBounds = Bounds3.Empty;
        for (int i = start; i < end; i++)
        {
            int p = _order[i];
            bounds.Include(_bounds[p]);
            centroidBounds.Include(_centroids[p]);
        }
        node.Bounds = bounds;
        int count = end - start;
        if (count == 1) return node;

        int mid;
        var extent = centroidBounds.Extent;
        int longest = extent.X >= extent.Y ? (extent.X >= extent.Z ? 0 : 2) : (extent.Y >= extent.Z ? 1 : 2);
        if (!(extent[longest] > 0))
        {
            // All centroids coincide: nothing separates them.
            if (count <= _maxLeafSize) return node;
            mid = (start + end) / 2;
            node.Axis = longest;
        }
        else if (depth >= SahDepthLimit)
        {
            mid = (start + end) / 2;
            MedianSplit(start, end, longest);
            node.Axis = longest;
        }
        else
        {
            var (axis, split, cost) = BestSplit(start, end, centroidBounds, bounds.HalfArea);
            if (count <= _maxLeafSize && count <= cost) return node;
            mid = Partition(start, end, axis, split, centroidBounds);
            node.Axis = axis;
            if (mid == start || mid == end) { mid = (start + end) / 2; MedianSplit(start, end, axis); }
        }

        if (_parallel && count >= ParallelThreshold)
            Parallel.Invoke(() => node.Left = Subtree(start, mid, depth + 1), () => node.Right = Subtree(mid, end, depth + 1));
        else
        {
            node.Left = Subtree(start, mid, depth + 1);
            node.Right = Subtree(mid, end, depth + 1);
        }
        return node;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int Bin(float c, float min, float scale) => Math.Clamp((int)((c - min) * scale), 0, Bins - 1);

    /// <summary>The SAH-cheapest (axis, last bin on the left) and its cost, in units of one primitive test.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    (int axis, int split, float cost) BestSplit(int start, int end, in Bounds3 centroidBounds, float nodeArea)
    {
        Span<int> counts = stackalloc int[3 * Bins];
        Span<Bounds3> binBounds = stackalloc Bounds3[3 * Bins];
        binBounds.Fill(Bounds3.Empty);
        var scale = new Vector3(Bins) / centroidBounds.Extent; // inf on a flat axis: every centroid lands in bin 0
        var min = centroidBounds.Min;
        for (int i = start; i < end; i++)
        {
            int p = _order[i];
            var c = _centroids[p];
            int bx = Bin(c.X, min.X, scale.X), by = Bins + Bin(c.Y, min.Y, scale.Y), bz = 2 * Bins + Bin(c.Z, min.Z, scale.Z);
            counts[bx]++; counts[by]++; counts[bz]++;
            binBounds[bx].Include(_bounds[p]); binBounds[by].Include(_bounds[p]); binBounds[bz].Include(_bounds[p]);
        }

        int bestAxis = 0, bestSplit = -1;
        float bestCost = float.PositiveInfinity;
        Span<float> rightCost = stackalloc float[Bins];
        float invArea = nodeArea > 0 ? 1 / nodeArea : 0;
        for (int axis = 0; axis < 3; axis++)
        {
            if (!(centroidBounds.Extent[axis] > 0)) continue;
            var ac = counts.Slice(axis * Bins, Bins);
            var ab = binBounds.Slice(axis * Bins, Bins);
            // Sweep from the right: N·A of bins (s+1 .. Bins-1).
            var acc = Bounds3.Empty;
            int n = 0;
            for (int s = Bins - 1; s > 0; s--)
            {
                acc.Include(ab[s]); n += ac[s];
                rightCost[s - 1] = n * acc.HalfArea;
            }
            acc = Bounds3.Empty; n = 0;
            for (int s = 0; s < Bins - 1; s++)
            {
                acc.Include(ab[s]); n += ac[s];
                if (n == 0 || n == end - start) continue;
                float cost = TraversalCost + (n * acc.HalfArea + rightCost[s]) * invArea;
                if (cost < bestCost) { bestCost = cost; bestAxis = axis; bestSplit = s; }
            }
        }
        return (bestAxis, bestSplit, bestCost);
    }

    /// <summary>Moves primitives whose centroid bin is ≤ split to the front; returns the first of the rest.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Partition(int start, int end, int axis, int split, in Bounds3 centroidBounds)
    {
        float min = centroidBounds.Min[axis];
        float scale = Bins / centroidBounds.Extent[axis];
        int i = start, j = end - 1;
        while (i <= j)
        {
            if (Bin(_centroids[_order[i]][axis], min, scale) <= split) i++;
            else { (_order[i], _order[j]) = (_order[j], _order[i]); j--; }
        }
        return i;
    }

    /// <summary>Orders the range by centroid along the axis (ties by primitive index, so the result is unique).</summary>
    void MedianSplit(int start, int end, int axis)
    {
        var centroids = _centroids;
        Array.Sort(_order, start, end - start, Comparer<int>.Create((a, b) =>
        {
            int c = centroids[a][axis].CompareTo(centroids[b][axis]);
            return c != 0 ? c : a.CompareTo(b);
        }));
    }
}
