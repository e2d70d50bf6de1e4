using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// The binary <see cref="Bvh"/> collapsed into nodes of up to eight children (Wald, Benthin &amp; Boulos, "Getting rid
/// of packets", 2008; Embree's BVH8), for single rays that go every which way (a path tracer's bounces and shadow rays):
/// one node's eight child boxes are met by one ray in a single 8-lane slab test, so a ray walks about a third as many
/// levels, and the children it enters are visited nearest first. The leaves and the primitive order are the binary
/// tree's, so primitive k is the same in both. Collapsing is greedy top-down: a node's children are its binary children,
/// and the interior child with the largest surface area is replaced by its two children until there are eight or only
/// leaves (the surface area heuristic's choice of what to open first). No allocation per ray; the stack is on the stack.
/// </summary>
[SkipLocalsInit]
public sealed class WideBvh
{
    /// <summary>Leaves larger than this are not encoded (a child reference keeps the count in 3 bits).</summary>
    public const int MaxLeafSize = WideNode.Width;
    const int MaxStack = 1024;

    readonly WideNode[] _nodes;
    readonly int _stackSize;

    WideBvh(WideNode[] nodes, int depth)
    {
        _nodes = nodes;
        Depth = depth;
        // Each node visited pushes at most seven more children than it pops: 7 per level, plus one.
        _stackSize = 7 * depth + 1;
        if (_stackSize > MaxStack) throw new InvalidOperationException($"wide BVH depth {depth} exceeds the traversal stack");
    }

    /// <summary>The wide hierarchy of <paramref name="binary"/> (whose leaves hold at most <see cref="MaxLeafSize"/> primitives).</summary>
    public static WideBvh Collapse(Bvh binary)
    {
        var bin = binary.Nodes;
        if (bin.Length == 0) return new WideBvh([], 0);
        if (binary.PrimitiveOrder.Length >= 1 << 28) throw new InvalidOperationException("too many primitives for a wide BVH");
        // Two passes over the same choices: count the nodes, then write them into an array of that size (no list
        // growing by doubling and copied at the end: on 16 M triangles that was twice the nodes' memory at once).
        var nodes = new WideNode[Count(bin, 0)];
        int next = 0, depth = 0;
        CollapseNode(bin, 0, nodes, ref next, 1, ref depth);
        return new WideBvh(nodes, depth);
    }

    /// <summary>The binary nodes that become the children of the wide node made from binary node <paramref name="index"/>: its
    /// two children, the interior one of largest surface area replaced by its own two until there are eight or only leaves
    /// (a binary leaf at the root is the one child of the root).</summary>
    static int Children(ReadOnlySpan<BvhNode> bin, int index, Span<int> kids)
    {
        int n;
        if (bin[index].IsLeaf) { kids[0] = index; n = 1; }
        else { kids[0] = index + 1; kids[1] = bin[index].Offset; n = 2; }
        while (n < WideNode.Width)
        {
            int open = -1;
            float largest = float.NegativeInfinity;
            for (int i = 0; i < n; i++)
            {
                ref readonly var c = ref bin[kids[i]];
                if (c.IsLeaf) continue;
                var d = c.Max - c.Min;
                float area = d.X * d.Y + d.Y * d.Z + d.Z * d.X;
                if (area > largest || open < 0) { largest = area; open = i; }
            }
            if (open < 0) break;
            int opened = kids[open];
            for (int j = n; j > open + 1; j--) kids[j] = kids[j - 1];
            kids[open] = opened + 1;
            kids[open + 1] = bin[opened].Offset;
            n++;
        }
        return n;
    }

    static int Count(ReadOnlySpan<BvhNode> bin, int index)
    {
        Span<int> kids = stackalloc int[WideNode.Width];
        int n = Children(bin, index, kids), count = 1;
        for (int i = 0; i < n; i++)
            if (!bin[kids[i]].IsLeaf) count += Count(bin, kids[i]);
        return count;
    }

    /// <summary>Wide nodes, depth first, each before its children; node 0 is the root.</summary>
    public ReadOnlySpan<WideNode> Nodes => _nodes;
    public int NodeCount => _nodes.Length;
    /// <summary>Levels of wide nodes from the root to the deepest leaf's parent.</summary>
    public int Depth { get; }
    /// <summary>Bytes the node array holds.</summary>
    public long Bytes => (long)_nodes.Length * Unsafe.SizeOf<WideNode>();

