using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// Top-down BVH construction with the binned surface area heuristic (Wald, "On fast Construction of SAH-based
/// Bounding Volume Hierarchies", 2007; pbrt-v4 §7.3.2): at each node the primitive centroids are binned into
/// 16 buckets along each axis (one per primitive in smaller nodes; ranges under 64 primitives weigh their
/// longest centroid axis only), and the split plane between buckets minimising
/// 1/2 + (N_left·A_left + N_right·A_right) / A_node is chosen, or a leaf when that is not cheaper than N;
/// two primitives always make a leaf.
/// Each primitive is a 32-byte box of two 4-lane vectors (Wald's "primitive reference"), so binning all three
/// axes and growing a box are a few SIMD instructions; centroids are used doubled (lower + upper), which bins
/// alike. The boxes are permuted in place as ranges are partitioned (Hoare's two-pointer scheme, which also
/// yields both children's bounds), so every pass reads memory in order. Large ranges are binned in parallel
/// chunks and large subtrees built in parallel. Bin counts and box unions are exact whatever the chunking, and
/// each subtree depends only on its range, so the node array is the same for any thread count.
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

    /// <summary>An axis-aligned box as two 4-lane vectors with w = 0.</summary>
    internal struct Box
    {
        public Vector128<float> Lo, Hi;

        public static Box Of(in Bounds3 b) => new() { Lo = b.Min.AsVector128(), Hi = b.Max.AsVector128() };

        /// <summary>Twice the centroid.</summary>
        public readonly Vector128<float> Centroid2 => Lo + Hi;
    }

    /// <summary>What a range of primitives spans: the union of their boxes, and of their (doubled) centroids.</summary>
    struct Extent
    {
        public Vector128<float> Lo, Hi, CLo, CHi;

        public static Extent Empty => new()
        {
            Lo = Vector128.Create(float.PositiveInfinity),
            Hi = Vector128.Create(float.NegativeInfinity),
            CLo = Vector128.Create(float.PositiveInfinity),
            CHi = Vector128.Create(float.NegativeInfinity),
        };

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Add(in Box b)
        {
            Lo = Vector128.MinNative(Lo, b.Lo); Hi = Vector128.MaxNative(Hi, b.Hi);
            var c = b.Centroid2;
            CLo = Vector128.MinNative(CLo, c); CHi = Vector128.MaxNative(CHi, c);
        }

        public readonly float HalfArea => BvhBuilder.HalfArea(Lo, Hi);
    }

    /// <summary>The binning of one range: bucket = clamp(⌊(2c − min)·scale⌋, 0, last) on every axis at once.</summary>
    readonly struct Binning(Vector128<float> min, Vector128<float> scale, int bins)
    {
        public readonly int Count = bins;
        readonly Vector128<float> _last = Vector128.Create((float)(bins - 1));

        // Clamped before the conversion, so every platform gives the same bucket: NaN (0·∞ on a flat axis) becomes 0
        // (x86's maxps returns its second operand; Arm's NaN converts to 0) and ∞ (a subnormal spread) the last.
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public Vector128<int> Of(in Box b) =>
            Vector128.ConvertToInt32Native(
                Vector128.MinNative(Vector128.MaxNative((b.Centroid2 - min) * scale, Vector128<float>.Zero), _last));
    }

    Box[]? _boxes;      // permuted with _order; dropped once the tree is built
    readonly int[] _order;
    readonly int _maxLeafSize;
    readonly bool _parallel;
    // The nodes, written in place: the subtree over primitives [start, end) owns the 2(end − start) − 1 slots
    // from its root on (a binary tree over n primitives has at most 2n − 1 nodes), its left child the next
    // 2·n_left − 1 and its right child the rest. So the first child directly follows its parent, parallel
    // subtrees write disjoint slots (no shared counter, no false sharing), and the array is the same for any
    // thread count; the slots a leaf of several primitives leaves unused are never written, and Compact drops them.
    readonly BvhNode[] _nodes;

    /// <summary>Takes <paramref name="boxes"/> (one per primitive) as its own: they are permuted as the tree is built.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    BvhBuilder(Box[] boxes, int maxLeafSize, bool parallel)
    {
        _boxes = boxes;
        _order = GC.AllocateUninitializedArray<int>(boxes.Length);
        for (int i = 0; i < boxes.Length; i++) _order[i] = i;
        _maxLeafSize = maxLeafSize;
        _parallel = parallel;
        // each used slot is written once; Compact reads only those
        _nodes = GC.AllocateUninitializedArray<BvhNode>(2 * boxes.Length - 1);
    }

    public static (BvhNode[] nodes, int[] order, int maxDepth) Build(ReadOnlySpan<Bounds3> bounds, int maxLeafSize, bool parallel)
    {
        var boxes = GC.AllocateUninitializedArray<Box>(bounds.Length);
        for (int i = 0; i < bounds.Length; i++) boxes[i] = Box.Of(bounds[i]);
        return Build(boxes, maxLeafSize, parallel);
    }

    /// <summary>As <see cref="Build(ReadOnlySpan{Bounds3}, int, bool)"/> from the primitives' boxes, which the builder permutes and
    /// then lets go (so a caller that made them for the build alone holds them no longer than the build needs them).</summary>
    public static (BvhNode[] nodes, int[] order, int maxDepth) Build(Box[] boxes, int maxLeafSize, bool parallel)
    {
        if (maxLeafSize < 1 || maxLeafSize > ushort.MaxValue) throw new ArgumentOutOfRangeException(nameof(maxLeafSize));
        if (boxes.Length == 0) return ([], [], 0);
        var builder = new BvhBuilder(boxes, maxLeafSize, parallel);
        int depth = builder.Subtree(0, boxes.Length, 0, 1, builder.RangeExtent(0, boxes.Length));
        builder._boxes = null;   // 32 bytes a primitive, free before the compacted nodes are allocated
        return (Compact(builder._nodes), builder._order, depth);
    }

    /// <summary>
    /// The nodes without the slots leaves left unused, in the same depth-first order (each first child right after
    /// its parent; second children renumbered): the same tree, traversed in the same order, in about half the memory.
    /// </summary>
    static BvhNode[] Compact(BvhNode[] slots)
    {
        int used = 0;
        Count(0);
        var nodes = GC.AllocateUninitializedArray<BvhNode>(used);
        int next = 0;
        Copy(0);
        return nodes;

        void Count(int at)
        {
            used++;
            if (slots[at].IsLeaf) return;
            Count(at + 1);
            Count(slots[at].Offset);
        }

        void Copy(int at)
        {
            var node = slots[at];
            int to = next++;
            if (node.IsLeaf) { nodes[to] = node; return; }
            Copy(at + 1);
            nodes[to] = BvhNode.Interior(node.Min, node.Max, next, node.Axis);
            Copy(node.Offset);
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    Extent RangeExtent(int start, int end)
    {
        var e = Extent.Empty;
        var boxes = _boxes!;
        for (int i = start; i < end; i++) e.Add(in boxes[i]);
        return e;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float HalfArea(Vector128<float> lo, Vector128<float> hi)
    {
        var d = hi - lo;
        float x = d.ToScalar(), y = d.GetElement(1), z = d.GetElement(2);
        return x * y + y * z + z * x;
    }

    static int LongestAxis(Vector128<float> extent)
    {
        float x = extent.ToScalar(), y = extent.GetElement(1), z = extent.GetElement(2);
        return x >= y ? (x >= z ? 0 : 2) : (y >= z ? 1 : 2);
    }

    /// <summary>Builds the subtree over [start, end) with its root in slot <paramref name="at"/>; returns its depth.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Subtree(int start, int end, int at, int depth, Extent extent)
    {
        int count = end - start;
        var min = extent.Lo.AsVector3();
        var max = extent.Hi.AsVector3();
        if (count <= Math.Min(LeafAtOnce, _maxLeafSize)) return Leaf(at, min, max, start, count, depth);

        int mid, axis;
        Extent left, right;
        var spread = extent.CHi - extent.CLo;
        int longest = LongestAxis(spread);
        if (!(spread.GetElement(longest) > 0) || depth > SahDepthLimit)
        {
            // All centroids coincide (nothing separates them), or deep enough: split at the median.
            if (!(spread.GetElement(longest) > 0) && count <= _maxLeafSize) return Leaf(at, min, max, start, count, depth);
            axis = longest;
            mid = MedianSplit(start, end, axis, out left, out right);
        }
        else
        {
            int nb = Math.Clamp(count, 2, Bins);
            var binning = new Binning(extent.CLo, Vector128.Create((float)nb) / spread, nb); // ∞ on a flat axis
            (axis, int split, float cost) = BestSplit(start, end, binning, extent, longest);
            if (count <= _maxLeafSize && count <= cost) return Leaf(at, min, max, start, count, depth);
            if (split < 0)
            {
                // No bucket boundary separates anything: split at the median of the longest axis.
                axis = longest;
                mid = MedianSplit(start, end, axis, out left, out right);
            }
            else
            {
                mid = Partition(start, end, axis, split, binning, out left, out right);
                if (mid == start || mid == end) mid = MedianSplit(start, end, axis, out left, out right);
            }
        }

        int second = at + 2 * (mid - start);
        _nodes[at] = BvhNode.Interior(min, max, second, axis);
        if (_parallel && count >= ParallelThreshold) return ChildrenInParallel(start, mid, end, at, depth + 1, left, right);
        return Math.Max(Subtree(start, mid, at + 1, depth + 1, left), Subtree(mid, end, second, depth + 1, right));
    }

    /// <summary>A leaf in slot <paramref name="at"/>; the 2·count − 2 slots after it, which its range owns, stay unused (Compact skips
    /// them).</summary>
    int Leaf(int at, Vector3 min, Vector3 max, int start, int count, int depth)
    {
        _nodes[at] = BvhNode.Leaf(min, max, start, count);
        return depth;
    }

    // The lambdas live in their own methods: a closure captured in Subtree or BestSplit would be allocated on
    // every call, parallel or not.
    int ChildrenInParallel(int start, int mid, int end, int at, int depth, Extent left, Extent right)
    {
        int l = 0, r = 0;
        Parallel.Invoke(() => l = Subtree(start, mid, at + 1, depth, left),
            () => r = Subtree(mid, end, at + 2 * (mid - start), depth, right));
        return Math.Max(l, r);
    }

    /// <summary>As <see cref="Fill"/>, in parallel chunks whose exact counts and unions are merged.</summary>
    void FillInParallel(Span<int> counts, Span<Box> buckets, int start, int end, Binning binning)
    {
        int count = end - start, n = counts.Length;
        int chunks = Math.Min(Environment.ProcessorCount, 8);
        var partCounts = new int[chunks][];
        var partBuckets = new Box[chunks][];
        Parallel.For(0, chunks, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (k) =>
        {
            partCounts[k] = new int[n];
            partBuckets[k] = new Box[n];
            Clear(partCounts[k], partBuckets[k]);
            Fill(partCounts[k], partBuckets[k], start + (int)((long)count * k / chunks), start + (int)((long)count * (k + 1) / chunks),
                binning);
        });
        for (int k = 0; k < chunks; k++)
            for (int i = 0; i < n; i++)
            {
                counts[i] += partCounts[k][i];
                buckets[i].Lo = Vector128.MinNative(buckets[i].Lo, partBuckets[k][i].Lo);
                buckets[i].Hi = Vector128.MaxNative(buckets[i].Hi, partBuckets[k][i].Hi);
            }
    }

    /// <summary>Counts and box unions per bucket of every axis over [start, end): 3·nb entries, axis-major.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Fill(Span<int> counts, Span<Box> buckets, int start, int end, in Binning binning)
    {
        int nb = binning.Count;
        var boxes = _boxes!;
        for (int i = start; i < end; i++)
        {
            ref readonly var b = ref boxes[i];
            var bin = binning.Of(in b);
            int x = bin.ToScalar(), y = nb + bin.GetElement(1), z = 2 * nb + bin.GetElement(2);
            counts[x]++; counts[y]++; counts[z]++;
            ref var bx = ref buckets[x]; bx.Lo = Vector128.MinNative(bx.Lo, b.Lo); bx.Hi = Vector128.MaxNative(bx.Hi, b.Hi);
            ref var by = ref buckets[y]; by.Lo = Vector128.MinNative(by.Lo, b.Lo); by.Hi = Vector128.MaxNative(by.Hi, b.Hi);
            ref var bz = ref buckets[z]; bz.Lo = Vector128.MinNative(bz.Lo, b.Lo); bz.Hi = Vector128.MaxNative(bz.Hi, b.Hi);
        }
    }

    /// <summary>As <see cref="Fill"/> along one axis only (nb entries).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void FillAxis(Span<int> counts, Span<Box> buckets, int start, int end, in Binning binning, int axis)
    {
        var boxes = _boxes!;
        for (int i = start; i < end; i++)
        {
            ref readonly var b = ref boxes[i];
            int k = Bucket(binning.Of(in b), axis);
            counts[k]++;
            ref var bk = ref buckets[k]; bk.Lo = Vector128.MinNative(bk.Lo, b.Lo); bk.Hi = Vector128.MaxNative(bk.Hi, b.Hi);
        }
    }

    static void Clear(Span<int> counts, Span<Box> buckets)
    {
        counts.Clear();
        buckets.Fill(new Box { Lo = Vector128.Create(float.PositiveInfinity), Hi = Vector128.Create(float.NegativeInfinity) });
    }

    /// <summary>The SAH-cheapest (axis, last bucket on the left) and its cost, in units of one primitive test.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    (int axis, int split, float cost) BestSplit(int start, int end, in Binning binning, in Extent extent, int longest)
    {
        int count = end - start;
        int nb = binning.Count;
        Span<int> counts = stackalloc int[3 * nb];
        Span<Box> buckets = stackalloc Box[3 * nb];
        Clear(counts, buckets);
        if (_parallel && count >= ParallelBinning) FillInParallel(counts, buckets, start, end, binning);
        else if (count < SmallRange)
            FillAxis(counts.Slice(longest * nb, nb), buckets.Slice(longest * nb, nb), start, end, binning, longest);
        else Fill(counts, buckets, start, end, binning);

        int bestAxis = 0, bestSplit = -1;
        float bestCost = float.PositiveInfinity;
        Span<float> rightCost = stackalloc float[nb];
        float area = extent.HalfArea;
        float invArea = area > 0 ? 1 / area : 0;
        var spread = extent.CHi - extent.CLo;
        // Small ranges weigh splits along the longest centroid axis only; large ones along all three.
        for (int axis = 0; axis < 3; axis++)
        {
            if (!(spread.GetElement(axis) > 0) || (count < SmallRange && axis != longest)) continue;
            var ac = counts.Slice(axis * nb, nb);
            var ab = buckets.Slice(axis * nb, nb);
            // Sweep from the right: N·A of buckets (s+1 .. nb−1); an empty union (n = 0) costs nothing.
            var lo = Vector128.Create(float.PositiveInfinity);
            var hi = Vector128.Create(float.NegativeInfinity);
            int n = 0;
            for (int s = nb - 1; s > 0; s--)
            {
                lo = Vector128.MinNative(lo, ab[s].Lo); hi = Vector128.MaxNative(hi, ab[s].Hi); n += ac[s];
                rightCost[s - 1] = n == 0 ? 0 : n * HalfArea(lo, hi);
            }
            lo = Vector128.Create(float.PositiveInfinity);
            hi = Vector128.Create(float.NegativeInfinity);
            n = 0;
            for (int s = 0; s < nb - 1; s++)
            {
                lo = Vector128.MinNative(lo, ab[s].Lo); hi = Vector128.MaxNative(hi, ab[s].Hi); n += ac[s];
                if (n == 0 || n == count) continue;
                float cost = TraversalCost + (n * HalfArea(lo, hi) + rightCost[s]) * invArea;
                if (cost < bestCost) { bestCost = cost; bestAxis = axis; bestSplit = s; }
            }
        }
        return (bestAxis, bestSplit, bestCost);
    }

    /// <summary>
    /// Moves the primitives whose bucket on the axis is ≤ split to the front, swapping only misplaced pairs
    /// (Hoare); returns the first of the rest, and both sides' extents.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Partition(int start, int end, int axis, int split, in Binning binning, out Extent left, out Extent right)
    {
        var l = Extent.Empty;
        var r = Extent.Empty;
        var boxes = _boxes!;
        int i = start, j = end - 1;
        while (true)
        {
            while (i <= j && Bucket(binning.Of(in boxes[i]), axis) <= split) l.Add(in boxes[i++]);
            while (i <= j && Bucket(binning.Of(in boxes[j]), axis) > split) r.Add(in boxes[j--]);
            if (i > j) break;
            // boxes[i] belongs right and boxes[j] left (i < j): exchange them.
            (boxes[i], boxes[j]) = (boxes[j], boxes[i]);
            (_order[i], _order[j]) = (_order[j], _order[i]);
            l.Add(in boxes[i++]);
            r.Add(in boxes[j--]);
        }
        left = l;
        right = r;
        return i;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static int Bucket(Vector128<int> buckets, int axis) =>
        axis == 0 ? buckets.ToScalar() : axis == 1 ? buckets.GetElement(1) : buckets.GetElement(2);

    /// <summary>Orders the range by centroid along the axis (ties by primitive index, so the result is unique); returns the
    /// middle.</summary>
    int MedianSplit(int start, int end, int axis, out Extent left, out Extent right)
    {
        int n = end - start;
        var all = _boxes!;
        var keys = new (float Key, int Primitive, int At)[n];
        for (int i = 0; i < n; i++) keys[i] = (all[start + i].Centroid2.GetElement(axis), _order[start + i], start + i);
        Array.Sort(keys, (a, b) => a.Key != b.Key ? a.Key.CompareTo(b.Key) : a.Primitive.CompareTo(b.Primitive));
        var boxes = new Box[n];
        for (int i = 0; i < n; i++) boxes[i] = all[keys[i].At];
        for (int i = 0; i < n; i++) { all[start + i] = boxes[i]; _order[start + i] = keys[i].Primitive; }
        int mid = (start + end) / 2;
        left = RangeExtent(start, mid);
        right = RangeExtent(mid, end);
        return mid;
    }
}
