using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// Shadow rays through index-matched (null) boundaries (Rendering/PathTracing/PathIntegrator.Media.cs, ShadowThrough): a
/// point light reaches a surface only by next-event estimation, so without it a light behind a null-bounded slab of medium
/// is black. Checked against the closed form of direct lighting through Beer–Lambert, per band.
/// </summary>
public class NullBoundaryTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const double I = 3, Rho = 0.5, H = 2, D = 1;

    /// <summary>
    /// A Lambertian floor (ρ = 0.5) lit by a point light of radiant intensity I at height H = 2 straight above the point the
    /// camera sees, through a wide null-bounded box of absorbing medium between heights 0.5 and 1.5 (d = 1, σ_a from 0.2 at
    /// 380 nm to 2 at 780 nm per unit: linear, so a band's mean is its centre's value), and optionally a second null-bounded
    /// slab above it, between 1.6 and 1.9, of σ_a = 0.5 (the shadow ray then crosses four null surfaces and T gains
    /// exp(−0.5·0.3)). The camera sees the floor below
    /// the slab, and the light bounced off the floor leaves the scene: L = (ρ/π)·(I/H²)·exp(−σ_a·d) per band, to 1e-4.
    /// </summary>
    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void A_point_light_behind_a_null_bounded_absorbing_slab_lights_the_floor_through_exp_minus_sigma_a_d(bool second)
    {
        var above = second
            ? """, { "type": "box", "center": [0, 1.75, 0], "size": [10, 0.3, 10], "material": "null", "medium": { "sigma_a": 0.5 } }"""
            : "";
        var scene = SceneText.Load($$"""
            { "radiometry": "physical", "bands": "380:780:80", "max_depth": 4,
              "integrator": { "type": "path", "spectral_grid": 5, "rr_depth": 1000, "sampler": "independent" },
              "camera": { "position": [-1, 0.3, 0], "look_at": [0, 0, 0] },
              "lights": [ { "type": "point", "position": [0, {{H}}, 0], "spectrum": [[380, 1], [780, 1]], "intensity": {{I}} } ],
              "materials": { "floor": { "type": "lambertian", "reflectance": {{Rho}} }, "null": { "transmit": 1, "ior": 1 } },
              "objects": [ { "type": "plane", "material": "floor" },
                           { "type": "box", "center": [0, 1, 0], "size": [10, {{D}}, 10], "material": "null",
                             "medium": { "sigma_a": [[380, 0.2], [780, 2]] } }{{above}} ] }
            """);
        var ray = new Ray(new Vector3(-1, 0.3f, 0), Vector3.Normalize(new Vector3(1, -0.3f, 0)));
        var (seen, _) = PathIntegratorTests.Estimate(scene, ray, 4);
        for (int b = 0; b < 80; b++)
        {
            double sigma = 0.2 + 1.8 * (382.5 + 5 * b - 380) / 400;
            double expected = Rho / Math.PI * I / (H * H) * Math.Exp(-sigma * D - (second ? 0.5 * 0.3 : 0));
            Assert.True(Math.Abs(seen[b] - expected) <= 1e-4 * expected, $"band {b}: {seen[b]} vs {expected}");
        }
        output.WriteLine($"second slab {second}: band 0 {seen[0]:g6}, band 79 {seen[79]:g6}");
    }
}
