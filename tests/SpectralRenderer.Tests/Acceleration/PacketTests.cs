using System.Numerics;
using System.Runtime.Intrinsics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Tests.Geometry;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>
/// Ray packets against single rays: every lane's answer (hit or not, distance, primitive, barycentrics, and
/// occlusion) must be the single ray's, bit for bit, at every SIMD width the kernels are compiled for; the
/// single-ray traversal is itself held to brute force (BvhTests), and so are the packets here.
/// </summary>
public class PacketTests(ITestOutputHelper output)
{
    public static TheoryData<int> Widths => new() { 16, 8, 4, 1 };

    static uint Intersect(int width, TriangleSet set, ref RayPacket p) => width switch
    {
        16 => set.Bvh.Intersect<Lanes512, TriangleSet>(ref set, ref p),
        8 => set.Bvh.Intersect<Lanes256, TriangleSet>(ref set, ref p),
        4 => set.Bvh.Intersect<Lanes128, TriangleSet>(ref set, ref p),
        _ => set.Bvh.Intersect<Lanes1, TriangleSet>(ref set, ref p),
    };

    static uint Occluded(int width, TriangleSet set, ref RayPacket p) => width switch
    {
        16 => set.Bvh.Occluded<Lanes512, TriangleSet>(ref set, ref p),
        8 => set.Bvh.Occluded<Lanes256, TriangleSet>(ref set, ref p),
        4 => set.Bvh.Occluded<Lanes128, TriangleSet>(ref set, ref p),
        _ => set.Bvh.Occluded<Lanes1, TriangleSet>(ref set, ref p),
    };

    static void SkipUnsupported(int width)
    {
        Skip.If(width == 16 && !Vector512.IsHardwareAccelerated, "no AVX-512 here");
        Skip.If(width == 8 && !Vector256.IsHardwareAccelerated, "no 256-bit SIMD here");
        Skip.If(width == 4 && !Vector128.IsHardwareAccelerated, "no 128-bit SIMD here");
    }

    /// <summary>What the comparison found: lanes compared, lanes that hit, disagreements, ties (a different primitive at the same
    /// distance).</summary>
    record struct Tally(int Lanes, int Hits, int Different, int Ties, int Occlusion);

    /// <summary>
    /// Traces the rays in packets of 16 (lanes left out in a pattern that changes from packet to packet) and
    /// compares each lane with the single ray: closest hit bit for bit, and occlusion up to half the hit distance
    /// and unbounded. With <paramref name="bruteForce"/> each lane is also compared with every triangle tested in order.
    /// </summary>
    static Tally Compare(int width, TriangleSet set, Ray[] rays, bool bruteForce)
    {
        var t = new Tally();
        var packet = new RayPacket();
        for (int first = 0, n = 0; first < rays.Length; first += RayPacket.Size, n++)
        {
            packet.Clear();
            uint skip = n % 3 == 0 ? 0u : (uint)(n * 0x9E3779B1u) & 0x1111u;   // some packets with holes
            for (int lane = 0; lane < RayPacket.Size && first + lane < rays.Length; lane++)
                if ((skip >> lane & 1) == 0) packet.Set(lane, rays[first + lane]);
            uint active = packet.Active;
            var shadow = packet;          // the same rays for the occlusion queries, prepared alike
            uint hits = Intersect(width, set, ref packet);
            Assert.Equal(0u, hits & ~active);
            var half = shadow;
            for (uint m = active; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                var s = set;
                var ray = rays[first + lane];
                var h = new Hit();
                bool hit = set.Bvh.Intersect(ref s, ref ray, ref h);
                t.Lanes++;
                if (hit) t.Hits++;
                bool laneHit = (hits >> lane & 1) != 0;
                if (laneHit != hit) { t.Different++; continue; }
                if (hit)
                {
                    bool sameBits = BitConverter.SingleToInt32Bits(packet.TMax[lane]) == BitConverter.SingleToInt32Bits(ray.TMax)
                                    && BitConverter.SingleToInt32Bits(packet.U[lane]) == BitConverter.SingleToInt32Bits(h.U)
                                    && BitConverter.SingleToInt32Bits(packet.V[lane]) == BitConverter.SingleToInt32Bits(h.V);
                    if (packet.Primitive[lane] != h.Primitive && packet.TMax[lane] == ray.TMax) t.Ties++;
                    else if (!sameBits || packet.Primitive[lane] != h.Primitive) t.Different++;
                    half.TMax[lane] = 0.5f * ray.TMax;
                }
                else if (BitConverter.SingleToInt32Bits(packet.TMax[lane]) != BitConverter.SingleToInt32Bits(rays[first + lane].TMax))
                    t.Different++;
                if (bruteForce)
                {
                    var b = rays[first + lane]; var hb = new Hit();
                    bool fb = BruteForce.Intersect(ref s, s.Count, ref b, ref hb);
                    if (fb != laneHit || fb && packet.TMax[lane] != b.TMax) t.Different++;
                }
            }
            // Occlusion: unbounded, and up to half the hit distance.
            uint blocked = Occluded(width, set, ref shadow);
            uint blockedHalf = Occluded(width, set, ref half);
            for (uint m = active; m != 0; m &= m - 1)
            {
                int lane = BitOperations.TrailingZeroCount(m);
                var s = set;
                if (((blocked >> lane) & 1) != (set.Bvh.Occluded(ref s, shadow.Ray(lane)) ? 1u : 0u)) t.Occlusion++;
                if (((blockedHalf >> lane) & 1) != (set.Bvh.Occluded(ref s, half.Ray(lane)) ? 1u : 0u)) t.Occlusion++;
            }
            Assert.Equal(0u, (blocked | blockedHalf) & ~active);
        }
        return t;
    }

