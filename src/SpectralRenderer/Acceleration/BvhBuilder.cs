using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// Top-down BVH construction with the binned surface area heuristic (Wald, "On fast Construction of SAH-based
/// Bounding Volume Hierarchies", 2007; pbrt-v4 §7.3.2): at each node the primitive centroids are binned into
/// 16 buckets along each axis (one per primitive in smaller nodes; ranges under 64 primitives weigh their
/// longest centroid axis only), and the split plane between buckets minimising
/// 1/2 + (N_left·A_left + N_right·A_right) / A_node is chosen, or a leaf when that is not cheaper than N;
/// two primitives always make a leaf.
/// The primitives' bounds and centroids are kept in arrays permuted in place as the ranges are partitioned,
/// so every pass reads memory in order; the partition also yields both children's bounds. Large ranges are
/// binned in parallel chunks and large subtrees built in parallel. Bin counts and box unions are exact
/// whatever the chunking, and each subtree depends only on its range, so the node array is the same for
/// any thread count.
/// </summary>
[SkipLocalsInit]
sealed class BvhBuilder
{
    const int Bins = 16;
    const int ParallelThreshold = 8192;
    const int ParallelBinning = 65536;
    /// <summary>Below this depth the SAH may cut off single primitives; deeper, the median is taken, which bounds the depth.</summary>
    const int SahDepthLimit = 40;
    const float TraversalCost = 0.5f;
    /// <summary>Ranges this small become leaves without weighing a split: two triangles are tested as fast as a box pair.</summary>
    const int LeafAtOnce = 2;
    const int SmallRange = 64;

    readonly Bounds3[] _bounds;     // permuted with _order
    readonly Vector3[] _centroids;  // permuted with _order
    readonly int[] _order;
    readonly int _maxLeafSize;
    readonly bool _parallel;
    int _nodeCount;
    // The tree while it is built: plain structs (no object graph for the GC to trace), indices handed out
    // as nodes are made (in any order when subtrees run in parallel); Flatten lays them out depth-first.
    readonly Node[] _tree;

    struct Node
    {
        public Bounds3 Bounds;
        public int Left, Right;   // Left = −1 for a leaf
        public int Start, Count, Axis;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    BvhBuilder(ReadOnlySpan<Bounds3> bounds, int maxLeafSize, bool parallel)
    {
        _bounds = bounds.ToArray();
        _centroids = new Vector3[bounds.Length];
        _order = new int[bounds.Length];
        for (int i = 0; i < bounds.Length; i++) { _centroids[i] = bounds[i].Centre; _order[i] = i; }
        _maxLeafSize = maxLeafSize;
        _parallel = parallel;
        _tree = new Node[Math.Max(1, 2 * bounds.Length - 1)];
    }

