using System.Numerics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Window portals (<c>"portal": true</c> on a quad; Rendering/Emitters/PortalSkyEmitter.cs): the sky drawn through them stays
/// unbiased — the illuminance on the floor of a closed black room under a uniform sky seen through a ceiling opening
/// against the opening's form factor, and the shipped window room's render against one without the portal.
/// </summary>
public class PortalTests(ITestOutputHelper output)
{
    /// <summary>
    /// A black 2 × 2 × 2 room (walls, floor and ceiling of reflectance 0) whose ceiling has an opening of 0.6 × 0.4 m at its
    /// centre, under a uniform sky of radiance 1; with <paramref name="portal"/> the opening is also a portal (normal down,
    /// into the room).
    /// </summary>
    static Scene Room(bool portal)
    {
        string Quad(string name, double x, double y, double z, double w, double h, string normal, string up) =>
            FormattableString.Invariant($"{{ \"type\": \"quad\", \"name\": \"{name}\", \"center\": [{x}, {y}, {z}], ")
            + FormattableString.Invariant($"\"size\": [{w}, {h}], \"normal\": {normal}, \"up\": {up}, \"material\": \"black\" }}");
        string down = "[0, -1, 0]", north = "[0, 0, -1]", upY = "[0, 1, 0]";
        var objects = new List<string>
        {
            Quad("floor", 0, 0, 0, 2, 2, "[0, 1, 0]", north),
            Quad("left", -1, 1, 0, 2, 2, "[1, 0, 0]", upY), Quad("right", 1, 1, 0, 2, 2, "[-1, 0, 0]", upY),
            Quad("back", 0, 1, -1, 2, 2, "[0, 0, 1]", upY), Quad("front", 0, 1, 1, 2, 2, "[0, 0, -1]", upY),
            // the ceiling around the opening x ∈ [−0.3, 0.3], z ∈ [−0.2, 0.2]
            Quad("c1", -0.65, 2, 0, 0.7, 2, down, north), Quad("c2", 0.65, 2, 0, 0.7, 2, down, north),
            Quad("c3", 0, 2, 0.6, 0.6, 0.8, down, north), Quad("c4", 0, 2, -0.6, 0.6, 0.8, down, north),
        };
        if (portal)
            objects.Add("{ \"type\": \"quad\", \"name\": \"opening\", \"center\": [0, 2, 0], \"size\": [0.6, 0.4], "
                + "\"normal\": [0, -1, 0], \"up\": [0, 0, -1], \"portal\": true }");
        var dir = Reference.TempDir();
        var file = Path.Combine(dir, "room.json");
        File.WriteAllText(file, $$"""
            { "radiometry": "physical", "bands": "500:520:20", "integrator": "path", "background": 1,
              "camera": { "position": [0, 1, 0.9], "look_at": [0, 0, 0], "width": 8, "height": 8 },
              "materials": { "black": { "type": "lambertian", "reflectance": 0 } },
              "objects": [ {{string.Join(", ", objects)}} ] }
            """);
        return SceneLoader.Load(file);
    }