    /// <summary>Camera rays in 4 × 4 pixel blocks from a pinhole at <paramref name="eye"/> looking at the box: the coherent case.</summary>
    static Ray[] CameraBlocks(Bounds3 b, Vector3 eye, int size)
    {
        var forward = Vector3.Normalize(b.Centre - eye);
        var right = Vector3.Normalize(Vector3.Cross(forward, Vector3.UnitY));
        var up = Vector3.Cross(right, forward);
        float half = 0.6f * b.Extent.Length() / (b.Centre - eye).Length();
        var rays = new List<Ray>();
        for (int by = 0; by < size; by += 4)
            for (int bx = 0; bx < size; bx += 4)
                for (int y = by; y < by + 4; y++)
                    for (int x = bx; x < bx + 4; x++)
                    {
                        float sx = (2 * (x + 0.5f) / size - 1) * half, sy = (1 - 2 * (y + 0.5f) / size) * half;
                        rays.Add(new Ray(eye, Vector3.Normalize(forward + sx * right + sy * up)));
                    }
        return [.. rays];
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Packets_of_random_rays_give_each_ray_its_single_ray_answer_bit_for_bit(int width)
    {
        SkipUnsupported(width);
        var set = TriangleSet.Build([BvhTests.Soup(2_000, 1)]);
        var rays = BvhTests.Rays(set.Bvh.Bounds, 20_000, 2);
        var t = Compare(width, set, rays, bruteForce: width == PacketLanes.Width);
        output.WriteLine($"width {width}: {t}");
        Assert.Equal(0, t.Different);
        Assert.Equal(0, t.Occlusion);
        Assert.Equal(0, t.Ties);                      // a soup has no shared edges
        Assert.InRange(t.Hits, t.Lanes / 20, t.Lanes - 1);
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Coherent_camera_packets_give_each_ray_its_single_ray_answer_bit_for_bit(int width)
    {
        SkipUnsupported(width);
        var set = TriangleSet.Build([BvhTests.Soup(20_000, 7)]);
        var b = set.Bvh.Bounds;
        var rays = CameraBlocks(b, b.Centre + new Vector3(0.3f, 0.4f, 2f), 128);
        var t = Compare(width, set, rays, bruteForce: false);
        output.WriteLine($"width {width}: {t}");
        Assert.Equal(0, t.Different);
        Assert.Equal(0, t.Occlusion);
        Assert.InRange(t.Hits, t.Lanes / 10, t.Lanes - 1);   // 3,029 of 15,022
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Rays_along_box_faces_and_through_shared_edges_agree_with_single_rays(int width)
    {
        SkipUnsupported(width);
        // As BvhTests: two unit squares in z = 0, rays parallel to the axes on the bounding planes (0 · ∞ slabs),
        // directions with −0 components, and rays through the shared edges, where two triangles tie.
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
        var t = Compare(width, set, [.. rays], bruteForce: true);
        output.WriteLine($"width {width}: {t}");
        Assert.Equal(0, t.Different);
        Assert.Equal(0, t.Ties);
        Assert.Equal(0, t.Occlusion);
        Assert.Equal(t.Lanes, t.Hits);
    }

    [SkippableFact]
    public void Bunny_camera_and_shadow_packets_equal_single_rays_bit_for_bit()
    {
        var mesh = ObjReader.Read(ModelFiles.Require("stanford-bunny.obj"));
        var set = TriangleSet.Build([mesh]);
        var b = set.Bvh.Bounds;
        var rays = CameraBlocks(b, b.Centre + new Vector3(0, 0.3f, 3f) * b.Extent.Length(), 256);
        var t = Compare(PacketLanes.Width, set, rays, bruteForce: false);
        output.WriteLine($"bunny, width {PacketLanes.Width}: {t}");
        Assert.Equal(0, t.Different);
        Assert.Equal(0, t.Occlusion);
        Assert.Equal(0, t.Ties);     // a different triangle at exactly the same distance (an edge): the smaller index wins in both
        Assert.InRange(t.Hits, t.Lanes / 10, t.Lanes - 1);
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Prepared_lanes_hold_the_single_rays_shear_and_inverse_bit_for_bit(int width)
    {
        SkipUnsupported(width);
        // Directions with ties between |d| components (the dominant axis is a choice), zeros, −0 and negatives.
        float[] values = [1, -1, 0, -0f, 0.5f, -0.5f, 2, 1e-30f];
        var dirs = new List<Vector3>();
        foreach (var x in values) foreach (var y in values) foreach (var z in values) dirs.Add(new Vector3(x, y, z));
        static int Bits(float f) => BitConverter.SingleToInt32Bits(f);
        for (int first = 0; first < dirs.Count; first += RayPacket.Size)
        {
            var p = new RayPacket();
            for (int lane = 0; lane < RayPacket.Size && first + lane < dirs.Count; lane++)
                p.Set(lane, new Ray(Vector3.One, dirs[first + lane]));
            switch (width)
            {
                case 16: p.Prepare<Lanes512>(); break;
                case 8: p.Prepare<Lanes256>(); break;
                case 4: p.Prepare<Lanes128>(); break;
                default: p.Prepare<Lanes1>(); break;
            }
            for (int lane = 0; lane < RayPacket.Size && first + lane < dirs.Count; lane++)
            {
                var d = dirs[first + lane];
                var s = new ShearedRay(new Ray(Vector3.One, d));
                float[] expected =
                    [s.RowX.X, s.RowX.Y, s.RowX.Z, s.RowY.X, s.RowY.Y, s.RowY.Z, s.RowZ.X, s.RowZ.Y, s.RowZ.Z, 1 / d.X, 1 / d.Y, 1 / d.Z];
                float[] actual = [p.RowXx[lane], p.RowXy[lane], p.RowXz[lane], p.RowYx[lane], p.RowYy[lane], p.RowYz[lane], p.RowZx[lane],
                    p.RowZy[lane], p.RowZz[lane],
                                  p.InverseX[lane], p.InverseY[lane], p.InverseZ[lane]];
                Assert.True(expected.Select(Bits).SequenceEqual(actual.Select(Bits)),
                    $"direction {d}: [{string.Join(", ", expected)}] vs [{string.Join(", ", actual)}]");
                Assert.Equal(d.X < 0 || Bits(d.X) < 0, Bits(p.NegativeX[lane]) == -1);
                Assert.Equal(Bits(d.Z) < 0, Bits(p.NegativeZ[lane]) == -1);
            }
        }
    }
}
