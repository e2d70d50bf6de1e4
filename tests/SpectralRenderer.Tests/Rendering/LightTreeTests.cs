using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Scenes.Loading;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The light tree (Rendering/Emitters/LightTree.cs) in the emitter set: its probabilities are a distribution at every point
/// (sum 1, the draw's intervals as long as the stated probabilities), and next-event estimation with it stays unbiased —
/// the irradiance under 200 small patches and spheres against the closed forms, a render's region means against the
/// choice by power alone.
/// </summary>
public class LightTreeTests(ITestOutputHelper output)
{
    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    /// <summary>
    /// A scene of <paramref name="quads"/> small one-sided emitting quads facing down (tilted up to ~35°) and
    /// <paramref name="spheres"/> small emitting spheres, all between heights 1 and 3 above a floor quad at y = 0, each of
    /// its own radiance (0.2–5, flat spectrum); point and spot lights, a directional light and a sky when asked. Returns the
    /// scene file and the emitters as (kind, centre, size, normal, up, L).
    /// </summary>
    static (string File, List<(bool Quad, Vector3 C, float S, Vector3 N, Vector3 Up, float L)> Emitters) ManyLights(
        int quads, int spheres, bool lights, string integrator, int width = 32, int height = 24, int spp = 16,
        bool twoSided = false, bool spots = true)
    {
        var rng = new Random(40);
        var list = new List<(bool, Vector3, float, Vector3, Vector3, float)>();
        var materials = new StringBuilder("\"floor\": { \"type\": \"lambertian\", \"reflectance\": 0.5 }");
        var objects = new StringBuilder("""
            { "type": "quad", "name": "floor", "center": [0, 0, 0], "size": 8, "normal": [0, 1, 0], "up": [0, 0, -1],
              "material": "floor" }
            """);
        for (int i = 0; i < quads + spheres; i++)
        {
            bool quad = i < quads;
            var c = new Vector3(rng.NextSingle() * 6 - 3, 1 + 2 * rng.NextSingle(), rng.NextSingle() * 6 - 3);
            float l = 0.2f + 4.8f * rng.NextSingle() * rng.NextSingle();
            float size = quad ? 0.05f + 0.15f * rng.NextSingle() : 0.02f + 0.06f * rng.NextSingle();
            var n = Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, -1.4f, rng.NextSingle() - 0.5f));
            var up = Vector3.Normalize(Vector3.Cross(n, Vector3.UnitX));
            list.Add((quad, c, size, n, up, l));
            materials.Append($", \"e{i}\": {{ \"type\": \"lambertian\", \"reflectance\": 0, \"emission\": {{ \"spectrum\": [[380, 1], "
                + $"[780, 1]], \"radiance\": {F(l)}, \"two_sided\": {(twoSided ? "true" : "false")} }} }}");
            objects.Append(quad
                ? $", {{ \"type\": \"quad\", \"name\": \"q{i}\", \"center\": [{F(c.X)}, {F(c.Y)}, {F(c.Z)}], \"size\": {F(size)}, "
                  + $"\"normal\": [{F(n.X)}, {F(n.Y)}, {F(n.Z)}], \"up\": [{F(up.X)}, {F(up.Y)}, {F(up.Z)}], \"material\": \"e{i}\" }}"
                : $", {{ \"type\": \"sphere\", \"name\": \"s{i}\", \"center\": [{F(c.X)}, {F(c.Y)}, {F(c.Z)}], \"radius\": {F(size)}, "
                  + $"\"material\": \"e{i}\" }}");
        }
        var extra = new StringBuilder();
        if (lights)
        {
            extra.Append(", \"background\": 0.05, \"lights\": [");
            for (int k = 0; k < 12; k++)
                extra.Append($"{(k > 0 ? ", " : "")}{{ \"type\": \"point\", \"position\": [{F(k - 6)}, 2.5, {F(k % 3 - 1)}], "
                    + "\"spectrum\": \"E\", \"intensity\": 0.3 }");
            for (int k = 0; k < (spots ? 4 : 0); k++)
                extra.Append($", {{ \"type\": \"spot\", \"position\": [{F(2 * k - 3)}, 3, 2], \"direction\": [0, -1, -0.3], "
                    + "\"cutoff\": 30, \"spectrum\": \"E\", \"intensity\": 1 }");
            extra.Append(", { \"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"spectrum\": \"E\", \"intensity\": 0.2 } ]");
        }
        var dir = Reference.TempDir();
        var file = Path.Combine(dir, "scene.json");
        File.WriteAllText(file, $$"""
            { "radiometry": "physical", "bands": "500:520:20", "integrator": {{integrator}},
              "camera": { "position": [0, 6, 5], "look_at": [0, 0, 0], "width": {{width}}, "height": {{height}}, "spp": {{spp}} },
              "materials": { {{materials}} },
              "objects": [ {{objects}} ] {{extra}} }
            """);
        return (file, list);
    }

    static EmitterSet Set(string file)
    {
        var scene = SceneLoader.Load(file);
        return new PathIntegrator(scene, new SceneGeometry(scene)).Emitters;
    }

    /// <summary>
    /// At 24 random points with random normals (and 6 without, as in a medium), among 229 emitters (200 two-sided objects
    /// and 12 point lights in two trees, a directional light, the sky), every one of which shines towards every point: the
    /// probabilities sum to 1; the draw with stratified u takes each emitter on an interval as long as its stated
    /// probability (the count within 2 of m·P) and states the probability <see cref="EmitterSet.SelectionPdf"/> gives. With
    /// one-sided quads and spot lights the tree gives P = 0 only to an emitter that cannot shine towards the point (checked
    /// from its geometry: the point behind the quad's plane, outside the spot's cone), and the draw finds none in the rest,
    /// 1 − Σ P. Choosing and the probabilities allocate nothing.
    /// </summary>
    [Fact]
    public void Probabilities_sum_to_one_and_match_the_draw_at_every_point()
    {
        var (file, _) = ManyLights(150, 50, lights: true, "\"path\"", twoSided: true, spots: false);
        var set = Set(file);
        Assert.Equal(12 + 1 + 200 + 1, set.Count);
        Assert.Equal(212, Enumerable.Range(0, set.Count).Count(set.InTree));
        var rng = new Random(7);
        const int m = 2_500;
        var counts = new int[set.Count];
        for (int t = 0; t < 30; t++)
        {
            var p = new Vector3(rng.NextSingle() * 8 - 4, rng.NextSingle() * 3.5f, rng.NextSingle() * 8 - 4);
            var n = t >= 24 ? Vector3.Zero
                : Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
            double sum = 0;
            for (int k = 0; k < set.Count; k++) sum += set.SelectionPdf(k, p, n);
            Assert.True(Math.Abs(sum - 1) < 1e-4, $"point {t} {p} {n}: sum {sum}");
            Array.Clear(counts);
            for (int i = 0; i < m; i++)
            {
                int k = set.Choose(p, n, (i + 0.5f) / m, out float pick);
                Assert.True(k >= 0);
                Assert.Equal(set.SelectionPdf(k, p, n), pick, 1e-6f * pick + 1e-12f);
                counts[k]++;
            }
            for (int k = 0; k < set.Count; k++)
                Assert.True(Math.Abs(counts[k] - m * (double)set.SelectionPdf(k, p, n)) <= 2 + 1e-3 * counts[k],
                    $"point {t}, {set[k].Describe()}: {counts[k]} of {m} against P = {set.SelectionPdf(k, p, n):G6}");
        }
        var q = new Vector3(0.5f, 0, 0.25f);
        set.Choose(q, Vector3.UnitY, 0.3f, out _);
        long before = GC.GetAllocatedBytesForCurrentThread();
        float total = 0;
        for (int i = 0; i < 10_000; i++)
        {
            int k = set.Choose(q, Vector3.UnitY, (i + 0.5f) / 10_000, out float pick);
            total += pick + set.SelectionPdf(k, q, Vector3.UnitY);
        }
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
        Assert.True(total > 0);

        // One-sided quads and spots: P = 0 only where nothing can arrive, and the draw's misses are the rest.
        var (oneSidedFile, emitters) = ManyLights(150, 50, lights: true, "\"path\"");
        var oneSided = Set(oneSidedFile);
        int zeros = 0;
        for (int t = 0; t < 30; t++)
        {
            var p = new Vector3(rng.NextSingle() * 8 - 4, rng.NextSingle() * 3.5f, rng.NextSingle() * 8 - 4);
            var n = Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
            double sum = 0;
            for (int k = 0; k < oneSided.Count; k++)
            {
                float pk = oneSided.SelectionPdf(k, p, n);
                sum += pk;
                if (pk > 0) continue;
                zeros++;
                if (k is >= 12 and < 16)
                {   // spot light k − 12 at (2(k − 12) − 3, 3, 2) shining along (0, −1, −0.3) into 30°: p outside that cone
                    var toP = Vector3.Normalize(p - new Vector3(2 * (k - 12) - 3, 3, 2));
                    Assert.True(Vector3.Dot(toP, Vector3.Normalize(new Vector3(0, -1, -0.3f))) < MathF.Cos(MathF.PI / 6) + 1e-5f,
                        $"{oneSided[k].Describe()} reaches {p} but has P = 0");
                    continue;
                }
                // emitters are the 16 lights at points, the directional light, then the objects in order
                Assert.True(k >= 17 && k < 17 + emitters.Count, $"{oneSided[k].Describe()} has P = 0 at {p}");
                var (quad, c, size, qn, up, _) = emitters[k - 17];
                Assert.True(quad, $"{oneSided[k].Describe()} is a sphere, which shines everywhere");
                var right = Vector3.Normalize(Vector3.Cross(up, qn));
                for (int corner = 0; corner < 4; corner++)
                {
                    var x = c + size / 2 * ((corner & 1) == 0 ? -right : right) + size / 2 * ((corner & 2) == 0 ? -up : up);
                    Assert.True(Vector3.Dot(qn, p - x) <= 1e-5f, $"{oneSided[k].Describe()} faces {p} but has P = 0");
                }
            }
            int misses = 0;
            for (int i = 0; i < m; i++) if (oneSided.Choose(p, n, (i + 0.5f) / m, out _) < 0) misses++;
            // each subtree that cannot shine towards p is one interval of u, counted to within 1 (10 intervals allowed)
            Assert.True(sum <= 1 + 1e-4 && Math.Abs(misses - m * (1 - sum)) <= 10,
                $"point {t}: Σ P {sum}, {misses} misses of {m}");
        }
        output.WriteLine($"emitters of P = 0 (all facing away) over 30 points: {zeros}");
    }

    /// <summary>
    /// E at the floor point p (normal +y) under 150 one-sided quads and 50 spheres, estimated by next-event estimation
    /// with the emitter drawn by the tree and, the same random numbers otherwise, by power alone, no shadow rays (the
    /// unoccluded sum): both within 3σ of Σ of the closed forms — Lambert's polygon formula E = L/2·Σ_i γ_i·n·ĝ_i for a
    /// quad (γ_i the angle its edge i subtends at p, ĝ_i the unit normal of the plane through p and the edge), πL(r/d)²cos θ
    /// for a sphere wholly above the plane —, and the tree's variance the lower.
    /// </summary>
    [Fact]
    public void Irradiance_from_many_small_emitters_matches_the_closed_forms_with_the_tree_and_by_power()
    {
        var (treeFile, emitters) = ManyLights(150, 50, lights: false, "{ \"type\": \"path\", \"light_tree\": true }");
        var (powerFile, _) = ManyLights(150, 50, lights: false, "{ \"type\": \"path\", \"light_tree\": false }");
        var sets = new[] { Set(treeFile), Set(powerFile) };
        Assert.True(sets[0].InTree(0) && !sets[1].InTree(0));
        var p = new Vector3(0.3f, 0, -0.4f);
        var n = Vector3.UnitY;
        double exact = 0;
        foreach (var (quad, c, s, qn, up, l) in emitters)
        {
            if (!quad)
            {
                var d = c - p;
                exact += Math.PI * l * s * s / d.LengthSquared() * (d.Y / d.Length());
                continue;
            }
            // The quad's corners c ± (s/2)·right ± (s/2)·up; it faces p (its normal points down, p is below every one).
            var right = Vector3.Normalize(Vector3.Cross(up, qn));
            Vector3[] v = [c - s / 2 * right - s / 2 * up, c + s / 2 * right - s / 2 * up, c + s / 2 * right + s / 2 * up,
                c - s / 2 * right + s / 2 * up];
            double polygon = 0;
            for (int i = 0; i < 4; i++)
            {
                Vector3 a = v[i] - p, b = v[(i + 1) % 4] - p;
                double gamma = Math.Acos(Math.Clamp(Vector3.Dot(a, b) / (a.Length() * b.Length()), -1, 1));
                polygon += gamma * Vector3.Dot(n, Vector3.Normalize(Vector3.Cross(a, b)));
            }
            Assert.True(Vector3.Dot(qn, p - c) > 0, "every quad faces the point");
            exact += l / 2 * Math.Abs(polygon);
        }
        const int samples = 200_000;
        var rng = new Random(11);
        double[] sum = new double[2], sum2 = new double[2];
        for (int i = 0; i < samples; i++)
        {
            float u = rng.NextSingle();
            var w = new Vector2(rng.NextSingle(), rng.NextSingle());
            for (int way = 0; way < 2; way++)
            {
                var set = sets[way];
                int k = set.Choose(p, n, u, out float pick);
                double value = 0;
                if (k >= 0 && set[k].Sample(p, n, w, out var e) && e.Pdf > 0)
                    value = set[k].Radiance[0] * Math.Max(0, Vector3.Dot(n, e.Direction)) / (pick * e.Pdf);
                sum[way] += value;
                sum2[way] += value * value;
            }
        }
        var variance = new double[2];
        for (int way = 0; way < 2; way++)
        {
            double mean = sum[way] / samples;
            variance[way] = sum2[way] / samples - mean * mean;
            double sigma = Math.Sqrt(variance[way] / samples);
            output.WriteLine($"{(way == 0 ? "tree" : "by power")}: E {mean:G6} ± {sigma:E2} (closed forms {exact:G6}), "
                + $"{(mean - exact) / sigma:F2}σ, variance per sample {variance[way]:G4}");
            Assert.InRange(mean, exact - 3 * sigma, exact + 3 * sigma);
        }
        output.WriteLine($"variance by power / tree: {variance[1] / variance[0]:G4}");
        Assert.True(variance[0] < variance[1] / 2, $"tree {variance[0]:G4} against by power {variance[1]:G4}");
    }

    /// <summary>
    /// A render of the floor under the 200 emitters (direct and one bounce, 16 spp, 32×24) with the tree and by power alone:
    /// the mean over the picture of their per-pixel difference is 0 within 3σ (σ from the differences' spread; pixels are
    /// independent), so the walk's MIS with the tree's point-dependent probabilities adds no bias.
    /// </summary>
    [Fact]
    public void A_render_with_the_tree_agrees_with_one_by_power()
    {
        var images = new SpectralRenderer.Spectra.SpectralImage[2];
        for (int way = 0; way < 2; way++)
        {
            var (file, _) = ManyLights(150, 50, lights: true,
                $"{{ \"type\": \"path\", \"max_depth\": 2, \"light_tree\": {(way == 0 ? "true" : "false")} }}");
            var scene = SceneLoader.Load(file);
            var integrator = new PathIntegrator(scene, new SceneGeometry(scene));
            Assert.Equal(way == 0, integrator.Emitters.InTree(20));
            images[way] = Renderer.Render(scene, integrator, 2).Image;
        }
        var (mean, sigma, level) = PairedImages.Difference(images[0], images[1]);
        output.WriteLine($"mean radiance {level:G5}; mean difference tree − power {mean:E3} ± {sigma:E2} ({mean / sigma:F2}σ)");
        Assert.True(level > 0.01, "the floor is lit");
        Assert.InRange(mean, -3 * sigma, 3 * sigma);
    }
}
