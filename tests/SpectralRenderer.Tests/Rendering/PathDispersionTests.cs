using System.Globalization;
using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Dispersion in the path integrator (issue 23): at the first dispersive vertex a path splits into one sub-path per output
/// band, each refracting with its band's index. Checked against the Whitted integrator's per-band refraction (a second
/// implementation of the same chain), against Snell's law traced here through a prism, against energy conservation in a
/// white furnace, for thread-count independence and for the per-light transfer (relight = re-render).
/// </summary>
public class PathDispersionTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string Num(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    static string V(Vector3 v) => $"[{Num(v.X)}, {Num(v.Y)}, {Num(v.Z)}]";

    /// <summary>One camera ray's band values from an integrator (the result's first <c>Bands</c> lanes).</summary>
    static float[] Bands(IIntegrator integrator, Scene scene, in CameraSample sample, out int first)
    {
        var result = new float[scene.PaddedBands];
        var scratch = new float[integrator.ScratchLength];
        var counters = new RayCounters();
        first = integrator.Radiance(in sample, result, scratch, ref counters);
        return result[..scene.Bands];
    }

    /// <summary>
    /// A camera looks through a tilted dispersive slab (Cauchy, Fresnel transmission only) at a Lambertian plane lit by a
    /// directional light, or a point light (whose fall-off makes each band's shifted image differ more), that the slab does
    /// not shadow; the path integrator stops at max_depth 3, so the only chain is camera → slab → slab → plane → light. Its radiance per
    /// band equals the Whitted integrator's (which refracts each band along its own ray, Eq2Walker) for every pixel behind the glass, while
    /// the bands differ from each other by dispersion.
    /// </summary>
    [Theory]
    [InlineData("""{ "type": "directional", "direction": [-1, 0.2, -0.3], "spectrum": { "constant": 1 }, "intensity": 0.5 }""", 0.005)]
    [InlineData("""{ "type": "point", "position": [2.5, 0.5, 1.2], "spectrum": { "constant": 1 }, "intensity": 4 }""", 0.02)]
    public void Through_a_dispersive_slab_each_band_equals_the_Whitted_integrators_refraction(string light, double minSpread)
    {
        var scene = SceneText.Load($$"""
        { "radiometry": "physical", "bands": "400:700:10", "max_depth": 6, "integrator": { "type": "path", "max_depth": 3 },
          "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 30, "width": 24, "height": 24 },
          "materials": { "glass": { "diffuse": 0, "ambient": 0, "transmit": 1, "fresnel": true, "ior": { "cauchy": [1.5, 30000] } },
                         "ground": { "diffuse": 0.8, "ambient": 0 } },
          "lights": [ {{light}} ],
          "objects": [ { "type": "box", "name": "slab", "center": [0, 0, 0], "size": [2.4, 2.4, 1.2],
                         "transform": { "rotate": [0, 40, 0], "translate": [0, 0, 3] }, "material": "glass" },
                       { "type": "plane", "name": "ground", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "ground" } ] }
        """);
        var geometry = new SceneGeometry(scene);
        var path = Integrators.Create(scene, geometry, "path");
        var whitted = Integrators.Create(scene, geometry, "whitted");
        int slab = scene.Objects.FindIndex(o => o.Name == "slab");
        int compared = 0;
        double worst = 0, spread = 0;
        for (int y = 0; y < 24; y++)
            for (int x = 0; x < 24; x++)
            {
                var sample = new CameraSample(x, y, 0, scene.Camera.Generate(x + 0.5f, y + 0.5f));
                var p = Bands(path, scene, in sample, out int first);
                var w = Bands(whitted, scene, in sample, out _);
                if (first != slab) continue;
                compared++;
                double max = w.Max();
                if (!(max > 0)) continue;
                for (int b = 0; b < scene.Bands; b++)
                {
                    worst = Math.Max(worst, Math.Abs(p[b] - w[b]) / max);
                    Assert.True(Math.Abs(p[b] - w[b]) <= 2e-5 * max, $"pixel ({x}, {y}) band {b}: path {p[b]:g7} vs Whitted {w[b]:g7}");
                }
                spread = Math.Max(spread, (max - w.Min()) / max);
            }
        output.WriteLine($"{compared} pixels through the slab: largest |path − Whitted| {worst:e2} of the pixel's largest "
            + $"band; band spread up to {spread:P1}");
        Assert.True(compared > 150, $"only {compared} pixels see the slab");
        Assert.True(spread > minSpread, $"the bands differ by at most {spread:P2}: no dispersion to check");
    }

    // The prism: an equilateral triangle of side 2 about an axis parallel to y through Axis, its faces' outward normals
    // (sin φ, 0, cos φ) at φ = −50°, 70°, 190°; the camera looks at the middle of the −50° face (rays leave through the 190° one).
    const double Side = 2, Phi0 = -50, CauchyA = 1.5, CauchyB = 20000;
    static readonly double Inradius = Side / (2 * Math.Sqrt(3));
    static readonly Vector3 Axis = (-FaceNormal(0) * (float)Inradius) with { Z = 0 };

    static Vector3 FaceNormal(int k)
    {
        double phi = (Phi0 + 120 * k) * Math.PI / 180;
        return new Vector3((float)Math.Sin(phi), 0, (float)Math.Cos(phi));
    }

    /// <summary>Snell's law in vector form (Hecht §4.4): d refracted at a surface of unit normal n facing d's origin,
    /// η = n_i/n_t; null under total internal reflection.</summary>
    static Vector3? Snell(Vector3 d, Vector3 n, double eta)
    {
        double cosI = -Vector3.Dot(n, d);
        double sin2T = eta * eta * (1 - cosI * cosI);
        if (sin2T >= 1) return null;
        double cosT = Math.Sqrt(1 - sin2T);
        return Vector3.Normalize((float)eta * d + (float)(eta * cosI - cosT) * n);
    }

    /// <summary>A ray through the prism (the intersection of the faces' half-spaces n_k·x ≤ r) at index n: where it leaves and
    /// in which direction, or null (missed, or totally reflected inside).</summary>
    static (Vector3 P, Vector3 D)? ThroughPrism(Vector3 o, Vector3 d, double n)
    {
        double tIn = double.NegativeInfinity, tOut = double.PositiveInfinity;
        int entry = -1;
        for (int k = 0; k < 3; k++)
        {
            var nk = FaceNormal(k);
            double dn = Vector3.Dot(nk, d), t = (Inradius - Vector3.Dot(nk, o - Axis)) / dn;
            if (dn < 0 && t > tIn) { tIn = t; entry = k; }
            else if (dn > 0) tOut = Math.Min(tOut, t);
        }
        if (entry < 0 || tIn >= tOut) return null;
        var p = o + (float)tIn * d;
        if (Snell(d, FaceNormal(entry), 1 / n) is not { } inside) return null;
        double tExit = double.PositiveInfinity;
        int exit = -1;
        for (int k = 0; k < 3; k++)
        {
            var nk = FaceNormal(k);
            double dn = Vector3.Dot(nk, inside);
            if (k == entry || dn <= 0) continue;
            double t = (Inradius - Vector3.Dot(nk, p - Axis)) / dn;
            if (t < tExit) { tExit = t; exit = k; }
        }
        var q = p + (float)tExit * inside;
        return Snell(inside, -FaceNormal(exit), n) is { } outside ? (q, outside) : null;
    }

    const int PrismWidth = 200, PrismHeight = 5;

    // "fov" is the vertical field of view: 0.75° over 5 rows is about 30° over 200 columns.
    static string PrismScene(string strip, int spp = 1, double mirror = 0, int width = PrismWidth, int height = PrismHeight) => $$"""
        { "radiometry": "physical", "bands": "400:700:10", "integrator": "path",
          "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": {{Num(0.75 * height / PrismHeight)}}, "width": {{width}},
            "height": {{height}}, "spp": {{spp}} },
          "materials": { "glass": { "diffuse": 0, "transmit": 1, "mirror": {{Num(mirror)}}, "fresnel": true,
            "ior": { "cauchy": [{{Num(CauchyA)}}, {{Num(CauchyB)}}] } },
                         "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": { "constant": 1 }, "radiance": 1,
                           "two_sided": true } } },
          "objects": [
            {{string.Join(",\n", Enumerable.Range(0, 3).Select(k =>
                $$"""{ "type": "quad", "name": "face{{k}}", "center": {{V(Axis + FaceNormal(k) * (float)Inradius)}},""" +
                    $$""" "size": [{{Num(Side)}}, 8], "normal": {{V(FaceNormal(k))}}, "up": [0, 1, 0], "material": "glass" }"""))}}
            {{strip}} ] }
        """;

    /// <summary>
    /// A white emitting slit seen through a glass prism (Cauchy n = 1.5 + 20000 nm²/λ²): each band's image of the slit lies
    /// where Snell's law, traced here through the prism's faces at the band's centre wavelength, sends the camera's pixel
    /// rays onto the slit — within a pixel — and the bands are spread over tens of pixels (a rainbow, not a white line).
    /// </summary>
    [Fact]
    public void A_prism_spreads_a_white_slit_into_bands_where_Snells_law_puts_them()
    {
        var camera = SceneText.Load(PrismScene("")).Camera;
        int row = PrismHeight / 2;
        double Index(double nm) => CauchyA + CauchyB / (nm * nm);
        // The slit: 4 units beyond the prism along the centre pixel's ray at 550 nm, facing back along it.
        var centre = camera.Generate(PrismWidth / 2 + 0.5f, row + 0.5f);
        var (exitPoint, exitDir) = ThroughPrism(centre.Origin, centre.Direction, Index(550))
            ?? throw new InvalidOperationException("the centre ray misses the prism");
        var slit = exitPoint + 4 * exitDir;
        var across = Vector3.Normalize(Vector3.Cross(Vector3.UnitY, -exitDir));
        // Signed distance across the slit of pixel x's ray at wavelength nm (NaN: it does not get through).
        double Across(int x, double nm)
        {
            var ray = camera.Generate(x + 0.5f, row + 0.5f);
            if (ThroughPrism(ray.Origin, ray.Direction, Index(nm)) is not { } through) return double.NaN;
            var (p, d) = through;
            float t = Vector3.Dot(slit - p, -exitDir) / Vector3.Dot(d, -exitDir);
            return Vector3.Dot(p + t * d - slit, across);
        }
        double step = Math.Abs(Across(PrismWidth / 2 + 1, 550) - Across(PrismWidth / 2, 550));
        double width = 3 * step;
        string strip = $$""", { "type": "quad", "name": "slit", "center": {{V(slit)}}, "size": [{{Num(width)}}, 40],""" +
            $$""" "normal": {{V(-exitDir)}}, "up": [0, 1, 0], "material": "lamp" }""";
        var scene = SceneText.Load(PrismScene(strip));
        var path = Integrators.Create(scene, new SceneGeometry(scene), "path");
        var image = new float[PrismWidth][];
        for (int x = 0; x < PrismWidth; x++)
            image[x] = Bands(path, scene, new CameraSample(x, row, 0, camera.Generate(x + 0.5f, row + 0.5f)), out _);

        var predicted = new double[scene.Bands];
        var seen = new double[scene.Bands];
        for (int b = 0; b < scene.Bands; b++)
        {
            double nm = 400 + 30 * (b + 0.5);   // the band's centre: 10 bands over 400–700 nm
            // Predicted: the (fractional) column where the ray crosses the slit's centre line.
            predicted[b] = double.NaN;
            for (int x = 0; x + 1 < PrismWidth; x++)
            {
                double a = Across(x, nm), c = Across(x + 1, nm);
                if (a * c <= 0 && a != c && Math.Abs(a - c) < 10 * step) { predicted[b] = x + a / (a - c); break; }
            }
            // Rendered: the slit's centroid over the columns in this band.
            double sum = 0, moment = 0;
            for (int x = 0; x < PrismWidth; x++) { sum += image[x][b]; moment += x * image[x][b]; }
            Assert.True(sum > 0, $"band {b} ({nm} nm): the slit is not seen through the prism");
            seen[b] = moment / sum;
            Assert.False(double.IsNaN(predicted[b]), $"band {b}: Snell's law sends no pixel ray onto the slit");
            Assert.True(Math.Abs(seen[b] - predicted[b]) <= 1,
                $"band {b} ({nm} nm): slit at column {seen[b]:F2}, Snell's law puts it at {predicted[b]:F2}");
            // Through glass only: a band's light comes from its own refraction (other columns of this band are dark).
            for (int x = 0; x < PrismWidth; x++)
                if (Math.Abs(x - predicted[b]) > 3)
                    Assert.True(image[x][b] == 0, $"band {b}: light at column {x}, far from the slit's image");
        }
        output.WriteLine("band centre → slit column (rendered / Snell): " + string.Join(", ",
            Enumerable.Range(0, scene.Bands)
                .Select(b => string.Create(CultureInfo.InvariantCulture, $"{400 + 30 * (b + 0.5)} nm {seen[b]:F1}/{predicted[b]:F1}"))));
        Assert.True(Math.Abs(predicted[0] - predicted[^1]) > 15, $"415 nm at {predicted[0]:F1}, 685 nm at {predicted[^1]:F1}: not spread");
    }

    [Fact]
    public void A_dispersive_path_render_is_the_same_bits_on_1_and_2_threads()
    {
        var camera = SceneText.Load(PrismScene("", width: 64, height: 16)).Camera;
        var centre = camera.Generate(32.5f, 8.5f);
        var (exitPoint, exitDir) =
            ThroughPrism(centre.Origin, centre.Direction, 1.57) ?? throw new InvalidOperationException("the centre ray misses the prism");
        string strip = $$""", { "type": "quad", "name": "slit", "center": {{V(exitPoint + 4 * exitDir)}}, "size": [0.3, 40],""" +
            $$""" "normal": {{V(-exitDir)}}, "up": [0, 1, 0], "material": "lamp" }""";
        var scene = SceneText.Load(PrismScene(strip, spp: 2, mirror: 1, width: 64, height: 16));
        var integrator = Integrators.Create(scene, new SceneGeometry(scene), "path");
        var one = Renderer.Render(scene, integrator, threads: 1);
        var two = Renderer.Render(scene, integrator, threads: 2);
        Assert.Equal(one.Image.Data, two.Image.Data);
        Assert.Equal(one.Xyz, two.Xyz);
        Assert.True(one.Image.Data.Any(v => v > 0), "the slit is seen");
    }

    /// <summary>
    /// A lossless dispersive glass sphere (Sellmeier N-BK7, k_r = k_t = 1 with Fresnel: R + T = 1 in every band) under a
    /// uniform sky: every ray, however it splits and bounces, leaves with the sky's radiance, so each band is the sky's
    /// band mean (computed here by quadrature of D65). Without Russian roulette before depth 100 exactly; with it from depth
    /// 2, within 4 standard errors.
    /// </summary>
    [Theory]
    [InlineData(100, 2e-4)]
    [InlineData(2, 0)]
    public void A_dispersive_glass_sphere_in_a_white_furnace_returns_the_sky_in_every_band(int rrDepth, double tolerance)
    {
        var scene = SceneText.Load($$"""
        { "radiometry": "physical", "bands": "400:700:10", "integrator": { "type": "path", "rr_depth": {{rrDepth}} },
          "camera": { "position": [0, 0, 4], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "background": { "name": "D65", "scale": 0.01 },
          "materials": { "glass": { "diffuse": 0, "ambient": 0, "mirror": 1, "transmit": 1, "fresnel": true,
            "ior": { "sellmeier": { "B1": 1.03961212, "B2": 0.231792344, "B3": 1.01046945, "C1": 0.00600069867, "C2": 0.0200179144,
              "C3": 103.560653 } } } },
          "objects": [ { "type": "sphere", "radius": 1, "material": "glass" } ] }
        """);
        Assert.True(scene.Materials[0].Dispersive);
        var d65 = SpectrumLibrary.Resolve("D65");
        foreach (var target in new[] { new Vector3(0.3f, 0.2f, 0), new Vector3(0.8f, -0.3f, 0), new Vector3(0, 0.95f, 0) })
        {
            var (mean, error) =
                PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0, 0, 4), Vector3.Normalize(target - new Vector3(0, 0, 4))), 2000);
            for (int b = 0; b < scene.Bands; b++)
            {
                double expected = PathIntegratorTests.BandMean(l => 0.01 * d65.Evaluate(l), scene.Grid.Lower(b), scene.Grid.Upper(b));
                double allowed = tolerance > 0 ? tolerance * expected : 4 * error[b] + 2e-4 * expected;
                Assert.True(Math.Abs(mean[b] - expected) <= allowed,
                    $"towards {target}, band {b}: {mean[b]:g6} vs the sky's {expected:g6} (±{error[b]:g2})");
            }
        }
    }

    /// <summary>
    /// The per-light transfer of a dispersive path render: relit to other light spectra it equals a path render of the
    /// changed scene (≤ 1e-5), as for any path render (PathRelightTests) — the split takes no decision from a light's spectrum.
    /// </summary>
    [Fact]
    public void A_dispersive_path_render_relit_equals_a_render_of_the_changed_light()
    {
        static string Scene(string spectrum) => $$"""
            { "radiometry": "physical", "bands": "400:700:10", "integrator": "path",
              "camera": { "position": [0, 1, 3.2], "look_at": [0, 0.5, 0], "fov": 50, "width": 16, "height": 12, "spp": 2 },
              "background": { "spectrum": "D65", "luminance": 5 },
              "materials": { "white": { "type": "lambertian", "reflectance": 0.75 },
                             "glass": { "diffuse": 0, "mirror": 1, "transmit": 1, "fresnel": true, "ior": { "cauchy": [1.5, 20000] } } },
              "lights": [ { "type": "point", "name": "bulb", "position": [0.5, 1.6, 0.5], "spectrum": "{{spectrum}}", "intensity": 0.3 } ],
              "objects": [ { "type": "quad", "name": "floor", "center": [0, 0, 0], "size": [3, 3], "normal": [0, 1, 0], "up": [0, 0, -1],
                "material": "white" },
                           { "type": "sphere", "name": "lens", "center": [0, 0.5, 0], "radius": 0.45, "material": "glass" } ] }
            """;
        var dir = Reference.TempDir();
        string Write(string name, string json) { var p = Path.Combine(dir, name); File.WriteAllText(p, json); return p; }
        float[] Npy(string folder, string file)
        {
            using var s = File.OpenRead(Path.Combine(dir, folder, file));
            return NpyReader.Read(s).Data;
        }
        Assert.Equal(0,
            CliRunner.Run("render", Write("a.json", Scene("A")), "-o", Path.Combine(dir, "a"), "--formats", "npy,lights", "--quiet").Exit);
        Assert.Equal(0,
            CliRunner.Run("render", Write("b.json", Scene("led-blue")), "-o", Path.Combine(dir, "b"), "--formats", "npy", "--quiet").Exit);
        var (code, _, err) =
            CliRunner.Run("relight", Path.Combine(dir, "a"), "-o", Path.Combine(dir, "relit"), "--light", "bulb=led-blue", "--quiet");
        Assert.True(code == 0, err);
        foreach (var file in new[] { "spectral.npy", "xyz.npy" })
        {
            float[] direct = Npy("b", file), relit = Npy("relit", file), source = Npy("a", file);
            double worst = 0, change = 0;
            for (int i = 0; i < direct.Length; i++)
            {
                double scale = Math.Max(Math.Abs(direct[i]), 1e-30);
                worst = Math.Max(worst, Math.Abs(direct[i] - relit[i]) / scale);
                change = Math.Max(change, Math.Abs(direct[i] - source[i]) / scale);
            }
            output.WriteLine($"{file}: relit vs direct {worst:e2}, source vs direct {change:e2}");
            Assert.True(worst <= 1e-5, $"{file}: relit differs from the direct render by {worst:e2}");
            Assert.True(change > 0.1, $"{file}: the relight changed little ({change:e2})");
        }
    }

    /// <summary>Sellmeier's formula for Schott N-BK7 against the catalogue's indices (Schott data sheet: n_F = 1.52238 at
    /// 486.13 nm, n_d = 1.51680 at 587.56 nm, n_C = 1.51432 at 656.27 nm), and the scene's bands take it at their centres.</summary>
    [Fact]
    public void Sellmeier_index_matches_the_N_BK7_catalogue_and_is_taken_at_the_band_centres()
    {
        double[] b = [1.03961212, 0.231792344, 1.01046945], c = [0.00600069867, 0.0200179144, 103.560653];
        Assert.Equal(1.52238, RefractiveIndex.Sellmeier(b, c, 486.13), 5);
        Assert.Equal(1.51680, RefractiveIndex.Sellmeier(b, c, 587.56), 5);
        Assert.Equal(1.51432, RefractiveIndex.Sellmeier(b, c, 656.27), 5);
        var scene = SceneText.Load("""
        { "bands": "400:700:10", "camera": { "position": [0, 0, 4], "look_at": [0, 0, 0], "width": 4, "height": 4 },
          "materials": { "glass": { "transmit": 1, "ior": { "sellmeier": { "B1": 1.03961212, "B2": 0.231792344, "B3": 1.01046945,
                                                                            "C1": 0.00600069867, "C2": 0.0200179144,
                                                                              "C3": 103.560653 } } } },
          "objects": [ { "type": "sphere", "material": "glass" } ] }
        """);
        var glass = scene.Materials[0];
        Assert.True(glass.Dispersive);
        for (int i = 0; i < 10; i++)
            Assert.Equal((float)RefractiveIndex.Sellmeier(b, c, 400 + 30 * (i + 0.5)), glass.Ior[i]);
    }

    /// <summary>
    /// A tabulated index {"spectrum": …} (how pbrt's named glasses arrive): at each band centre the linear interpolant of the
    /// table, computed here from the pairs by hand; a varying table makes the glass dispersive, a flat one does not.
    /// </summary>
    [Fact]
    public void A_tabulated_index_is_the_tables_interpolant_at_each_band_centre()
    {
        double[] wl = [380, 450, 560, 700, 780], n = [1.56, 1.53, 1.52, 1.51, 1.505];
        var scene = SceneText.Load("""
        { "bands": "400:700:10", "camera": { "position": [0, 0, 4], "look_at": [0, 0, 0], "width": 4, "height": 4 },
          "materials": { "glass": { "transmit": 1,
                                    "ior": { "spectrum": [[380, 1.56], [450, 1.53], [560, 1.52], [700, 1.51], [780, 1.505]] } },
                         "flat": { "transmit": 1, "ior": { "spectrum": 1.45 } } },
          "objects": [ { "type": "sphere", "material": "glass" }, { "type": "sphere", "center": [3, 0, 0], "material": "flat" } ] }
        """);
        var glass = scene.Materials[0];
        Assert.True(glass.Dispersive);
        for (int i = 0; i < 10; i++)
        {
            double centre = 400 + 30 * (i + 0.5);
            int k = Array.FindLastIndex(wl, w => w <= centre);
            double expected = n[k] + (centre - wl[k]) / (wl[k + 1] - wl[k]) * (n[k + 1] - n[k]);
            Assert.Equal((float)expected, glass.Ior[i]);
        }
        Assert.False(scene.Materials[1].Dispersive);
        Assert.Equal(1.45f, scene.Materials[1].Ior[3]);
    }

    [Theory]
    [InlineData("""{ "sellmeier": [1, 2] }""", "$.materials.glass.ior.sellmeier", "expected an object of B1")]
    [InlineData("""{ "sellmeier": { "B1": 1, "B4": 1 } }""", "$.materials.glass.ior.sellmeier", "unknown field 'B4'")]
    [InlineData("""{ "sellmeier": { "B1": 1, "C1": 0.3 } }""", "$.materials.glass.ior", "resonance")]
    [InlineData("""{ "cauchy": [1.5, 4200], "sellmeier": { "B1": 1 } }""", "$.materials.glass.ior", "give one dispersion formula")]
    [InlineData("""{ }""", "$.materials.glass.ior", "expected \"cauchy\" or \"sellmeier\"")]
    [InlineData("""{ "spectrum": [[500, 1.5], [600, 1.4]] }""", "$.materials.glass.ior.spectrum", "but the bands need")]
    [InlineData("""{ "spectrum": 1.5, "cauchy": [1.5, 0] }""", "$.materials.glass.ior", "give one dispersion formula")]
    public void A_bad_dispersion_formula_names_its_place(string ior, string place, string message)
    {
        var e = Assert.Throws<InputException>(() => SceneText.Load($$"""
        { "bands": "400:700:10", "camera": { "position": [0, 0, 4], "look_at": [0, 0, 0], "width": 4, "height": 4 },
          "materials": { "glass": { "transmit": 1, "ior": {{ior}} } }, "objects": [ { "type": "sphere", "material": "glass" } ] }
        """));
        Assert.Contains(place, e.Message);
        Assert.Contains(message, e.Message);
    }
}
