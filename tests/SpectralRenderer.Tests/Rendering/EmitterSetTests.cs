using System.Globalization;
using System.Numerics;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Rendering;
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

    static EmitterSet Load()
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
        return new PathIntegrator(scene, new SceneGeometry(scene)).Emitters;
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
        // Uniform choice: P(k) = 1/N and Choose covers each index with its share of [0, 1).
        Assert.All(Enumerable.Range(0, 9), k => Assert.Equal(1f / 9, set.SelectionPdf(k)));
        Assert.Equal(Enumerable.Range(0, 9), Enumerable.Range(0, 9).Select(k => set.Choose((k + 0.5f) / 9)));
        Assert.Equal(8, set.Choose(0.99999994f));
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
