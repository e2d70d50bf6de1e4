using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path tracer's multiple importance sampling of emitting objects is unbiased: the direct light a rough conductor
/// reflects from a small and a large emissive sphere, a disk and a cylinder, as <c>path</c> estimates it (next-event
/// estimation and BSDF sampling combined by the power heuristic), agrees within 3σ with two single-strategy estimators
/// written here — light sampling only (each emitter's own draw, shadow rays) and BSDF sampling only (closest hits on the
/// emitters). A wrong emitter density in the MIS weight would bias the first against the other two, which share nothing
/// but the BSDF and the emitter's point draw (BSDF-only uses neither the draw nor its density).
/// </summary>
public class EmitterMisTests(Xunit.Abstractions.ITestOutputHelper output)
{
    // One 20-nm band and constant spectra, so the path tracer's sub-band grid and the output band agree exactly; direct
    // light only (max_depth 1); independent samples, so the standard errors are honest.
    const string Json = """
        { "radiometry": "physical", "bands": "500:520:20",
          "integrator": { "type": "path", "sampler": "independent", "seed": 5, "max_depth": 1 },
          "camera": { "position": [0, 1, 2], "look_at": [0, 0, 0] },
          "materials": {
            "metal": { "type": "conductor", "conductor": { "n": 0.2, "k": 3 }, "roughness": 0.3 },
            "bulb": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": 40 } },
            "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": 2 } } },
          "objects": [
            { "type": "quad", "size": 4, "normal": [0, 1, 0], "up": [0, 0, -1], "material": "metal" },
            { "type": "sphere", "center": [0.3, 0.6, -1.2], "radius": 0.05, "material": "bulb" },
            { "type": "sphere", "center": [1.5, 1.2, -0.5], "radius": 0.8, "material": "lamp" },
            { "type": "disk", "center": [-0.2, 0.9, -1.7], "radius": 0.4, "normal": [0, -0.45, 0.9], "material": "lamp" },
            { "type": "cylinder", "p0": [-1.2, 0.3, -1], "p1": [-0.8, 1, -1.4], "radius": 0.15, "material": "lamp" } ] }
        """;

    [Fact]
    public void Mis_agrees_with_light_only_and_bsdf_only_sampling()
    {
        var scene = SceneText.Load(Json);
        var geometry = new SceneGeometry(scene);
        var ray = new Ray(new Vector3(0, 1, 2), Vector3.Normalize(new Vector3(0, -1, -2)));
        var (misMean, misError) = PathIntegratorTests.Estimate(scene, ray, 20_000);
        double mis = misMean[0], misSigma = misError[0];

        var traced = ray;
        Assert.True(geometry.Intersect(ref traced, out var hit));
        var p = hit.Position;
        var n = hit.Normal;
        var wo = -ray.Direction;
        var bsdf = scene.Materials[scene.Objects[hit.Object].Material].Bsdf;
        var f = new float[scene.PaddedBands];
        var rng = new Random(17);

        // Light sampling only: Σ over the emitters of E[f·L_e·|cos θ|/p_ω] with each emitter's own draw.
        double light = 0, lightVariance = 0;
        const int perEmitter = 40_000;
        foreach (var o in scene.Objects)
        {
            if (scene.Materials[o.Material].Emission is not { } emission) continue;
            var emitter = new AreaEmitter(o, emission.Radiance, emission.TwoSided, "test");
            double sum = 0, sum2 = 0;
            for (int i = 0; i < perEmitter; i++)
            {
                double value = 0;
                if (emitter.Sample(p, new Vector2(rng.NextSingle(), rng.NextSingle()), out var x, out var nx, out float pdf))
                {
                    var d = x - p;
                    float distance = d.Length();
                    var wi = d / distance;
                    // The shadow ray leaves from just above p and aims at x itself (from p's offset a ray along wi would
                    // pass beside x and meet a sphere early at grazing points).
                    var origin = p + geometry.Epsilon * n;
                    float length = Vector3.Distance(origin, x);
                    if (emitter.Emits(nx, -wi) && Vector3.Dot(n, wi) > 0
                        && !geometry.Occluded(new Ray(origin, (x - origin) / length, length - 2 * geometry.Epsilon)))
                    {
                        bsdf.Evaluate(wo, wi, n, f);
                        value = f[0] * emission.Radiance[0] * Vector3.Dot(n, wi) / pdf;
                    }
                }
                sum += value;
                sum2 += value * value;
            }
            double mean = sum / perEmitter;
            light += mean;
            lightVariance += (sum2 / perEmitter - mean * mean) / (perEmitter - 1);
        }

        // BSDF sampling only: E[f·|cos θ|/p·L_e] over directions from the BSDF, L_e where the closest hit emits towards p.
        double bsdfSum = 0, bsdfSum2 = 0;
        const int directions = 200_000;
        for (int i = 0; i < directions; i++)
        {
            double value = 0;
            if (bsdf.Sample(wo, n, new Vector2(rng.NextSingle(), rng.NextSingle()), f, out var bs) && bs.Pdf > 0)
            {
                var next = new Ray(p + geometry.Epsilon * n, bs.Wi);
                if (geometry.Intersect(ref next, out var found) && scene.Materials[scene.Objects[found.Object].Material].Emission is { } e
                    && (e.TwoSided || Vector3.Dot(found.GeometricNormal, -bs.Wi) > 0))
                    value = f[0] * MathF.Abs(Vector3.Dot(n, bs.Wi)) / bs.Pdf * e.Radiance[0];
            }
            bsdfSum += value;
            bsdfSum2 += value * value;
        }
        double bsdfOnly = bsdfSum / directions;
        double bsdfSigma = Math.Sqrt((bsdfSum2 / directions - bsdfOnly * bsdfOnly) / (directions - 1));
        double lightSigma = Math.Sqrt(lightVariance);

        output.WriteLine($"MIS {mis:F5} ± {misSigma:F5}; light only {light:F5} ± {lightSigma:F5}; "
            + $"BSDF only {bsdfOnly:F5} ± {bsdfSigma:F5}");
        foreach (var (what, sigma) in new[] { ("MIS", misSigma), ("light only", lightSigma), ("BSDF only", bsdfSigma) })
            Assert.True(sigma < 0.02 * light, $"{what}: standard error {sigma:g3} too large to judge {light:g4}");
        Assert.True(Math.Abs(mis - light) < 3 * Math.Sqrt(misSigma * misSigma + lightSigma * lightSigma),
            $"MIS {mis:F5} vs light only {light:F5}");
        Assert.True(Math.Abs(mis - bsdfOnly) < 3 * Math.Sqrt(misSigma * misSigma + bsdfSigma * bsdfSigma),
            $"MIS {mis:F5} vs BSDF only {bsdfOnly:F5}");
        Assert.True(Math.Abs(light - bsdfOnly) < 3 * Math.Sqrt(lightSigma * lightSigma + bsdfSigma * bsdfSigma),
            $"light only {light:F5} vs BSDF only {bsdfOnly:F5}");
    }
}
