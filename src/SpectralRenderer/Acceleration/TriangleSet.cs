using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// The triangles of one or more meshes, copied into BVH order (three corners per triangle, contiguous) so a
/// leaf's triangles sit together in memory, and tested with <see cref="TriangleIntersection"/>.
/// Single rays (<see cref="Intersect(ref Ray, ref Hit)"/>, <see cref="Occluded(in Ray)"/>) walk the 8-wide <see cref="Wide"/>
/// tree, ray packets the binary <see cref="Bvh"/>; both have the same leaves and order.
/// Hit.Primitive is the position k in this order; <see cref="MeshOf"/>[k] and <see cref="TriangleOf"/>[k] lead
/// back to the source mesh and its triangle.
/// </summary>
public partial struct TriangleSet : IPrimitiveIntersector, IPacketIntersector
{
    readonly Vector3[] _corners; // 3 per triangle, in BVH order
    ShearedRay _ray;              // the current query's ray, prepared once (Woop et al. 2013)

    public Bvh Bvh { get; }
    /// <summary><see cref="Bvh"/> collapsed to 8-wide nodes, for single rays.</summary>
    public WideBvh Wide { get; }
    /// <summary>k → index of the mesh (in the list given to <see cref="Build"/>).</summary>
    public int[] MeshOf { get; }
    /// <summary>k → triangle index within its mesh.</summary>
    public int[] TriangleOf { get; }
    public int Count => MeshOf.Length;

    TriangleSet(Vector3[] corners, Bvh bvh, int[] meshOf, int[] triangleOf)
    {
        _corners = corners; Bvh = bvh; Wide = WideBvh.Collapse(bvh); MeshOf = meshOf; TriangleOf = triangleOf; _ray = default;
    }

    /// <summary>Bytes held per triangle: corners, the binary and the wide nodes, the primitive order and the mesh and triangle
    /// indices (not the source meshes).</summary>
    public double BytesPerTriangle => Count == 0 ? 0 :
        (12.0 * _corners.Length + (long)Bvh.NodeCount * Unsafe.SizeOf<BvhNode>() + Wide.Bytes + 4L * Bvh.PrimitiveOrder.Length
         + 8L * Count) / Count;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Prepare(in Ray ray) => _ray = new ShearedRay(ray);

    /// <summary>Builds the BVH over all triangles of the meshes and stores the triangles in its order.</summary>
    /// <param name="maxLeafSize">At most <see cref="WideBvh.MaxLeafSize"/>.</param>
    public static TriangleSet Build(IReadOnlyList<TriangleMesh> meshes, int maxLeafSize = 4, bool parallel = true)
    {
        if (maxLeafSize > WideBvh.MaxLeafSize) throw new ArgumentOutOfRangeException(nameof(maxLeafSize));
        // Triangle i of the concatenation is triangle i − firsts[m] of mesh m, firsts[m] ≤ i < firsts[m + 1].
        var firsts = new int[meshes.Count + 1];
        for (int m = 0; m < meshes.Count; m++) firsts[m + 1] = firsts[m] + meshes[m].TriangleCount;
        int total = firsts[^1];
        // The boxes go straight to the builder, which lets them go once the tree is built (no local here keeps them).
        var bvh = Bvh.Build(BoundTriangles(meshes, firsts), maxLeafSize, parallel);
        var corners = GC.AllocateUninitializedArray<Vector3>(3 * total);
        var orderedMesh = GC.AllocateUninitializedArray<int>(total);
        var orderedTriangle = GC.AllocateUninitializedArray<int>(total);
        Parallel.For(0, (total + 4095) / 4096, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (chunk) =>
        {
            int k1 = Math.Min(total, (chunk + 1) * 4096);
            for (int k = chunk * 4096; k < k1; k++)
            {
                int original = bvh.PrimitiveOrder[k];
                int m = Array.BinarySearch(firsts, original);
                if (m < 0) m = ~m - 1;
                while (m + 1 < firsts.Length && firsts[m + 1] == original) m++;   // skip empty meshes
                orderedMesh[k] = m;
                orderedTriangle[k] = original - firsts[m];
                var (p0, p1, p2) = meshes[m].Triangle(orderedTriangle[k]);
                corners[3 * k] = p0; corners[3 * k + 1] = p1; corners[3 * k + 2] = p2;
            }
        });
        return new TriangleSet(corners, bvh, orderedMesh, orderedTriangle);
    }

    /// <summary>The box of each triangle of the meshes, in the order of their concatenation.</summary>
    static BvhBuilder.Box[] BoundTriangles(IReadOnlyList<TriangleMesh> meshes, int[] firsts)
    {
        var boxes = GC.AllocateUninitializedArray<BvhBuilder.Box>(firsts[^1]);
        for (int m = 0; m < meshes.Count; m++)
        {
            var mesh = meshes[m];
            int offset = firsts[m];
            Parallel.For(0, (mesh.TriangleCount + 4095) / 4096, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (chunk) =>
            {
                int t1 = Math.Min(mesh.TriangleCount, (chunk + 1) * 4096);
                for (int t = chunk * 4096; t < t1; t++)
                {
                    var (p0, p1, p2) = mesh.Triangle(t);
                    var b = new Bounds3(p0, p0);
                    b.Include(p1); b.Include(p2);
                    boxes[offset + t] = BvhBuilder.Box.Of(b);
                }
            });
        }
        return boxes;
    }

    public (Vector3 P0, Vector3 P1, Vector3 P2) Corners(int k) => (_corners[3 * k], _corners[3 * k + 1], _corners[3 * k + 2]);

    /// <summary>
    /// Closest hit: triangle k wins when it is nearer than the hit so far, or exactly as near and earlier in BVH order
    /// (k &lt; hit.Primitive; a query starts with hit.Primitive = 0 or −1, so no tie is taken before a first hit). So the
    /// closest hit is the least (t, k) whatever order the triangles are met in: the binary and the wide hierarchy, packets
    /// and single rays, and brute force all give the same triangle.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Intersect(int k, ref Ray ray, ref Hit hit)
    {
        ref Vector3 c = ref _corners[3 * k];
        if (!TriangleIntersection.Distance(_ray, c, Unsafe.Add(ref c, 1), Unsafe.Add(ref c, 2), out float t, out float b1, out float b2)
            || !(t < ray.TMax || t == ray.TMax && k < hit.Primitive))
            return false;
        ray.TMax = t;
        hit.Primitive = k; hit.U = b1; hit.V = b2;
        return true;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Occluded(int k, in Ray ray)
    {
        ref Vector3 c = ref _corners[3 * k];
        return TriangleIntersection.Distance(_ray, c, Unsafe.Add(ref c, 1), Unsafe.Add(ref c, 2), out float t, out _, out _)
            && t < ray.TMax;
    }

    /// <summary>The closest hit among all triangles, through the wide BVH.</summary>
    public bool Intersect(ref Ray ray, ref Hit hit)
    {
        var self = this;
        return Wide.Intersect(ref self, ref ray, ref hit);
    }

    /// <summary>Whether any triangle is hit in (0, ray.TMax).</summary>
    public bool Occluded(in Ray ray)
    {
        var self = this;
        return Wide.Occluded(ref self, in ray);
    }
}
