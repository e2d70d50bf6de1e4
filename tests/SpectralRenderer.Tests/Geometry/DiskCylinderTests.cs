using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Geometry;

/// <summary>
/// The registered disk and cylinder (Geometry/Disk.cs, Cylinder.cs) placed by their scene keys, against hits worked out by
/// hand for each ray: the distance, the outward normal and the texture coordinates, grazing rays, rays from inside and
/// misses; their world areas and sampling densities against closed forms (a circle, an ellipse, a tube, an elliptic tube
/// by Ramanujan's perimeter); and each rendered as a plain white diffuser under a uniform sky, whose radiance is ρ·L_sky.
/// </summary>
public class DiskCylinderTests
{
    static AnalyticShape Shape(string objectJson) => SceneText.Load($$"""
        { "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0] },
          "materials": { "white": { "diffuse": 1 } },
          "objects": [ {{objectJson}} ] }
        """).Objects[0].Shape!;

    static void Hits(AnalyticShape shape, Vector3 origin, Vector3 towards, float t, Vector3 normal, Vector2 uv)
    {
        var ray = new Ray(origin, Vector3.Normalize(towards));
        Assert.True(shape.Intersect(ray, 0, out float found, out var n), $"ray from {origin} along {towards} misses");
        Assert.Equal(t, found, 4e-6f * MathF.Max(1, t));
        Assert.True(Vector3.Distance(normal, n) < 1e-6f, $"normal {n}, expected {normal}");
        var coords = TextureCoordinates.OfShape(shape, ray.At(found), out float density);
        Assert.True(Vector2.Distance(uv, coords) < 2e-6f, $"uv {coords}, expected {uv}");
        Assert.True(density > 0);
    }

    static void Misses(AnalyticShape shape, Vector3 origin, Vector3 towards) =>
        Assert.False(shape.Intersect(new Ray(origin, Vector3.Normalize(towards)), 0, out _, out _),
            $"ray from {origin} along {towards} hits");

    // A disk of radius 2 at (1, 2, 3) facing +y, its texture's up +x.
    const string Disk = """
        { "type": "disk", "center": [1, 2, 3], "radius": 2, "normal": [0, 1, 0], "up": [1, 0, 0], "material": "white" }
        """;

    [Fact]
    public void A_disk_is_hit_inside_its_radius_with_its_one_normal_and_planar_texture_coordinates()
    {
        var disk = Shape(Disk);
        // Object axes: z = normal = +y, x = up × normal = +x × +y = +z, y = z × x = +x. So world (dx, dz) from the centre is
        // object (x, y) = (dz, dx)/2, and u = (x + 1)/2, v = (y + 1)/2.
        Hits(disk, new Vector3(1, 7, 3), -Vector3.UnitY, 5, Vector3.UnitY, new Vector2(0.5f, 0.5f));
        Hits(disk, new Vector3(2, 6, 3.5f), -Vector3.UnitY, 4, Vector3.UnitY, new Vector2(0.5f + 0.5f / 4, 0.5f + 1 / 4f));
        // From below: the same normal (one-sided like the quad; the integrators face it themselves).
        Hits(disk, new Vector3(1, -1, 1.2f), Vector3.UnitY, 3, Vector3.UnitY, new Vector2((-0.9f + 1) / 2, 0.5f));
        // Slanted: from (1, 5, 3) towards (2, 2, 3) − hits at distance |(1, −3, 0)| = √10.
        Hits(disk, new Vector3(1, 5, 3), new Vector3(1, -3, 0), MathF.Sqrt(10), Vector3.UnitY, new Vector2(0.5f, 0.75f));
        Misses(disk, new Vector3(1 + 2.01f, 5, 3), -Vector3.UnitY);           // just outside the rim
        Misses(disk, new Vector3(1 + 1.42f, 5, 3 + 1.42f), -Vector3.UnitY);   // outside the circle, inside its square
        Misses(disk, new Vector3(-5, 2, 3), Vector3.UnitX);                  // grazing: in the disk's plane
        Misses(disk, new Vector3(1, 7, 3), Vector3.UnitY);                   // pointing away
        Assert.True(Vector3.Distance(disk.Bounds.Min, new Vector3(-1, 2, 1)) < 1e-6f, $"{disk.Bounds.Min}");
        Assert.True(Vector3.Distance(disk.Bounds.Max, new Vector3(3, 2, 5)) < 1e-6f, $"{disk.Bounds.Max}");
    }

