using System.Diagnostics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Tests.Geometry;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>The scanned meshes of the paper's scenes (skipped, with the reason, when SPECTRAL_MODELS does not lead to them).</summary>
[Trait("Category", "Slow")]
public class ModelMeshTests(ITestOutputHelper output)
{
    [SkippableFact]
    public void The_bunny_loads_with_its_69451_triangles()
    {
        var path = ModelFiles.Require("stanford-bunny.obj");
        var sw = Stopwatch.StartNew();
        var m = ObjReader.Read(path);
        output.WriteLine($"stanford-bunny.obj: {sw.Elapsed.TotalMilliseconds:F0} ms (this build, first call)");
        Assert.Equal(69_451, m.TriangleCount);
        Assert.Equal(0, m.DegenerateCount);
        Assert.Equal(35_947, m.Positions.Length);
        Assert.NotNull(m.Normals);
    }

    [SkippableFact]
    public void Igea_strips_give_268686_triangles()
    {
        // 134,345 vertices in one strip list with −1 restarts; every strip triangle has three distinct corners
        // of non-zero area, so none is dropped.
        var path = ModelFiles.Require("igea.ply");
        var sw = Stopwatch.StartNew();
        var m = PlyReader.Read(path);
        output.WriteLine($"igea.ply: {sw.Elapsed.TotalMilliseconds:F0} ms (this build, first call); {m.TriangleCount} triangles, "
            + $"{m.DegenerateCount} degenerate");
        Assert.Equal(134_345, m.Positions.Length);
        Assert.Equal(268_686, m.TriangleCount);
        Assert.Equal(0, m.DegenerateCount);
    }

    [SkippableFact]
    public void Bunny_closest_hits_and_occlusion_equal_brute_force()
    {
        var m = ObjReader.Read(ModelFiles.Require("stanford-bunny.obj"));
        var set = TriangleSet.Build([m]);
        const int rays = 1_000; // × 69,451 brute-force tests; 100k rays were checked in Release
        var (closest, occluded, hits) = BruteForce.Compare(set, BvhTests.Rays(set.Bvh.Bounds, rays, 5));
        output.WriteLine($"bunny: {set.Bvh.NodeCount} nodes, depth {set.Bvh.MaxDepth}; {rays} rays, {hits} hit");
        Assert.Equal(0, closest);
        Assert.Equal(0, occluded);
        Assert.InRange(hits, rays / 4, rays - 1);
    }
}
