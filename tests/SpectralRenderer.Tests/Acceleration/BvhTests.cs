using System.Numerics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

public class BvhTests(ITestOutputHelper output)
{
    /// <summary>Random triangles of size ~0.01–0.05 in the unit cube (a "soup": overlapping, any orientation).</summary>
    internal static TriangleMesh Soup(int count, int seed)
    {
        var rng = new Random(seed);
        var p = new Vector3[3 * count];
        for (int i = 0; i < count; i++)
        {
            var c = new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle());
            float size = 0.01f + 0.04f * rng.NextSingle();
            for (int j = 0; j < 3; j++)
                p[3 * i + j] = c + size * new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f);
        }
        return new TriangleMesh(p, Enumerable.Range(0, 3 * count).ToArray(), source: "soup");
    }

    /// <summary>Rays from random points around the bounds towards random points inside; every 10th is axis-aligned (zero direction
    /// components).</summary>
    internal static Ray[] Rays(Bounds3 b, int count, int seed)
    {
        var rng = new Random(seed);
        var rays = new Ray[count];
        var e = b.Extent;
        for (int i = 0; i < count; i++)
        {
            var inside = b.Min + new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle()) * e;
            if (i % 10 == 0)
            {
                int axis = rng.Next(3);
                var d = axis == 0 ? Vector3.UnitX : axis == 1 ? Vector3.UnitY : Vector3.UnitZ;
                if (rng.Next(2) == 0) d = -d;
                rays[i] = new Ray(inside - 2 * e.Length() * d, d);
            }
            else
            {
                var o = b.Centre
                    + (0.5f + rng.NextSingle()) * e.Length() * Vector3.Normalize(
                        new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
                if (i % 10 == 1) o = inside; // some rays start inside the geometry
                rays[i] = new Ray(o, Vector3.Normalize(b.Min + new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle()) * e - o));
            }
        }
        return rays;
    }

    [Fact]
    public void Each_triangle_of_several_meshes_maps_back_to_its_mesh_and_index()
    {
        // Three meshes, the middle one with no triangles (all degenerate): positions k in BVH order lead back to
        // (mesh, triangle) and hold exactly that triangle's corners.
        var a = Soup(700, 3);
        var empty = new TriangleMesh([Vector3.Zero, Vector3.UnitX], [0, 0, 1], source: "empty");
        var c = Soup(500, 4);
        var meshes = new[] { a, empty, c };
        var set = TriangleSet.Build(meshes);
        Assert.Equal(0, empty.TriangleCount);
        Assert.Equal(1200, set.Count);
        var seen = new HashSet<(int, int)>();
        for (int k = 0; k < set.Count; k++)
        {
            int m = set.MeshOf[k], t = set.TriangleOf[k];
            Assert.NotEqual(1, m);
            Assert.InRange(t, 0, meshes[m].TriangleCount - 1);
            Assert.Equal(meshes[m].Triangle(t), set.Corners(k));
            Assert.True(seen.Add((m, t)));
        }
    }

    /// <summary>100k rays against brute force: rays × triangles tests, so the soup is kept to 2,000 triangles.</summary>
    const int SoupRays = 100_000;

    [Fact]
    [Trait("Category", "Slow")]
    public void Closest_hits_and_occlusion_equal_brute_force_on_100k_random_rays()
    {
        var set = TriangleSet.Build([Soup(2_000, 1)]);
        var (closest, occluded, hits) = BruteForce.Compare(set, Rays(set.Bvh.Bounds, SoupRays, 2));
        output.WriteLine($"soup: 2,000 triangles, {set.Bvh.NodeCount} nodes, depth {set.Bvh.MaxDepth}; {SoupRays} rays, {hits} hit");
        Assert.Equal(0, closest);
        Assert.Equal(0, occluded);
        Assert.InRange(hits, SoupRays / 20, SoupRays - 1); // the comparison is not vacuous (12,529 of 100k hit)
    }

    [Fact]
    public void Leaves_hold_at_most_the_leaf_size_and_cover_every_primitive_once()
    {
        var soup = Soup(5000, 3);
        var bounds = new Bounds3[soup.TriangleCount];
        for (int t = 0; t < bounds.Length; t++)
        {
            var (a, b, c) = soup.Triangle(t);
            bounds[t] = new Bounds3(a, a);
            bounds[t].Include(b); bounds[t].Include(c);
        }
        foreach (int leafSize in new[] { 1, 4, 8 })
        {
            var bvh = Bvh.Build(bounds, leafSize);
            var seen = new int[bounds.Length];
            foreach (var n in bvh.Nodes.ToArray().Where(n => n.IsLeaf))
            {
                Assert.InRange(n.Count, 1, leafSize);
                for (int k = n.Offset; k < n.Offset + n.Count; k++)
                {
                    seen[k]++;
                    var b = bounds[bvh.PrimitiveOrder[k]];
                    Assert.True(Vector3.Min(b.Min, n.Min) == n.Min && Vector3.Max(b.Max, n.Max) == n.Max,
                        "leaf bounds contain their primitives");
                }
            }
            Assert.All(seen, s => Assert.Equal(1, s));
            Assert.Equal(Enumerable.Range(0, bounds.Length), bvh.PrimitiveOrder.Order());
        }
    }

    /// <summary>
    /// The node array is a depth-first tree with no gaps: every node is reached exactly once, each interior node's
    /// first child follows it directly and its second child follows the first child's subtree; every primitive is in
    /// exactly one leaf, leaves hold consecutive primitives in order, each node's box holds its children's, and there
    /// are at most 2n − 1 nodes. Soups, identical boxes (the median path), flat boxes and a single primitive, for several
    /// leaf sizes.
    /// </summary>
    [Fact]
    public void The_nodes_are_a_gapless_depth_first_tree()
    {
        var soup = Soup(3_000, 9);
        var cases = new List<Bounds3[]>
        {
            Enumerable.Range(0, soup.TriangleCount)
                .Select(t => { var (a, b, c) = soup.Triangle(t); var x = new Bounds3(a, a); x.Include(b); x.Include(c); return x; })
                .ToArray(),
            Enumerable.Repeat(new Bounds3(new Vector3(1, 2, 3), new Vector3(2, 3, 4)), 500).ToArray(),
            Enumerable.Range(0, 700).Select(i => new Bounds3(new Vector3(i % 37, i / 37, 0), new Vector3(i % 37 + 0.5f, i / 37 + 0.5f, 0)))
                .ToArray(),
            new[] { new Bounds3(Vector3.Zero, Vector3.One) },
        };
        foreach (var bounds in cases)
            foreach (int leafSize in new[] { 1, 2, 4 })
            {
                var bvh = Bvh.Build(bounds, leafSize);
                var nodes = bvh.Nodes.ToArray();
                Assert.InRange(nodes.Length, 1, 2 * bounds.Length - 1);
                var reached = new int[nodes.Length];
                var seen = new int[bounds.Length];
                // Returns (primitives, nodes) of the subtree at `at`; its primitives are [first, first + primitives).
                (int Primitives, int Nodes) Walk(int at, int first)
                {
                    reached[at]++;
                    var n = nodes[at];
                    if (n.IsLeaf)
                    {
                        Assert.Equal(first, n.Offset);
                        for (int k = n.Offset; k < n.Offset + n.Count; k++) seen[k]++;
                        return (n.Count, 1);
                    }
                    var left = Walk(at + 1, first);
                    Assert.Equal(at + 1 + left.Nodes, n.Offset);   // the second child right after the first child's subtree
                    var right = Walk(n.Offset, first + left.Primitives);
                    foreach (var c in new[] { nodes[at + 1], nodes[n.Offset] })
                        Assert.True(Vector3.Min(c.Min, n.Min) == n.Min && Vector3.Max(c.Max, n.Max) == n.Max,
                            "a node's box holds its children's");
                    return (left.Primitives + right.Primitives, 1 + left.Nodes + right.Nodes);
                }
                var root = Walk(0, 0);
                Assert.Equal(bounds.Length, root.Primitives);
                Assert.Equal(nodes.Length, root.Nodes);
                Assert.All(reached, r => Assert.Equal(1, r));
                Assert.All(seen, s => Assert.Equal(1, s));
            }
    }

    [Fact]
    public void The_node_array_does_not_depend_on_parallelism()
    {
        // Large enough that subtrees are built on several threads.
        var mesh = Soup(100_000, 4);
        var one = TriangleSet.Build([mesh], parallel: false).Bvh;
        var many = TriangleSet.Build([mesh]).Bvh;
        var again = TriangleSet.Build([mesh]).Bvh;
        output.WriteLine($"{one.NodeCount} nodes, depth {one.MaxDepth}");
        Assert.True(one.Nodes.SequenceEqual(many.Nodes));
        Assert.True(many.Nodes.SequenceEqual(again.Nodes));
        Assert.Equal(one.PrimitiveOrder, many.PrimitiveOrder);
        Assert.Equal(32, System.Runtime.CompilerServices.Unsafe.SizeOf<BvhNode>());
    }

    [Fact]
    public void Rays_with_zero_direction_components_along_box_faces_are_not_lost()
    {
        // Two unit squares side by side in z = 0 (4 triangles); rays parallel to the axes with origins exactly on
        // the bounding planes x = 0, x = 2, y = 0, y = 1 (0 · ∞ in a naive slab test) must agree with brute force.
        var m = new TriangleMesh([new(0, 0, 0), new(1, 0, 0), new(1, 1, 0), new(0, 1, 0), new(2, 0, 0), new(2, 1, 0)],
            [0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2]);
        var set = TriangleSet.Build([m], maxLeafSize: 1);
        var rays = new List<Ray>();
        foreach (float x in new[] { 0f, 0.5f, 1f, 2f })
            foreach (float y in new[] { 0f, 0.5f, 1f })
            {
                rays.Add(new Ray(new Vector3(x, y, 1), -Vector3.UnitZ));
                rays.Add(new Ray(new Vector3(x, y, -1), new Vector3(0, 0, 1)));
                rays.Add(new Ray(new Vector3(x, y, -1), new Vector3(-0f, -0f, 1)));
            }
        var (closest, occluded, hits) = BruteForce.Compare(set, [.. rays]);
        Assert.Equal(0, closest);
        Assert.Equal(0, occluded);
        Assert.Equal(rays.Count, hits); // every one of them is on the squares, edges included
    }

    [Fact]
    public void An_empty_hierarchy_hits_nothing()
    {
        var bvh = Bvh.Build([]);
        var prims = new TriangleSetStub();
        var ray = new Ray(Vector3.Zero, Vector3.UnitX);
        var hit = new Hit();
        Assert.Equal(0, bvh.NodeCount);
        Assert.False(bvh.Intersect(ref prims, ref ray, ref hit));
        Assert.False(bvh.Occluded(ref prims, ray));
    }

    struct TriangleSetStub : IPrimitiveIntersector
    {
        public void Prepare(in Ray ray) { }
        public bool Intersect(int k, ref Ray ray, ref Hit hit) => throw new InvalidOperationException();
        public bool Occluded(int k, in Ray ray) => throw new InvalidOperationException();
    }
}