    public static (BvhNode[] nodes, int[] order, int maxDepth) Build(ReadOnlySpan<Bounds3> bounds, int maxLeafSize, bool parallel)
    {
        if (maxLeafSize < 1 || maxLeafSize > ushort.MaxValue) throw new ArgumentOutOfRangeException(nameof(maxLeafSize));
        if (bounds.Length == 0) return ([], [], 0);
        var builder = new BvhBuilder(bounds, maxLeafSize, parallel);
        var (b, c) = builder.RangeBounds(0, bounds.Length);
        int root = builder.Subtree(0, bounds.Length, 0, b, c);
        var nodes = new BvhNode[builder._nodeCount];
        int next = 0, maxDepth = 0;
        builder.Flatten(root, nodes, ref next, 1, ref maxDepth);
        return (nodes, builder._order, maxDepth);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Flatten(int at, BvhNode[] nodes, ref int next, int depth, ref int maxDepth)
    {
        ref readonly var n = ref _tree[at];
        int index = next++;
        maxDepth = Math.Max(maxDepth, depth);
        if (n.Left < 0)
        {
            nodes[index] = BvhNode.Leaf(n.Bounds.Min, n.Bounds.Max, n.Start, n.Count);
            return index;
        }
        Flatten(n.Left, nodes, ref next, depth + 1, ref maxDepth);
        int second = Flatten(n.Right, nodes, ref next, depth + 1, ref maxDepth);
        nodes[index] = BvhNode.Interior(n.Bounds.Min, n.Bounds.Max, second, n.Axis);
        return index;
    }

    /// <summary>The union of the primitives' bounds and of their centroids over [start, end).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    (Bounds3, Bounds3) RangeBounds(int start, int end)
    {
        var b = Bounds3.Empty;
        var c = Bounds3.Empty;
        for (int i = start; i < end; i++) { b.Include(_bounds[i]); c.Include(_centroids[i]); }
        return (b, c);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Subtree(int start, int end, int depth, Bounds3 bounds, Bounds3 centroidBounds)
    {
        int at = Interlocked.Increment(ref _nodeCount) - 1;
        ref var node = ref _tree[at];
        node = new Node { Start = start, Count = end - start, Bounds = bounds, Left = -1, Right = -1 };
        int count = end - start;
        if (count <= Math.Min(LeafAtOnce, _maxLeafSize)) return at;

        int mid;
        Bounds3 lb, lc, rb, rc;
        var extent = centroidBounds.Extent;
        int longest = extent.X >= extent.Y ? (extent.X >= extent.Z ? 0 : 2) : (extent.Y >= extent.Z ? 1 : 2);
        int axis;
        if (!(extent[longest] > 0) || depth >= SahDepthLimit)
        {
            // All centroids coincide (nothing separates them), or deep enough: split at the median.
            if (!(extent[longest] > 0) && count <= _maxLeafSize) return at;
            MedianSplit(start, end, longest);
            mid = (start + end) / 2;
            axis = longest;
            (lb, lc) = RangeBounds(start, mid);
            (rb, rc) = RangeBounds(mid, end);
        }
        else
        {
            (axis, int split, float cost) = BestSplit(start, end, centroidBounds, bounds.HalfArea);
            if (count <= _maxLeafSize && count <= cost) return at;
            mid = Partition(start, end, axis, split, centroidBounds, out lb, out lc, out rb, out rc);
            if (mid == start || mid == end)
            {
                MedianSplit(start, end, axis);
                mid = (start + end) / 2;
                (lb, lc) = RangeBounds(start, mid);
                (rb, rc) = RangeBounds(mid, end);
            }
        }

        int left, right;
        if (_parallel && count >= ParallelThreshold)
        {
            int l = 0, r = 0;
            Parallel.Invoke(() => l = Subtree(start, mid, depth + 1, lb, lc), () => r = Subtree(mid, end, depth + 1, rb, rc));
            (left, right) = (l, r);
        }
        else
        {
            left = Subtree(start, mid, depth + 1, lb, lc);
            right = Subtree(mid, end, depth + 1, rb, rc);
        }
        // _tree is never reallocated, so the reference is still good; set the fields after the children exist.
        _tree[at].Left = left;
        _tree[at].Right = right;
        _tree[at].Axis = axis;
        return at;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static int Bin(float c, float min, float scale, int bins) => Math.Clamp((int)((c - min) * scale), 0, bins - 1);

    /// <summary><see cref="Bins"/> buckets, or one per primitive in a node with fewer primitives than that.</summary>
    static int BinsFor(int count) => Math.Clamp(count, 2, Bins);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Fill(Span<int> counts, Span<Bounds3> bb, int start, int end, Vector3 min, Vector3 scale, int bins)
    {
        for (int i = start; i < end; i++)
        {
            var c = _centroids[i];
            ref readonly var b = ref _bounds[i];
            int bx = Bin(c.X, min.X, scale.X, bins), by = bins + Bin(c.Y, min.Y, scale.Y, bins), bz = 2 * bins + Bin(c.Z, min.Z, scale.Z, bins);
            counts[bx]++; counts[by]++; counts[bz]++;
            bb[bx].Include(b); bb[by].Include(b); bb[bz].Include(b);
        }
    }

    /// <summary>The SAH-cheapest (axis, last bin on the left) and its cost, in units of one primitive test.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    (int axis, int split, float cost) BestSplit(int start, int end, in Bounds3 centroidBounds, float nodeArea)
    {
        int count = end - start;
        int nb = BinsFor(count);
        var scale = new Vector3(nb) / centroidBounds.Extent; // inf on a flat axis: every centroid lands in bin 0
        var min = centroidBounds.Min;
        // Bin counts and box unions (exact, so parallel chunks merge to the same result).
        Span<int> counts = stackalloc int[3 * nb];
        Span<Bounds3> binBounds = stackalloc Bounds3[3 * nb];
        counts.Clear();
        binBounds.Fill(Bounds3.Empty);
        if (_parallel && count >= ParallelBinning)
        {
            int chunks = Math.Min(Environment.ProcessorCount, 8);
            var partCounts = new int[chunks][];
            var partBounds = new Bounds3[chunks][];
            Parallel.For(0, chunks, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (k) =>
            {
                partCounts[k] = new int[3 * nb];
                partBounds[k] = new Bounds3[3 * nb];
                Array.Fill(partBounds[k], Bounds3.Empty);
                Fill(partCounts[k], partBounds[k], start + (int)((long)count * k / chunks), start + (int)((long)count * (k + 1) / chunks), min, scale, nb);
            });
            for (int k = 0; k < chunks; k++)
                for (int i = 0; i < counts.Length; i++) { counts[i] += partCounts[k][i]; binBounds[i].Include(partBounds[k][i]); }
        }
        else Fill(counts, binBounds, start, end, min, scale, nb);

        int bestAxis = 0, bestSplit = -1;
        float bestCost = float.PositiveInfinity;
        Span<float> rightCost = stackalloc float[nb];
        float invArea = nodeArea > 0 ? 1 / nodeArea : 0;
        // Small ranges weigh splits along the longest centroid axis only; large ones along all three.
        var ext = centroidBounds.Extent;
        int longest = ext.X >= ext.Y ? (ext.X >= ext.Z ? 0 : 2) : (ext.Y >= ext.Z ? 1 : 2);
        for (int axis = 0; axis < 3; axis++)
        {
            if (!(centroidBounds.Extent[axis] > 0) || (count < SmallRange && axis != longest)) continue;
            var ac = counts.Slice(axis * nb, nb);
            var ab = binBounds.Slice(axis * nb, nb);
            // Sweep from the right: N·A of bins (s+1 .. Bins-1).
            var acc = Bounds3.Empty;
            int n = 0;
            for (int s = nb - 1; s > 0; s--)
            {
                acc.Include(ab[s]); n += ac[s];
                rightCost[s - 1] = n * acc.HalfArea;
            }
            acc = Bounds3.Empty; n = 0;
            for (int s = 0; s < nb - 1; s++)
            {
                acc.Include(ab[s]); n += ac[s];
                if (n == 0 || n == count) continue;
                float cost = TraversalCost + (n * acc.HalfArea + rightCost[s]) * invArea;
                if (cost < bestCost) { bestCost = cost; bestAxis = axis; bestSplit = s; }
            }
        }
        return (bestAxis, bestSplit, bestCost);
    }

    /// <summary>
    /// Moves primitives whose centroid bin is ≤ split to the front (bounds, centroids and order together);
    /// returns the first of the rest, and both sides' bounds and centroid bounds.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Partition(int start, int end, int axis, int split, in Bounds3 centroidBounds, out Bounds3 lb, out Bounds3 lc, out Bounds3 rb, out Bounds3 rc)
    {
        float min = centroidBounds.Min[axis];
        int nb = BinsFor(end - start);
        float scale = nb / centroidBounds.Extent[axis];
        lb = lc = rb = rc = Bounds3.Empty;
        int i = start, j = end - 1;
        while (i <= j)
        {
            var c = _centroids[i];
            if (Bin(axis == 0 ? c.X : axis == 1 ? c.Y : c.Z, min, scale, nb) <= split)
            {
                lb.Include(_bounds[i]); lc.Include(c);
                i++;
            }
            else
            {
                rb.Include(_bounds[i]); rc.Include(c);
                (_bounds[i], _bounds[j]) = (_bounds[j], _bounds[i]);
                (_centroids[i], _centroids[j]) = (_centroids[j], _centroids[i]);
                (_order[i], _order[j]) = (_order[j], _order[i]);
                j--;
            }
        }
        return i;
    }

    /// <summary>Orders the range by centroid along the axis (ties by primitive index, so the result is unique).</summary>
    void MedianSplit(int start, int end, int axis)
    {
        int n = end - start;
        var keys = new (float Key, int Primitive, int At)[n];
        for (int i = 0; i < n; i++) keys[i] = (_centroids[start + i][axis], _order[start + i], start + i);
        Array.Sort(keys, (a, b) => a.Key != b.Key ? a.Key.CompareTo(b.Key) : a.Primitive.CompareTo(b.Primitive));
        var bounds = new Bounds3[n];
        var centroids = new Vector3[n];
        for (int i = 0; i < n; i++) { bounds[i] = _bounds[keys[i].At]; centroids[i] = _centroids[keys[i].At]; }
        for (int i = 0; i < n; i++) { _bounds[start + i] = bounds[i]; _centroids[start + i] = centroids[i]; _order[start + i] = keys[i].Primitive; }
    }
}
