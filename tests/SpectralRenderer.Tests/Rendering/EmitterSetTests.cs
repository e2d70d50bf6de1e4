using System.Globalization;
using System.Numerics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The path tracer's one emitter set (Rendering/Emitters): every kind of emitter of a scene — point, spot, directional and
/// goniometric lights, an emitting sphere, quad, disk and mesh, the sky — is in it once, and each non-delta emitter's
/// <see cref="Emitter.Pdf"/> is the density of its own <see cref="Emitter.Sample"/>: the Monte Carlo mean of 1/p_ω over
/// its samples (p_ω from <c>Pdf</c> at the sampled point) is the solid angle the emitter subtends, checked against the
/// closed forms of each shape (cone of a sphere, on-axis disk and rectangle, Van Oosterom–Strackee for a triangle, the
/// hemisphere for the sky), and ∫cos θ dω/p_ω against the on-axis form factor πr²/(r² + h²) of a disk.
/// </summary>
public class EmitterSetTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    static EmitterSet Load() => LoadScene().Set;

    static (EmitterSet Set, SpectralRenderer.Scenes.Scene Scene) LoadScene()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "triangle.obj"), "v 30 0 0\nv 31 0 0\nv 30 1 0\nf 1 2 3\n");
        File.WriteAllText(Path.Combine(dir, "lamp.ies"), """
            IESNA:LM-63-2002
            [TEST] written by EmitterSetTests
            TILT=NONE
            1 1000 1 3 1 1 2 0.1 0.1 0
            1 1 50
            0 90 180
            0
            100 60 20
            """);
        File.WriteAllText(Path.Combine(dir, "scene.json"), """
            { "radiometry": "physical", "bands": "500:520:20", "background": 0.5,
              "integrator": { "type": "path" },
              "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0] },
              "materials": {
                "white": { "type": "lambertian", "reflectance": 0.5 },
                "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": 2 } } },
              "lights": [
                { "type": "point", "name": "p", "position": [0, 5, 0], "spectrum": "D65" },
                { "type": "spot", "name": "s", "position": [0, 5, 1], "direction": [0, -1, 0], "cutoff": 30, "spectrum": "D65" },
                { "type": "directional", "name": "d", "direction": [0, -1, 0], "spectrum": "D65" },
                { "type": "goniometric", "name": "g", "position": [1, 5, 0], "file": "lamp.ies", "spectrum": "D65" } ],
              "objects": [
                { "type": "sphere", "name": "ball", "center": [0, 0, 10], "radius": 0.5, "material": "lamp" },
                { "type": "sphere", "name": "plain", "center": [0, -3, 0], "radius": 0.5, "material": "white" },
                { "type": "quad", "name": "panel", "center": [10, 0, 0], "size": 1, "normal": [0, 0, 1], "up": [0, 1, 0],
                  "material": "lamp" },
                { "type": "disk", "name": "round", "center": [20, 0, 0], "radius": 0.6, "normal": [0, 0, 1], "up": [0, 1, 0],
                  "material": "lamp" },
                { "type": "mesh", "name": "tri", "file": "triangle.obj", "material": "lamp" } ] }
            """);
        var scene = SceneLoader.Load(Path.Combine(dir, "scene.json"));
        return (new PathIntegrator(scene, new SceneGeometry(scene)).Emitters, scene);
    }

    [Fact]
    public void Every_kind_of_emitter_is_in_the_set_once_in_one_index_space()
    {
        var set = Load();
        Assert.Equal(["point light 'p'", "spot light 's'", "directional light 'd'", "goniometric light 'g'",
            "emitting object 'ball'", "emitting object 'panel'", "emitting object 'round'", "emitting object 'tri'",
            "sky (uniform background)"], set.All.Select(e => e.Describe()));
        // The scene lights keep their index (their transfer slot); objects map to their emitter, a plain object to none.
        Assert.Equal([0, 1, 2, 3, -1, -1, -1, -1, -1], set.All.Select(e => e.SceneLight));
        Assert.Equal([4, -1, 5, 6, 7], Enumerable.Range(0, 5).Select(set.OfObject));
        Assert.Equal(8, set.Sky);
        Assert.Equal([true, true, true, true, false, false, false, false, false], set.All.Select(e => e.IsDelta));
        // A delta light is never met by a direction drawn at random, nor hit by a ray.
        for (int k = 0; k < 4; k++)
        {
            Assert.True(set[k].Sample(Vector3.Zero, Vector3.UnitY, new Vector2(0.3f, 0.7f), out var s), set[k].Describe());
            Assert.True(s.IsDelta);
            Assert.Equal(0f, set[k].Pdf(Vector3.Zero, Vector3.UnitY, s.Direction, default, default));
            Assert.Equal(0f, set[k].Emitted(Vector3.UnitY, -s.Direction));
        }
    }

    [Fact]
    public void Each_emitter_is_chosen_by_its_analytic_power_share_the_scene_lights_uniformly_within_theirs()
    {
        var (set, scene) = LoadScene();
        // Radiant power per unit of the spectrum's integral over the band (500–520 nm), from the scene's numbers: the lamp's
        // L = 2 (flat) on one side of a sphere r 0.5 (4π²r²L), a 1 × 1 quad (πAL), a disk r 0.6, a triangle of area ½;
        // the sky L = 0.5 through the sphere about the finite geometry's box (x −0.5…31, y −3.5…1, z −0.5…10.5): 4π²R²L.
        double r2 = (31.5 * 31.5 + 4.5 * 4.5 + 11.0 * 11.0) / 4;
        double[] objects = [Math.PI * 4 * Math.PI * 0.25 * 2, Math.PI * 1 * 2, Math.PI * Math.PI * 0.36 * 2, Math.PI * 0.5 * 2,
            4 * Math.PI * Math.PI * r2 * 0.5];
        for (int k = 4; k < 9; k++) Assert.Equal(objects[k - 4] * 20, set.Power(k), 1e-4 * set.Power(k));
        // The scene lights (all D65 at scale 1, so I_λ is the same spectrum): 4πI for the point, 2π(1 − cos 30°)·I for the spot
        // of exponent 0, πR²·E for the directional, and the luminaire's ∫I dΩ / (K_m ∫V·S dλ) · I: its table (100, 60, 20 cd at
        // γ 0°, 90°, 180°, linear in γ, one C plane) gives ∫I dΩ = 2π·∫I(γ) sin γ dγ = 2π·120 lm.
        double point = set.Power(0);
        Assert.Equal(2 * Math.PI * (1 - Math.Cos(Math.PI / 6)) / (4 * Math.PI), set.Power(1) / point, 1e-5);
        Assert.Equal(Math.PI * r2 / (4 * Math.PI), set.Power(2) / point, 1e-4);
        double luminous = SpectralRenderer.Color.Photometry.Luminous(scene.Lights[3].Spectrum!);
        Assert.Equal(2 * Math.PI * 120 / luminous / (4 * Math.PI), set.Power(3) / point, 1e-4 * set.Power(3) / point);
        double d65 = scene.Lights[0].Spectrum!.Integrate(500, 520) * scene.Lights[0].Scale;   // ∫I dλ over the band
        Assert.Equal(4 * Math.PI * d65, point, 1e-5 * point);

        // P(k): the 4 lights 1/9 each; the 5 other emitters share 5/9 by power.
        double total = objects.Sum();
        for (int k = 0; k < 4; k++) Assert.Equal(1.0 / 9, set.SelectionPdf(k, default, default), 1e-7);
        for (int k = 4; k < 9; k++)
        {
            double expected = 5.0 / 9 * objects[k - 4] / total;
            output.WriteLine($"{set[k].Describe()}: P {set.SelectionPdf(k, default, default):G6}, analytic power share {expected:G6}");
            Assert.Equal(expected, set.SelectionPdf(k, default, default), 1e-6 * expected + 1e-9);
        }
        // Choose takes each emitter with its P(k): the fraction of a sub-band grid of u that lands on it.
        const int m = 1 << 20;
        var counts = new int[9];
        for (int i = 0; i < m; i++) counts[set.Choose(default, default, (i + 0.5f) / m, out _)]++;
        for (int k = 0; k < 9; k++) Assert.Equal(set.SelectionPdf(k, default, default), counts[k] / (double)m, 2.0 / m + 1e-6);
        Assert.Equal(8, set.Choose(default, default, 0.99999994f, out _));
    }

    /// <summary>
    /// Next-event estimation of the irradiance at a floor point under a strong and a weak emitting sphere, the emitter chosen
    /// by the set (by power) and, the same samples otherwise, uniformly (P = ½): both agree with the closed form
    /// Σ πL·(r/d)²·cos θ (each sphere wholly above the floor's plane) within 3σ, and the choice by power has the smaller variance.
    /// </summary>
    [Fact]
    public void Choosing_by_power_keeps_the_expectation_and_lowers_the_variance()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "scene.json"), """
            { "radiometry": "physical", "bands": "500:520:20", "integrator": "path",
              "camera": { "position": [0, 1, 5], "look_at": [0, 0, 0] },
              "materials": {
                "white": { "type": "lambertian", "reflectance": 0.5 },
                "strong": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": 50 } },
                "weak": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": 0.5 } } },
              "objects": [
                { "type": "quad", "name": "floor", "center": [0, 0, 0], "size": 4, "normal": [0, 1, 0], "up": [0, 0, -1],
                  "material": "white" },
                { "type": "sphere", "name": "strong", "center": [1, 2, 0], "radius": 0.25, "material": "strong" },
                { "type": "sphere", "name": "weak", "center": [-1, 1, 0.5], "radius": 0.5, "material": "weak" } ] }
            """);
        var scene = SceneLoader.Load(Path.Combine(dir, "scene.json"));
        var set = new PathIntegrator(scene, new SceneGeometry(scene)).Emitters;
        Assert.Equal(2, set.Count);
        var p = Vector3.Zero;
        var n = Vector3.UnitY;
        // E = πL (r/d)² cos θ per sphere: cos θ = y/d of its centre.
        static double Sphere(double l, double r, double x, double y, double z)
        {
            double d2 = x * x + y * y + z * z;
            return Math.PI * l * r * r / d2 * (y / Math.Sqrt(d2));
        }
        double exact = Sphere(50, 0.25, 1, 2, 0) + Sphere(0.5, 0.5, -1, 1, 0.5);
        // P(strong) = Φ share: 4π²r²L, 50·0.0625 against 0.5·0.25.
        Assert.Equal(50 * 0.0625 / (50 * 0.0625 + 0.5 * 0.25), set.SelectionPdf(0, default, default), 1e-6);
        const int samples = 100_000;
        var rng = new Random(5);
        double[] sum = new double[2], sum2 = new double[2];
        for (int i = 0; i < samples; i++)
        {
            float u = rng.NextSingle();
            var v = new Vector2(rng.NextSingle(), rng.NextSingle());
            for (int way = 0; way < 2; way++)
            {
                int k = way == 0 ? set.Choose(default, default, u, out _) : Math.Min((int)(u * 2), 1);
                double pick = way == 0 ? set.SelectionPdf(k, default, default) : 0.5;
                double value = 0;
                if (set[k].Sample(p, n, v, out var s))
                    value = set[k].Radiance[0] * Math.Max(0, Vector3.Dot(n, s.Direction)) / (pick * s.Pdf);
                sum[way] += value; sum2[way] += value * value;
            }
        }
        var mean = new double[2];
        var variance = new double[2];
        for (int way = 0; way < 2; way++)
        {
            mean[way] = sum[way] / samples;
            variance[way] = sum2[way] / samples - mean[way] * mean[way];
            double sigma = Math.Sqrt(variance[way] / samples);
            output.WriteLine($"{(way == 0 ? "by power" : "uniform")}: E {mean[way]:G6} ± {sigma:E2} (exact {exact:G6}), "
                + $"variance per sample {variance[way]:G4}");
            Assert.InRange(mean[way], exact - 3 * sigma, exact + 3 * sigma);
        }
        output.WriteLine($"variance ratio uniform / by power: {variance[1] / variance[0]:G4}");
        Assert.True(variance[0] < variance[1] / 4, $"by power {variance[0]:G4} against uniform {variance[1]:G4}");
    }

    /// <summary>tan(Ω/2) = |a·(b×c)| / (abc + (a·b)c + (a·c)b + (b·c)a) (Van Oosterom and Strackee 1983).</summary>
    static double TriangleSolidAngle(Vector3 p, Vector3 v0, Vector3 v1, Vector3 v2)
    {
        Vector3 a = v0 - p, b = v1 - p, c = v2 - p;
        double la = a.Length(), lb = b.Length(), lc = c.Length();
        double numerator = Math.Abs(Vector3.Dot(a, Vector3.Cross(b, c)));
        double denominator = la * lb * lc + Vector3.Dot(a, b) * lc + Vector3.Dot(a, c) * lb + Vector3.Dot(b, c) * la;
        return 2 * Math.Atan2(numerator, denominator);
    }

    public static TheoryData<int, double, double, double, double> Emitters => new()
    {
        // emitter, p (x, y, z), Ω
        { 4, 0, 0, 7, 2 * Math.PI * (1 - Math.Sqrt(1 - 0.25 / 9)) },                 // sphere r 0.5 at distance 3: its cone
        // 1 × 1 square at h 2 on its axis: 4·asin(ab/√((a² + 4h²)(b² + 4h²)))
        { 5, 10, 0, 2, 4 * Math.Asin(1.0 / 17) },
        { 6, 20, 0, 1.5, 2 * Math.PI * (1 - 1.5 / Math.Sqrt(1.5 * 1.5 + 0.36)) },     // disk r 0.6 at h 1.5 on its axis
        { 7, 30.2, 0.3, 1, TriangleSolidAngle(new(30.2f, 0.3f, 1), new(30, 0, 0), new(31, 0, 0), new(30, 1, 0)) },
        { 8, 0, 0, 0, 2 * Math.PI },                                                   // the sky: the hemisphere about n
    };

    [Theory]
    [MemberData(nameof(Emitters))]
    public void An_emitters_pdf_is_the_density_of_its_own_sample(int k, double x, double y, double z, double solidAngle)
    {
        var emitter = Load()[k];
        var p = new Vector3((float)x, (float)y, (float)z);
        var front = Vector3.UnitZ;   // the sky's hemisphere; every other emitter is straight above or below p
        var rng = new Random(11 + k);
        const int n = 200_000;
        double sum = 0, sum2 = 0, cosSum = 0, cosSum2 = 0;
        for (int i = 0; i < n; i++)
        {
            if (!emitter.Sample(p, front, new Vector2(rng.NextSingle(), rng.NextSingle()), out var s)) continue;
            float pdf = emitter.Pdf(p, front, s.Direction, s.Point, s.Normal);
            Assert.Equal(s.Pdf, pdf, 1e-4f * s.Pdf);
            Assert.Equal(1f, emitter.Emitted(s.Normal, -s.Direction));
            double inverse = 1.0 / pdf;
            sum += inverse; sum2 += inverse * inverse;
            double projected = Math.Abs(Vector3.Dot(front, s.Direction)) * inverse;   // |cos θ| about the z axis
            cosSum += projected; cosSum2 += projected * projected;
        }
        double mean = sum / n, sigma = Math.Sqrt(Math.Max(0, sum2 / n - mean * mean) / n);
        output.WriteLine($"{emitter.Describe()}: Ω {mean:G6} ± {sigma:E2} sr, closed form {solidAngle:G6} sr");
        // 3σ, and float rounding where every sample gives Ω exactly (a sphere's cone)
        Assert.InRange(mean, solidAngle - 3 * sigma - 1e-5 * solidAngle, solidAngle + 3 * sigma + 1e-5 * solidAngle);
        if (k == 6)
        {   // the disk's irradiance per unit radiance on its axis: π·r²/(r² + h²)
            double formFactor = Math.PI * 0.36 / (0.36 + 1.5 * 1.5), cosMean = cosSum / n;
            double cosSigma = Math.Sqrt(Math.Max(0, cosSum2 / n - cosMean * cosMean) / n);
            Assert.InRange(cosMean, formFactor - 3 * cosSigma, formFactor + 3 * cosSigma);
        }
        if (k == 8) Assert.Equal(Math.PI, cosSum / n, 1e-4);   // the sky's cosine draw: ∫cos dω/p = π for every sample
    }
}
