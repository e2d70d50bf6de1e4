using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 26: the path integrator's fluorescence from indirect light (PathIntegrator.Fluorescence.cs). A white furnace — a
/// closed sphere whose inside emits L_e and reflects with a Lambertian diagonal R plus a re-radiation S — holds one uniform
/// radiance L with L = L_e + R·L + S·L per band (the irradiance of a uniform radiance L is π·L, and the shifted lobe S/π
/// returns S·L), so L = (I − R − S)⁻¹·L_e: solved here by Gaussian elimination on the matrix written to the CSV, with the
/// render's bands the matrix's 5 nm cells (then the engine's band matrix is S itself). And the photon balance of a column
/// of unit quantum yield: in a furnace lit only in that excitation band, every other band's light is re-emitted light, so
/// the photons the walls absorb in the other bands equal those they absorb in the excitation band.
/// </summary>
public sealed class FluorescentPathTests(Xunit.Abstractions.ITestOutputHelper output) : IDisposable
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    readonly string _dir = Directory.CreateTempSubdirectory("fluorescent-path-").FullName;

    public void Dispose() => Directory.Delete(_dir, true);

    static double[] Cells => FluorescenceTests.Cells;   // 302.5 … 777.5 nm, the 5 nm bands of 300:780:96
    static int N => Cells.Length;

    string WriteCsv(string file, double[] d)
    {
        var path = Path.Combine(_dir, file);
        File.WriteAllText(path, FluorescenceTests.MatrixCsv(Cells, d));
        return path.Replace("\\", "/");
    }

    static Scene Furnace(string matrix, string emission, bool glass = false) => SceneText.Load($$"""
        { "radiometry": "physical", "bands": "300:780:96", "white": "D50", "integrator": { "type": "path" },
          "camera": { "position": [0, 0, 0], "look_at": [0, 0, -1], "width": 8, "height": 8 },
          "materials": { "wall": { "type": "lambertian", "fluorescence": { "matrix": "{{matrix}}" },
                                   "emission": { "spectrum": {{emission}}, "radiance": 1, "two_sided": true } }{{(glass ? Glass : "")}} },
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wall" }{{(glass ? Ball : "")}} ] }
        """);

    // A lossless dispersive glass ball (k_r = k_t = 1 with Fresnel: R + T = 1 in every band, Cauchy n = 1.5 + 20000 nm²/λ²)
    // inside the furnace, across the camera ray Inside: it neither absorbs nor emits, so the furnace's uniform radiance
    // (I − R − S)⁻¹·L_e is unchanged, however a path splits at it into bands and takes shifted bounces on either side.
    const string Glass = """, "glass": { "diffuse": 0, "ambient": 0, "mirror": 1, "transmit": 1, "fresnel": true, """
        + """ "ior": { "cauchy": [1.5, 20000] } }""";
    const string Ball = """, { "type": "sphere", "center": [0.32, -0.24, 0.41], "radius": 0.35, "material": "glass" }""";

    static readonly Ray Inside = new(new Vector3(0.1f, 0.2f, 0.3f), Vector3.Normalize(new Vector3(1, -2, 0.5f)));

    /// <summary>x with A·x = b, by Gaussian elimination with partial pivoting (A row-major, n × n).</summary>
    internal static double[] Solve(double[] a, double[] b)
    {
        int n = b.Length;
        a = (double[])a.Clone();
        b = (double[])b.Clone();
        for (int c = 0; c < n; c++)
        {
            int p = c;
            for (int r = c + 1; r < n; r++) if (Math.Abs(a[r * n + c]) > Math.Abs(a[p * n + c])) p = r;
            for (int k = 0; k < n; k++) (a[c * n + k], a[p * n + k]) = (a[p * n + k], a[c * n + k]);
            (b[c], b[p]) = (b[p], b[c]);
            for (int r = c + 1; r < n; r++)
            {
                double f = a[r * n + c] / a[c * n + c];
                if (f == 0) continue;
                for (int k = c; k < n; k++) a[r * n + k] -= f * a[c * n + k];
                b[r] -= f * b[c];
            }
        }
        var x = new double[n];
        for (int r = n - 1; r >= 0; r--)
        {
            double s = b[r];
            for (int k = r + 1; k < n; k++) s -= a[r * n + k] * x[k];
            x[r] = s / a[r * n + r];
        }
        return x;
    }

    [Fact]
    public void A_fluorescent_white_furnace_converges_to_the_linear_solution_of_re_radiation_and_reflection()
    {
        // The brightener of FluorescenceTests on a flat diagonal R = 0.5: D[o, i] = q·a_i·λi·p_o/λo for λo > λi (Stokes),
        // a_i = 0.9·G(λi; 365, 15), p ∝ G(λo; 440, 18), q = 0.55 (photons: q·a_i ≤ 0.495 < 1 − R).
        const double r = 0.5, q = 0.55;
        var p = Cells.Select(l => FluorescenceTests.Gauss(l, 440, 18)).ToArray();
        double sum = p.Sum();
        var d = new double[N * N];
        for (int i = 0; i < N; i++)
        {
            d[i * N + i] = r;
            double a = 0.9 * FluorescenceTests.Gauss(Cells[i], 365, 15);
            for (int o = i + 1; o < N; o++) d[o * N + i] = q * a * Cells[i] * (p[o] / sum) / Cells[o];
        }
        // L_e is linear in λ: its 5 nm band means are its values at the band centres.
        CheckFurnace("brightener", d, r, "[[300, 1], [780, 2]]", Cells.Select(l => 1 + (l - 300) / 480).ToArray());
    }

    [Fact]
    public void A_furnace_of_a_two_step_cascade_needs_nested_shifted_bounces_and_converges_too()
    {
        // R = 0.3; band a (347.5 nm) re-emits 90 % of its absorbed photons into band b (452.5 nm), b 90 % of its into c
        // (602.5 nm); the walls emit only in a (a triangle within it, band mean 0.5). Light reaches c only by two
        // re-emissions, and the part excited by a's indirect light (R of L_a) only through two shifted bounces of one path.
        const double r = 0.3, yield = 0.9;
        const int a = 9, b = 30, c = 60;
        var d = new double[N * N];
        for (int i = 0; i < N; i++) d[i * N + i] = r;
        d[b * N + a] = yield * (1 - r) * Cells[a] / Cells[b];
        d[c * N + b] = yield * (1 - r) * Cells[b] / Cells[c];
        var le = new double[N];
        le[a] = 0.5;
        string emission = string.Create(Inv, $"[[300, 0], [{Cells[a] - 2.5}, 0], [{Cells[a]}, 1], [{Cells[a] + 2.5}, 0], [780, 0]]");
        var mean = CheckFurnace("cascade", d, r, emission, le);
        Assert.True(mean[c] > 0.05, "light reaches the cascade's last band");
    }

    /// <summary>
    /// The two-step cascade's furnace with a lossless dispersive glass ball across the camera ray: every camera path splits
    /// into one sub-path per band at the ball, sub-paths take shifted bounces (their light then at the excitation bands,
    /// at the ball again one band drawn), and paths split after shifted bounces — the furnace's solution all the same.
    /// </summary>
    [Fact]
    [Trait("Category", "Slow")]   // ~10 s (90 s with SIMD off): the default run only
    public void A_furnace_of_the_cascade_with_a_dispersive_glass_ball_converges_to_the_same_solution()
    {
        const double r = 0.3, yield = 0.9;
        const int a = 9, b = 30, c = 60;
        var d = new double[N * N];
        for (int i = 0; i < N; i++) d[i * N + i] = r;
        d[b * N + a] = yield * (1 - r) * Cells[a] / Cells[b];
        d[c * N + b] = yield * (1 - r) * Cells[b] / Cells[c];
        var le = new double[N];
        le[a] = 0.5;
        string emission = string.Create(Inv, $"[[300, 0], [{Cells[a] - 2.5}, 0], [{Cells[a]}, 1], [{Cells[a] + 2.5}, 0], [780, 0]]");
        var mean = CheckFurnace("dispersive-cascade", d, r, emission, le, glass: true);
        Assert.True(mean[c] > 0.05, "light reaches the cascade's last band");
    }

    /// <summary>The furnace of matrix <paramref name="d"/> against (I − D)⁻¹·L_e per band, within 4 standard errors (+1e-5).</summary>
    double[] CheckFurnace(string label, double[] d, double r, string emission, double[] le, bool glass = false)
    {
        var scene = Furnace(WriteCsv($"{label}.csv", d), emission, glass);
        Assert.Equal(glass, scene.Materials.Any(m => m.Dispersive));
        var a2 = new double[N * N];
        for (int k = 0; k < N * N; k++) a2[k] = (k % (N + 1) == 0 ? 1 : 0) - d[k];
        var expected = Solve(a2, le);
        // What next-event excitation alone gave (before this issue): L = (I − R)⁻¹·(L_e + S·L_e), S the off-diagonal part.
        var old = new double[N];
        for (int o = 0; o < N; o++)
        {
            double s = le[o];
            for (int i = 0; i < N; i++) if (i != o) s += d[o * N + i] * le[i];
            old[o] = s / (1 - r);
        }
        var (mean, error) = PathIntegratorTests.Estimate(scene, Inside, 20_000);
        double worst = 0, separation = 0;
        int peak = Array.IndexOf(expected, expected.Max());
        for (int b = 0; b < N; b++)
        {
            double allowed = 4 * error[b] + 1e-5 * expected[b];
            if (error[b] > 0)
            {
                worst = Math.Max(worst, Math.Abs(mean[b] - expected[b]) / error[b]);
                separation = Math.Max(separation, Math.Abs(expected[b] - old[b]) / error[b]);
            }
            Assert.True(Math.Abs(mean[b] - expected[b]) <= allowed,
                $"{label}, band {Cells[b]} nm: {mean[b]:F5} vs (I − R − S)⁻¹·L_e = {expected[b]:F5} (±{error[b]:g2}); "
                    + $"next-event excitation only: {old[b]:F5}");
        }
        output.WriteLine(
            $"{label} furnace: largest |path − solution| {worst:F2} standard errors; at {Cells[peak]} nm path {mean[peak]:F4} ± " +
            $"{error[peak]:F4}, solution {expected[peak]:F4}, next-event excitation only {old[peak]:F4} (up to "
                + $"{separation:F0} standard errors away)");
        Assert.True(separation > 20, "the test must tell indirect excitation from its absence");
        return mean;
    }

    [Fact]
    public void A_furnace_of_a_bright_brightened_paper_converges_with_every_path_bounded_by_its_vertex_count()
    {
        // An optically brightened paper: reflective diagonal 0.9 but for an absorption dip around 365 nm, whose absorbed
        // photons (90 %) are re-emitted narrowly around 440 nm (row sums of S up to ≈ 0.86). The lobe choice of
        // PathIntegrator.Fluorescence.cs takes the shifted lobe with P ≤ 1 − Â/0.95, so a smooth bounce leaves β's largest band
        // at most 0.95 of what it was, and Russian roulette (survival min(0.95, max β·gain)) then never raises it above
        // max(itself, 1); a shifted bounce multiplies it by B̂/P ≤ W = max(â + ŝ, ŝ/(1 − â/0.95)) (â the largest diagonal, ŝ the
        // largest row sum of S), and a second shift adds nothing here (S·S = 0: blue does not excite). A vertex adds at most
        // Y = max_o (L_e + a·L_e + S·L_e)[o] per unit of that bound (its emission, its next-event sample through both lobes:
        // inside a sphere cos/pdf of an area sample is π). So every sample is at most (vertices)·Y·max(1, W) in every band:
        // the estimator's weights do not compound. The former fixed share (P ≈ 0.49) gave the diagonal 0.9/0.51 ≈ 1.8 per
        // bounce: swapped in, this test saw a sample 9.9× over the bound, a per-sample relative sd of 7.9 (0.71 now) at 442.5 nm.
        var d = new double[N * N];
        var p = Cells.Select(l => FluorescenceTests.Gauss(l, 440, 10)).ToArray();
        for (int i = 0; i < N; i++)
        {
            double di = 0.9 - 0.8 * FluorescenceTests.Gauss(Cells[i], 365, 12);
            d[i * N + i] = di;
            if (di > 0.85) continue;
            double sum = Enumerable.Range(i + 1, N - i - 1).Sum(o => p[o]);
            for (int o = i + 1; o < N; o++) d[o * N + i] = 0.9 * (1 - di) * Cells[i] * (p[o] / sum) / Cells[o];
        }
        var le = Cells.Select(l => 1 + (l - 300) / 480).ToArray();
        var scene = Furnace(WriteCsv("paper.csv", d), "[[300, 1], [780, 2]]");
        // The diagonal is a reflectance, piecewise linear between the cell centres (the shift is constant on cells): its mean
        // over cell i is (d[i−1] + 6·d[i] + d[i+1])/8, continued flat beyond the ends.
        var a2 = new double[N * N];
        for (int k = 0; k < N * N; k++) a2[k] = -d[k];
        for (int i = 0; i < N; i++)
            a2[i * N + i] = 1 - (d[Math.Max(i - 1, 0) * (N + 1)] + 6 * d[i * (N + 1)] + d[Math.Min(i + 1, N - 1) * (N + 1)]) / 8;
        var expected = Solve(a2, le);
        double aMax = 0, sMax = 0, y = 0;
        for (int o = 0; o < N; o++)
        {
            double rowSum = 0, shifted = 0;
            for (int i = 0; i < N; i++) if (i != o) { rowSum += d[o * N + i]; shifted += d[o * N + i] * le[i]; }
            aMax = Math.Max(aMax, d[o * N + o]);
            sMax = Math.Max(sMax, rowSum);
            y = Math.Max(y, le[o] * (1 + d[o * N + o]) + shifted);
        }
        double w = Math.Max(1, Math.Max(aMax + sMax, sMax / (1 - aMax / 0.95)));
        var path = Integrators.Create(scene, new SceneGeometry(scene), "path");
        var result = new float[scene.PaddedBands];
        var scratch = new float[path.ScratchLength];
        var counters = new RayCounters();
        const int n = 20_000;
        var sum1 = new double[N];
        var sum2 = new double[N];
        double worstRatio = 0;   // the largest sample over its bound (≤ 1)
        long longest = 0;
        for (int k = 0; k < n; k++)
        {
            long before = counters.Secondary;
            path.Radiance(new CameraSample(k % 97, k / 97, k, Inside), result, scratch, ref counters);
            long vertices = counters.Secondary - before + 1;
            longest = Math.Max(longest, vertices);
            for (int b = 0; b < N; b++)
            {
                sum1[b] += result[b];
                sum2[b] += (double)result[b] * result[b];
                worstRatio = Math.Max(worstRatio, result[b] / (vertices * y * w));
            }
        }
        double worst = 0;
        int peak = 28;   // 442.5 nm
        for (int b = 0; b < N; b++)
        {
            double mean = sum1[b] / n, error = Math.Sqrt(Math.Max(0, sum2[b] / n - mean * mean) / (n - 1));
            worst = Math.Max(worst, Math.Abs(mean - expected[b]) / Math.Max(error, 1e-12));
            Assert.True(Math.Abs(mean - expected[b]) <= 4 * error + 1e-5 * expected[b],
                $"band {Cells[b]} nm: {mean:F5} vs (I − R − S)⁻¹·L_e = {expected[b]:F5} (±{error:g2})");
        }
        double peakMean = sum1[peak] / n, peakSd = Math.Sqrt(Math.Max(0, sum2[peak] / n - peakMean * peakMean));
        output.WriteLine($"bright paper furnace: largest |path − solution| {worst:F2} standard errors; at {Cells[peak]} nm " +
            $"{peakMean:F4} (solution {expected[peak]:F4}, L_e/(1 − 0.9) = {le[peak] / (1 - d[peak * N + peak]):F4}), per-sample " +
            $"relative sd {peakSd / peakMean:F3}; largest sample / ((vertices)·Y·W) = {worstRatio:F3} (Y {y:F3}, W {w:F2}); " +
            $"longest path {longest} vertices");
        Assert.True(expected[peak] > 1.05 * le[peak] / (1 - d[peak * N + peak]), "the paper must fluoresce markedly");
        Assert.True(worstRatio <= 1, $"a sample exceeds its bound by {worstRatio:F3}: the path's weights compound");
    }

    [Theory]
    [InlineData(9)]    // 347.5 nm
    [InlineData(14)]   // 372.5 nm
    public void Photons_re_emitted_from_an_excitation_band_equal_those_it_absorbs_at_unit_quantum_yield(int a)
    {
        // R = 0.3 everywhere; column a re-emits every photon it absorbs, (1 − R)·λa, over the longer bands as p_o. The walls
        // emit only in band a (a triangle inside it), so every other band's light is re-emitted light, absorbed at (1 − R)
        // per bounce: photons absorbed in the other bands Σ_o (1 − R)·π·L_o·w·λo (per hc) are those re-emitted from band a,
        // and they may not exceed (here: equal) those absorbed in band a, (1 − R)·π·L_a·w·λa.
        const double r = 0.3;
        var p = Cells.Select(l => FluorescenceTests.Gauss(l, 470, 25)).ToArray();
        double sum = Enumerable.Range(a + 1, N - a - 1).Sum(o => p[o]);
        var d = new double[N * N];
        for (int i = 0; i < N; i++) d[i * N + i] = r;
        for (int o = a + 1; o < N; o++) d[o * N + a] = (1 - r) * Cells[a] * (p[o] / sum) / Cells[o];
        double lo = Cells[a] - 2.5, hi = Cells[a] + 2.5;
        string emission = string.Create(Inv, $"[[300, 0], [{lo}, 0], [{Cells[a]}, 1], [{hi}, 0], [780, 0]]");
        var scene = Furnace(WriteCsv($"column-{a}.csv", d), emission);
        // Per path sample: the photons of the other bands minus those of band a, (1 − R)·(Σ_o L_o·λo − L_a·λa) (× π·w/hc);
        // its mean and standard error over the samples (the bands of one path are correlated, so the difference is taken first).
        var geometry = new SceneGeometry(scene);
        var path = Integrators.Create(scene, geometry, "path");
        var result = new float[scene.PaddedBands];
        var scratch = new float[path.ScratchLength];
        var counters = new RayCounters();
        const int n = 20_000;
        double sumD = 0, sumD2 = 0, sumA = 0, sumE = 0, sumLa = 0, sumLa2 = 0;
        for (int k = 0; k < n; k++)
        {
            path.Radiance(new CameraSample(k % 97, k / 97, k, Inside), result, scratch, ref counters);
            double absorbedK = (1 - r) * result[a] * Cells[a], emittedK = 0;
            for (int o = 0; o < N; o++) if (o != a) emittedK += (1 - r) * result[o] * Cells[o];
            sumD += emittedK - absorbedK; sumD2 += (emittedK - absorbedK) * (emittedK - absorbedK);
            sumA += absorbedK; sumE += emittedK; sumLa += result[a]; sumLa2 += (double)result[a] * result[a];
        }
        double difference = sumD / n, differenceError = Math.Sqrt(Math.Max(0, sumD2 / n - difference * difference) / (n - 1));
        double absorbed = sumA / n, emitted = sumE / n;
        double la = sumLa / n, laError = Math.Sqrt(Math.Max(0, sumLa2 / n - la * la) / (n - 1));
        double allowed = 4 * differenceError;
        output.WriteLine($"excitation {Cells[a]} nm: photons re-emitted {emitted:G6}, absorbed {absorbed:G6} (× π·w/hc), " +
            $"ratio {emitted / absorbed:F4} ± {differenceError / absorbed:F4}; L_a {la:F5} ± {laError:F5}, expected "
                + $"0.5/(1 − R) = {0.5 / (1 - r):F5}");
        Assert.True(difference <= allowed, $"{Cells[a]} nm re-emits more photons than it absorbs");
        Assert.True(Math.Abs(difference) <= allowed, $"{Cells[a]} nm: re-emitted − absorbed {difference} (±{differenceError:g2})");
        Assert.True(allowed < 0.1 * r * absorbed, "the test must tell this from next-event excitation only, which re-emits (1 − R) of it");
        Assert.True(Math.Abs(la - 0.5 / (1 - r)) <= 4 * laError + 1e-5, $"L_a {la} vs {0.5 / (1 - r)}");
    }
    /// <summary>
    /// A fluorescent scene lit only by emitters keeps a per-light transfer (nothing to relight, one fixed group): its fixed light,
    /// collected by the transfer's walk through the same shifted bounces, is the film's radiance (5 nm bands = the sub-bands).
    /// </summary>
    [Fact]
    public void A_fluorescent_scene_lit_by_emitters_only_has_its_fixed_transfer_equal_to_the_film()
    {
        var d = new double[N * N];
        for (int i = 0; i < N; i++) d[i * N + i] = 0.5;
        for (int o = 20; o < N; o++) d[o * N + 10] = 0.4 * Cells[10] / Cells[o] / (N - 20);
        var scene = Furnace(WriteCsv("transfer.csv", d), "[[300, 1], [780, 2]]");
        var transfer = PathTransfer.Trace(scene, new PathIntegrator(scene, new SceneGeometry(scene)));
        var film = Renderer.Render(scene, new PathIntegrator(scene, new SceneGeometry(scene))).Image;
        Assert.Equal(0, transfer.Lights);
        double worst = 0;
        for (int y = 0; y < film.Height; y++)
            for (int x = 0; x < film.Width; x++)
                for (int b = 0; b < N; b++)
                {
                    double t = transfer.Data[(y * film.Width + x) * transfer.SubBands + b], f = film[x, y, b];
                    worst = Math.Max(worst, Math.Abs(t - f) / f);
                }
        output.WriteLine($"fixed transfer vs film: largest relative difference {worst:E2}");
        Assert.True(worst < 1e-5, $"{worst:E2}");
    }
    [Fact]
    public void A_fluorescent_path_render_is_the_same_on_one_thread_and_on_several()
    {
        // The cascade's furnace (nested shifted bounces): random numbers only from each camera sample's sampler, scratch per thread.
        var d = new double[N * N];
        for (int i = 0; i < N; i++) d[i * N + i] = 0.3;
        d[30 * N + 9] = 0.6 * Cells[9] / Cells[30];
        d[60 * N + 30] = 0.6 * Cells[30] / Cells[60];
        var scene = Furnace(WriteCsv("threads.csv", d), "[[300, 1], [780, 2]]");
        var one = Renderer.Render(scene, new PathIntegrator(scene, new SceneGeometry(scene)), threads: 1);
        var several = Renderer.Render(scene, new PathIntegrator(scene, new SceneGeometry(scene)), threads: 3);
        Assert.Equal(one.Image.Data, several.Image.Data);
        Assert.Equal(one.Xyz!, several.Xyz!);
    }
}