    static int CollapseNode(ReadOnlySpan<BvhNode> bin, int index, WideNode[] nodes, ref int next, int level, ref int depth)
    {
        depth = Math.Max(depth, level);
        Span<int> kids = stackalloc int[WideNode.Width];
        int n = Children(bin, index, kids);
        int at = next++;
        var node = WideNode.Empty;
        for (int i = 0; i < n; i++)
        {
            ref readonly var c = ref bin[kids[i]];
            node.LoX[i] = c.Min.X; node.HiX[i] = c.Max.X;
            node.LoY[i] = c.Min.Y; node.HiY[i] = c.Max.Y;
            node.LoZ[i] = c.Min.Z; node.HiZ[i] = c.Max.Z;
            if (c.IsLeaf)
            {
                if (c.Count > MaxLeafSize)
                    throw new InvalidOperationException($"a leaf of {c.Count} primitives is too large for a wide BVH");
                node.Child[i] = WideNode.LeafReference(c.Offset, c.Count);
            }
            else node.Child[i] = CollapseNode(bin, kids[i], nodes, ref next, level + 1, ref depth);
        }
        nodes[at] = node;
        return at;
    }

    /// <summary>
    /// Closest hit, as <see cref="Bvh.Intersect{T}"/>: shortens ray.TMax to each hit found. The children a ray enters are
    /// pushed farthest first, so the nearest is visited next; a child popped after a closer hit was found is skipped.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Intersect<T>(ref T prims, ref Ray ray, ref Hit hit) where T : struct, IPrimitiveIntersector =>
        Avx.IsSupported ? Intersect<T, Slabs8>(ref prims, ref ray, ref hit) : Intersect<T, Slabs1>(ref prims, ref ray, ref hit);

    /// <summary>Whether anything is hit in (0, ray.TMax); stops at the first hit.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Occluded<T>(ref T prims, in Ray ray) where T : struct, IPrimitiveIntersector =>
        Avx.IsSupported ? Occluded<T, Slabs8>(ref prims, ray) : Occluded<T, Slabs1>(ref prims, ray);

    /// <summary>As <see cref="Intersect{T}(ref T, ref Ray, ref Hit)"/> with the slab test <typeparamref name="TSlabs"/> (tests pick
    /// the scalar one on an AVX machine).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal bool Intersect<T, TSlabs>(ref T prims, ref Ray ray, ref Hit hit) where T : struct, IPrimitiveIntersector
        where TSlabs : struct, ISlabs8
    {
        if (_nodes.Length == 0) return false;
        var slabs = new WideRay(ray);
        prims.Prepare(ray);
        ref WideNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        Span<int> stack = stackalloc int[_stackSize];
        Span<float> entries = stackalloc float[_stackSize];
        WideFloats entry = default;
        int sp = 0, current = 0;
        bool found = false;
        while (true)
        {
            if (current >= 0)
            {
                ref WideNode node = ref Unsafe.Add(ref root, current);
                uint mask = TSlabs.Hits(in slabs, in node, ray.TMax, ref entry);
                if (mask != 0)
                {
                    if ((mask & (mask - 1)) == 0)
                    {
                        current = node.Child[BitOperations.TrailingZeroCount(mask)];
                        continue;
                    }
                    // Insert each child entered so the stack holds them farthest first, nearest on top.
                    int bottom = sp;
                    for (; mask != 0; mask &= mask - 1)
                    {
                        int i = BitOperations.TrailingZeroCount(mask);
                        float d = entry[i];
                        int j = sp++;
                        while (j > bottom && entries[j - 1] < d) { stack[j] = stack[j - 1]; entries[j] = entries[j - 1]; j--; }
                        stack[j] = node.Child[i]; entries[j] = d;
                    }
                    current = stack[--sp];
                    continue;
                }
            }
            else
            {
                int reference = ~current;
                int last = (reference >> 3) + (reference & 7) + 1;
                for (int k = reference >> 3; k < last; k++)
                    if (prims.Intersect(k, ref ray, ref hit)) found = true;
            }
            while (true)
            {
                if (sp == 0) return found;
                sp--;
                if (entries[sp] <= ray.TMax) { current = stack[sp]; break; }
            }
        }
    }

