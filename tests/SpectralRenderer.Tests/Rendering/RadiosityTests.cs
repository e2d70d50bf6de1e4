using System.Globalization;
using System.Numerics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// An independent method (issue 23): a closed unit box of Lambertian walls (a reflectance per wall and band, the ceiling
/// emitting L_e downwards) solved by radiosity here — 8 × 8 patches per wall, patch-to-patch form factors from the exact
/// differential-area-to-polygon formula (Lambert; Hottel &amp; Sarofim) averaged over 3 × 3 points of the patch, the system
/// L_i = L_e,i + ρ_i Σ_j F_ij L_j solved by iteration — then the radiance at a point gathered once more with the exact
/// point-to-patch form factors. The path tracer's converged radiance at that point agrees per band within 1 %.
/// </summary>
public class RadiosityTests(Xunit.Abstractions.ITestOutputHelper output)
{
    // Walls: (name, centre, inward normal, two in-plane axes), reflectance in band 0 (400–550 nm) and band 1 (550–700 nm).
    static readonly (string Name, Vector3 Centre, Vector3 Normal, Vector3 U, Vector3 V, double Rho0, double Rho1)[] Walls =
    [
        ("floor", new(0.5f, 0, 0.5f), Vector3.UnitY, Vector3.UnitX, Vector3.UnitZ, 0.7, 0.4),
        ("ceiling", new(0.5f, 1, 0.5f), -Vector3.UnitY, Vector3.UnitX, Vector3.UnitZ, 0.6, 0.6),
        ("left", new(0, 0.5f, 0.5f), Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, 0.2, 0.8),
        ("right", new(1, 0.5f, 0.5f), -Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, 0.8, 0.3),
        ("back", new(0.5f, 0.5f, 0), Vector3.UnitZ, Vector3.UnitX, Vector3.UnitY, 0.5, 0.5),
        ("front", new(0.5f, 0.5f, 1), -Vector3.UnitZ, Vector3.UnitX, Vector3.UnitY, 0.5, 0.7),
    ];
    const double Emitted = 1;   // the ceiling's L_e in both bands

    /// <summary>The form factor from a differential area at x (unit normal n) to the polygon: (1/2π)|Σ_k γ_k n·(R_k × R_k+1)/|R_k ×
    /// R_k+1||.</summary>
    static double PointToPolygon(Vector3 x, Vector3 n, ReadOnlySpan<Vector3> polygon)
    {
        double sum = 0;
        for (int k = 0; k < polygon.Length; k++)
        {
            var a = Vector3.Normalize(polygon[k] - x);
            var b = Vector3.Normalize(polygon[(k + 1) % polygon.Length] - x);
            var c = Vector3.Cross(a, b);
            double len = c.Length();
            if (len < 1e-12) continue;
            double gamma = Math.Atan2(len, Vector3.Dot(a, b));
            sum += gamma * Vector3.Dot(n, c) / len;
        }
        return Math.Abs(sum) / (2 * Math.PI);
    }

    sealed record Patch(int Wall, Vector3 Centre, Vector3 Normal, Vector3[] Corners, Vector3[] Points);

    static List<Patch> Patches(int n, int q)
    {
        var patches = new List<Patch>();
        for (int w = 0; w < Walls.Length; w++)
        {
            var (_, c, normal, u, v, _, _) = Walls[w];
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                {
                    Vector3 At(double s, double t) => c + (float)(s - 0.5) * u + (float)(t - 0.5) * v;
                    double s0 = (double)i / n, t0 = (double)j / n, h = 1.0 / n;
                    var corners = new[] { At(s0, t0), At(s0 + h, t0), At(s0 + h, t0 + h), At(s0, t0 + h) };
                    var points = new Vector3[q * q];
                    for (int a = 0; a < q; a++)
                        for (int b = 0; b < q; b++) points[a * q + b] = At(s0 + (a + 0.5) * h / q, t0 + (b + 0.5) * h / q);
                    patches.Add(new Patch(w, At(s0 + h / 2, t0 + h / 2), normal, corners, points));
                }
        }
        return patches;
    }

