using System.Globalization;
using System.Text;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Issue 26, fluorescence: a material's re-radiation (Donaldson) matrix in the Whitted integrator. The matrices are built
/// here from Gaussian shapes and written as CSV; the expected band values are computed here by a direct matrix–vector
/// product on D50's own table (the cells of the matrix are aligned with the table's 5 nm knots, so each cell's mean
/// irradiance is the mean of two tabulated values), and photon balances by sums of λ over the cells.
/// </summary>
public sealed class FluorescenceTests(Xunit.Abstractions.ITestOutputHelper output) : IDisposable
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    readonly string _dir = Directory.CreateTempSubdirectory("fluorescence-").FullName;

    public void Dispose() => Directory.Delete(_dir, true);

    /// <summary>Cell centres 302.5, 307.5, …, 777.5 nm: cells [300, 305], …, [775, 780], on D50's 5 nm knots.</summary>
    internal static readonly double[] Cells = Enumerable.Range(0, 96).Select(j => 302.5 + 5 * j).ToArray();

    internal static double Gauss(double x, double mu, double sigma) => Math.Exp(-0.5 * (x - mu) * (x - mu) / (sigma * sigma));

    /// <summary>
    /// An optically brightened paper: a slightly yellow pulp R₀ (reflectance 0.88, absorbing towards the blue), an OBA that
    /// absorbs a(λ) (Gaussian at 365 nm, σ 15 nm: excitation 340–400 nm) and re-emits with quantum yield q a Gaussian
    /// photon distribution peaking at 440 nm (σ 18 nm), only towards longer wavelengths (Stokes):
    ///   D[i, i] = R₀(λ_i)·(1 − a(λ_i)),  D[o, i] = q·a(λ_i)·λ_i·p_o / λ_o  (o ≠ i, λ_o > λ_i), Σ_o p_o = 1.
    /// </summary>
    internal static double[] ObaPaper(double q = 0.8, double strength = 0.9, double[]? at = null)
    {
        var cells = at ?? Cells;
        int n = cells.Length;
        var d = new double[n * n];
        var p = cells.Select(l => Gauss(l, 440, 18)).ToArray();
        double sum = p.Sum();
        for (int i = 0; i < n; i++)
        {
            double l = cells[i];
            double r0 = 0.88 - 0.10 * Gauss(l, 400, 35);
            double a = strength * Gauss(l, 365, 15);
            d[i * n + i] = r0 * (1 - a);
            for (int o = 0; o < n; o++)
                if (cells[o] > l) d[o * n + i] = q * a * l * (p[o] / sum) / cells[o];
        }
        return d;
    }

    [Fact]
    public void The_shipped_matrix_is_the_model_of_this_test_on_10_nm_cells_to_its_six_printed_digits()
    {
        var lines = File.ReadAllLines(Repo.PathOf("scenes", "oba-paper-matrix.csv"));
        var cells = lines[0].Split(',').Skip(1).Select(x => double.Parse(x, Inv)).ToArray();
        Assert.Equal(Enumerable.Range(0, 48).Select(j => 305.0 + 10 * j), cells);
        var d = ObaPaper(at: cells);
        for (int o = 0; o < 48; o++)
        {
            var row = lines[o + 1].Split(',').Skip(1).Select(x => double.Parse(x, Inv)).ToArray();
            for (int i = 0; i < 48; i++)
                Assert.True(Math.Abs(row[i] - d[o * 48 + i]) <= 5e-6 * d[o * 48 + i] + 1e-12,
                    $"D[{cells[o]}, {cells[i]}] = {row[i]}, model {d[o * 48 + i]}");
        }
    }

    /// <summary>A re-radiation matrix as the documented CSV: a header of excitation wavelengths, then per emission wavelength
    /// its row (<paramref name="d"/> row-major, emission × excitation).</summary>
    internal static string MatrixCsv(double[] cells, double[] d)
    {
        int n = cells.Length;
        var sb = new StringBuilder("emission_nm");
        foreach (var l in cells) sb.Append(',').Append(l.ToString("R", Inv));
        sb.Append('\n');
        for (int o = 0; o < n; o++)
        {
            sb.Append(cells[o].ToString("R", Inv));
            for (int i = 0; i < n; i++) sb.Append(',').Append(d[o * n + i].ToString("R", Inv));
            sb.Append('\n');
        }
        return sb.ToString();
    }

    string WriteMatrix(string name, double[] d)
    {
        var path = Path.Combine(_dir, name);
        File.WriteAllText(path, MatrixCsv(Cells, d));
        return path;
    }

    static double[] Diagonal(double[] d)
    {
        int n = Cells.Length;
        var r = new double[n * n];
        for (int i = 0; i < n; i++) r[i * n + i] = d[i * n + i];
        return r;
    }

    internal static string Scene(string material, string light = "\"D50\"", string bands = "300:780:48", string extra = "") => $$"""
        { "bands": "{{bands}}", "white": "D50", {{extra}}
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 1, "width": 1, "height": 1 },
          "materials": { "paper": {{material}} },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": {{light}} } ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "normal": [0, 0, 1], "size": [100, 100], "material": "paper" } ],
          "background": 0 }
        """;

    internal static string Fluorescent(string path) => $$"""{ "fluorescence": { "matrix": "{{path.Replace("\\", "/")}}" } }""";

    static RenderResult Render(string json) => SceneText.Render(json);

    static double[] Difference(RenderResult a, RenderResult b) =>
        Enumerable.Range(0, a.Image.Bands).Select(k => (double)a.Image[0, 0, k] - b.Image[0, 0, k]).ToArray();

    internal static RenderResult RenderPath(string json)
    {
        var scene = SceneText.Load(json);
        return Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"));
    }

    /// <summary>The tabulated D50 column of data/illuminants-300-780.csv, read here.</summary>
    static Dictionary<double, double> D50()
    {
        var lines = File.ReadAllLines(Repo.PathOf("data", "illuminants-300-780.csv"));
        int c = Array.IndexOf(lines[0].Split(','), "D50");
        return lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(','))
            .ToDictionary(r => double.Parse(r[0], Inv), r => double.Parse(r[c], Inv));
    }

    [Fact]
    public void Bands_below_the_CIE_tables_carry_light_but_no_colour()
    {
        // 300:780:48 under D50 (tabulated from 300 nm): the CMFs start at 360 nm, so the six bands below carry zero weight.
        var scene = SceneText.Load(Scene("{ \"diffuse\": 0.5 }"));
        for (int b = 0; b < 6; b++)
        {
            Assert.Equal(0, scene.Colorimeter.Wx[b]);
            Assert.Equal(0, scene.Colorimeter.Wy[b]);
            Assert.Equal(0, scene.Colorimeter.Wz[b]);
        }
        Assert.True(scene.Colorimeter.Wz[6] > 0);   // 360–370 nm
        var image = SceneText.Render(Scene("{ \"diffuse\": 0.5 }")).Image;
        Assert.True(image[0, 0, 0] > 0, "D50's UV reaches the surface");
        Assert.Equal(0.5 * (D50()[300] + D50()[305]) / 2 * 0.5 + 0.5 * (D50()[305] + D50()[310]) / 2 * 0.5, image[0, 0, 0], 4);
    }

    [Fact]
    public void A_purely_diagonal_matrix_renders_bit_for_bit_as_the_plain_reflectance()
    {
        var d = ObaPaper();
        var matrix = WriteMatrix("diagonal.csv", Diagonal(d));
        // The same reflectance as a plain CSV spectrum at the same wavelengths.
        var csv = new StringBuilder("wavelength_nm,R\n");
        for (int i = 0; i < Cells.Length; i++) csv.Append(Inv, $"{Cells[i]:R},{d[i * Cells.Length + i]:R}\n");
        File.WriteAllText(Path.Combine(_dir, "plain.csv"), csv.ToString());
        var plainSpectrum = $"\"{Path.Combine(_dir, "plain.csv").Replace("\\", "/")}:R\"";
        foreach (var bands in new[] { "310:770:46", "400:700:31", "380:770:39" })
            foreach (var extra in new[] { "", "\"radiometry\": \"physical\"," })
            {
                var plain = Render(Scene($$"""{ "diffuse": {{plainSpectrum}} }""", bands: bands, extra: extra));
                var fluorescent = Render(Scene(Fluorescent(matrix), bands: bands, extra: extra));
                Assert.Equal(plain.Image.Data, fluorescent.Image.Data);
                Assert.Equal(plain.Xyz!, fluorescent.Xyz!);
                Assert.True(plain.Image.Data[0] > 0);
            }
    }

    [Fact]
    public void A_shift_matrix_adds_the_direct_matrix_vector_product_of_the_light()
    {
        var d = ObaPaper();
        var full = Render(Scene(Fluorescent(WriteMatrix("oba.csv", d))));
        var diagonal = Render(Scene(Fluorescent(WriteMatrix("diagonal.csv", Diagonal(d)))));
        // Direct: Ē_i = (D50(λ_i − 2.5) + D50(λ_i + 2.5)) / 2 (the linear table's mean over the cell), L_o = Σ_{i≠o} D[o,i]·Ē_i,
        // and a 10 nm band holds two whole 5 nm cells: its mean is (L_2b + L_2b+1) / 2.
        var d50 = D50();
        int n = Cells.Length;
        var e = Cells.Select(l => (d50[l - 2.5] + d50[l + 2.5]) / 2).ToArray();
        var l = new double[n];
        for (int o = 0; o < n; o++)
            for (int i = 0; i < n; i++)
                if (i != o) l[o] += d[o * n + i] * e[i];
        double worst = 0, peak = 0;
        for (int b = 0; b < 48; b++)
        {
            double expected = (l[2 * b] + l[2 * b + 1]) / 2;
            double shift = full.Image[0, 0, b] - (double)diagonal.Image[0, 0, b];
            peak = Math.Max(peak, expected);
            worst = Math.Max(worst, Math.Abs(shift - expected) / Math.Max(full.Image[0, 0, b], 1e-30));
        }
        output.WriteLine($"largest shifted band value {peak:G6}; largest |rendered − direct| relative to the band value {worst:E2}");
        Assert.True(peak > 1, "the OBA emits visibly");
        Assert.True(worst <= 1e-6, $"relative deviation {worst:E2}");
    }

    /// <summary>The shifted emission per cell for a light whose cell means are <paramref name="e"/>: L_o = Σ_{i≠o} D[o,i]·Ē_i.</summary>
    static double[] Shifted(double[] d, double[] e)
    {
        int n = Cells.Length;
        var l = new double[n];
        for (int o = 0; o < n; o++)
            for (int i = 0; i < n; i++)
                if (i != o) l[o] += d[o * n + i] * e[i];
        return l;
    }

    [Fact]
    public void The_path_integrator_adds_the_shift_of_direct_light_from_a_delta_light_and_from_a_uniform_sky()
    {
        var d = ObaPaper();
        string full = Fluorescent(WriteMatrix("oba.csv", d)), diag = Fluorescent(WriteMatrix("diagonal.csv", Diagonal(d)));
        const string path = "\"radiometry\": \"physical\", \"integrator\": { \"type\": \"path\", \"max_depth\": 1 },";
        // Direct light only, head-on: next-event estimation of the delta light adds the same shift as Whitted's tables (the
        // path's 5 nm sub-bands are the matrix's cells here; the diagonal parts differ, a product of sub-band means there).
        var pathShift = Difference(RenderPath(Scene(full, extra: path)), RenderPath(Scene(diag, extra: path)));
        var whittedShift = Difference(Render(Scene(full, extra: "\"radiometry\": \"physical\",")), Render(Scene(diag,
            extra: "\"radiometry\": \"physical\",")));
        double worst = 0, peak = whittedShift.Max();
        for (int b = 0; b < 48; b++) worst = Math.Max(worst, Math.Abs(pathShift[b] - whittedShift[b]) / peak);
        output.WriteLine($"path vs whitted shift, D50 head-on: largest difference {worst:E2} of the peak {peak:G6}");
        Assert.True(worst <= 1e-5, $"path vs whitted {worst:E2}");
        // A uniform sky of radiance 1 and no light: an unoccluded plane's shifted part is (S·1)_b in every direction, found by
        // next-event estimation of the sky (the shifted lobe's only estimator for light sources). Without fluorescence every
        // sample is exact (cosine sampling on both strategies); with it, the continuation's lobe choice gives the reflective
        // diagonal some variance, so the fluorescent render is a mean of 4000 samples, within 4 standard errors (+1e-5).
        // Expected here: two 5 nm cells per 10 nm band, each cell's mean irradiance 1.
        string sky = path;
        string Sky(string material) => Scene(material, extra: sky).Replace("\"background\": 0", "\"background\": 1")
            .Replace("\"lights\": [ { \"type\": \"directional\", \"direction\": [0, 0, -1], \"spectrum\": \"D50\" } ]", "\"lights\": []");
        var (withShift, error) =
            PathIntegratorTests.Estimate(SceneText.Load(Sky(full)), new SpectralRenderer.Geometry.Ray(new System.Numerics.Vector3(0, 0, 5),
            new System.Numerics.Vector3(0, 0, -1)), 4000);
        var without = RenderPath(Sky(diag)).Image;
        var l = Shifted(d, Enumerable.Repeat(1.0, Cells.Length).ToArray());
        worst = 0;
        for (int b = 0; b < 48; b++)
        {
            double expected = without[0, 0, b] + (l[2 * b] + l[2 * b + 1]) / 2;
            worst = Math.Max(worst, Math.Abs(withShift[b] - expected) / error[b]);
            Assert.True(Math.Abs(withShift[b] - expected) <= 4 * error[b] + 1e-5 * expected,
                $"sky, band {b}: {withShift[b]} vs {expected} (±{error[b]:g2})");
        }
        output.WriteLine($"path under a uniform sky: largest |rendered − (R + S·1)| {worst:F2} standard errors");
    }

    [Fact]
    public void A_unit_quantum_yield_matrix_re_emits_exactly_the_photons_it_absorbs_per_excitation_band()
    {
        // R = 0.3 everywhere; column a re-emits all it absorbs, (1 − R)·λ_a photons, spread as p_o over the longer cells.
        int n = Cells.Length;
        var p = Cells.Select(x => Gauss(x, 470, 25)).ToArray();
        const double r = 0.3;
        // The render's bands are the matrix's cells: 5 nm from 300 to 780 nm; the light is flat (E = 1).
        foreach (int a in new[] { 6, 10, 14, 18, 30 })   // 332.5, 352.5, 372.5, 392.5, 452.5 nm
        {
            var d = new double[n * n];
            for (int i = 0; i < n; i++) d[i * n + i] = r;
            double sum = Enumerable.Range(a + 1, n - a - 1).Sum(o => p[o]);
            for (int o = a + 1; o < n; o++) d[o * n + a] = (1 - r) * Cells[a] * (p[o] / sum) / Cells[o];
            var img = Render(Scene(Fluorescent(WriteMatrix($"column-{a}.csv", d)), light: "\"constant:1\"", bands: "300:780:96")).Image;
            // Photons per unit hc: emitted Σ_b (L_b − R)·w·λ_b (L constant on each band, so ∫_b L·λ dλ = L·w·λ_b), absorbed (1 − R)·w·λ_a.
            double emitted = 0;
            for (int b = 0; b < n; b++) emitted += (img[0, 0, b] - (double)(float)r) * 5 * Cells[b];   // R as the float band holds it
            double absorbed = (1 - r) * 5 * Cells[a];
            output.WriteLine($"excitation {Cells[a]} nm: emitted {emitted:G8}, absorbed {absorbed:G8} photons (× w/hc)");
            // Equal up to the float32 band values (≈ 6e-8 relative each): 1e-6.
            Assert.True(emitted <= absorbed * (1 + 1e-6), $"{Cells[a]} nm emits more photons than it absorbs");
            Assert.True(emitted >= absorbed * (1 - 1e-6), $"{Cells[a]} nm loses photons: {emitted} of {absorbed}");
        }
    }

    [Fact]
    public void A_matrix_that_re_emits_more_photons_than_it_absorbs_is_refused_in_one_line()
    {
        var d = ObaPaper(q: 0.8, strength: 0.9);
        int n = Cells.Length, i = 13;   // 367.5 nm: absorbs 1 − D[i,i]; make it emit twice that
        for (int o = 0; o < n; o++) if (o != i) d[o * n + i] *= 2 * (1 - d[i * n + i]) / (0.8 * 0.9 * Gauss(Cells[i], 365, 15));
        var path = WriteMatrix("bright.csv", d);
        var ex = Assert.Throws<InputException>(() => SceneText.Load(Scene(Fluorescent(path))));
        output.WriteLine(ex.Message);
        Assert.Contains("bright.csv:1", ex.Message);
        Assert.Contains("367.5 nm re-emits", ex.Message);
        Assert.DoesNotContain('\n', ex.Message);
        // And "diffuse" given beside the matrix is refused.
        var material = $$"""{ "diffuse": 0.5, "fluorescence": { "matrix": "{{path}}" } }""";
        var both = Assert.Throws<InputException>(() => SceneText.Load(Scene(material)));
        Assert.Contains("$.materials.paper.diffuse", both.Message);
    }

    /// <summary>
    /// Issue 42: the shipped fluorescence demos' previews do not clip. Their XYZ (xyz.npy) through IEC 61966-2-1's XYZ → linear
    /// sRGB matrix (written here) times the scene's exposure stays below 1 in every channel, where exposure 1 clipped the plain
    /// white's red (the scene white D50, not adapted).
    /// </summary>
    [Theory]
    [InlineData("fluorescence-paper-m1.json")]
    [InlineData("fluorescence-paper-m2.json")]
    public void The_fluorescence_demos_previews_do_not_clip(string scene)
    {
        var outDir = Path.Combine(_dir, Path.GetFileNameWithoutExtension(scene));
        var (code, _, err) = Cli.CliRunner.Run("render", Repo.PathOf("scenes", scene), "-o", outDir, "--width", "48", "--height", "24",
            "--formats", "npy", "--quiet");
        Assert.True(code == 0, err);
        var (_, xyz) = SpectralRenderer.Imaging.NpyReader.Read(File.OpenRead(Path.Combine(outDir, "xyz.npy")));
        double[,] m = { { 3.2406, -1.5372, -0.4986 }, { -0.9689, 1.8758, 0.0415 }, { 0.0557, -0.2040, 1.0570 } };
        double max = 0;
        for (int i = 0; i + 2 < xyz.Length; i += 3)
            for (int c = 0; c < 3; c++) max = Math.Max(max, m[c, 0] * xyz[i] + m[c, 1] * xyz[i + 1] + m[c, 2] * xyz[i + 2]);
        var manifest = System.Text.Json.Nodes.JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "render.json")))!;
        double exposure = (double)manifest["colour"]!["exposure"]!;
        Assert.True(max > 1, $"{scene}: brightest linear channel {max} at exposure 1: the test wants a scene that clipped there");
        Assert.True(max * exposure < 0.98, $"{scene}: brightest linear channel {max * exposure} at exposure {exposure}");
    }

    /// <summary>
    /// The shipped scene (its matrix from scripts/oba-paper-matrix.py) rendered under D50 with the per-light transfer, then
    /// relit to D65: the relit cube is byte for byte the fresh render under D65 (the shift follows the new light).
    /// </summary>
    [Fact]
    public void Relighting_a_fluorescent_render_equals_a_fresh_render_of_the_new_light()
    {
        File.Copy(Repo.PathOf("scenes", "oba-paper-matrix.csv"), Path.Combine(_dir, "oba-paper-matrix.csv"));
        var m1 = File.ReadAllText(Repo.PathOf("scenes", "fluorescence-paper-m1.json")).Replace("\"width\": 240, \"height\": 120",
            "\"width\": 24, \"height\": 12");
        var m2 = File.ReadAllText(Repo.PathOf("scenes", "fluorescence-paper-m2.json")).Replace("\"width\": 240, \"height\": 120",
            "\"width\": 24, \"height\": 12");
        Assert.Contains("\"filter\": \"uv-cut\"", m2);
        File.WriteAllText(Path.Combine(_dir, "m1.json"), m1);
        File.WriteAllText(Path.Combine(_dir, "d65.json"), m1.Replace("\"spectrum\": \"D50\" }", "\"spectrum\": \"D65\" }"));
        string Out(string name) => Path.Combine(_dir, name);
        var (code, _, err) = Cli.CliRunner.Run("render", Out("m1.json"), "-o", Out("m1"), "--formats", "npy,lights", "--quiet");
        Assert.True(code == 0, err);
        (code, _, err) = Cli.CliRunner.Run("render", Out("d65.json"), "-o", Out("d65"), "--formats", "npy", "--quiet");
        Assert.True(code == 0, err);
        (code, _, err) = Cli.CliRunner.Run("relight", Out("m1"), "--light", "light-0=D65", "-o", Out("relit"), "--quiet");
        Assert.True(code == 0, err);
        Assert.Equal(File.ReadAllBytes(Path.Combine(Out("d65"), "spectral.npy")), File.ReadAllBytes(Path.Combine(Out("relit"),
            "spectral.npy")));
        Assert.NotEqual(File.ReadAllBytes(Path.Combine(Out("m1"), "spectral.npy")), File.ReadAllBytes(Path.Combine(Out("relit"),
            "spectral.npy")));
    }

    /// <summary>
    /// The brightened paper under D50 with its UV (ISO 13655 M1) and through a UV-cut filter (M2), 2° observer, D50 white:
    /// the OBA's blue emission lowers b* under M1. Published sign and size: high-OBA papers measure b* ≈ −6 to −10 with UV in
    /// the illumination (print-audit.com, "Optical brighteners in substrates &amp; instrument errors: M0, M1, M2, M3", 2024),
    /// while the same papers without UV excitation (M2) read near the base paper's slightly yellow b*; R. Pasic, I. Kuzmanov,
    /// S. Mijakovska, "Print quality control management for papers containing optical brightening agents", IJSER 7(2) 271
    /// (2016) compare M-conditions on an OBA and a non-OBA board. So Δb* = b*(M1) − b*(M2) is negative and of a few units
    /// (1 &lt; |Δb*| &lt; 15). CIE whiteness (CIE 15:2004 §9.4, D65 10°): W = Y + 800(x_n − x) + 1700(y_n − y), reported with and without
    /// the UV part of D65: the OBA must raise W.
    /// </summary>
    [Fact]
    public void The_brightened_paper_is_bluer_under_M1_than_under_M2_by_a_published_amount()
    {
        var matrix = Fluorescent(WriteMatrix("oba.csv", ObaPaper()));
        Lab LabOf(string light, string white = "D50", string observer = "2")
        {
            var scene = SceneText.Load(Scene(matrix, light: light,
                extra: $"\"observer\": {observer},").Replace("\"white\": \"D50\"", $"\"white\": \"{white}\""));
            var result = Integrators.Render(scene, 0);
            var xyz = new Xyz(result.Xyz![0], result.Xyz[1], result.Xyz[2]);
            lastXyz = xyz;
            return Lab.FromXyz(xyz, scene.Colorimeter.White);
        }
        var m1 = LabOf("\"D50\"");
        var m2 = LabOf("\"D50\", \"filter\": \"uv-cut\"");
        double db = m1.B - m2.B;
        output.WriteLine($"M1 (D50 with UV): L* {m1.L:F2} a* {m1.A:F2} b* {m1.B:F2}; " +
            $"M2 (UV cut): L* {m2.L:F2} a* {m2.A:F2} b* {m2.B:F2}; Δb* = {db:F2}");
        Assert.True(m1.B < 0, "the brightened paper is bluish under M1");
        Assert.True(db < -1 && db > -15, $"Δb* {db}");

        double Whiteness(string light)
        {
            LabOf(light, "D65", "10");
            var c = lastXyz;
            double s = c.X + c.Y + c.Z, x = c.X / s, y = c.Y / s;
            return 100 * c.Y + 800 * (0.3138 - x) + 1700 * (0.3310 - y);
        }
        double withUv = Whiteness("\"D65\""), uvCut = Whiteness("\"D65\", \"filter\": \"uv-cut\"");
        output.WriteLine($"CIE whiteness (D65, 10°): {withUv:F1} with UV, {uvCut:F1} UV cut");
        Assert.True(withUv > uvCut + 10, "the OBA raises the CIE whiteness");
    }

    Xyz lastXyz;
}
