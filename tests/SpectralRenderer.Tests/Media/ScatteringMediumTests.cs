using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// The path tracer's transport through a scattering homogeneous medium (Rendering/PathTracing/PathIntegrator.Media.cs:
/// spectral tracking against one majorant for every band, a phase-function vertex with next-event estimation and MIS),
/// each band against an independent reference: the furnace, an analog random walk written here, and the closed form of
/// single scattering in a half-space. The three bands have σ_t = 1, 2, 3 per unit (one sub-band each), so the majorant
/// σ̄ = 3 makes null collisions in two of them: every band must stay unbiased although all share one free flight.
/// </summary>
public class ScatteringMediumTests(Xunit.Abstractions.ITestOutputHelper output)
{
    const string Bands = "\"bands\": \"400:700:3\"";
    static string Integrator(int maxDepth = -1) =>
        $"\"integrator\": {{ \"type\": \"path\", \"spectral_grid\": 100, \"rr_depth\": 1000, \"sampler\": "
            + $"\"independent\", \"max_depth\": {maxDepth} }}";
    // σ_t(λ) = 0.5 + 0.01·(λ − 400): linear, so a 100 nm band's mean is its centre's value, 1, 2 and 3 per unit.
    const string SigmaT = "[[400, 0.5], [700, 3.5]]";
    static readonly double[] SigmaTBands = [1, 2, 3];
    const double Le = 2;

    /// <summary>
    /// A black sphere of radius 1 about the camera whose inside emits L_e, in a medium everywhere (the scene's): an infinite
    /// medium seen from inside a closed emitting boundary, index-matched (the sphere is no medium boundary).
    /// </summary>
    static Scene Furnace(string albedo, double g) => SceneText.Load($$"""
        { "radiometry": "physical", {{Bands}}, {{Integrator()}},
          "medium": { "albedo": {{albedo}}, "sigma_t": {{SigmaT}}, "phase": { "type": "hg", "g": {{g}} } },
          "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1] },
          "materials": { "wall": { "type": "lambertian", "reflectance": 0,
                                   "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": {{Le}}, "two_sided": true } } },
          "objects": [ { "type": "sphere", "radius": 1, "material": "wall" } ] }
        """);

