using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Geometry;
using SpectralRenderer.Tests.Relight;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Extending;

/// <summary>
/// ARCHITECTURE.md, "Extending: a participating medium (where it plugs in)": a kind of medium is one <see cref="Medium"/>
/// class plus one <see cref="MediumTypes.Register"/> line, named by an object's "medium" (its interior) or the scene's
/// "medium" (around the objects), and the path tracer's walk carries it: β gains the transmittance of every segment and
/// next-event estimation the transmittance of its shadow ray. This purely absorbing homogeneous medium lives in the test
/// assembly (the engine's own are in Scenes/HomogeneousMedium.cs), and the walk through it must obey Beer–Lambert, L·exp(−σ_a·d) per band:
/// a straight ray through an absorber is deterministic, so the law holds to float precision.
/// </summary>
public class MediumRecipeTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>The example: σ_a per band (per scene length unit), no scattering: T = exp(−σ_a·t).</summary>
    sealed class AbsorbingMedium(float[] sigmaA) : Medium
    {
        public override void Attenuate(Vector3 origin, Vector3 direction, float distance, Span<float> values)
        {
            for (int i = 0; i < values.Length && i < sigmaA.Length; i++)
                if (sigmaA[i] > 0) values[i] *= MathF.Exp(-sigmaA[i] * distance);   // (σ = 0: T = 1, also for t = ∞)
        }

        public override Medium Resampled(Func<float[], float[]> resample) => new AbsorbingMedium(resample(sigmaA));
    }

    internal const string Name = "test-absorbing";

    internal static void EnsureRegistered()
    {
        lock (typeof(MediumRecipeTests))
            if (!MediumTypes.ByName.ContainsKey(Name))
                MediumTypes.Register(Name, new MediumType(["sigma_a"], s =>
                {
                    var sigma = s.Spectrum("sigma_a");
                    foreach (double v in sigma.Values)
                        if (!(v >= 0 && double.IsFinite(v)))
                            throw s.Error("sigma_a", "an absorption coefficient is negative or not finite", "give σ_a ≥ 0 per unit length");
                    return new AbsorbingMedium(s.Bands(sigma, "sigma_a"));
                }));
    }

    // Three 100-nm bands, each one sub-band of the path tracer's grid (spectral_grid 100), so a band's σ_a is the band mean
    // of σ_a(λ) = 0.5 + 0.01·(λ − 400) m⁻¹, linear: its value at the band's centre, 1, 2 and 3 m⁻¹ (a second way to it).
    const string Bands = "\"bands\": \"400:700:3\"";
    const string Integrator =
        "\"integrator\": { \"type\": \"path\", \"spectral_grid\": 100, \"rr_depth\": 1000, \"sampler\": \"independent\" }";
    const string Sigma = "{ \"type\": \"" + Name + "\", \"sigma_a\": [[400, 0.5], [700, 3.5]] }";
    static readonly double[] SigmaA = [1, 2, 3];
    const double L = 3;

    /// <summary>
    /// A box of the medium d thick along z, bounded by an index-matched surface (k_t = 1, n = 1: a null boundary), in front
    /// of an emitting quad of radiance L; without <paramref name="medium"/> the box is empty.
    /// </summary>
    static Scene Slab(double d, bool medium = true) => SceneText.Load($$"""
        { "radiometry": "physical", {{Bands}}, {{Integrator}},
          "camera": { "position": [0, 0, -3], "look_at": [0, 0, 0] },
          "materials": { "boundary": { "transmit": 1, "ior": 1 },
                         "lamp": { "type": "lambertian", "reflectance": 0,
                                   "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": {{L}} } } },
          "objects": [ { "type": "box", "center": [0, 0, 0], "size": [1, 1, {{d}}], "material": "boundary"
                         {{(medium ? ", \"medium\": " + Sigma : "")}} },
                       { "type": "quad", "center": [0, 0, 2], "size": 4, "normal": [0, 0, -1], "material": "lamp" } ] }
        """);

    [Theory]
    [InlineData(0.25)]
    [InlineData(0.5)]
    [InlineData(1.0)]
    public void An_emitter_seen_through_a_slab_of_absorber_is_L_exp_minus_sigma_d_per_band(double d)
    {
        EnsureRegistered();
        var ray = new Ray(new Vector3(0.1f, 0.05f, -3), Vector3.UnitZ);
        var (seen, _) = PathIntegratorTests.Estimate(Slab(d), ray, 16);
        for (int b = 0; b < SigmaA.Length; b++)
        {
            double expected = L * Math.Exp(-SigmaA[b] * d);
            output.WriteLine($"d = {d}, band {b}: {seen[b]:g7} vs L·exp(−σ_a·d) = {expected:g7}");
            Assert.Equal(expected, seen[b], 2e-6 * expected);
        }
    }

    [Fact]
    public void The_empty_box_is_an_index_matched_boundary_that_shows_the_emitter_unchanged()
    {
        var ray = new Ray(new Vector3(0.1f, 0.05f, -3), Vector3.UnitZ);
        var (seen, _) = PathIntegratorTests.Estimate(Slab(1, medium: false), ray, 16);
        for (int b = 0; b < SigmaA.Length; b++) Assert.Equal(L, seen[b], 1e-6 * L);
    }

    // A white Lambertian floor (y = 0) lit by a point light of radiant intensity I at (x, h, 0), seen straight down from
    // height c above the origin: L = ρ/π·I·cos θ/r²·exp(−σ_a·(r + c)) in a scene-wide medium, r the light's distance.
    const double I = 2, X = 0.6, H = 1.2, C = 1.5;

    static Scene Floor(bool medium) => SceneText.Load(FloorText(medium ? Sigma : null));

    static string FloorText(string? medium) => $$"""
        { "radiometry": "physical", {{Bands}}, {{Integrator}},
          {{(medium is null ? "" : "\"medium\": " + medium + ",")}}
          "camera": { "position": [0, {{C}}, -1], "look_at": [0, 0, 0] },
          "lights": [ { "type": "point", "position": [{{X}}, {{H}}, 0], "spectrum": [[380, 1], [780, 1]], "intensity": {{I}} } ],
          "materials": { "floor": { "type": "lambertian", "reflectance": 1 } },
          "objects": [ { "type": "plane", "material": "floor" } ] }
        """;

    [Fact]
    public void A_floor_lit_through_the_medium_reads_exp_minus_sigma_times_its_light_on_the_shadow_ray_and_camera_ray()
    {
        EnsureRegistered();
        var ray = new Ray(new Vector3(0, (float)C, 0), -Vector3.UnitY);
        var (clear, _) = PathIntegratorTests.Estimate(Floor(medium: false), ray, 16);
        var (hazy, _) = PathIntegratorTests.Estimate(Floor(medium: true), ray, 16);
        double r = Math.Sqrt(X * X + H * H), unlit = I * (H / r) / (r * r) / Math.PI;
        for (int b = 0; b < SigmaA.Length; b++)
        {
            double transmittance = Math.Exp(-SigmaA[b] * (r + C));
            output.WriteLine($"band {b}: {hazy[b]:g7} / {clear[b]:g7} = {hazy[b] / clear[b]:g7} vs exp(−σ_a(r + c)) = {transmittance:g7}");
            Assert.Equal(unlit, clear[b], 2e-6 * unlit);
            Assert.Equal(unlit * transmittance, hazy[b], 2e-6 * unlit * transmittance);
        }
    }

    // The floor in the medium, seen by a small film, with a named bulb of spectrum S and intensity k and a box of absorber on the floor.
    static string Lit(string spectrum, double k) => $$"""
        { "radiometry": "physical", "bands": "400:700:6", "integrator": "path", "medium": {{Sigma}},
          "camera": { "position": [0, 1.5, 2], "look_at": [0, 0, 0], "width": 8, "height": 8, "spp": 2 },
          "lights": [ { "type": "point", "name": "bulb", "position": [0.6, 1.2, 0], "spectrum": "{{spectrum}}", "intensity": {{k}} } ],
          "materials": { "floor": { "type": "lambertian", "reflectance": 0.8 }, "boundary": { "transmit": 1, "ior": 1 } },
          "objects": [ { "type": "plane", "material": "floor" },
                       { "type": "box", "center": [0, 0.3, 0], "size": [0.6, 0.6, 0.6], "material": "boundary", "medium": {{Sigma}} } ] }
        """;

    [Fact]
    public void A_path_render_through_media_relit_to_another_bulb_equals_a_render_with_that_bulb()
    {
        EnsureRegistered();
        PathRelightTests.RelitToD65EqualsRerender(Lit("A", 2), Lit("D65", 0.5));
    }

    [Fact]
    public void A_scene_names_only_a_registered_medium_and_whitted_carries_it()
    {
        EnsureRegistered();
        var unknown = Assert.Throws<InputException>(() => SceneText.Load(FloorText("{ \"type\": \"fog\" }")));
        Assert.Contains("unknown medium type 'fog'", unknown.Message);
        Assert.DoesNotContain('\n', unknown.Message);
        var negative = Assert.Throws<InputException>(() => SceneText.Load(FloorText("{ \"type\": \"" + Name + "\", \"sigma_a\": -1 }")));
        Assert.Contains("$.medium.sigma_a", negative.Message);
        var scene = Floor(medium: true);
        Assert.NotNull(Integrators.Create(scene, new SceneGeometry(scene), "whitted"));   // Beer–Lambert along its rays (BeerLambertTests)
    }
}