    /// <summary>The radiance leaving point x (on wall w) per band by radiosity with a final gather.</summary>
    static double[] Radiosity(Vector3 x, int wall)
    {
        var patches = Patches(8, 3);
        int m = patches.Count;
        var f = new double[m, m];
        for (int i = 0; i < m; i++)
            for (int j = 0; j < m; j++)
            {
                if (patches[i].Wall == patches[j].Wall) continue;
                double s = 0;
                foreach (var p in patches[i].Points) s += PointToPolygon(p, patches[i].Normal, patches[j].Corners);
                f[i, j] = s / patches[i].Points.Length;
            }
        var result = new double[2];
        for (int band = 0; band < 2; band++)
        {
            double Rho(int w) => band == 0 ? Walls[w].Rho0 : Walls[w].Rho1;
            double Le(int w) => Walls[w].Name == "ceiling" ? Emitted : 0;
            var l = new double[m];
            for (int it = 0; it < 500; it++)
            {
                var next = new double[m];
                for (int i = 0; i < m; i++)
                {
                    double g = 0;
                    for (int j = 0; j < m; j++) g += f[i, j] * l[j];
                    next[i] = Le(patches[i].Wall) + Rho(patches[i].Wall) * g;
                }
                l = next;
            }
            double gather = 0;
            for (int j = 0; j < m; j++)
                if (patches[j].Wall != wall) gather += PointToPolygon(x, Walls[wall].Normal, patches[j].Corners) * l[j];
            result[band] = Le(wall) + Rho(wall) * gather;
        }
        return result;
    }

    static string Step(double a, double b) =>
        string.Create(CultureInfo.InvariantCulture, $"[[400, {a}], [549.995, {a}], [550.005, {b}], [700, {b}]]");

    [Fact]
    public void Path_traced_radiance_in_a_closed_Lambertian_box_matches_a_radiosity_solution_per_band()
    {
        var materials = string.Join(",\n", Walls.Select(w =>
            $$"""    "{{w.Name}}": { "type": "lambertian", "reflectance": {{Step(w.Rho0, w.Rho1)}}""" +
                $$"""{{(w.Name == "ceiling" ? $", \"emission\": {{ \"spectrum\": {Emitted} }}" : "")}} }"""));
        var objects = string.Join(",\n", Walls.Select(w =>
            string.Create(CultureInfo.InvariantCulture,
                $$"""    { "type": "quad", "name": "{{w.Name}}", "center": [{{w.Centre.X}}, {{w.Centre.Y}}, {{w.Centre.Z}}],""" +
                    $$""" "size": [1, 1], "normal": [{{w.Normal.X}}, {{w.Normal.Y}}, {{w.Normal.Z}}],""" +
                    $$""" "up": [{{w.V.X}}, {{w.V.Y}}, {{w.V.Z}}], "material": "{{w.Name}}" }""")));
        var scene = SceneText.Load($$"""
        { "radiometry": "physical", "bands": "400:700:2", "integrator": { "type": "path", "rr_depth": 40 },
          "camera": { "position": [0.5, 0.5, 0.5], "look_at": [0.3, 0, 0.6], "width": 8, "height": 8 },
          "materials": {
        {{materials}} },
          "objects": [
        {{objects}} ] }
        """);
        // A floor point and a left-wall point, seen from the box's centre.
        foreach (var (point, wall) in new[] { (new Vector3(0.3f, 0, 0.6f), 0), (new Vector3(0, 0.35f, 0.25f), 2) })
        {
            var origin = new Vector3(0.5f, 0.5f, 0.5f);
            var (mean, error) = PathIntegratorTests.Estimate(scene, new Ray(origin, Vector3.Normalize(point - origin)), 20_000);
            var expected = Radiosity(point, wall);
            for (int b = 0; b < 2; b++)
                output.WriteLine($"{Walls[wall].Name} band {b}: path {mean[b]:F5} ± {error[b]:g2}, radiosity {expected[b]:F5}, "
                    + $"{mean[b] / expected[b] - 1:+0.0000;-0.0000} relative");
            for (int b = 0; b < 2; b++)
                Assert.True(Math.Abs(mean[b] / expected[b] - 1) < 0.01,
                    $"{Walls[wall].Name} band {b}: path {mean[b]:F5} ± {error[b]:g2} vs radiosity {expected[b]:F5}");
        }
    }
}
