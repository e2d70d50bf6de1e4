using System.Globalization;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Distributed;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// Relight = re-render for path renders (issue 23): a path render with the per-light transfer (a point light, a spot, an
/// area light and a sky), relit to other light spectra and intensities (one switched off), against a path render of the
/// scene with those lights — an independent computation: the renderer traces every path again with the changed spectra,
/// relight traces nothing. Bar: ≤ 1e-5 relative in every band and colour channel of every pixel.
/// </summary>
public class PathRelightTests(Xunit.Abstractions.ITestOutputHelper output)
{
    static string Scene(string bulb, double bulbIntensity, double spotIntensity, int height = 16) => $$"""
        { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
          "camera": { "position": [0, 1, 3.2], "look_at": [0, 1, 0], "fov": 50, "width": 16, "height": {{height}}, "spp": 2 },
          "background": { "spectrum": "D65", "luminance": 20 },
          "materials": {
            "white": { "type": "lambertian", "reflectance": 0.75 },
            "red": { "type": "lambertian", "reflectance": "colorchecker:red" },
            "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 0.05 } },
            "gloss": { "diffuse": 0.05, "specular": 0.2, "shininess": 60, "mirror": 0.7 } },
          "lights": [
            { "type": "point", "name": "bulb", "position": [0.5, 1.6, 0.5], "spectrum": "{{bulb}}", "intensity": {{Num(bulbIntensity)}} },
            { "type": "spot", "name": "spot", "position": [-0.5, 1.8, 0.5], "look_at": [0, 0, 0], "spectrum": "D65",
              "intensity": {{Num(spotIntensity)}} } ],
          "objects": [
            { "type": "quad", "name": "floor", "center": [0, 0, 0], "size": [2, 2], "normal": [0, 1, 0], "up": [0, 0, -1],
              "material": "white" },
            { "type": "quad", "name": "back", "center": [0, 1, -1], "size": [2, 2], "normal": [0, 0, 1], "material": "white" },
            { "type": "quad", "name": "left", "center": [-1, 1, 0], "size": [2, 2], "normal": [1, 0, 0], "material": "red" },
            { "type": "quad", "name": "lamp", "center": [0, 1.99, 0], "size": [0.5, 0.5], "normal": [0, -1, 0], "up": [0, 0, -1],
              "material": "lamp" },
            { "type": "sphere", "name": "ball", "center": [0.4, 0.3, -0.3], "radius": 0.3, "material": "gloss" } ] }
        """;

    static string Num(double v) => v.ToString(CultureInfo.InvariantCulture);

    internal static string Write(string dir, string name, string json)
    {
        var p = Path.Combine(dir, name);
        File.WriteAllText(p, json);
        return p;
    }

    internal static (int Exit, string Err) Cli(params string[] args)
    {
        var (code, _, err) = CliRunner.Run([.. args, "--quiet"]);
        return (code, err);
    }

    internal static float[] Npy(string dir, string file)
    {
        using var s = File.OpenRead(Path.Combine(dir, file));
        return NpyReader.Read(s).Data;
    }

    /// <summary>
    /// Renders <paramref name="withA"/> (a light named "bulb" of spectrum A, intensity 2) with its per-light transfer, relights
    /// it to bulb = D65 at 0.5, and requires the relit cube to equal a render of <paramref name="withD65"/> (that light) to
    /// 1e-5 relative in every band value.
    /// </summary>
    internal static void RelitToD65EqualsRerender(string withA, string withD65)
    {
        var dir = Reference.TempDir();
        var source = Path.Combine(dir, "source");
        var (code, err) = Cli("render", Write(dir, "a.json", withA), "-o", source, "--formats", "npy,lights");
        Assert.True(code == 0, err);
        var relit = Path.Combine(dir, "relit");
        (code, err) = Cli("relight", source, "-o", relit, "--light", "bulb=D65", "--intensity", "bulb=0.5");
        Assert.True(code == 0, err);
        var direct = Path.Combine(dir, "direct");
        (code, err) = Cli("render", Write(dir, "b.json", withD65), "-o", direct, "--formats", "npy");
        Assert.True(code == 0, err);
        float[] expected = Npy(direct, "spectral.npy"), actual = Npy(relit, "spectral.npy");
        Assert.Equal(expected.Length, actual.Length);
        Assert.Contains(expected, v => v > 0);
        for (int i = 0; i < expected.Length; i++) Assert.Equal(expected[i], actual[i], 1e-5 * Math.Abs(expected[i]) + 1e-12);
    }

    /// <summary>The largest relative difference of <paramref name="actual"/> from <paramref name="expected"/> (both 0: none).</summary>
    static double WorstRelative(float[] expected, float[] actual)
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

