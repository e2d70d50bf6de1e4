using System.Numerics;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics.X86;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>
/// The 8-wide BVH of single rays against an independent reference: every triangle tested with the watertight test on its
/// own, the closest hit taken as the least (t, k) — written here, not through the hierarchy or TriangleSet's tie rule — so
/// the traversal must give the same triangle and the same bits whatever order it visits the leaves in.
/// </summary>
public class WideBvhTests(ITestOutputHelper output)
{
    /// <summary>The reference: the least (t, k) over all triangles with 0 &lt; t &lt; TMax, and its barycentrics.</summary>
    static (bool Hit, float T, int K, float U, float V) Reference(TriangleSet set, Ray ray)
    {
        var sheared = new ShearedRay(ray);
        (bool, float, int, float, float) best = (false, ray.TMax, -1, 0, 0);
        for (int k = 0; k < set.Count; k++)
        {
            var (p0, p1, p2) = set.Corners(k);
            if (!TriangleIntersection.Distance(sheared, p0, p1, p2, out float t, out float u, out float v) || !(t < ray.TMax)) continue;
            if (!best.Item1 || t < best.Item2 || t == best.Item2 && k < best.Item3) best = (true, t, k, u, v);
        }
        return best;
    }

    /// <summary>
    /// A random soup, with degenerate triangles (a repeated corner, three corners on a line), triangles in axis planes,
    /// exact duplicates (ties at every hit) and a grid of shared edges and corners (ties along them).
    /// </summary>
    internal static TriangleMesh Awkward(int seed)
    {
        var rng = new Random(seed);
        var p = new List<Vector3>();
        var soup = BvhTests.Soup(1_500, seed);
        for (int i = 0; i < soup.TriangleCount; i++)
        {
            var (a, b, c) = soup.Triangle(i);
            switch (i % 10)
            {
                case 0: c = b; break;                                     // a repeated corner: zero area
                case 1: c = a + 2 * (b - a); break;                       // on a line
                case 2: a.X = b.X = c.X = MathF.Round(a.X * 8) / 8; break; // in the plane x = const, on the grid of rays below
                case 3: a.Y = b.Y = c.Y = MathF.Round(a.Y * 8) / 8; break;
                case 4: p.AddRange([a, b, c]); break;                      // duplicated (added twice)
            }
            p.AddRange([a, b, c]);
        }
        // A 16 × 16 grid of squares in z = 0.5, each split into two triangles: shared edges and corners.
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 16; x++)
            {
                Vector3 q(int i, int j) => new(i / 16f, j / 16f, 0.5f);
                p.AddRange([q(x, y), q(x + 1, y), q(x + 1, y + 1), q(x, y), q(x + 1, y + 1), q(x, y + 1)]);
            }
        return new TriangleMesh([.. p], Enumerable.Range(0, p.Count).ToArray(), source: "awkward");
    }

    /// <summary>Random rays, rays along the axes through the grid's corners and edges (and the axis planes), and −0 directions.</summary>
    static Ray[] AwkwardRays(Bounds3 b, int seed)
    {
        var rays = new List<Ray>(BvhTests.Rays(b, 10_000, seed));
        for (int y = 0; y <= 16; y++)
            for (int x = 0; x <= 16; x++)
            {
                var at = new Vector3(x / 16f, y / 16f, 0.5f);
                rays.Add(new Ray(at + Vector3.UnitZ, -Vector3.UnitZ));
                rays.Add(new Ray(at - Vector3.UnitZ, new Vector3(-0f, -0f, 1)));
                rays.Add(new Ray(at + new Vector3(0.25f, 0, 1), Vector3.Normalize(new Vector3(-0.25f, 0, -1))));
                rays.Add(new Ray(new Vector3(-1, y / 8f, x / 8f), Vector3.UnitX));              // in the planes y, z = k/8
                rays.Add(new Ray(new Vector3(x / 8f, -1, y / 8f), new Vector3(-0f, 1, 0)));
            }
        return [.. rays];
    }

    static (int Different, int Hits, int Ties) CompareWithReference(TriangleSet set, Ray[] rays, bool scalar)
    {
        int different = 0, hits = 0, ties = 0;
        foreach (var r in rays)
        {
            var reference = Reference(set, r);
            var s = set;
            var ray = r;
            var h = new Hit();
            bool hit = scalar ? set.Wide.Intersect<TriangleSet, Slabs1>(ref s, ref ray, ref h) : set.Intersect(ref ray, ref h);
            if (hit != reference.Hit) { different++; continue; }
            if (!hit) { if (BitConverter.SingleToInt32Bits(ray.TMax) != BitConverter.SingleToInt32Bits(r.TMax)) different++; }
            else
            {
                hits++;
                if (h.Primitive != reference.K || !Same(ray.TMax, reference.T) || !Same(h.U, reference.U) || !Same(h.V, reference.V))
                    different++;
                // Another triangle at the same distance: where the order of the visit would have decided.
                for (int k = 0; k < set.Count; k++)
                {
                    if (k == reference.K) continue;
                    var (p0, p1, p2) = set.Corners(k);
                    if (TriangleIntersection.Distance(new ShearedRay(r), p0, p1, p2, out float t, out _, out _) && t == reference.T)
                    {
                        ties++;
                        break;
                    }
                }
            }
            // Any hit: up to the closest hit (exclusive, so a tie with it does not count), to half of it, and unbounded.
            foreach (float tMax in new[] { r.TMax, reference.Hit ? reference.T : r.TMax, reference.Hit ? 0.5f * reference.T : r.TMax })
            {
                var q = new Ray(r.Origin, r.Direction, tMax);
                bool expected = Reference(set, q).Hit;
                bool blocked = scalar ? set.Wide.Occluded<TriangleSet, Slabs1>(ref s, q) : set.Occluded(q);
                if (blocked != expected) different++;
            }
        }
        return (different, hits, ties);
    }

    static bool Same(float a, float b) => BitConverter.SingleToInt32Bits(a) == BitConverter.SingleToInt32Bits(b);

    [Fact]
    public void Closest_and_any_hits_equal_the_least_distance_then_index_over_all_triangles()
    {
        foreach (int seed in new[] { 1, 2 })
        {
            var set = TriangleSet.Build([Awkward(seed)]);
            var rays = AwkwardRays(set.Bvh.Bounds, seed + 10);
            var (different, hits, ties) = CompareWithReference(set, rays, scalar: false);
            output.WriteLine($"seed {seed}: {set.Count} triangles, {set.Wide.NodeCount} wide nodes (depth {set.Wide.Depth}), "
                             + $"{rays.Length} rays, {hits} hits, {ties} ties at the hit, {different} different");
            Assert.Equal(0, different);
            Assert.InRange(hits, rays.Length / 5, rays.Length - 1);
            Assert.True(ties > 500, $"only {ties} ties: the case the tie rule is for is not exercised");
        }
    }

    [Fact]
    public void The_scalar_slab_test_gives_the_same_hits_as_the_vector_one()
    {
        var set = TriangleSet.Build([Awkward(3)]);
        var rays = AwkwardRays(set.Bvh.Bounds, 13);
        // The scalar path against the reference, on every machine (CI also runs the suite with AVX off).
        Assert.Equal(0, CompareWithReference(set, rays, scalar: true).Different);
        if (!Avx.IsSupported) return;
        // Node by node, bit for bit: the mask and the entry distances of all eight lanes, NaN slabs (an origin on a box
        // face with a zero direction component) and empty slots included.
        int nodes = 0;
        foreach (var r in rays)
        {
            var slabs = new WideRay(r);
            foreach (ref readonly var node in set.Wide.Nodes)
            {
                WideFloats a = default, b = default;
                uint m8 = Slabs8.Hits(slabs, node, r.TMax, ref a);
                uint m1 = Slabs1.Hits(slabs, node, r.TMax, ref b);
                Assert.Equal(m8, m1);
                for (int i = 0; i < WideNode.Width; i++) Assert.True(Same(a[i], b[i]), $"entry {a[i]} against {b[i]}");
                if (++nodes > 2_000_000) return;
            }
        }
    }

    [Fact]
    public void The_wide_nodes_do_not_depend_on_the_thread_count()
    {
        var mesh = BvhTests.Soup(60_000, 5);
        var one = TriangleSet.Build([mesh], parallel: false).Wide;
        var many = TriangleSet.Build([mesh]).Wide;
        Assert.True(MemoryMarshal.AsBytes(one.Nodes).SequenceEqual(MemoryMarshal.AsBytes(many.Nodes)));
    }

    [Fact]
    public void Every_primitive_is_in_one_wide_leaf_inside_every_box_above_it()
    {
        var set = TriangleSet.Build([Awkward(4)]);
        var seen = new int[set.Count];
        var nodes = set.Wide.Nodes.ToArray();
        int maxDepth = 0;
        Walk(0, Bounds3.Empty, isRoot: true, 1);
        Assert.All(seen, n => Assert.Equal(1, n));
        Assert.Equal(set.Wide.Depth, maxDepth);

        void Walk(int index, Bounds3 parent, bool isRoot, int depth)
        {
            maxDepth = Math.Max(maxDepth, depth);
            var node = nodes[index];
            for (int i = 0; i < WideNode.Width; i++)
            {
                var box = new Bounds3(new(node.LoX[i], node.LoY[i], node.LoZ[i]), new(node.HiX[i], node.HiY[i], node.HiZ[i]));
                if (box.IsEmpty) continue;
                if (!isRoot) Assert.True(Contains(parent, box));
                int c = node.Child[i];
                if (c >= 0) { Assert.True(c > index); Walk(c, box, false, depth + 1); continue; }
                var (first, count) = WideNode.Leaf(c);
                Assert.InRange(count, 1, 4);
                for (int k = first; k < first + count; k++)
                {
                    seen[k]++;
                    var (p0, p1, p2) = set.Corners(k);
                    Assert.True(Contains(box, new Bounds3(Vector3.Min(p0, Vector3.Min(p1, p2)), Vector3.Max(p0, Vector3.Max(p1, p2)))));
                }
            }
        }

        static bool Contains(Bounds3 outer, Bounds3 inner) =>
            Vector3.Min(outer.Min, inner.Min) == outer.Min && Vector3.Max(outer.Max, inner.Max) == outer.Max;
    }

    [Fact]
    public void An_empty_wide_hierarchy_and_a_single_triangle_are_handled()
    {
        var one = TriangleSet.Build([new TriangleMesh([new(0, 0, 0), new(1, 0, 0), new(0, 1, 0)], [0, 1, 2])]);
        Assert.Equal(1, one.Wide.NodeCount);
        var ray = new Ray(new Vector3(0.25f, 0.25f, 1), -Vector3.UnitZ);
        var h = new Hit();
        Assert.True(one.Intersect(ref ray, ref h));
        Assert.Equal(1f, ray.TMax);
        Assert.True(one.Occluded(new Ray(new Vector3(0.25f, 0.25f, 1), -Vector3.UnitZ, 1.5f)));
        Assert.False(one.Occluded(new Ray(new Vector3(0.25f, 0.25f, 1), -Vector3.UnitZ, 1f)));
        var empty = WideBvh.Collapse(Bvh.Build([], 4));
        Assert.Equal(0, empty.NodeCount);
    }
}
