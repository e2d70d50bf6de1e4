using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Extending;

/// <summary>
/// ARCHITECTURE.md, "Extending: an emissive shape (a disk light)": a new kind of analytic shape is one
/// <see cref="CanonicalShape"/> class plus one <see cref="ShapeTypes.Register"/> line, and with an emissive material it is
/// an area light of the path tracer. This disk lives in the test assembly (the engine's own "disk" is not used), and
/// under <c>path</c> it lights its axis as a Lambertian disk of radiance L must: E(h) = πL·r²/(r² + h²) at height h.
/// </summary>
public class EmissiveShapeRecipeTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>The example: the unit disk x² + y² ≤ 1 at z = 0, normal +z, uv polar (u = φ/2π, v = r).</summary>
    sealed class UnitDisk : CanonicalShape
    {
        public override bool Intersect(Vector3 o, Vector3 d, float tMin, float tMax, out float t, out Vector3 normal)
        {
            normal = Vector3.UnitZ;
            t = d.Z == 0 ? 0 : -o.Z / d.Z;
            if (d.Z == 0 || !(t > tMin && t < tMax)) return false;
            var p = o + t * d;
            return p.X * p.X + p.Y * p.Y <= 1;
        }

        public override Bounds3 Bounds => new(new Vector3(-1, -1, 0), new Vector3(1, 1, 0));
        public override Vector3? FlatNormal => Vector3.UnitZ;
        public override float Area => MathF.PI;

        public override Vector3 SampleArea(Vector2 u, out Vector3 normal)
        {
            normal = Vector3.UnitZ;
            float r = MathF.Sqrt(u.X), phi = 2 * MathF.PI * u.Y;
            return new Vector3(r * MathF.Cos(phi), r * MathF.Sin(phi), 0);
        }

        public override Vector2 TexCoord(Vector3 p) =>
            new((MathF.Atan2(p.Y, p.X) / (2 * MathF.PI) + 1) % 1, MathF.Sqrt(p.X * p.X + p.Y * p.Y));

        public override float TexCoordArea => 1;
    }

    internal const string Name = "test-disk";

    internal static void EnsureRegistered()
    {
        lock (typeof(EmissiveShapeRecipeTests))
            if (!ShapeTypes.ByName.ContainsKey(Name))
                ShapeTypes.Register(Name, new ShapeType(["center", "radius", "normal", "up"], new UnitDisk(),
                    s => Matrix4x4.CreateScale(s.Size("radius"), s.Size("radius"), 1) * s.Frame("normal", "up") * s.Translation("center")));
    }

    const double R = 0.5, L = 3;

    // A disk light of radius r and radiance L facing down at height h over a white Lambertian floor (ρ = 1); the lamp
    // reflects nothing, so the floor's radiance is ρ/π·E = L·r²/(r² + h²). One 20-nm band, independent samples.
    static Scene Lit(double h) => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "500:520:20",
          "integrator": { "type": "path", "sampler": "independent", "seed": 11 },
          "camera": { "position": [3, 0.1, 0], "look_at": [0, 0, 0] },
          "materials": { "floor": { "type": "lambertian", "reflectance": 1 },
                         "lamp": { "type": "lambertian", "reflectance": 0,
                                   "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": {{L}} } } },
          "objects": [ { "type": "plane", "material": "floor" },
                       { "type": "{{Name}}", "center": [0, {{h}}, 0], "radius": {{R}}, "normal": [0, -1, 0], "up": [1, 0, 0],
                         "material": "lamp" } ] }
        """);

    [Theory]
    [InlineData(0.25)]
    [InlineData(0.5)]
    [InlineData(1.0)]
    [InlineData(2.0)]
    public void The_disk_light_gives_the_axial_irradiance_pi_L_r2_over_r2_plus_h2(double h)
    {
        EnsureRegistered();
        var scene = Lit(h);
        var origin = new Vector3(3, 0.1f, 0);
        var (mean, error) = PathIntegratorTests.Estimate(scene, new Ray(origin, Vector3.Normalize(-origin)), 4000);
        double irradiance = Math.PI * L * R * R / (R * R + h * h);
        double expected = irradiance / Math.PI;   // ρ/π·E with ρ = 1
        output.WriteLine($"h = {h}: radiance {mean[0]:F5} ± {error[0]:F5}, ρ/π·E = {expected:F5}");
        Assert.True(error[0] < 0.02 * expected, $"standard error {error[0]:g3} too large to judge {expected:g4}");
        Assert.True(Math.Abs(mean[0] - expected) < 3 * error[0],
            $"h = {h}: {mean[0]:F5} vs πL·r²/(r² + h²)/π = {expected:F5} (±{error[0]:g2})");
    }

    [Fact]
    public void Camera_rays_that_meet_the_disk_see_its_radiance_and_past_its_rim_see_nothing()
    {
        EnsureRegistered();
        var scene = Lit(1);
        var (onDisk, _) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0.3f, 0.05f, -0.2f), Vector3.UnitY), 64);
        Assert.Equal(L, onDisk[0], 1e-5 * L);
        var (pastRim, _) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0.3f, 0.05f, -0.45f), Vector3.UnitY), 64);
        Assert.Equal(0, pastRim[0]);
        // The top (its back) does not emit.
        var (back, _) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0.1f, 3, 0), -Vector3.UnitY), 64);
        Assert.Equal(0, back[0]);
    }
}
