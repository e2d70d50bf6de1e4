using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// A render that says how exact it is (issue 23): each pixel's standard error against the analytic variance of estimators
/// whose variance is known, against the spread of independent renders with different seeds; adaptive sampling's achieved
/// error and where it stops; the same bits on any thread count.
/// </summary>
public class NoiseTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>A two-valued estimator: every band (and Y) is a with probability p, else b, from the sample's first 1D draw.</summary>
    sealed class TwoValued(int bands, float a, float b, float p) : IIntegrator
    {
        public int ScratchLength => 0;

        public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
        {
            result.Clear();
            float v = Value(sample.Sampler.Next1D());
            for (int i = 0; i < bands; i++) result[i] = v;
            result[bands + 1] = v;   // Y
            return -1;
        }

        public float Value(float u) => u < p ? a : b;
    }

    const string Flat = """
        { "radiometry": "physical", "bands": "400:700:3",
          "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 16, "height": 16, "spp": 64 },
          "materials": { "m": { "type": "lambertian", "reflectance": 0.5 } },
          "objects": [ { "type": "sphere", "center": [0, 0, -100], "radius": 1, "material": "m" } ] }
        """;

    [Fact]
    public void A_two_valued_estimator_has_the_binomial_standard_error()
    {
        var scene = SceneText.Load(Flat);
        var integrator = new TwoValued(scene.Bands, 3f, 1f, 0.3f);
        var r = Renderer.Render(scene, integrator, threads: 2, noise: true);
        int n = 64, channels = scene.Bands + 1;
        // Per pixel: the same numbers the test draws itself, the standard error computed here in double (a second way).
        double meanSquare = 0;
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 16; x++)
            {
                // The film jitter is stratified on 8 × 8 cells (sample s in cell (s mod 8, s div 8)): the variance of a cell's
                // sample from the squared differences of neighbours in a row, Σ(v_s − v_{s−1})²/(2P), P = 8·7 pairs.
                double pairs = 0, previous = 0;
                for (int s = 0; s < n; s++)
                {
                    double v = integrator.Value(new Sampler(x, y, s, 2).Next1D());
                    if (s % 8 != 0) pairs += (v - previous) * (v - previous);
                    previous = v;
                }
                double se = Math.Sqrt(pairs / (2 * 56) / n);
                for (int k = 0; k < channels; k++)
                    Assert.Equal(se, r.Noise![(y * 16 + x) * channels + k], 5e-6 + 1e-5 * se);
                meanSquare += se * se;
            }
        // E[se²] = p(1 − p)(a − b)²/n exactly (E[(v_s − v_{s−1})²] = 2σ² for independent draws): 0.21·4/64 = 0.013125, over 256 pixels
        // within ~9 % (2σ).
        double expected = 0.3 * 0.7 * 4 / n;
        output.WriteLine($"mean s²/n {meanSquare / 256:G5}, analytic {expected:G5}");
        Assert.InRange(meanSquare / 256 / expected, 0.9, 1.1);
    }

    [Fact]
    public void A_pixel_of_constant_radiance_has_error_zero()
    {
        // The path tracer looking at a black emitter of radiance L_e filling the view: every sample is L_e exactly.
        var scene = SceneText.Load("""
            { "radiometry": "physical", "bands": "400:700:4", "integrator": "path",
              "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 8, "height": 8, "spp": 8 },
              "materials": { "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 0.01 } } },
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": [20, 20], "normal": [0, 0, 1], "material": "lamp" } ] }
            """);
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"), noise: true);
        Assert.All(r.Noise!, v => Assert.Equal(0f, v));
        Assert.True(r.Image.Data.All(v => v > 0));
    }

    /// <summary>A sphere on a diffuse plane under a uniform sky: noisy at the contact shadow, the sky itself constant.</summary>
    internal static string SkyScene(string sampler, int seed, int spp, double target = 0) => $$"""
        { "radiometry": "physical", "bands": "400:700:3",
          "integrator": { "type": "path", "max_depth": 3, "sampler": "{{sampler}}", "seed": {{seed}} },
          "camera": { "position": [0, 1.2, 3], "look_at": [0, 0.2, 0], "fov": 50, "width": 8, "height": 8, "spp": {{spp}},
            "target_error": {{target}} },
          "background": { "name": "D65", "scale": 0.01 },
          "materials": { "white": { "type": "lambertian", "reflectance": 0.8 } },
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white" },
                       { "type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "white" } ] }
        """;

    static RenderResult RenderSky(string sampler, int seed, int spp, double target = 0, int threads = 0)
    {
        var scene = SceneText.Load(SkyScene(sampler, seed, spp, target));
        return Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), "path"), threads, noise: true);
    }

    [Fact]
    public void The_standard_error_matches_the_spread_of_renders_with_different_seeds()
    {
        const int renders = 16, spp = 16;
        var runs = Enumerable.Range(1, renders).Select(s => RenderSky("independent", s, spp)).ToList();
        int pixels = 64, bands = 3, channels = bands + 1;
        // Per pixel and band: the empirical variance of the renders' values against the mean of their s²/n.
        double empirical = 0, predicted = 0;
        for (int i = 0; i < pixels; i++)
            for (int b = 0; b < channels; b++)
            {
                double Value(RenderResult r) => b < bands ? r.Image.Data[i * bands + b] : r.Xyz![3 * i + 1];
                double mean = runs.Average(Value);
                empirical += runs.Sum(r => (Value(r) - mean) * (Value(r) - mean)) / (renders - 1);
                predicted += runs.Average(r => (double)r.Noise![i * channels + b] * r.Noise[i * channels + b]);
            }
        output.WriteLine($"independent: empirical variance / predicted {empirical / predicted:F3}");
        Assert.InRange(empirical / predicted, 0.8, 1.25);
        // Scrambled Sobol: the samples of one net are not independent (stratified, they cancel); its standard error comes
        // from the spread of its independent randomisations (Sampler.Randomisations), which predicts the spread of renders.
        var sobol = Enumerable.Range(1, renders).Select(s => RenderSky("sobol", s, spp)).ToList();
        double sobolSpread = 0, sobolPredicted = 0;
        for (int i = 0; i < pixels * bands; i++)
        {
            double mean = sobol.Average(r => r.Image.Data[i]);
            sobolSpread += sobol.Sum(r => Math.Pow(r.Image.Data[i] - mean, 2)) / (renders - 1);
            sobolPredicted += sobol.Average(r => Math.Pow(r.Noise![i / bands * channels + i % bands], 2));
        }
        output.WriteLine($"sobol: empirical variance / predicted {sobolSpread / sobolPredicted:F3}");
        Assert.InRange(sobolSpread / sobolPredicted, 0.8, 1.25);
    }

    [Fact]
    public void Statistics_and_adaptive_sampling_are_the_same_bits_on_1_and_2_threads_and_leave_the_picture_as_it_was()
    {
        var one = RenderSky("sobol", 0, 64, 0.05, threads: 1);
        var two = RenderSky("sobol", 0, 64, 0.05, threads: 2);
        Assert.Equal(one.Image.Data, two.Image.Data);
        Assert.Equal(one.Noise, two.Noise);
        Assert.Equal(one.SamplesUsed, two.SamplesUsed);
        // Without adaptive sampling, asking for the noise does not change the picture.
        var scene = SceneText.Load(SkyScene("sobol", 0, 8));
        var path = Integrators.Create(scene, new SceneGeometry(scene), "path");
        Assert.Equal(Renderer.Render(scene, path).Image.Data, Renderer.Render(scene, path, noise: true).Image.Data);
        var w =
            SceneText.Load(PathRenderTests.Room.Replace("\"integrator\": \"path\",", ""), new SceneOverrides { Width = 16, Height = 12 });
        var whitted = Integrators.Create(w, new SceneGeometry(w));
        var plain = Renderer.Render(w, whitted);
        var noisy = Renderer.Render(w, whitted, noise: true);
        Assert.Equal(plain.Image.Data, noisy.Image.Data);
        Assert.Equal(plain.Xyz, noisy.Xyz);
    }

    [Fact]
    public void Adaptive_sampling_meets_its_target_and_stops_flat_pixels_first()
    {
        const double target = 0.05;
        const int renders = 12, cap = 1024;
        var runs = Enumerable.Range(1, renders).Select(s => RenderSky("independent", s, cap, target)).ToList();
        // The achieved error: the spread of the renders' luminance per pixel, relative to its mean, against the target.
        double sum2 = 0;
        int counted = 0;
        for (int i = 0; i < 64; i++)
        {
            double mean = runs.Average(r => r.Xyz![3 * i + 1]);
            if (!(mean > 0)) continue;
            double sd = Math.Sqrt(runs.Sum(r => Math.Pow(r.Xyz![3 * i + 1] - mean, 2)) / (renders - 1));
            sum2 += Math.Pow(sd / mean, 2);
            counted++;
        }
        double achieved = Math.Sqrt(sum2 / counted);
        var used = runs[0].SamplesUsed!;
        output.WriteLine(
            $"RMS achieved relative error {achieved:F4} (target {target}); spp min {used.Min()} mean {used.Average():F1} max {used.Max()}");
        Assert.InRange(achieved, 0, target * 1.15);
        // The sky seen directly (top rows) is constant: its pixels stop at the minimum; the contact shadow takes more.
        int sky = 0 * 8 + 4, shadow = Enumerable.Range(0, 64).MaxBy(i => used[i]);
        Assert.Equal(Renderer.MinAdaptiveSamples, used[sky]);
        Assert.True(used[shadow] > 4 * Renderer.MinAdaptiveSamples, $"the noisiest pixel took {used[shadow]} samples");
        Assert.True(used.Max() <= cap);
    }
}

