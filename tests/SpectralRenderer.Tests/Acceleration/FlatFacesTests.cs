using System.Numerics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Acceleration;

/// <summary>
/// The path integrator's flat faces (quads and box sides met all at once in world space) against the object-space test of
/// each shape (<see cref="AnalyticShape.Intersect"/>, a second method): the same closest shape, distance and normal for
/// random rays among randomly placed, rotated, scaled and sheared quads and boxes, the same occlusion answers.
/// </summary>
public class FlatFacesTests(ITestOutputHelper output)
{
    static AnalyticShape[] Shapes(int count, int seed)
    {
        var rng = new Random(seed);
        var shapes = new AnalyticShape[count];
        float R() => rng.NextSingle() * 2 - 1;
        for (int i = 0; i < count; i++)
        {
            var scale = Matrix4x4.CreateScale(0.2f + rng.NextSingle(), 0.2f + rng.NextSingle(), 0.2f + rng.NextSingle());
            var shear = Matrix4x4.Identity;
            if (i % 3 == 0) shear.M21 = 0.4f * R();   // a sheared box is a parallelepiped, its sides parallelograms
            var rotation = Matrix4x4.CreateFromYawPitchRoll(3 * R(), 3 * R(), 3 * R());
            var m = scale * shear * rotation * Matrix4x4.CreateTranslation(2 * R(), 2 * R(), 2 * R());
            shapes[i] = new AnalyticShape(i % 2 == 0 ? ShapeKind.Quad : ShapeKind.Box, m);
        }
        return shapes;
    }

    /// <summary>The closest shape by testing every one in object space: index, t and normal (−1 if none).</summary>
    static int Closest(AnalyticShape[] shapes, Ray ray, out float t, out Vector3 normal)
    {
        int best = -1;
        t = ray.TMax; normal = default;
        for (int k = 0; k < shapes.Length; k++)
            if (shapes[k].Intersect(new Ray(ray.Origin, ray.Direction, t), 0, out float tk, out var nk)) { best = k; t = tk; normal = nk; }
        return best;
    }

    [Theory]
    [InlineData(1, 1)]
    [InlineData(7, 2)]    // the Cornell room's count: one register of 8 lanes (AVX2), two of 4 (128-bit)
    [InlineData(10, 3)]   // 5 quads + 5 boxes = 35 faces: several registers, a partly filled last one
    public void Closest_hits_and_occlusion_agree_with_each_shapes_object_space_test(int count, int seed)
    {
        var shapes = Shapes(count, seed);
        var faces = FlatFaces.TryBuild(shapes);
        Assert.NotNull(faces);
        var rng = new Random(seed + 100);
        int hits = 0, edgeCases = 0;
        for (int i = 0; i < 20000; i++)
        {
            var origin = 3 * new Vector3(rng.NextSingle() * 2 - 1, rng.NextSingle() * 2 - 1, rng.NextSingle() * 2 - 1);
            // aimed near a random shape's centre, so most rays meet something
            var target = Vector3.Transform(Vector3.Zero, shapes[rng.Next(count)].ObjectToWorld)
                + 0.6f * new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f);
            var d = Vector3.Normalize(target - origin);
            if (i % 10 == 0) d = (i / 10 % 3) switch { 0 => Vector3.UnitX, 1 => -Vector3.UnitY, _ => Vector3.UnitZ };   // zero components
            float tMax = i % 4 == 0 ? 1 + 3 * rng.NextSingle() : float.PositiveInfinity;   // shadow-ray-like segments too
            var ray = new Ray(origin, d, tMax);
            int expected = Closest(shapes, ray, out float tExpected, out var nExpected);

            var probe = ray;
            int face = faces.Intersect(ref probe);
            bool occluded = faces.Occluded(ray);
            int got = face < 0 ? -1 : faces.ShapeOf(face);
            if (got != expected)
            {
                // Only where two answers are a rounding apart: a hit within 1e-4 of a face's edge, or of another face's distance.
                var p = ray.At(expected >= 0 ? tExpected : probe.TMax);
                Assert.True(NearAnEdge(shapes, p),
                    $"ray {i}: flat faces say shape {got} (t {probe.TMax}), object space {expected} (t {tExpected})");
                edgeCases++;
                continue;
            }
            Assert.Equal(expected >= 0, occluded);
            if (expected < 0) continue;
            hits++;
            Assert.True(MathF.Abs(probe.TMax - tExpected) <= 1e-5f * MathF.Max(1, tExpected),
                $"ray {i}: t {probe.TMax} against {tExpected}");
            Assert.True(Vector3.Distance(faces.Normal(face), nExpected) < 1e-5f,
                $"ray {i}: normal {faces.Normal(face)} against {nExpected}");
        }
        output.WriteLine($"{count} shapes: {hits} hits agree, {edgeCases} rays at an edge differ");
        Assert.True(hits > 1000);
        Assert.True(edgeCases < 20);
    }

    static bool NearAnEdge(AnalyticShape[] shapes, Vector3 p)
    {
        foreach (var s in shapes)
        {
            var o = Vector3.Transform(p, s.WorldToObject);
            float[] c = [MathF.Abs(o.X), MathF.Abs(o.Y), MathF.Abs(o.Z)];
            int near = c.Count(x => MathF.Abs(x - 0.5f) < 1e-4f);
            if (s.Kind == ShapeKind.Quad ? near >= 1 && MathF.Abs(o.Z) < 1e-4f : near >= 2) return true;
        }
        return false;
    }

    [Fact]
    public void Spheres_and_too_many_faces_keep_the_hierarchy()
    {
        Assert.Null(FlatFaces.TryBuild([new AnalyticShape(ShapeKind.Sphere, Matrix4x4.Identity)]));
        var boxes = Enumerable.Range(0, FlatFaces.MaxFaces / 6 + 1)
            .Select(i => new AnalyticShape(ShapeKind.Box, Matrix4x4.CreateTranslation(i, 0, 0))).ToArray();
        Assert.Null(FlatFaces.TryBuild(boxes));
    }
}