    [Fact]
    public void A_relit_path_render_equals_a_path_render_of_the_changed_lights_and_relights_back()
    {
        var dir = Reference.TempDir();
        var source = Path.Combine(dir, "source");
        Assert.Equal(0, Cli("render", Write(dir, "a.json", Scene("A", 0.2, 0.3)), "-o", source, "--formats", "npy,lights").Exit);
        // The bulb to D65 at 2.5× its intensity, the spot switched off.
        var relit = Path.Combine(dir, "relit");
        var (code, err) = Cli("relight", source, "-o", relit, "--light", "bulb=D65", "--intensity", "bulb=0.5", "--intensity", "spot=0");
        Assert.True(code == 0, err);
        var direct = Path.Combine(dir, "direct");
        Assert.Equal(0, Cli("render", Write(dir, "b.json", Scene("D65", 0.5, 0)), "-o", direct, "--formats", "npy").Exit);
        double bands = WorstRelative(Npy(direct, "spectral.npy"), Npy(relit, "spectral.npy"));
        double colour = WorstRelative(Npy(direct, "xyz.npy"), Npy(relit, "xyz.npy"));
        output.WriteLine($"relit vs direct: worst relative difference {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
        Assert.True(bands <= 1e-5 && colour <= 1e-5,
            $"relit differs from the direct render by {bands:0.###e0} (bands), {colour:0.###e0} (XYZ)");
        // The change is not small: the relight did something.
        Assert.True(WorstRelative(Npy(direct, "spectral.npy"), Npy(source, "spectral.npy")) > 0.1);

        // The relit folder has its own transfer: relit back to the source's lights (the spot on again), it is the source.
        var back = Path.Combine(dir, "back");
        (code, err) = Cli("relight", relit, "-o", back, "--light", "bulb=A", "--intensity", "bulb=0.2", "--intensity", "spot=0.3");
        Assert.True(code == 0, err);
        double again = WorstRelative(Npy(source, "spectral.npy"), Npy(back, "spectral.npy"));
        Assert.True(again <= 1e-5, $"relit back differs from the source by {again:0.###e0}");
    }

    [Fact]
    public void What_a_path_relight_or_transfer_cannot_do_is_refused_with_a_hint()
    {
        var dir = Reference.TempDir();
        var scene = Write(dir, "a.json", Scene("A", 0.2, 0.3));
        var source = Path.Combine(dir, "source");
        Assert.Equal(0, Cli("render", scene, "-o", source, "--formats", "npy,lights").Exit);
        var (code, err) = Cli("relight", source, "-o", Path.Combine(dir, "r1"), "--intensity", "lamp=2");
        Assert.Equal(2, code);
        Assert.Contains("emitting material", err);
        (code, err) = Cli("relight", source, "-o", Path.Combine(dir, "r2"), "--light", "sky=A");
        Assert.Equal(2, code);
        Assert.Contains("sky", err);
        // Adaptive sampling stops pixels by a luminance that follows the lights' spectra: no transfer.
        (code, err) = Cli("render", scene, "-o", Path.Combine(dir, "r3"), "--formats", "npy,lights", "--target-error", "0.1");
        Assert.Equal(2, code);
        Assert.Contains("adaptive", err);
        (code, err) = Cli("render", scene, "-o", Path.Combine(dir, "r4"), "--formats", "npy,lights", "--crop", "0,0,8,8");
        Assert.Equal(2, code);
        Assert.Contains("crop", err);
    }

    [Fact]
    public void A_path_render_with_its_transfer_is_the_same_bits_on_1_and_2_threads_and_from_4_shards_merged_and_relit()
    {
        var dir = Reference.TempDir();
        var scene = Write(dir, "a.json", Scene("A", 0.2, 0.3, height: 128));
        var whole = Path.Combine(dir, "whole");
        ShardMergeTests.Render(scene, whole, "--formats", "npy,exr,lights", "--threads", "2");
        var one = Path.Combine(dir, "one");
        ShardMergeTests.Render(scene, one, "--formats", "npy,exr,lights", "--threads", "1");
        ShardMergeTests.AssertSameRender(whole, one);
        var shards = new List<string>();
        for (int i = 0; i < 4; i++)
        {
            shards.Add(Path.Combine(dir, $"shard-{i}"));
            ShardMergeTests.Render(scene, shards[^1], "--formats", "npy,exr,lights", "--shard", $"{i}/4");
        }
        var merged = Path.Combine(dir, "merged");
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", merged]);
        Assert.True(code == 0, err);
        ShardMergeTests.AssertSameRender(whole, merged);
        // The merged transfer relights as the whole render's does, bit for bit.
        foreach (var (from, to) in new[] { (whole, "relit-whole"), (merged, "relit-merged") })
            Assert.Equal(0, Cli("relight", from, "-o", Path.Combine(dir, to), "--light", "bulb=D65").Exit);
        Assert.Equal(File.ReadAllBytes(Path.Combine(dir, "relit-whole", "spectral.npy")),
            File.ReadAllBytes(Path.Combine(dir, "relit-merged", "spectral.npy")));
    }

    [Fact]
    public void The_memory_estimate_counts_the_path_transfer()
    {
        // 16 × 16 pixels, (2 lights + emitters and sky) groups, 6 bands of 50 nm in 5 nm sub-bands: 60 floats per group.
        var scene = SceneLoader.Parse(System.Text.Encoding.UTF8.GetBytes(Scene("A", 0.2, 0.3)), "a.json",
            new SceneOverrides { Formats = "npy,lights" });
        var part = RenderMemory.Estimate(scene, 1).Single(p => p.Part.Contains("transfer"));
        Assert.Equal(4L * 16 * 16 * 3 * (6 * 50 / 5), part.Bytes);
    }
}