/// <summary>The noise product's files and render.json through the command line: 4 shards merged are the whole render.</summary>
public class NoiseProductTests
{
    [Fact]
    public void Four_shards_of_a_path_render_with_noise_and_adaptive_sampling_merge_into_the_whole_render_byte_for_byte()
    {
        var dir = Reference.TempDir();
        var scenePath = Path.Combine(dir, "sky.json");
        File.WriteAllText(scenePath, NoiseTests.SkyScene("sobol", 0, 8, 0.05));
        string[] extra = ["--width", "8", "--height", "128", "--formats", "exr,noise"];
        Distributed.ShardMergeTests.Render(scenePath, Path.Combine(dir, "whole"), extra);
        var shards = new List<string>();
        for (int i = 0; i < 4; i++)
        {
            shards.Add(Path.Combine(dir, $"shard-{i}"));
            Distributed.ShardMergeTests.Render(scenePath, shards[^1], [.. extra, "--shard", $"{i}/4"]);
        }
        var (code, _, err) = Cli.CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(code == 0, err);
        string whole = Path.Combine(dir, "whole"), merged = Path.Combine(dir, "merged");
        foreach (var f in new[] { "noise.npy", "noise.img", "noise.hdr", "spectral.exr" })
            Assert.True(File.ReadAllBytes(Path.Combine(whole, f)).AsSpan().SequenceEqual(File.ReadAllBytes(Path.Combine(merged, f))),
                $"{f} differs");
        var a = SpectralRenderer.Output.RenderManifest.Read(whole).Sampling!;
        var b = SpectralRenderer.Output.RenderManifest.Read(merged).Sampling!;
        Assert.Equal("sobol", a.Sampler);
        Assert.Equal(a.Noise!.Pixels, b.Noise!.Pixels);
        Assert.Equal(a.Noise.MaxRelative, b.Noise.MaxRelative);
        Assert.Equal(a.Noise.MeanRelative!.Value, b.Noise.MeanRelative!.Value, 1e-12);
        Assert.Equal((a.Adaptive!.Min, a.Adaptive.Max, a.Adaptive.Cap), (b.Adaptive!.Min, b.Adaptive.Max, b.Adaptive.Cap));
        Assert.Equal(a.Adaptive.Mean, b.Adaptive.Mean, 1e-12);
        // The summary is the files' own: mean and max relative error of luminance from noise.npy and the EXR's Y.
        var exr = SpectralRenderer.Imaging.ExrReader.Read(Path.Combine(whole, "spectral.exr"));
        var y = exr.OtherChannels["Y"];
        var se = exr.OtherChannels["stderr.Y"];
        var rel = Enumerable.Range(0, y.Length).Where(i => y[i] > 0).Select(i => (double)se[i] / y[i]).ToList();
        Assert.Equal(rel.Max(), a.Noise.MaxRelative!.Value, 1e-9);
        Assert.Equal(rel.Average(), a.Noise.MeanRelative!.Value, 1e-9);
        Assert.True(a.Adaptive.Max <= 8 && a.Adaptive.Min >= 1);
    }

    [Fact]
    public void Noise_with_one_sample_per_pixel_is_bad_input()
    {
        var (code, _, err) = Cli.CliRunner.Run(
            ["render", Distributed.ShardMergeTests.Scene("glass-mirror.json"), "-o", Path.Combine(Reference.TempDir(), "x"),
            "--width", "8", "--height", "8", "--spp", "1", "--formats", "noise"]);
        Assert.Equal(2, code);
        Assert.Contains("--formats", err);
        Assert.Contains("spp", err);
        (code, _, err) = Cli.CliRunner.Run(
            ["render", Distributed.ShardMergeTests.Scene("glass-mirror.json"), "-o", Path.Combine(Reference.TempDir(), "x"),
            "--target-error", "2"]);
        Assert.Equal(2, code);
        Assert.Contains("--target-error", err);
    }
}