    /// <summary>As <see cref="Occluded{T}(ref T, in Ray)"/> with the slab test <typeparamref name="TSlabs"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal bool Occluded<T, TSlabs>(ref T prims, in Ray ray) where T : struct, IPrimitiveIntersector where TSlabs : struct, ISlabs8
    {
        if (_nodes.Length == 0) return false;
        var slabs = new WideRay(ray);
        prims.Prepare(ray);
        ref WideNode root = ref MemoryMarshal.GetArrayDataReference(_nodes);
        Span<int> stack = stackalloc int[_stackSize];
        WideFloats entry = default;
        int sp = 0, current = 0;
        while (true)
        {
            if (current >= 0)
            {
                ref WideNode node = ref Unsafe.Add(ref root, current);
                uint mask = TSlabs.Hits(in slabs, in node, ray.TMax, ref entry);
                if (mask != 0)
                {
                    for (; (mask & (mask - 1)) != 0; mask &= mask - 1) stack[sp++] = node.Child[BitOperations.TrailingZeroCount(mask)];
                    current = node.Child[BitOperations.TrailingZeroCount(mask)];
                    continue;
                }
            }
            else
            {
                int reference = ~current;
                int last = (reference >> 3) + (reference & 7) + 1;
                for (int k = reference >> 3; k < last; k++)
                    if (prims.Occluded(k, in ray)) return true;
            }
            if (sp == 0) return false;
            current = stack[--sp];
        }
    }
}

/// <summary>Eight floats in a row.</summary>
[InlineArray(WideNode.Width)]
public struct WideFloats
{
    float _element;
}

/// <summary>Eight ints in a row.</summary>
[InlineArray(WideNode.Width)]
public struct WideInts
{
    int _element;
}

/// <summary>
/// One node of a <see cref="WideBvh"/>, 224 bytes: the boxes of up to eight children, coordinate by coordinate (structure of
/// arrays, so one 8-lane load brings one bound of all eight), and a reference per child: ≥ 0 a wide node's index, &lt; 0 a
/// leaf, ~(first · 8 + count − 1) for its primitives first … first + count − 1. An unused slot has an empty box
/// (+∞ … −∞), which no ray enters, and refers to the leaf of primitive 0 alone: were it entered all the same (a NaN
/// direction enters every box), one primitive more is tested, which changes no closest hit (the least (t, k) wins).
/// </summary>
[StructLayout(LayoutKind.Sequential)]
public struct WideNode
{
    public const int Width = 8;

    public WideFloats LoX, HiX, LoY, HiY, LoZ, HiZ;
    public WideInts Child;

    public static WideNode Empty
    {
        get
        {
            var n = new WideNode();
            for (int i = 0; i < Width; i++)
            {
                n.Child[i] = LeafReference(0, 1);
                n.LoX[i] = n.LoY[i] = n.LoZ[i] = float.PositiveInfinity;
                n.HiX[i] = n.HiY[i] = n.HiZ[i] = float.NegativeInfinity;
            }
            return n;
        }
    }

    public static int LeafReference(int first, int count) => ~(first << 3 | (count - 1));

    /// <summary>A child reference that is a leaf: its first primitive and count.</summary>
    public static (int First, int Count) Leaf(int reference) => (~reference >> 3, (~reference & 7) + 1);
}

/// <summary>
/// A ray prepared for the 8-lane slab test: origin and inverse direction in every lane, and per axis the offset (in floats,
/// within <see cref="WideNode"/>) of the bound entered first and of the one left last — chosen by the direction's sign bit,
/// as <see cref="SlabRay"/> does for one box.
/// </summary>
internal readonly struct WideRay
{
    public readonly Vector256<float> Ox, Oy, Oz, Ix, Iy, Iz;
    public readonly float ScalarOx, ScalarOy, ScalarOz, ScalarIx, ScalarIy, ScalarIz;
    public readonly int NearX, FarX, NearY, FarY, NearZ, FarZ;

    public WideRay(in Ray ray)
    {
        var o = ray.Origin;
        var inv = Vector3.One / ray.Direction;
        ScalarOx = o.X; ScalarOy = o.Y; ScalarOz = o.Z;
        ScalarIx = inv.X; ScalarIy = inv.Y; ScalarIz = inv.Z;
        Ox = Vector256.Create(o.X); Oy = Vector256.Create(o.Y); Oz = Vector256.Create(o.Z);
        Ix = Vector256.Create(inv.X); Iy = Vector256.Create(inv.Y); Iz = Vector256.Create(inv.Z);
        const int w = WideNode.Width;
        bool nx = float.IsNegative(ray.Direction.X), ny = float.IsNegative(ray.Direction.Y), nz = float.IsNegative(ray.Direction.Z);
        NearX = nx ? w : 0; FarX = nx ? 0 : w;
        NearY = ny ? 3 * w : 2 * w; FarY = ny ? 2 * w : 3 * w;
        NearZ = nz ? 5 * w : 4 * w; FarZ = nz ? 4 * w : 5 * w;
    }
}

