using System.Globalization;
using System.Text;
using System.Text.Json.Nodes;
using SpectralRenderer.Geometry;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Distributed;
using SpectralRenderer.Tests.Rendering;
using static SpectralRenderer.Tests.Relight.PathRelightTests;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// Issue 26: relighting a path render of a fluorescent scene. A fluorescent shift moves light between sub-bands, so light
/// k reaches a pixel through a matrix — its diagonal transfer T_k plus a block B_k (emission × excitation sub-bands) kept in
/// lights/shift.npy. The path integrator takes no sampling decision from a light's spectrum (lobes by the albedos under
/// the camera-side throughput β, Russian roulette by β and the shifts' gain), so a relight makes the same decisions as a
/// render of the relit scene: the bar is float rounding (≤ 1e-5 relative per band, XYZ channel and sub-band; no
/// statistical tolerance is needed), checked against the independent computation — the renderer tracing every path again
/// with the changed spectra (the film's own sink and its shifted-bounce carrying, PathIntegrator.Fluorescence.cs). A room
/// of an optically brightened sheet on a brightened floor (paths through two and more shifted bounces) beside a white
/// ball, under a D50 point lamp, a D65 directional light and a dim D65 sky (the fixed part, not relit), relit to the lamp
/// behind a UV-cut filter (ISO 13655 M2) and the directional light ×3, and with the directional light off.
/// </summary>
public class PathFluorescentRelightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    static double[] Cells => FluorescenceTests.Cells;   // 302.5 … 777.5 nm: the 5 nm cells of the matrices, the path's sub-bands
    static int N => Cells.Length;

    static string Room(string lamp = "D50", double lampIntensity = 6, double sunIntensity = 1, int width = 24, int height = 16,
        int spp = 4, string matrix = "oba.csv") => $$"""
        { "radiometry": "physical", "bands": "300:780:48", "white": "D50", "integrator": "path",
          "camera": { "position": [0, 1.2, 5], "look_at": [0, 0, 0], "fov": 45, "width": {{width}}, "height": {{height}}, "spp": {{spp}} },
          "background": { "spectrum": "D65", "luminance": 3 },
          "materials": {
            "paper": { "type": "lambertian", "fluorescence": { "matrix": "{{matrix}}" } },
            "white": { "type": "lambertian", "reflectance": 0.8 } },
          "lights": [
            { "type": "point", "name": "lamp", "position": [0.5, 2.5, 2], "spectrum": "{{lamp}}", "intensity": {{Num(lampIntensity)}} },
            { "type": "directional", "name": "sun", "direction": [0.3, -1, -0.4], "spectrum": "D65", "intensity": {{Num(sunIntensity)}} } ],
          "objects": [
            { "type": "quad", "name": "sheet", "center": [-0.8, 0.3, 0], "normal": [0, 0, 1], "size": [1.4, 1.4], "material": "paper" },
            { "type": "plane", "name": "floor", "point": [0, -1, 0], "material": "paper" },
            { "type": "sphere", "name": "ball", "center": [0.8, -0.4, 0], "radius": 0.6, "material": "white" } ] }
        """;

    static string Num(double v) => v.ToString("R", Inv);

    /// <summary>A folder with the brightener's matrix (FluorescenceTests.ObaPaper on the 5 nm cells) as oba.csv and a UV-cut D50.</summary>
    static string Folder()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "oba.csv"), FluorescenceTests.MatrixCsv(Cells, FluorescenceTests.ObaPaper()));
        // D50 (data/illuminants-300-780.csv, read here) times a UV-cut edge: 0 to 395 nm, rising linearly to 1 at 405 nm.
        var lines = File.ReadAllLines(Repo.PathOf("data", "illuminants-300-780.csv"));
        int c = Array.IndexOf(lines[0].Split(','), "D50");
        var csv = new StringBuilder("wavelength_nm,E\n");
        foreach (var r in lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')))
        {
            double l = double.Parse(r[0], Inv), e = double.Parse(r[c], Inv);
            csv.Append(Inv, $"{l:R},{e * Math.Clamp((l - 395) / 10, 0, 1):R}\n");
        }
        File.WriteAllText(Path.Combine(dir, "d50-uvcut.csv"), csv.ToString());
        return dir;
    }

    static string UvCut(string dir) => Path.Combine(dir, "d50-uvcut.csv").Replace("\\", "/") + ":E";

    /// <summary>The largest relative difference of <paramref name="actual"/> from <paramref name="expected"/> (both 0: none).</summary>
    static double WorstRelative(ReadOnlySpan<float> expected, ReadOnlySpan<float> actual)
    {
        Assert.Equal(expected.Length, actual.Length);
        double worst = 0;
        for (int i = 0; i < expected.Length; i++)
        {
            if (expected[i] == actual[i]) continue;
            worst = Math.Max(worst, Math.Abs(expected[i] - actual[i]) / Math.Max(Math.Abs(expected[i]), 1e-30));
        }
        return worst;
    }

    static Scene Load(string dir, string json) => SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));

    [Fact]
    public void A_fluorescent_path_render_relit_to_its_own_lights_is_the_render_and_to_other_spectra_a_render_of_them()
    {
        var dir = Folder();
        var source = Path.Combine(dir, "source");
        var (code, err) = PathRelightTests.Cli("render", Write(dir, "a.json", Room()), "-o", source, "--formats", "npy,lights");
        Assert.True(code == 0, err);
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(source, "lights", "lights.json")))!;
        Assert.Equal(2, (int)json["version"]!);
        // The block spans the brightener's excitation (its absorption peaks at 365 nm) and its emission (peak 440 nm).
        double[] ex = [.. json["shift"]!["excitation_nm"]!.AsArray().Select(x => (double)x!)];
        double[] em = [.. json["shift"]!["emission_nm"]!.AsArray().Select(x => (double)x!)];
        Assert.True(ex[0] <= 340 && ex[1] >= 400 && em[0] <= 420 && em[1] >= 470,
            $"excitation {ex[0]}–{ex[1]} nm, emission {em[0]}–{em[1]} nm");

        // Unchanged lights (the directional light given its own intensity): the render itself.
        var same = Path.Combine(dir, "same");
        (code, err) = PathRelightTests.Cli("relight", source, "-o", same, "--intensity", "sun=1");
        Assert.True(code == 0, err);
        double bands = WorstRelative(Npy(source, "spectral.npy"), Npy(same, "spectral.npy"));
        double colour = WorstRelative(Npy(source, "xyz.npy"), Npy(same, "xyz.npy"));
        output.WriteLine($"relit to its own lights vs the render: {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
        Assert.True(bands <= 1e-5 && colour <= 1e-5, $"{bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");

        // M1 → M2: the lamp behind a UV-cut filter, the directional light ×3; then the directional light off.
        int run = 0;
        foreach (var (name, args, scene) in new[]
        {
            ("uv-cut lamp, sun ×3", new[] { "--light", $"lamp={UvCut(dir)}", "--intensity", "sun=3" }, Room(UvCut(dir), sunIntensity: 3)),
            ("lamp ×0.5, sun off", new[] { "--intensity", "lamp=3", "--intensity", "sun=0" }, Room(lampIntensity: 3, sunIntensity: 0)),
        })
        {
            var relit = Path.Combine(dir, $"relit-{++run}");
            (code, err) = PathRelightTests.Cli(["relight", source, "-o", relit, .. args]);
            Assert.True(code == 0, err);
            var direct = Path.Combine(dir, $"direct-{run}");
            (code, err) = PathRelightTests.Cli("render", Write(dir, $"direct-{run}.json", scene), "-o", direct, "--formats", "npy");
            Assert.True(code == 0, err);
            bands = WorstRelative(Npy(direct, "spectral.npy"), Npy(relit, "spectral.npy"));
            colour = WorstRelative(Npy(direct, "xyz.npy"), Npy(relit, "xyz.npy"));
            // The change itself, as the largest difference from the source relative to the source's brightest band value.
            var (before, after) = (Npy(source, "spectral.npy"), Npy(direct, "spectral.npy"));
            double change = before.Zip(after).Max(p => Math.Abs(p.First - p.Second)) / before.Max();
            output.WriteLine($"{name}: relit vs rendered {bands:0.###e0} (bands), {colour:0.###e0} (XYZ); " +
                $"the change itself {change:P0} of the peak");
            Assert.True(bands <= 1e-5 && colour <= 1e-5, $"{name}: {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
            Assert.True(change > 0.1, $"{name}: the relight changed little ({change})");
        }
    }

    [Fact]
    public void The_block_carries_the_shifted_light_and_the_fine_film_from_it_is_the_traced_one_under_other_lights_too()
    {
        var dir = Folder();
        var scene = Load(dir, Room());
        var integrator = new PathIntegrator(scene, new SceneGeometry(scene));
        var t = PathTransfer.Trace(scene, integrator, threads: 2);
        Assert.False(t.Shift.IsEmpty);
        var render = Renderer.Render(scene, integrator, threads: 2);
        var (image, xyz) = t.Relight(scene);
        double bands = WorstRelative(render.Image.Data, image.Data), colour = WorstRelative(render.Xyz!, xyz);
        output.WriteLine($"relight in memory vs the render: {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
        Assert.True(bands <= 1e-5 && colour <= 1e-5);

        // The camera's exact route and libspectral read the sub-band film from the transfer: against the film traced again (the
        // render's samples through the film's sink), under the render's lights and under the UV-cut lamp.
        foreach (var lit in new[] { scene, Load(dir, Room(UvCut(dir), sunIntensity: 3)) })
        {
            var fromTransfer = PathFilm.FromTransfer(t, lit);
            var traced = PathFilm.Trace(lit, new PathIntegrator(lit, new SceneGeometry(lit)), threads: 2);
            double fine = WorstRelative(traced.Data, fromTransfer.Data);
            string lamp = ReferenceEquals(lit, scene) ? "D50" : "UV-cut";
            output.WriteLine($"fine film from the transfer vs traced (lamp {lamp}): {fine:0.###e0}");
            Assert.True(fine <= 1e-5, $"{fine:0.###e0}");
        }

        // Without its block the transfer misses the brightener's emission: the sheet's and the floor's blue sub-bands lose
        // more than 5 % (the OBA re-emits around 440 nm what it absorbs at 340–400 nm).
        var plain = new PathTransfer
        {
            FilmWidth = t.FilmWidth,
            FilmHeight = t.FilmHeight,
            Region = t.Region,
            Bands = t.Bands,
            Lights = t.Lights,
            SpectralGrid = t.SpectralGrid,
            SubBands = t.SubBands,
            Data = t.Data,
            ObjectIds = t.ObjectIds,
            LitMasks = t.LitMasks,
        };
        var with = PathFilm.FromTransfer(t, scene);
        var without = PathFilm.FromTransfer(plain, scene);
        int f440 = Array.FindIndex(with.Lower, l => l >= 440);
        double loss = 0;
        for (int i = 0; i < t.ObjectIds.Length; i++)
            if (t.ObjectIds[i] is 0 or 1 && with.Data[i * with.SubBands + f440] > 0)
                loss = Math.Max(loss, 1 - without.Data[i * with.SubBands + f440] / with.Data[i * with.SubBands + f440]);
        output.WriteLine($"largest share of the 440–445 nm radiance that the block carries on the brightened surfaces: {loss:P1}");
        Assert.True(loss > 0.05, $"{loss:P1}");
    }

    /// <summary>
    /// Inside a closed brightened sphere (the paper of FluorescenceTests, diagonal ≈ 0.88, no emission) lit by a point lamp
    /// and a second, UV-rich point light: paths bounce many times, most through one or more shifted bounces, so the block is
    /// carried through products of shifts (P = A_1⋯A_j).
    /// </summary>
    static string Furnace(string lamp, double uv, bool glass = false) => $$"""
        { "radiometry": "physical", "bands": "300:780:48", "white": "D50", "integrator": "path",
          "camera": { "position": [0, 0, 0.5], "look_at": [0, 0, -1], "fov": 70, "width": 12, "height": 8, "spp": 4 },
          "materials": { "paper": { "type": "lambertian", "fluorescence": { "matrix": "oba.csv" } }{{(glass ? Glass : "")}} },
          "lights": [ { "type": "point", "name": "lamp", "position": [0.3, 0.4, -0.2], "spectrum": "{{lamp}}", "intensity": 1 },
                      { "type": "point", "name": "uv", "position": [-0.4, -0.3, 0.1], "spectrum": "D65", "intensity": {{Num(uv)}} } ],
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "paper" }{{(glass ? Ball : "")}} ] }
        """;

    // A dispersive glass ball in the furnace's view (Cauchy n = 1.5 + 20000 nm²/λ², Fresnel mirror and transmission).
    const string Glass = """, "glass": { "diffuse": 0, "mirror": 1, "transmit": 1, "fresnel": true, "ior": { "cauchy": [1.5, 20000] } }""";
    const string Ball = """, { "type": "sphere", "center": [0.1, 0, -0.4], "radius": 0.35, "material": "glass" }""";

    /// <summary>
    /// The furnace as rendered and relit, and with a dispersive glass ball in view: paths split into bands at the ball
    /// before and after shifted bounces, and the bands' sub-paths take shifted bounces of their own — each sub-path's
    /// block carried from the split's state (PathIntegrator.Dispersion.cs), still the render's to float rounding.
    /// </summary>
    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void Inside_a_brightened_furnace_paths_through_many_shifted_bounces_relight_as_they_render(bool glass)
    {
        var dir = Folder();
        var scene = Load(dir, Furnace("D50", 0.5, glass));
        Assert.Equal(glass, scene.Materials.Any(m => m.Dispersive));
        var t = PathTransfer.Trace(scene, new PathIntegrator(scene, new SceneGeometry(scene)), threads: 2);
        foreach (var (name, lit) in new[] { ("as rendered", scene), ("UV-cut lamp, D65 ×4", Load(dir, Furnace(UvCut(dir), 2, glass))) })
        {
            var (image, xyz) = t.Relight(lit);
            var render = Renderer.Render(lit, new PathIntegrator(lit, new SceneGeometry(lit)), threads: 2);
            double bands = WorstRelative(render.Image.Data, image.Data), colour = WorstRelative(render.Xyz!, xyz);
            output.WriteLine($"furnace, {name}: relit vs rendered {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
            Assert.True(bands <= 1e-5 && colour <= 1e-5, $"{name}: {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
        }
    }

    [Fact]
    public void A_purely_diagonal_matrix_writes_the_plain_reflectances_transfer_bit_for_bit()
    {
        var dir = Folder();
        var d = FluorescenceTests.ObaPaper();
        var diagonal = new double[N * N];
        // The plain spectrum: the matrix's diagonal at the cell centres, continued to the cells' outer edges 300 and 780 nm
        // (as the matrix's reflective diagonal is read).
        var csv = new StringBuilder("wavelength_nm,R\n");
        csv.Append(Inv, $"300,{d[0]:R}\n");
        for (int i = 0; i < N; i++)
        {
            diagonal[i * N + i] = d[i * N + i];
            csv.Append(Inv, $"{Cells[i]:R},{d[i * N + i]:R}\n");
        }
        csv.Append(Inv, $"780,{d[N * N - 1]:R}\n");
        File.WriteAllText(Path.Combine(dir, "diagonal.csv"), FluorescenceTests.MatrixCsv(Cells, diagonal));
        File.WriteAllText(Path.Combine(dir, "plain.csv"), csv.ToString());
        var matrix = Path.Combine(dir, "matrix");
        // Both on the uniform 5 nm grid: the default adaptive grid follows a plain reflectance's spectrum (the plain scene's)
        // and leaves a fluorescent material's matrix out of its prediction.
        static string Uniform(string scene) =>
            scene.Replace("\"integrator\": \"path\"", "\"integrator\": { \"type\": \"path\", \"spectral_grid\": 5 }",
                StringComparison.Ordinal);
        var (code, err) = PathRelightTests.Cli("render", Write(dir, "m.json", Uniform(Room(matrix: "diagonal.csv"))), "-o", matrix,
            "--formats", "npy,lights");
        Assert.True(code == 0, err);
        var plainScene = Room().Replace("{ \"type\": \"lambertian\", \"fluorescence\": { \"matrix\": \"oba.csv\" } }",
            $"{{ \"type\": \"lambertian\", \"reflectance\": \"{Path.Combine(dir, "plain.csv").Replace("\\", "/")}:R\" }}");
        Assert.Contains("plain.csv", plainScene);
        var plain = Path.Combine(dir, "plain");
        (code, err) = PathRelightTests.Cli("render", Write(dir, "p.json", Uniform(plainScene)), "-o", plain, "--formats", "npy,lights");
        Assert.True(code == 0, err);
        Assert.False(File.Exists(Path.Combine(matrix, "lights", PathTransferFiles.ShiftFile)));
        foreach (var f in new[] { "spectral.npy", "xyz.npy", "lights/transfer.npy", "lights/ids.npy" })
            Assert.True(File.ReadAllBytes(Path.Combine(plain, f)).AsSpan().SequenceEqual(File.ReadAllBytes(Path.Combine(matrix, f))),
                $"{f} differs");
    }

    [Fact]
    public void A_fluorescent_transfer_is_the_same_bytes_on_1_and_2_threads_and_from_2_shards_merged_and_relit()
    {
        var dir = Folder();
        var scene = Write(dir, "a.json", Room(width: 32, height: 64, spp: 2));
        var two = Path.Combine(dir, "two");
        ShardMergeTests.Render(scene, two, "--formats", "npy,lights", "--threads", "2");
        var one = Path.Combine(dir, "one");
        ShardMergeTests.Render(scene, one, "--formats", "npy,lights", "--threads", "1");
        Assert.True(File.Exists(Path.Combine(two, "lights", PathTransferFiles.ShiftFile)));
        ShardMergeTests.AssertSameRender(two, one);
        var shards = new List<string>();
        for (int i = 0; i < 2; i++)
        {
            shards.Add(Path.Combine(dir, $"shard-{i}"));
            ShardMergeTests.Render(scene, shards[^1], "--formats", "npy,lights", "--shard", $"{i}/2");
        }
        var merged = Path.Combine(dir, "merged");
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", merged]);
        Assert.True(code == 0, err);
        ShardMergeTests.AssertSameRender(two, merged);
        foreach (var (from, to) in new[] { (two, "relit-two"), (merged, "relit-merged") })
            Assert.Equal(0, PathRelightTests.Cli("relight", from, "-o", Path.Combine(dir, to), "--light", $"lamp={UvCut(dir)}").Exit);
        Assert.Equal(File.ReadAllBytes(Path.Combine(dir, "relit-two", "spectral.npy")),
            File.ReadAllBytes(Path.Combine(dir, "relit-merged", "spectral.npy")));
        // The viewer of such a folder shows its cube (a path render has no eq. 2 components for its sliders).
        (code, _, err) = CliRunner.Run("view", two);
        Assert.True(code == 0, err);
    }

    [Fact]
    public void The_memory_estimate_counts_the_block_of_a_band_limited_shift()
    {
        // A brightener cut to excitation 340–400 nm (12 cells of 5 nm) and emission 410–500 nm (18 cells): on 5 nm
        // sub-bands aligned with the cells, a block of 18 × 12 per light beside the (K + 1) × 96 of the diagonal transfer.
        var dir = Folder();
        var d = FluorescenceTests.ObaPaper();
        for (int o = 0; o < N; o++)
            for (int i = 0; i < N; i++)
                if (o != i && !(Cells[i] is > 340 and < 400 && Cells[o] is > 410 and < 500)) d[o * N + i] = 0;
        File.WriteAllText(Path.Combine(dir, "cut.csv"), FluorescenceTests.MatrixCsv(Cells, d));
        var json = Room(matrix: "cut.csv");
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"),
            new SceneOverrides { Formats = "npy,lights" });
        var part = RenderMemory.Estimate(scene, 1).Single(p => p.Part.Contains("transfer"));
        Assert.Equal(4L * 24 * 16 * (3 * 96 + 2 * 18 * 12), part.Bytes);
        // And the written block is that size.
        var source = Path.Combine(dir, "cut");
        Assert.Equal(0, PathRelightTests.Cli("render", Write(dir, "cut.json", json), "-o", source, "--formats", "npy,lights").Exit);
        using var s = File.OpenRead(Path.Combine(source, "lights", PathTransferFiles.ShiftFile));
        Assert.Equal([16, 24, 2, 18, 12], NpyReader.Read(s).Shape);
    }

    [Fact]
    public void A_transfer_folder_of_version_1_still_relights_and_a_newer_one_or_a_missing_block_is_refused()
    {
        var dir = Folder();
        var source = Path.Combine(dir, "source");
        Assert.Equal(0, PathRelightTests.Cli("render", Write(dir, "a.json", Room()), "-o", source, "--formats", "npy,lights").Exit);
        var lightsJson = Path.Combine(source, "lights", "lights.json");
        var json = JsonNode.Parse(File.ReadAllText(lightsJson))!.AsObject();

        // A plain scene's lights/ as written before the block (no version key, no shift): relit as before.
        var plainDir = Path.Combine(dir, "plain");
        var plainScene = Room().Replace("\"fluorescence\": { \"matrix\": \"oba.csv\" }", "\"reflectance\": 0.85");
        Assert.Equal(0, PathRelightTests.Cli("render", Write(dir, "p.json", plainScene), "-o", plainDir, "--formats", "npy,lights").Exit);
        var plainJson = Path.Combine(plainDir, "lights", "lights.json");
        var v2 = Path.Combine(dir, "plain-v2");
        Assert.Equal(0, PathRelightTests.Cli("relight", plainDir, "-o", v2, "--light", "lamp=A").Exit);
        var old = JsonNode.Parse(File.ReadAllText(plainJson))!.AsObject();
        Assert.Null(old["shift"]);
        old.Remove("version");
        File.WriteAllText(plainJson, old.ToJsonString());
        var v1 = Path.Combine(dir, "plain-v1");
        Assert.Equal(0, PathRelightTests.Cli("relight", plainDir, "-o", v1, "--light", "lamp=A").Exit);
        Assert.Equal(File.ReadAllBytes(Path.Combine(v2, "spectral.npy")), File.ReadAllBytes(Path.Combine(v1, "spectral.npy")));

        json["version"] = 3;
        File.WriteAllText(lightsJson, json.ToJsonString());
        var (code, err) = PathRelightTests.Cli("relight", source, "-o", Path.Combine(dir, "r1"), "--light", "lamp=A");
        Assert.Equal(2, code);
        Assert.Contains("newer", err);
        json["version"] = 2;
        File.WriteAllText(lightsJson, json.ToJsonString());
        File.Delete(Path.Combine(source, "lights", PathTransferFiles.ShiftFile));
        (code, err) = PathRelightTests.Cli("relight", source, "-o", Path.Combine(dir, "r2"), "--light", "lamp=A");
        Assert.Equal(2, code);
        Assert.Contains(PathTransferFiles.ShiftFile, err);
    }
}