    static readonly Ray Centre = new(Vector3.Zero, Vector3.Normalize(new Vector3(0.3f, 0.1f, 1)));

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.7)]
    [InlineData(-0.4)]
    public void A_white_medium_inside_an_emitting_boundary_is_a_furnace_L_e_in_every_band(double g)
    {
        var (seen, error) = PathIntegratorTests.Estimate(Furnace("1", g), Centre, 20000);
        for (int b = 0; b < 3; b++)
        {
            output.WriteLine($"g = {g}, band {b} (σ_t = {SigmaTBands[b]}): {seen[b]:g6} ± {error[b]:g3} vs L_e = {Le}");
            Assert.True(Math.Abs(seen[b] - Le) <= Math.Max(3 * error[b], 1e-5 * Le), $"band {b}: {seen[b]} ± {error[b]}");
        }
    }

    /// <summary>
    /// Albedo α &lt; 1: L = L_e·E[α^N], N the number of real collisions before a walk from the centre leaves the sphere
    /// (the boundary emits L_e, the medium absorbs 1 − α at each collision). The reference is an analog random walk written
    /// here (exponential flights of rate σ_t, directions by its own inversion of the Henyey–Greenstein CDF), per band.
    /// </summary>
    [Theory]
    [InlineData(0.0)]
    [InlineData(0.6)]
    public void An_absorbing_scattering_medium_inside_an_emitting_boundary_matches_an_analog_random_walk(double g)
    {
        const double alpha = 0.8;
        var (seen, error) = PathIntegratorTests.Estimate(Furnace($"{alpha}", g), Centre, 20000);
        for (int b = 0; b < 3; b++)
        {
            var (reference, referenceError) = AnalogWalk(SigmaTBands[b], alpha, g, 200_000, seed: 7 + b);
            double combined = Math.Sqrt(error[b] * error[b] + referenceError * referenceError);
            output.WriteLine($"g = {g}, band {b}: {seen[b]:g6} ± {error[b]:g3} vs analog walk {reference:g6} ± {referenceError:g3}");
            Assert.True(Math.Abs(seen[b] - reference) <= 3 * combined, $"band {b}: {seen[b]} vs {reference}, σ = {combined}");
            Assert.True(reference < 0.95 * Le);   // the albedo matters here: the case is not the furnace
        }
    }

    /// <summary>L_e·α^N from the centre of the unit sphere along <see cref="Centre"/>'s direction, analog: mean and its error.</summary>
    static (double Mean, double Error) AnalogWalk(double sigmaT, double alpha, double g, int n, int seed)
    {
        var random = new Random(seed);
        double sum = 0, sum2 = 0;
        var start = Vector3.Normalize(new Vector3(0.3f, 0.1f, 1));
        for (int i = 0; i < n; i++)
        {
            double x = 0, y = 0, z = 0, dx = start.X, dy = start.Y, dz = start.Z, weight = Le;
            for (; ; )
            {
                double s = -Math.Log(1 - random.NextDouble()) / sigmaT;
                // distance to the unit sphere along d from inside: −b + √(b² − c), b = x·d, c = |x|² − 1
                double bb = x * dx + y * dy + z * dz, c = x * x + y * y + z * z - 1, exit = -bb + Math.Sqrt(bb * bb - c);
                if (s >= exit) break;
                x += s * dx; y += s * dy; z += s * dz;
                weight *= alpha;
                // cos θ of Henyey–Greenstein by inverting its CDF: μ = (1 + g² − ((1 − g²)/(1 + g − 2g·ξ))²)/(2g)
                double xi = random.NextDouble(), mu;
                if (Math.Abs(g) < 1e-6) mu = 2 * xi - 1;
                else
                {
                    double k = (1 - g * g) / (1 + g - 2 * g * xi);
                    mu = (1 + g * g - k * k) / (2 * g);
                }
                double phi = 2 * Math.PI * random.NextDouble(), sin = Math.Sqrt(Math.Max(0, 1 - mu * mu));
                // a frame about d: any unit vector orthogonal to d, and d × it
                double ax = Math.Abs(dx) < 0.9 ? 1 : 0, ay = ax == 1 ? 0 : 1;
                double tx = dy * 0 - dz * ay, ty = dz * ax - dx * 0, tz = dx * ay - dy * ax;
                double tl = Math.Sqrt(tx * tx + ty * ty + tz * tz);
                tx /= tl; ty /= tl; tz /= tl;
                double ux = dy * tz - dz * ty, uy = dz * tx - dx * tz, uz = dx * ty - dy * tx;
                double nx = mu * dx + sin * (Math.Cos(phi) * tx + Math.Sin(phi) * ux);
                double ny = mu * dy + sin * (Math.Cos(phi) * ty + Math.Sin(phi) * uy);
                double nz = mu * dz + sin * (Math.Cos(phi) * tz + Math.Sin(phi) * uz);
                double nl = Math.Sqrt(nx * nx + ny * ny + nz * nz);
                dx = nx / nl; dy = ny / nl; dz = nz / nl;
            }
            sum += weight; sum2 += weight * weight;
        }
        double mean = sum / n;
        return (mean, Math.Sqrt(Math.Max(0, sum2 / n - mean * mean) / (n - 1)));
    }

    /// <summary>
    /// Single scattering in a half-space. A Lambertian emitter of radiance L_e fills the plane z = 0 and faces +z; an isotropic
    /// medium (σ_t, σ_s = α·σ_t, p = 1/4π) fills the space; the ray starts on the plane and looks along +z, so it sees the
    /// emitter only through light scattered once towards it. At depth s the unscattered radiance from the plane along a
    /// direction of cosine μ to its normal is L_e·exp(−σ_t·s/μ), so the in-scattered source is
    ///   J(s) = σ_s·∫p·L dω = σ_s·(1/4π)·2π·∫₀¹ L_e·e^{−σ_t s/μ} dμ = (σ_s·L_e/2)·E₂(σ_t·s)   (E_n the exponential integral),
    /// and the radiance along the ray
    ///   L = ∫₀^∞ e^{−σ_t s}·J(s) ds = (α·L_e/2)·∫₀^∞ e^{−x}·E₂(x) dx = (α·L_e/2)·∫₁^∞ dt/(t²(1 + t))
    ///     = (α·L_e/2)·[ln((1 + t)/t) − 1/t]₁^∞ = α·L_e·(1 − ln 2)/2,
    /// using ∫₀^∞ e^{−x}·e^{−xt} dx = 1/(1 + t) and 1/(t²(1 + t)) = 1/t² − 1/t + 1/(1 + t). max_depth 1 keeps single
    /// scattering only (next-event estimation at the first vertex and its phase sample, MIS-weighted). The emitter is a
    /// 40 × 40 quad and σ_t = 1: what lies beyond it is attenuated by e^{−20} at least.
    /// </summary>
    [Fact]
    public void Single_scattering_in_a_half_space_lit_by_its_emitting_plane_is_alpha_L_e_one_minus_ln2_over_2()
    {
        var scene = SceneText.Load($$"""
            { "radiometry": "physical", {{Bands}}, {{Integrator(maxDepth: 1)}},
              "medium": { "albedo": [[400, 0.2], [700, 0.8]], "sigma_t": 1 },
              "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0] },
              "materials": { "lamp": { "type": "lambertian", "reflectance": 0,
                                       "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": {{Le}} } } },
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 40, "normal": [0, 0, 1], "material": "lamp" } ] }
            """);
        var ray = new Ray(new Vector3(0.1f, 0.2f, 1e-4f), Vector3.UnitZ);
        var (seen, error) = PathIntegratorTests.Estimate(scene, ray, 200_000);
        double[] albedo = [0.3, 0.5, 0.7];   // band means of the linear α(λ)
        for (int b = 0; b < 3; b++)
        {
            double expected = albedo[b] * Le * (1 - Math.Log(2)) / 2;
            output.WriteLine($"band {b}: {seen[b]:g6} ± {error[b]:g3} vs α·L_e·(1 − ln 2)/2 = {expected:g6}");
            Assert.True(Math.Abs(seen[b] - expected) <= 3 * error[b] + 1e-4 * expected, $"band {b}: {seen[b]} ± {error[b]} vs {expected}");
            Assert.True(error[b] < 0.01 * expected);   // tight enough to tell the closed form from a neighbour
        }
    }
}
