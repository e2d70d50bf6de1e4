using System.Diagnostics;
using System.Text.Json.Nodes;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.Distributed;

/// <summary>
/// Shards (render --shard I/N, --crop) against the single-process render of the same scene: the reference is the
/// whole render, computed in one piece; the merge must reproduce its every file byte for byte.
/// </summary>
public class ShardMergeTests
{
    internal static string Scene(string name) => Path.GetFullPath(Path.Combine(AppContext.BaseDirectory, "../../../../../scenes", name));

    /// <summary>render.json keys that describe the run rather than the image (the merge's are its own).</summary>
    public static readonly string[] RunFields = ["created_utc", "timings_s", "threads", "run"];

    /// <summary>Every file of two render folders equal byte for byte; render.json equal but for <see cref="RunFields"/> and
    /// rays.mrays_per_s.</summary>
    internal static void AssertSameRender(string expected, string actual)
    {
        static List<string> Files(string d) => Directory.GetFiles(d, "*", SearchOption.AllDirectories)
            .Select(f => Path.GetRelativePath(d, f)).Order(StringComparer.Ordinal).ToList();
        var files = Files(expected);
        Assert.Equal(files, Files(actual));
        foreach (var f in files.Where(f => f != "render.json"))
            Assert.True(File.ReadAllBytes(Path.Combine(expected, f)).AsSpan().SequenceEqual(File.ReadAllBytes(Path.Combine(actual, f))),
                $"{f} differs");
        Assert.Equal(Manifest(expected), Manifest(actual));

        static string Manifest(string dir)
        {
            var m = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "render.json")))!.AsObject();
            foreach (var k in RunFields) m.Remove(k);
            m["rays"]!.AsObject().Remove("mrays_per_s");
            return m.ToJsonString();
        }
    }

    internal static void Render(string scene, string outDir, params string[] extra)
    {
        var (code, _, err) = CliRunner.Run(["render", scene, "-o", outDir, "--quiet", .. extra]);
        Assert.True(code == 0, err);
    }

    static List<string> Shards(string scene, string dir, int n, params string[] extra)
    {
        var dirs = new List<string>();
        for (int i = 0; i < n; i++)
        {
            dirs.Add(Path.Combine(dir, $"shard-{i}"));
            Render(scene, dirs[^1], ["--shard", $"{i}/{n}", .. extra]);
        }
        return dirs;
    }

    [Fact]
    public void Four_shards_of_the_glass_and_mirror_scene_merge_into_the_single_render_byte_for_byte()
    {
        var dir = Reference.TempDir();
        string[] size = ["--width", "96", "--height", "128"];
        var scene = Scene("glass-mirror.json");
        Render(scene, Path.Combine(dir, "whole"), size);
        var shards = Shards(scene, dir, 4, size);
        shards.Reverse();   // any order
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(code == 0, err);
        AssertSameRender(Path.Combine(dir, "whole"), Path.Combine(dir, "merged"));
    }

    /// <summary>
    /// Issue 42: a shipped GI scene (path-cornell-room.json: "exposure": "auto") cannot be sharded as it is — each strip would
    /// pick its own exposure — and says to give one with --exposure; given one, its shards merge into the whole render at
    /// that exposure byte for byte, and render.json says the exposure given.
    /// </summary>
    [Fact]
    public void A_scene_with_auto_exposure_shards_with_a_fixed_exposure_option_and_merges_byte_for_byte()
    {
        var dir = Reference.TempDir();
        var scene = Scene("path-cornell-room.json");
        string[] size = ["--width", "40", "--height", "72", "--spp", "2"];
        var (code, _, err) = CliRunner.Run(["render", scene, "-o", Path.Combine(dir, "refused"), "--quiet", "--shard", "0/2", .. size]);
        Assert.Equal(2, code);
        Assert.Contains("--exposure E", err);
        string[] args = [.. size, "--exposure", "0.75"];
        Render(scene, Path.Combine(dir, "whole"), args);
        var shards = Shards(scene, dir, 2, args);
        (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(code == 0, err);
        AssertSameRender(Path.Combine(dir, "whole"), Path.Combine(dir, "merged"));
        var manifest = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "merged", "render.json")))!;
        Assert.Equal(0.75, (double)manifest["colour"]!["exposure"]!);
        Assert.Equal("fixed", (string)manifest["colour"]!["exposure_mode"]!);
    }

    [Theory]
    [InlineData("whitted", 3)]
    [InlineData("whitted", 2)]
    public void Shards_with_the_photometry_product_merge_into_the_single_renders_photometry_byte_for_byte(string integrator, int n)
    {
        // Issue 27: photometry.exr (luminance cd/m², illuminance lx) of every shard's rows, and the false-colour pictures
        // drawn again on the whole image's scale; a box's shadow and a spot's edge across the strips; the calculation grid's files.
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, $$"""
            { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "400:700:50", "integrator": "{{integrator}}",
              "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 50, "width": 8, "height": 96, "spp": 1 },
              "materials": { "white": { "diffuse": 0.8 }, "grey": { "diffuse": 0.3 } },
              "lights": [ { "type": "spot", "position": [0.5, 1, 3], "look_at": [0, 0, 0], "cutoff": 25, "spectrum": "A",
                "luminous_intensity": 500 },
                          { "type": "point", "position": [-1, -2, 2], "spectrum": "led-blue", "luminous_flux": 2000 } ],
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 6, "material": "white" },
                           { "type": "box", "center": [0, 0.3, 0.6], "size": [0.6, 0.6, 0.6], "material": "grey" } ],
              "calculation_grids": [ { "name": "floor", "origin": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "points": [6, 5] } ] }
            """);
        string[] formats = ["--formats", "png,photometry"];
        Render(scene, Path.Combine(dir, "whole"), formats);
        var shards = Shards(scene, dir, n, formats);
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(code == 0, err);
        AssertSameRender(Path.Combine(dir, "whole"), Path.Combine(dir, "merged"));
        Assert.True(File.Exists(Path.Combine(dir, "merged", "illuminance-scale.svg")));
        // the scene's calculation grid, the same in every shard
        Assert.True(File.Exists(Path.Combine(dir, "merged", "grids", "floor.csv")));
    }

    [SkippableFact]
    public void Four_shards_of_the_paper_bunny_merge_into_the_single_render_byte_for_byte()
    {
        // The §3.2 bunny; 1024² is the recorded bar (BENCHMARKS.md), CI renders it at SPECTRAL_SHARD_TEST_SIZE (default 256).
        var models = Path.GetDirectoryName(ModelFiles.Require("stanford-bunny.obj"))!;
        var n = Environment.GetEnvironmentVariable("SPECTRAL_SHARD_TEST_SIZE") ?? "256";
        var dir = Reference.TempDir();
        string[] extra = ["--width", n, "--height", n, "--models", models];
        var scene = Scene("paper-3.2-bunny-19.json");
        Render(scene, Path.Combine(dir, "whole"), extra);
        var shards = Shards(scene, dir, 4, extra);
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(code == 0, err);
        AssertSameRender(Path.Combine(dir, "whole"), Path.Combine(dir, "merged"));
    }

    [Fact]
    public void A_crop_holds_the_same_values_as_those_pixels_of_the_whole_render()
    {
        var dir = Reference.TempDir();
        var scene = Scene("glass-mirror.json");
        string[] size = ["--width", "90", "--height", "70", "--formats", "npy,exr"];
        Render(scene, Path.Combine(dir, "whole"), size);
        Render(scene, Path.Combine(dir, "crop"), [.. size, "--crop", "13,21,77,50"]);   // not on tile boundaries
        var whole = NpyReader.ReadImage(Path.Combine(dir, "whole", "spectral.npy"), SpectralRenderer.Spectra.BandGrid.Default);
        var crop = NpyReader.ReadImage(Path.Combine(dir, "crop", "spectral.npy"), SpectralRenderer.Spectra.BandGrid.Default);
        Assert.Equal((64, 29), (crop.Width, crop.Height));
        for (int y = 0; y < crop.Height; y++)
            for (int x = 0; x < crop.Width; x++)
                Assert.True(crop.Pixel(x, y).SequenceEqual(whole.Pixel(x + 13, y + 21)), $"pixel {x + 13},{y + 21}");
        var m = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "crop", "render.json")))!;
        Assert.Equal("""{"x0":13,"y0":21,"x1":77,"y1":50}""", m["crop"]!.ToJsonString());
        Assert.Equal(90, m["width"]!.GetValue<int>());
        Assert.Equal(JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "whole", "render.json")))!["scene_hash"]!.GetValue<string>(),
            m["scene_hash"]!.GetValue<string>());
        // The EXR reads back as the crop (its data window); exrheader checks the windows below.
        var exr = ExrReader.Read(Path.Combine(dir, "crop", "spectral.exr")).Image;
        Assert.Equal((64, 29), (exr.Width, exr.Height));
        Assert.Equal(crop.Data, exr.Data);
    }

    [SkippableFact]
    public void OpenEXR_reads_a_shard_as_its_data_window_inside_the_full_display_window()
    {
        Skip.IfNot(File.Exists("/usr/bin/exrheader"), "exrheader (Debian package openexr) is not installed");
        var dir = Reference.TempDir();
        Render(Scene("glass-mirror.json"), dir, "--width", "96", "--height", "128", "--formats", "exr", "--shard", "1/4");
        var psi = new ProcessStartInfo("/usr/bin/exrheader", Path.Combine(dir, "spectral.exr")) { RedirectStandardOutput = true };
        using var p = Process.Start(psi)!;
        var text = p.StandardOutput.ReadToEnd();
        p.WaitForExit();
        Assert.Equal(0, p.ExitCode);
        // Strip 1 of 4 of 128 rows is rows 32–63 (whole 32-row tile strips).
        Assert.Matches(@"dataWindow \(type box2i\): \(0 32\) - \(95 63\)", text);
        Assert.Matches(@"displayWindow \(type box2i\): \(0 0\) - \(95 127\)", text);
    }

    static (int Code, string Err) Merge(params string[] args)
    {
        var (code, _, err) = CliRunner.Run(["merge", .. args, "--quiet"]);
        return (code, err.Trim());
    }

    [Fact]
    public void Merge_refuses_missing_overlapping_foreign_and_half_written_shards_in_one_line()
    {
        var dir = Reference.TempDir();
        var scene = Scene("glass-mirror.json");
        string[] size = ["--width", "64", "--height", "96", "--formats", "envi,png"];
        var s = Shards(scene, dir, 3, size);
        var outDir = Path.Combine(dir, "merged");

        var missing = Merge(s[0], s[2], "-o", outDir);
        Assert.Equal(2, missing.Code);
        Assert.Contains("rows 32–63 are in no shard", missing.Err);

        Render(scene, Path.Combine(dir, "half-of-2"), [.. size, "--shard", "0/2"]);   // rows 0–63: overlaps shard 1 of 3
        var overlap = Merge(s[0], Path.Combine(dir, "half-of-2"), s[2], "-o", outDir);
        Assert.Equal(2, overlap.Code);
        Assert.Contains("overlaps", overlap.Err);

        Render(scene, Path.Combine(dir, "other"),
            ["--width", "64", "--height", "96", "--formats", "envi,png", "--spp", "3", "--shard", "1/3"]);
        var foreign = Merge(s[0], Path.Combine(dir, "other"), s[2], "-o", outDir);
        Assert.Equal(2, foreign.Code);
        Assert.Contains("another scene or settings", foreign.Err);

        File.Delete(Path.Combine(s[1], "render.json"));
        var half = Merge(s[0], s[1], s[2], "-o", outDir);
        Assert.Equal(2, half.Code);
        Assert.Contains("half-written", half.Err);

        foreach (var e in new[] { missing.Err, overlap.Err, foreign.Err, half.Err }) Assert.DoesNotContain('\n', e);
        Assert.False(File.Exists(Path.Combine(outDir, "render.json")));
    }

    [Fact]
    public void Merge_refuses_a_shard_whose_cube_was_cut_short()
    {
        var dir = Reference.TempDir();
        var s = Shards(Scene("glass-mirror.json"), dir, 2, "--width", "32", "--height", "64", "--formats", "envi");
        using (var f = new FileStream(Path.Combine(s[1], "spectral.img"), FileMode.Open)) f.SetLength(f.Length - 4);
        var (code, err) = Merge(s[0], s[1], "-o", Path.Combine(dir, "merged"));
        Assert.Equal(2, code);
        Assert.Contains("half-written", err);
        Assert.False(File.Exists(Path.Combine(dir, "merged", "spectral.img")));
    }
}

