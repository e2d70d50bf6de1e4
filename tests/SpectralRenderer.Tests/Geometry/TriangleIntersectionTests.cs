using System.Numerics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Geometry;

public class TriangleIntersectionTests
{
    static readonly Vector3 P0 = new(0, 0, 0), P1 = new(4, 0, 0), P2 = new(0, 2, 0);

    [Theory]
    [InlineData(1, 0.5, 1, 0.25, 0.25)]
    [InlineData(1, 0.5, -1, 0.25, 0.25)]   // from below: no back-face culling
    [InlineData(0.4, 1.2, 3, 0.1, 0.6)]
    public void Hit_distance_and_barycentrics_are_exact(float x, float y, float side, float b1, float b2)
    {
        var ray = new Ray(new Vector3(x, y, 3 * side), new Vector3(0, 0, -side));
        Assert.True(TriangleIntersection.Intersect(ray, P0, P1, P2, out float t, out float u, out float v));
        Assert.Equal(3f, t);
        Assert.Equal(b1, u, 6);
        Assert.Equal(b2, v, 6);
    }

    [Fact]
    public void Misses_outside_behind_and_beyond_tmax()
    {
        Assert.False(TriangleIntersection.Intersect(new Ray(new Vector3(3, 1.5f, 1), -Vector3.UnitZ), P0, P1, P2, out _, out _, out _));
        Assert.False(TriangleIntersection.Intersect(new Ray(new Vector3(1, 0.5f, 1), Vector3.UnitZ), P0, P1, P2, out _, out _, out _));
        Assert.False(
            TriangleIntersection.Intersect(new Ray(new Vector3(1, 0.5f, 1), -Vector3.UnitZ, 0.999f), P0, P1, P2, out _, out _, out _));
        // Parallel to the plane.
        Assert.False(TriangleIntersection.Intersect(new Ray(new Vector3(-1, 0.5f, 0), Vector3.UnitX), P0, P1, P2, out _, out _, out _));
    }

    [Fact]
    public void Watertight_no_ray_slips_between_the_triangles_of_a_fan()
    {
        // A fan of 7 thin triangles around a shared vertex; rays aimed exactly at the shared edges and the centre
        // (in float) must hit at least one triangle — the property of the Woop–Benthin–Wald test.
        var centre = new Vector3(0.1f, 0.3f, 0.7f);
        // nearly flat: no fold-over silhouettes
        var ring = Enumerable.Range(0, 7).Select(i => centre + new Vector3(MathF.Cos(i * 0.9f), MathF.Sin(i * 0.9f), 0.05f * MathF.Sin(i)))
            .ToArray();
        var rng = new Random(3);
        int misses = 0;
        for (int n = 0; n < 20000; n++)
        {
            int e = rng.Next(7);
            float s = n % 10 == 0 ? 0 : rng.NextSingle();
            var target = centre + s * (ring[e] - centre);
            var origin = new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, 5);
            var ray = new Ray(origin, target - origin);
            bool any = false;
            for (int k = 0; k < 6; k++)
                any |= TriangleIntersection.Intersect(ray, centre, ring[k], ring[k + 1], out _, out _, out _);
            if (!any && s > 0 && e is >= 1 and <= 5) misses++; // interior edges (the open fan's centre and outer edges are its boundary)
        }
        Assert.Equal(0, misses);
    }
}