/// <summary>The slab test of one ray against a wide node's eight boxes: the children entered in [0, tMax] (bit i for child i) and
/// the distance at which each is entered.</summary>
internal interface ISlabs8
{
    static abstract uint Hits(in WideRay ray, in WideNode node, float tMax, ref WideFloats entry);
}

/// <summary>
/// All eight boxes in one AVX pass. Per axis, near = (bound entered − o)·(1/d) and far = (bound left − o)·(1/d)·(1 + 2γ₃);
/// entry = max(0, near x, near y, near z) and exit = min(tMax, far x, far y, far z), a NaN slab (0·∞: an origin on a box
/// face with d = 0 on that axis) dropping out as in <see cref="SlabRay"/> (maxps/minps keep their second operand then).
/// </summary>
internal struct Slabs8 : ISlabs8
{
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint Hits(in WideRay r, in WideNode node, float tMax, ref WideFloats entry)
    {
        ref float b = ref Unsafe.As<WideNode, float>(ref Unsafe.AsRef(in node));
        var scale = Vector256.Create(SlabRay.ExitScale);
        var nx = (Vector256.LoadUnsafe(ref b, (nuint)r.NearX) - r.Ox) * r.Ix;
        var ny = (Vector256.LoadUnsafe(ref b, (nuint)r.NearY) - r.Oy) * r.Iy;
        var nz = (Vector256.LoadUnsafe(ref b, (nuint)r.NearZ) - r.Oz) * r.Iz;
        var fx = (Vector256.LoadUnsafe(ref b, (nuint)r.FarX) - r.Ox) * r.Ix * scale;
        var fy = (Vector256.LoadUnsafe(ref b, (nuint)r.FarY) - r.Oy) * r.Iy * scale;
        var fz = (Vector256.LoadUnsafe(ref b, (nuint)r.FarZ) - r.Oz) * r.Iz * scale;
        var e = Avx.Max(nz, Avx.Max(ny, Avx.Max(nx, Vector256<float>.Zero)));
        var x = Avx.Min(fz, Avx.Min(fy, Avx.Min(fx, Vector256.Create(tMax))));
        e.StoreUnsafe(ref entry[0]);
        return Avx.CompareLessThanOrEqual(e, x).ExtractMostSignificantBits();
    }
}

/// <summary>The same test one box at a time in scalar code, with maxps/minps's rule written out: the result is
/// <see cref="Slabs8"/>'s bit for bit (for machines without AVX; checked by the tests on machines with it).</summary>
internal struct Slabs1 : ISlabs8
{
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint Hits(in WideRay r, in WideNode node, float tMax, ref WideFloats entry)
    {
        ref float b = ref Unsafe.As<WideNode, float>(ref Unsafe.AsRef(in node));
        uint mask = 0;
        for (int i = 0; i < WideNode.Width; i++)
        {
            float nx = (Unsafe.Add(ref b, r.NearX + i) - r.ScalarOx) * r.ScalarIx;
            float ny = (Unsafe.Add(ref b, r.NearY + i) - r.ScalarOy) * r.ScalarIy;
            float nz = (Unsafe.Add(ref b, r.NearZ + i) - r.ScalarOz) * r.ScalarIz;
            float fx = (Unsafe.Add(ref b, r.FarX + i) - r.ScalarOx) * r.ScalarIx * SlabRay.ExitScale;
            float fy = (Unsafe.Add(ref b, r.FarY + i) - r.ScalarOy) * r.ScalarIy * SlabRay.ExitScale;
            float fz = (Unsafe.Add(ref b, r.FarZ + i) - r.ScalarOz) * r.ScalarIz * SlabRay.ExitScale;
            float e = Max(nz, Max(ny, Max(nx, 0)));
            float x = Min(fz, Min(fy, Min(fx, tMax)));
            entry[i] = e;
            if (e <= x) mask |= 1u << i;
        }
        return mask;
    }

    /// <summary>maxps: candidate &gt; current ? candidate : current (a NaN candidate leaves current).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float Max(float candidate, float current) => candidate > current ? candidate : current;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float Min(float candidate, float current) => candidate < current ? candidate : current;
}