    [Fact]
    public void A_disks_area_and_sampling_density_follow_its_placement()
    {
        var disk = Shape(Disk);
        Assert.Equal(4 * MathF.PI, disk.Area, 1e-5f * 4 * MathF.PI);
        Assert.Equal(1 / (4 * MathF.PI), disk.AreaPdf(Vector3.UnitY), 1e-7f);
        // Stretched ×3 along the world x by its transform: an ellipse of semi-axes 2·3 and 2.
        var ellipse = Shape("""
            { "type": "disk", "radius": 2, "normal": [0, 1, 0], "up": [1, 0, 0], "transform": { "scale": [3, 1, 1] }, "material": "white" }
            """);
        Assert.Equal(12 * MathF.PI, ellipse.Area, 1e-5f * 12 * MathF.PI);
        var rng = new Random(3);
        for (int i = 0; i < 100; i++)
        {
            var x = ellipse.SampleArea(new Vector2(rng.NextSingle(), rng.NextSingle()), out var n, out float pdf);
            Assert.Equal(1 / (12 * MathF.PI), pdf, 1e-7f);
            Assert.Equal(pdf, ellipse.AreaPdf(n), 1e-7f);
            Assert.True(x.X * x.X / 36 + x.Z * x.Z / 4 <= 1 + 1e-5f && MathF.Abs(x.Y) < 1e-6f, $"{x} is off the ellipse");
        }
    }

    // A tube of radius 0.5 from (0, 0, 0) to (0, 2, 0): object z along +y, object x (the seam, u = 0) towards +x, object
    // y = z × x = +y × +x = −z; so a point at angle φ from +x towards −z has u = φ/2π, and v = height/2.
    const string Tube = """{ "type": "cylinder", "p0": [0, 0, 0], "p1": [0, 2, 0], "radius": 0.5, "material": "white" }""";

    [Fact]
    public void A_cylinder_is_an_open_tube_hit_from_outside_and_inside_with_outward_normals()
    {
        var tube = Shape(Tube);
        Hits(tube, new Vector3(3, 1, 0), -Vector3.UnitX, 2.5f, Vector3.UnitX, new Vector2(0, 0.5f));
        Hits(tube, new Vector3(0, 0.5f, 3), -Vector3.UnitZ, 2.5f, Vector3.UnitZ, new Vector2(0.75f, 0.25f));
        Hits(tube, new Vector3(0, 1.5f, -3), Vector3.UnitZ, 2.5f, -Vector3.UnitZ, new Vector2(0.25f, 0.75f));
        // From the axis (inside): the wall at the radius, its normal still outward.
        Hits(tube, new Vector3(0, 1, 0), -Vector3.UnitX, 0.5f, -Vector3.UnitX, new Vector2(0.5f, 0.5f));
        // Through the open top onto the inner wall: from (−1, 3, 0) towards (0.5, 1, 0) the near root (x = −0.5) is at
        // height 2.33, above the tube; the far one is the hit, at distance |(1.5, −2)| = 2.5.
        Hits(tube, new Vector3(-1, 3, 0), new Vector3(1.5f, -2, 0), 2.5f, Vector3.UnitX, new Vector2(0, 0.5f));
        // Grazing the side: 1e-4 inside the radius hits near the tangent point, 1e-4 outside misses.
        var grazing = new Ray(new Vector3(0.4999f, 1, -3), Vector3.UnitZ);
        Assert.True(tube.Intersect(grazing, 0, out float tg, out var ng));
        Assert.Equal(3 - MathF.Sqrt(0.25f - 0.4999f * 0.4999f), tg, 1e-4f);
        Assert.True(ng.X > 0.999f, $"normal {ng}");
        Misses(tube, new Vector3(0.5001f, 1, -3), Vector3.UnitZ);
        Misses(tube, new Vector3(3, 2.1f, 0), -Vector3.UnitX);   // above the top
        Misses(tube, new Vector3(3, -0.1f, 0), -Vector3.UnitX);  // below the bottom
        Misses(tube, new Vector3(0, -1, 0), Vector3.UnitY);      // along the axis through both open ends
        Misses(tube, new Vector3(0.2f, -1, 0.1f), Vector3.UnitY);
        Assert.True(Vector3.Distance(tube.Bounds.Min, new Vector3(-0.5f, 0, -0.5f)) < 1e-6f, $"{tube.Bounds.Min}");
        Assert.True(Vector3.Distance(tube.Bounds.Max, new Vector3(0.5f, 2, 0.5f)) < 1e-6f, $"{tube.Bounds.Max}");
    }