    /// <summary>
    /// E at a floor point of the black room, next-event estimation of the sky with shadow rays (the walls and ceiling block
    /// it), with and without the portal: both within 3σ of L·π·F, F the point-to-rectangle form factor of the opening —
    /// by Lambert's polygon formula πF = ½·Σ_i γ_i·n·ĝ_i over its edges (γ_i the angle an edge subtends at p, ĝ_i the unit
    /// normal of the plane through p and the edge) —, and the portal's variance far lower. The portal is no object.
    /// </summary>
    [Fact]
    public void Illuminance_through_a_ceiling_opening_matches_its_form_factor_with_and_without_a_portal()
    {
        var p = new Vector3(0.15f, 0, -0.1f);
        var n = Vector3.UnitY;
        // Lambert's formula over the opening's corners (the sky beyond it has radiance 1 in the band).
        Vector3[] corners = [new(-0.3f, 2, -0.2f), new(0.3f, 2, -0.2f), new(0.3f, 2, 0.2f), new(-0.3f, 2, 0.2f)];
        double polygon = 0;
        for (int i = 0; i < 4; i++)
        {
            Vector3 a = corners[i] - p, b = corners[(i + 1) % 4] - p;
            double gamma = Math.Acos(Math.Clamp(Vector3.Dot(a, b) / (a.Length() * b.Length()), -1, 1));
            polygon += gamma * Vector3.Dot(n, Vector3.Normalize(Vector3.Cross(a, b)));
        }
        double exact = Math.Abs(polygon) / 2;
        const int samples = 100_000;
        var variance = new double[2];
        for (int way = 0; way < 2; way++)
        {
            var scene = Room(portal: way == 0);
            Assert.Equal(9, scene.Objects.Count);   // the portal is no object
            Assert.Equal(way == 0 ? 1 : 0, scene.Portals.Count);
            var geometry = new SceneGeometry(scene);
            var set = new PathIntegrator(scene, geometry).Emitters;
            var sky = set[set.Sky];
            Assert.Equal(way == 0, sky is PortalSkyEmitter);
            float radiance = sky.Radiance[0];
            var rng = new Random(3);
            double sum = 0, sum2 = 0;
            for (int i = 0; i < samples; i++)
            {
                double value = 0;
                if (sky.Sample(p, n, new Vector2(rng.NextSingle(), rng.NextSingle()), out var s) && s.Pdf > 0
                    && !geometry.Occluded(Visibility.ShadowRay(p, n, s.Direction, s.Distance, geometry.Epsilon)))
                {
                    value = radiance * s.Factor * Math.Max(0, Vector3.Dot(n, s.Direction)) / s.Pdf;
                    // the density the MIS weight of a BSDF ray takes is the draw's own
                    Assert.Equal(s.Pdf, sky.Pdf(p, n, s.Direction, default, default), 1e-4f * s.Pdf);
                }
                sum += value;
                sum2 += value * value;
            }
            double mean = sum / samples;
            variance[way] = sum2 / samples - mean * mean;
            double sigma = Math.Sqrt(variance[way] / samples);
            output.WriteLine($"{(way == 0 ? "portal" : "no portal")}: E {mean:G6} ± {sigma:E2} (form factor {radiance * exact:G6}), "
                + $"{(mean - radiance * exact) / sigma:F2}σ, variance per sample {variance[way]:G4}");
            Assert.InRange(mean, radiance * exact - 3 * sigma, radiance * exact + 3 * sigma);
        }
        output.WriteLine($"variance without / with the portal: {variance[1] / variance[0]:G4}");
        Assert.True(variance[0] < variance[1] / 5, $"portal {variance[0]:G4} against {variance[1]:G4}");
    }

    /// <summary>
    /// scenes/path-window-room.json (sky and sun through the window, Lambertian walls) rendered small with its portal and
    /// without it: the mean over the picture of their per-pixel difference is 0 within 3σ (σ from the differences' spread).
    /// </summary>
    [Fact]
    public void The_window_room_renders_the_same_in_expectation_with_and_without_its_portal()
    {
        var text = File.ReadAllText(Repo.PathOf("scenes", "path-window-room.json"));
        var lines = text.Split('\n');
        Assert.Single(lines, l => l.Contains("\"portal\": true"));
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "with.json"), text);
        File.WriteAllText(Path.Combine(dir, "without.json"), string.Join('\n', lines.Where(l => !l.Contains("\"portal\": true"))));
        var overrides = new SceneOverrides { Width = 32, Height = 22, SamplesPerPixel = 16, Bands = "500:600:1" };
        var images = new SpectralRenderer.Spectra.SpectralImage[2];
        for (int way = 0; way < 2; way++)
        {
            var scene = SceneLoader.Load(Path.Combine(dir, way == 0 ? "with.json" : "without.json"), overrides);
            Assert.Equal(way == 0 ? 1 : 0, scene.Portals.Count);
            images[way] = Renderer.Render(scene, new PathIntegrator(scene, new SceneGeometry(scene)), 2).Image;
        }
        var (mean, sigma, level) = PairedImages.Difference(images[0], images[1]);
        output.WriteLine($"mean radiance {level:G5}; with − without the portal {mean:E3} ± {sigma:E2} ({mean / sigma:F2}σ)");
        Assert.True(level > 0, "the room is lit");
        Assert.InRange(mean, -3 * sigma, 3 * sigma);
    }
}
