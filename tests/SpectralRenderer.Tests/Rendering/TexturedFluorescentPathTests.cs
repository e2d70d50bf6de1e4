using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 26: a diffuse texture beside a re-radiation matrix is the reflective diagonal per texel, the matrix's shifted part
/// the same at every texel (path integrator, and the whitted integrator's texel tables). Checked against the untextured
/// material whose matrix diagonal is the texture (the same render), against the analytic answers — a flat quad under a
/// uniform sky reflects (T̄_b + Σ_i≠b S[b, i])·L per 5 nm band (the bands are the matrix's cells, so the engine's band
/// matrix is S itself), under whitted and a flat directional light (T̄_b + Σ_i≠b S[b, i])·E/π, a closed furnace holds
/// (I − diag(T) − S)⁻¹·L_e solved here by elimination — and a texture of two halves against the two uniform renders.
/// The loader refuses a plain diffuse spectrum beside a matrix and a texel that breaks the photon balance with the shift.
/// </summary>
public sealed class TexturedFluorescentPathTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    static double[] Cells => FluorescenceTests.Cells;   // 302.5 … 777.5 nm, the 5 nm bands of 300:780:96
    static int N => Cells.Length;
    readonly string _dir = Reference.TempDir();

    /// <summary>
    /// The brightener of FluorescentPathTests on the diagonal <paramref name="diagonal"/>: D[o, i] = q·a_i·λi·p_o/λo for
    /// λo > λi, a_i = 0.9·G(λi; 365, 15), p ∝ G(λo; 440, 18), q = 0.55 (photons re-emitted per absorbed: q·a_i ≤ 0.495).
    /// </summary>
    static double[] Brightener(Func<double, double> diagonal)
    {
        const double q = 0.55;
        var p = Cells.Select(l => FluorescenceTests.Gauss(l, 440, 18)).ToArray();
        double sum = p.Sum();
        var d = new double[N * N];
        for (int i = 0; i < N; i++)
        {
            d[i * N + i] = diagonal(Cells[i]);
            double a = 0.9 * FluorescenceTests.Gauss(Cells[i], 365, 15);
            for (int o = i + 1; o < N; o++) d[o * N + i] = q * a * Cells[i] * (p[o] / sum) / Cells[o];
        }
        return d;
    }

    string WriteCsv(string file, double[] d)
    {
        File.WriteAllText(Path.Combine(_dir, file), FluorescenceTests.MatrixCsv(Cells, d));
        return file;
    }

    /// <summary>A w × h ENVI texture at the cells' wavelengths, texel (x, y) the reflectance texel(x, y)(λ); its JSON object.</summary>
    string WriteTexture(string name, int w, int h, Func<int, int, double, double> texel)
    {
        var v = new float[w * h * N];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int j = 0; j < N; j++) v[(y * w + x) * N + j] = (float)texel(x, y, Cells[j]);
        SpectralTextureTests.WriteEnvi(Path.Combine(_dir, name + ".img"), w, h, Cells, v);
        return $$"""{ "texture": "{{name}}.hdr" }""";
    }

    Scene Load(string json) => SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(_dir, "scene.json"));

    static RenderResult Render(Scene scene, int threads = 2) =>
        Renderer.Render(scene, new PathIntegrator(scene, new SceneGeometry(scene)), threads: threads);

    /// <summary>
    /// A fluorescent floor (<paramref name="paper"/>) with a white sphere on it under a point light of A and a dim sky:
    /// interreflection, indirect excitation.
    /// </summary>
    static string Room(string paper) => $$"""
        { "radiometry": "physical", "bands": "300:780:96", "white": "D50", "integrator": { "type": "path", "max_depth": 5 },
          "camera": { "position": [0, 1.5, 5], "look_at": [0, -0.5, 0], "width": 40, "height": 28, "spp": 4 },
          "lights": [ { "type": "point", "position": [1, 3, 2], "spectrum": "A", "intensity": 8 } ],
          "materials": { "paper": {{paper}}, "white": { "diffuse": 0.8 } },
          "objects": [ { "type": "plane", "point": [0, -1, 0], "material": "paper" },
                       { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white" } ],
          "background": 0.05 }
        """;

    /// <summary>A 6 × 4 quad of <paramref name="paper"/> alone, face on, under a uniform sky <paramref name="sky"/> and the
    /// lights.</summary>
    static string Quad(string paper, string lights, double sky, int maxDepth) => $$"""
        { "radiometry": "physical", "bands": "300:780:96", "white": "D50", "integrator": { "type": "path", "max_depth": {{maxDepth}} },
          "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 16, "width": 96, "height": 64, "spp": 2 },
          "lights": [ {{lights}} ],
          "materials": { "paper": {{paper}} },
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": [6, 4], "material": "paper" } ],
          "background": {{sky.ToString(Inv)}} }
        """;

    /// <summary>
    /// A pixel of <see cref="Quad"/> whose footprint lies on the quad, a texel (6 pixels) or more from its edges — the
    /// bilinear lookup wraps (repeat) there — and from the seam at u = ½ (a texel is 8.5 pixels wide).
    /// </summary>
    static bool Inner(Scene scene, int x, int y)
    {
        var cam = scene.Camera;
        var lo = cam.Project(new Vector3(-3, 2, 0))!.Value;
        var hi = cam.Project(new Vector3(3, -2, 0))!.Value;
        float x0 = MathF.Min(lo.X, hi.X), x1 = MathF.Max(lo.X, hi.X), y0 = MathF.Min(lo.Y, hi.Y), y1 = MathF.Max(lo.Y, hi.Y);
        float px = x + 0.5f, py = y + 0.5f;
        return px > x0 + 6 && px < x1 - 6 && py > y0 + 6 && py < y1 - 6 && Math.Abs(px - (x0 + x1) / 2) > 6;
    }

    static string Fluorescent(string matrix, string? texture) =>
        texture is null
            ? $$"""{ "fluorescence": { "matrix": "{{matrix}}" } }"""
            : $$"""{ "diffuse": {{texture}}, "fluorescence": { "matrix": "{{matrix}}" } }""";

    /// <summary>Largest relative difference over every pixel and band of two renders (and their XYZ), relative to the larger.</summary>
    static double Difference(RenderResult a, RenderResult b, Func<int, int, bool>? where = null)
    {
        double worst = 0;
        var img = a.Image;
        for (int y = 0; y < img.Height; y++)
            for (int x = 0; x < img.Width; x++)
            {
                if (where is not null && !where(x, y)) continue;
                for (int k = 0; k < img.Bands; k++)
                {
                    double u = a.Image[x, y, k], v = b.Image[x, y, k];
                    if (u != v) worst = Math.Max(worst, Math.Abs(u - v) / Math.Max(Math.Abs(u), Math.Abs(v)));
                }
                for (int c = 0; c < 3; c++)
                {
                    double u = a.Xyz![3 * (y * img.Width + x) + c], v = b.Xyz![3 * (y * img.Width + x) + c];
                    if (u != v) worst = Math.Max(worst, Math.Abs(u - v) / Math.Max(Math.Abs(u), Math.Abs(v)));
                }
            }
        return worst;
    }

    static double Ramp(double l) => 0.3 + 0.4 * (l - 300) / 480;   // a diagonal that varies over the bands: 0.3 … 0.7

    [Fact]
    public void A_uniform_texture_of_the_matrix_diagonal_renders_as_the_untextured_fluorescent_material()
    {
        // Every texel is the matrix's diagonal, tabulated at the same wavelengths (its interpolant continues flat beyond
        // them, as the diagonal's half end cells do): the same material, so the same render with the same random numbers
        // but for float rounding of the texel's projection and the lobe choice's channel share.
        string matrix = WriteCsv("ramp.csv", Brightener(Ramp));
        string texture = WriteTexture("ramp", 4, 4, (_, _, l) => Ramp(l));
        var plain = Render(Load(Room(Fluorescent(matrix, null))));
        var textured = Render(Load(Room(Fluorescent(matrix, texture))));
        double worst = Difference(textured, plain);
        int identical = 0, total = plain.Image.Data.Length;
        for (int k = 0; k < total; k++) if (plain.Image.Data[k] == textured.Image.Data[k]) identical++;
        output.WriteLine($"uniform texture vs untextured fluorescent: largest relative difference {worst:G3}; " +
            $"{identical} of {total} values bit-identical");
        Assert.True(worst <= 1e-5, $"{worst:G3}");
        // It is a fluorescent render: the brightener's blue (440 nm) band is far above what the diagonal alone reflects.
        var reflectOnly = Render(Load(Room($$"""{ "diffuse": {{texture}} }""")));
        Assert.True(Difference(textured, reflectOnly) > 0.05, "the texture keeps the matrix's shifted part");
    }

    /// <summary>∫ of the piecewise-linear table (x, y), continued flat beyond its ends, over [lo, hi] (exact, by segments).</summary>
    static double Integral(double[] x, double[] y, double lo, double hi)
    {
        double[] xs = [lo - 1, .. x, hi + 1], ys = [y[0], .. y, y[^1]];
        double sum = 0;
        for (int i = 0; i + 1 < xs.Length; i++)
        {
            double a = Math.Max(lo, xs[i]), b = Math.Min(hi, xs[i + 1]);
            if (!(b > a)) continue;
            double Y(double t) => ys[i] + (ys[i + 1] - ys[i]) * (t - xs[i]) / (xs[i + 1] - xs[i]);
            sum += (b - a) * (Y(a) + Y(b)) / 2;
        }
        return sum;
    }

    static double Left(double l) => 0.25 + 0.3 * FluorescenceTests.Gauss(l, 560, 60);   // 0.25 … 0.55 (absorbs 0.75 in the UV)
    static double Right(double l) => 0.5 - 0.3 * (l - 300) / 480;                     // 0.5 … 0.2

    [Fact]
    public void A_two_half_textured_quad_under_a_uniform_sky_reflects_its_texel_plus_the_shift_times_L_sky()
    {
        // Under a sky of radiance L from every direction a Lambertian surface reflects T·L and the shifted lobe S/π returns
        // S·(π·L)/π: band b is L·(T̄_b + Σ_i≠b S[b, i]), T̄_b the band mean of the texel's straight segments. (Next-event
        // estimation draws the sky by its cosine density, so the shift's sample is exact; the diagonal's is MIS-weighted with
        // the continuation, which chooses the shifted lobe at times: noisy.) So per half, the mean over its pixels (each an
        // independent estimate of the same value) against the analytic value within 4 standard errors of that mean. The
        // matrix's own diagonal (0.1) is not the answer: the texture is. Left half Left(λ), right half Right(λ).
        const double sky = 0.7;
        var d = Brightener(_ => 0.1);
        string matrix = WriteCsv("brightener.csv", d);
        string texture = WriteTexture("halves", 8, 4, (x, _, l) => x < 4 ? Left(l) : Right(l));
        var scene = Load(Quad(Fluorescent(matrix, texture), "", sky, 1)
            .Replace("\"lights\": [  ],", "").Replace("\"spp\": 2", "\"spp\": 8"));
        var r = Render(scene);
        float seam = scene.Camera.Project(Vector3.Zero)!.Value.X;
        double worst = 0, worstRelative = 0, separation = double.MaxValue;
        foreach (bool leftHalf in new[] { true, false })
        {
            Func<double, double> texel = leftHalf ? Left : Right;
            var rho = Cells.Select(texel).ToArray();
            var sum = new double[N];
            var sum2 = new double[N];
            int n = 0;
            for (int y = 0; y < scene.Camera.Height; y++)
                for (int x = 0; x < scene.Camera.Width; x++)
                {
                    if (!Inner(scene, x, y) || (x + 0.5 < seam) != leftHalf) continue;
                    for (int b = 0; b < N; b++) { double v = r.Image[x, y, b]; sum[b] += v; sum2[b] += v * v; }
                    n++;
                }
            Assert.True(n > 300, $"{n} pixels");
            for (int b = 0; b < N; b++)
            {
                double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b), shift = 0;
                for (int i = 0; i < N; i++) if (i != b) shift += d[b * N + i];
                double expected = sky * (Integral(Cells, rho, lo, hi) / (hi - lo) + shift);
                double mean = sum[b] / n, error = Math.Sqrt(Math.Max(0, sum2[b] / n - mean * mean) / (n - 1));
                Assert.True(Math.Abs(mean - expected) <= 4 * error + 1e-5 * expected,
                    $"{(leftHalf ? "left" : "right")} half, band {Cells[b]} nm: {mean:R} ± {error:g2} vs (T̄ + ΣS)·L = {expected:R}");
                if (error > 0) worst = Math.Max(worst, Math.Abs(mean - expected) / error);
                worstRelative = Math.Max(worstRelative, Math.Abs(mean / expected - 1));
                if (b == 27)   // 437.5 nm: the brightener's peak, where the matrix's diagonal would give 0.1 + shift
                    separation = Math.Min(separation, Math.Abs(expected - sky * (0.1 + shift)) / error);
            }
            output.WriteLine($"{(leftHalf ? "left" : "right")} half: {n} pixels");
        }
        output.WriteLine($"largest |mean − (T̄ + ΣS)·L_sky| {worst:F2} standard errors ({worstRelative:G3} relative); " +
            $"the matrix's diagonal would be ≥ {separation:F0} standard errors off at 437.5 nm");
        Assert.True(separation > 20, "the test must tell the texel diagonal from the matrix's");
    }

    [Fact]
    public void Each_half_of_a_two_half_texture_renders_as_its_uniform_texture()
    {
        // A quad alone (no interreflection) under a point light of A and a sky, through shifted bounces (max_depth 4): each
        // pixel depends on its own texel only, so each half is the uniform texture's render, pixel for pixel (same samples).
        var d = Brightener(_ => 0.1);
        string matrix = WriteCsv("brightener.csv", d);
        string halves = WriteTexture("halves", 8, 4, (x, _, l) => x < 4 ? Left(l) : Right(l));
        string left = WriteTexture("left", 8, 4, (_, _, l) => Left(l));
        string right = WriteTexture("right", 8, 4, (_, _, l) => Right(l));
        const string Lamp = """{ "type": "point", "position": [2, 1, 6], "spectrum": "A", "intensity": 3 }""";
        var scene = Load(Quad(Fluorescent(matrix, halves), Lamp, 0.05, 4));
        var split = Render(scene);
        var l = Render(Load(Quad(Fluorescent(matrix, left), Lamp, 0.05, 4)));
        var r = Render(Load(Quad(Fluorescent(matrix, right), Lamp, 0.05, 4)));
        float seam = scene.Camera.Project(Vector3.Zero)!.Value.X;
        double worstLeft = Difference(split, l, (x, y) => Inner(scene, x, y) && x + 0.5 < seam);
        double worstRight = Difference(split, r, (x, y) => Inner(scene, x, y) && x + 0.5 > seam);
        double apart = Difference(l, r, (x, y) => Inner(scene, x, y));
        output.WriteLine($"two halves vs uniform renders: largest relative difference left {worstLeft:G3}, right {worstRight:G3} " +
            $"(left vs right {apart:G3})");
        Assert.True(worstLeft <= 1e-5 && worstRight <= 1e-5, $"{worstLeft:G3} {worstRight:G3}");
        Assert.True(apart > 0.1);
    }

    static readonly Ray Inside = new(new Vector3(0.1f, 0.2f, 0.3f), Vector3.Normalize(new Vector3(1, -2, 0.5f)));

    [Fact]
    public void A_textured_fluorescent_furnace_converges_to_the_solution_with_the_texel_diagonal()
    {
        // A closed sphere whose inside emits L_e (linear in λ: band means at the centres) and reflects with the texture's
        // flat T = 0.45 (every texel) beside the brightener whose own diagonal is 0.2: L = (I − T − S)⁻¹·L_e per band.
        const double t = 0.45, own = 0.2;
        var d = Brightener(_ => own);
        string matrix = WriteCsv("furnace.csv", d);
        string texture = WriteTexture("flat", 2, 2, (_, _, _) => t);
        var scene = Load($$"""
            { "radiometry": "physical", "bands": "300:780:96", "white": "D50", "integrator": { "type": "path" },
              "camera": { "position": [0, 0, 0], "look_at": [0, 0, -1], "width": 8, "height": 8 },
              "materials": { "wall": { "diffuse": {{texture}}, "fluorescence": { "matrix": "{{matrix}}" },
                                       "emission": { "spectrum": [[300, 1], [780, 2]], "radiance": 1, "two_sided": true } } },
              "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wall" } ] }
            """);
        var le = Cells.Select(l => 1 + (l - 300) / 480).ToArray();
        double[] Solution(double diagonal)
        {
            var a = new double[N * N];
            for (int k = 0; k < N * N; k++) a[k] = (k % (N + 1) == 0 ? 1 - diagonal : -d[k]);
            return FluorescentPathTests.Solve(a, le);
        }
        var expected = Solution(t);
        var matrixDiagonal = Solution(own);
        var (mean, error) = PathIntegratorTests.Estimate(scene, Inside, 20_000);
        double worst = 0;
        int peak = Array.IndexOf(expected, expected.Max());
        for (int b = 0; b < N; b++)
        {
            Assert.True(Math.Abs(mean[b] - expected[b]) <= 4 * error[b] + 1e-5 * expected[b],
                $"band {Cells[b]} nm: {mean[b]:F5} vs (I − T − S)⁻¹·L_e = {expected[b]:F5} (±{error[b]:g2})");
            if (error[b] > 0) worst = Math.Max(worst, Math.Abs(mean[b] - expected[b]) / error[b]);
        }
        double separation = Math.Abs(matrixDiagonal[peak] - expected[peak]) / error[peak];
        output.WriteLine($"textured furnace: largest |path − solution| {worst:F2} standard errors; at {Cells[peak]} nm path " +
            $"{mean[peak]:F4} ± {error[peak]:F4}, solution {expected[peak]:F4}; with the matrix's own diagonal " +
            $"{matrixDiagonal[peak]:F4} ({separation:F0} standard errors away)");
        Assert.True(separation > 20, "the test must tell the texel diagonal from the matrix's");
    }

    [Fact]
    public void A_textured_fluorescent_render_is_the_same_on_one_thread_and_on_two()
    {
        string matrix = WriteCsv("ramp.csv", Brightener(Ramp));
        string texture = WriteTexture("halves", 8, 4, (x, _, l) => x < 4 ? Ramp(l) : Right(l));
        var scene = Load(Room(Fluorescent(matrix, texture)));
        var one = Render(scene, threads: 1);
        var two = Render(scene, threads: 2);
        Assert.Equal(one.Image.Data, two.Image.Data);
        Assert.Equal(one.Xyz!, two.Xyz!);
    }

    [Fact]
    public void A_plain_diffuse_spectrum_beside_a_matrix_is_still_refused()
    {
        string matrix = WriteCsv("ramp.csv", Brightener(Ramp));
        var e = Assert.Throws<InputException>(() => Load(Room($$"""{ "diffuse": 0.5, "fluorescence": { "matrix": "{{matrix}}" } }""")));
        output.WriteLine(e.Message);
        Assert.Contains("$.materials.paper.diffuse", e.Message);
        Assert.Contains("are both given", e.Message);
    }

    [Fact]
    public void A_texel_that_re_emits_more_photons_than_it_absorbs_is_refused_naming_it()
    {
        // The brightener re-emits q·a(λi) ≤ 0.495 photons per photon at λi (0.495 at 362.5–367.5 nm); a texel reflecting
        // 0.6 there absorbs only 0.4. One such texel among texels of 0.45 (which absorb 0.55) is refused, by its place.
        string matrix = WriteCsv("shift.csv", Brightener(_ => 0.1));
        string bad = WriteTexture("bad", 4, 3, (x, y, _) => x == 2 && y == 1 ? 0.6 : 0.45);
        var e = Assert.Throws<InputException>(() => Load(Room(Fluorescent(matrix, bad))));
        output.WriteLine(e.Message);
        Assert.Contains("$.materials.paper.diffuse.texture", e.Message);
        Assert.Contains("texel (2, 1)", e.Message);
        Assert.Contains("photons", e.Message);
        // The photon balance of the first excitation wavelength it breaks, computed here: Σ_o≠i D[o, i]·λo/λi > 1 − 0.6.
        var d = Brightener(_ => 0.1);
        double Emitted(int i) => Enumerable.Range(0, N).Where(o => o != i).Sum(o => d[o * N + i] * Cells[o]) / Cells[i];
        int first = Enumerable.Range(0, N).First(i => Emitted(i) > 0.4);
        Assert.Contains($" at {Cells[first].ToString("0.###", Inv)} nm", e.Message);
        // The same texels at 0.45 everywhere keep the balance: loaded.
        Load(Room(Fluorescent(matrix, WriteTexture("good", 4, 3, (_, _, _) => 0.45))));
    }

    static RenderResult RenderWith(Scene scene, string integrator) =>
        Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), integrator), threads: 2);

    [Fact]
    public void Under_whitted_a_uniform_texture_of_the_diagonal_renders_as_the_untextured_material_and_halves_as_their_textures()
    {
        // The whitted integrator's texel tables (TexturedTerms) gain the shift per light: a uniform texture of the matrix's
        // diagonal is the untextured fluorescent material (its term tables, FluorescenceTests), to float rounding; each half
        // of a two-half texture is its uniform texture (one flat quad, no mirror: every pixel sees its own texels).
        string matrix = WriteCsv("ramp.csv", Brightener(Ramp));
        string texture = WriteTexture("ramp", 4, 4, (_, _, l) => Ramp(l));
        string Whitted(string json) => json.Replace("\"type\": \"path\", \"max_depth\": 5", "\"type\": \"whitted\"");
        var plain = RenderWith(Load(Whitted(Room(Fluorescent(matrix, null)))), "whitted");
        var textured = RenderWith(Load(Whitted(Room(Fluorescent(matrix, texture)))), "whitted");
        var reflectOnly = RenderWith(Load(Whitted(Room($$"""{ "diffuse": {{texture}} }"""))), "whitted");
        double uniform = Difference(textured, plain), shift = Difference(textured, reflectOnly);
        Assert.True(uniform <= 1e-5, $"{uniform:G3}");
        Assert.True(shift > 0.05, "the texture keeps the matrix's shifted part");

        var d = Brightener(_ => 0.1);
        string m2 = WriteCsv("brightener.csv", d);
        const string Lamp = """{ "type": "point", "position": [2, 1, 6], "spectrum": "A", "intensity": 3 }""";
        string Q(string tex) => Quad(Fluorescent(m2, WriteTexture(tex, 8, 4,
                (x, _, l) => tex == "left" || (tex == "halves" && x < 4) ? Left(l) : Right(l))), Lamp, 0.05, 1)
            .Replace("\"type\": \"path\", \"max_depth\": 1", "\"type\": \"whitted\"");
        var scene = Load(Q("halves"));
        var split = RenderWith(scene, "whitted");
        var l = RenderWith(Load(Q("left")), "whitted");
        var r = RenderWith(Load(Q("right")), "whitted");
        float seam = scene.Camera.Project(Vector3.Zero)!.Value.X;
        double worstLeft = Difference(split, l, (x, y) => Inner(scene, x, y) && x + 0.5 < seam);
        double worstRight = Difference(split, r, (x, y) => Inner(scene, x, y) && x + 0.5 > seam);
        output.WriteLine($"whitted: uniform texture vs untextured {uniform:G3} (vs the texture without the matrix {shift:G3}); " +
            $"two halves vs uniform left {worstLeft:G3}, right {worstRight:G3}");
        Assert.True(worstLeft <= 1e-5 && worstRight <= 1e-5, $"{worstLeft:G3} {worstRight:G3}");
        Assert.True(Difference(l, r, (x, y) => Inner(scene, x, y)) > 0.1);
    }

    [Fact]
    public void Under_whitted_a_textured_fluorescent_quad_in_a_flat_light_reflects_its_texel_plus_the_shift_over_pi()
    {
        // Physical radiometry: a directional light of flat irradiance E (1 per nm) at normal incidence; eq. 2's diffuse term
        // is E·(T̄_b + Σ_i S[b, i]·Ē_i)/π, Ē_i = 1 the light's mean over excitation cell i (no ambient light, no sky).
        var d = Brightener(_ => 0.1);
        string matrix = WriteCsv("brightener.csv", d);
        string texture = WriteTexture("halves", 8, 4, (x, _, l) => x < 4 ? Left(l) : Right(l));
        const string Flat = """{ "type": "directional", "direction": [0, 0, -1], "spectrum": 1, "intensity": 1 }""";
        var scene = Load(Quad(Fluorescent(matrix, texture), Flat, 0, 1)
            .Replace("\"type\": \"path\", \"max_depth\": 1", "\"type\": \"whitted\""));
        var r = RenderWith(scene, "whitted");
        float seam = scene.Camera.Project(Vector3.Zero)!.Value.X;
        double worst = 0;
        int compared = 0;
        for (int y = 0; y < scene.Camera.Height; y++)
            for (int x = 0; x < scene.Camera.Width; x++)
            {
                if (!Inner(scene, x, y)) continue;
                Func<double, double> texel = x + 0.5 < seam ? Left : Right;
                var rho = Cells.Select(texel).ToArray();
                for (int b = 0; b < N; b++)
                {
                    double lo = scene.Grid.Lower(b), hi = scene.Grid.Upper(b), shift = 0;
                    for (int i = 0; i < N; i++) if (i != b) shift += d[b * N + i];
                    double expected = (Integral(Cells, rho, lo, hi) / (hi - lo) + shift) / Math.PI;
                    double diff = Math.Abs(r.Image[x, y, b] / expected - 1);
                    worst = Math.Max(worst, diff);
                    Assert.True(diff <= 1e-5, $"pixel ({x}, {y}) band {Cells[b]} nm: {r.Image[x, y, b]:R} vs (T̄ + ΣS)·E/π = {expected:R}");
                }
                compared++;
            }
        output.WriteLine($"whitted, {compared} pixels: largest relative difference from (T̄ + ΣS)·E/π {worst:G3}");
        Assert.True(compared > 600);
    }
}