    [Fact]
    public void A_cylinders_area_is_its_circumference_times_its_length_also_elliptic()
    {
        var tube = Shape(Tube);
        Assert.Equal(2 * MathF.PI * 0.5f * 2, tube.Area, 1e-5f * 2 * MathF.PI);
        // Squashed to semi-axes a = 0.5·2, b = 0.5 across its axis: area = Ramanujan's perimeter π(3(a+b) − √((3a+b)(a+3b))) × 2.
        var elliptic = Shape("""
            { "type": "cylinder", "p1": [0, 2, 0], "radius": 0.5, "transform": { "scale": [2, 1, 1] }, "material": "white" }
            """);
        double a = 1, b = 0.5, perimeter = Math.PI * (3 * (a + b) - Math.Sqrt((3 * a + b) * (a + 3 * b)));
        Assert.Equal(perimeter * 2, elliptic.Area, 1e-4 * perimeter * 2);
        // The density of a draw, from the draw and again from its world normal alone; 1/p_A integrates to the area.
        var rng = new Random(5);
        double sum = 0, sum2 = 0;
        const int n = 20000;
        for (int i = 0; i < n; i++)
        {
            elliptic.SampleArea(new Vector2(rng.NextSingle(), rng.NextSingle()), out var normal, out float pdf);
            Assert.Equal(pdf, elliptic.AreaPdf(normal), 2e-6f * pdf);
            sum += 1 / pdf;
            sum2 += 1 / ((double)pdf * pdf);
        }
        double mean = sum / n, error = Math.Sqrt((sum2 / n - mean * mean) / (n - 1));
        Assert.True(Math.Abs(mean - perimeter * 2) < 4 * error, $"E[1/p_A] = {mean:F5} ± {error:g2}, area {perimeter * 2:F5}");
    }

    /// <summary>
    /// A Lambertian surface of albedo ρ that sees only a uniform sky of radiance L_sky over its hemisphere returns ρ·L_sky
    /// (the cosine-weighted hemisphere integrates to π, f = ρ/π): the disk's top and the tube's outer wall, alone in the
    /// sky, seen by camera rays under <c>path</c> (independent samples, so the standard error is honest).
    /// </summary>
    [Theory]
    [InlineData("""
        { "type": "disk", "center": [0, 1, 0], "radius": 0.5, "normal": [0, 1, 0], "up": [0, 0, -1], "material": "white" }
        """, 0.3f, 3, 0.2f, 0, -1, 0)]
    [InlineData("""{ "type": "cylinder", "p0": [0, 0, 0], "p1": [0, 2, 0], "radius": 0.5, "material": "white" }""",
        3, 1, 0.1f, -1, 0, 0)]
    public void A_white_diffuser_of_either_kind_under_a_uniform_sky_returns_albedo_times_sky(string objectJson,
        float x, float y, float z, float dx, float dy, float dz)
    {
        var scene = SceneText.Load($$"""
            { "radiometry": "physical", "bands": "400:700:100",
              "integrator": { "type": "path", "sampler": "independent", "seed": 2 },
              "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0] },
              "background": { "name": "D65", "scale": 0.01 },
              "materials": { "white": { "type": "lambertian", "reflectance": 0.5 } },
              "objects": [ {{objectJson}} ] }
            """);
        var (mean, error) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(x, y, z), new Vector3(dx, dy, dz)), 2000);
        var d65 = SpectrumLibrary.Resolve("D65");
        for (int b = 0; b < scene.Bands; b++)
        {
            double sky = PathIntegratorTests.BandMean(l => 0.01 * d65.Evaluate(l), scene.Grid.Lower(b), scene.Grid.Upper(b));
            Assert.True(error[b] < 0.01 * sky, $"band {b}: standard error {error[b]:g3} too large to judge");
            Assert.True(Math.Abs(mean[b] - 0.5 * sky) < 3 * error[b] + 1e-6 * sky,
                $"band {b}: {mean[b]:g6} vs ρ·L_sky = {0.5 * sky:g6} (±{error[b]:g2})");
        }
    }

    [Fact]
    public void Bad_keys_are_refused_with_their_path()
    {
        var e = Assert.Throws<InputException>(() =>
            Shape("""{ "type": "cylinder", "p0": [0, 1, 0], "p1": [0, 1, 0], "material": "white" }"""));
        Assert.Contains("$.objects[0].p1", e.Message);
        e = Assert.Throws<InputException>(() => Shape("""{ "type": "disk", "radius": 0, "material": "white" }"""));
        Assert.Contains("$.objects[0].radius", e.Message);
        e = Assert.Throws<InputException>(() => Shape("""{ "type": "disk", "size": 2, "material": "white" }"""));
        Assert.Contains("size", e.Message);
        e = Assert.Throws<InputException>(() => Shape("""{ "type": "disc", "material": "white" }"""));
        Assert.Contains("disk", e.Message);
    }
}