/// <summary>Sets a job array's variables for the whole process: alone, so no other test sees them.</summary>
[Collection("Alone")]
public class ShardEnvironmentTests
{
    [Fact]
    public void Shard_from_the_environment_renders_the_strip_of_that_task()
    {
        // As a Slurm array task 2 of --array=0-3 would; --shard none opts out.
        var dir = Reference.TempDir();
        var vars = new Dictionary<string, string>
        {
            ["SLURM_ARRAY_TASK_ID"] = "2",
            ["SLURM_ARRAY_TASK_MIN"] = "0",
            ["SLURM_ARRAY_TASK_MAX"] = "3",
            ["SLURM_ARRAY_TASK_STEP"] = "1"
        };
        try
        {
            foreach (var (k, v) in vars) Environment.SetEnvironmentVariable(k, v);
            ShardMergeTests.Render(ShardMergeTests.Scene("glass-mirror.json"), Path.Combine(dir, "env"), "--width", "40", "--height", "128",
                "--formats", "npy");
            ShardMergeTests.Render(ShardMergeTests.Scene("glass-mirror.json"), Path.Combine(dir, "none"), "--width", "40", "--height",
                "128", "--formats", "npy", "--shard", "none");
        }
        finally { foreach (var k in vars.Keys) Environment.SetEnvironmentVariable(k, null); }
        var m = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "env", "render.json")))!;
        Assert.Equal("""{"x0":0,"y0":64,"x1":40,"y1":96}""", m["crop"]!.ToJsonString());
        Assert.Equal("2/4 (Slurm)", m["run"]!["shard"]!.GetValue<string>());
        Assert.Null(JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "none", "render.json")))!["crop"]);
    }
}
