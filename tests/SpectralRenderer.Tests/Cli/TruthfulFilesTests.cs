using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.Cli;

/// <summary>The paper's scenes as shipped, and what the files of a render say about their numbers.</summary>
public class TruthfulFilesTests
{
    static string Repo(string relative)
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
            if (File.Exists(Path.Combine(d.FullName, "SpectralRenderer.sln"))) return Path.Combine(d.FullName, relative);
        throw new InvalidOperationException("repository root not found");
    }

    [Fact]
    public void Paper_3_1_preview_patch_codes_equal_the_1nm_reference_within_one()
    {
        var outDir = Path.Combine(Reference.TempDir(), "out");
        var (code, _, err) =
            CliRunner.Run("render", Repo("scenes/paper-3.1-colorchecker-d65.json"), "-o", outDir, "--quiet", "--formats", "png,aov");
        Assert.True(code == 0, err);
        var preview = PngReader.Read(Path.Combine(outDir, "preview.png"));
        var ids = PngReader.Read(Path.Combine(outDir, "object-id.png"));
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "render.json")))!;
        var names = json["objects"]!.AsArray().Select(o => (string)o!["name"]!).ToList();
        var rows = Reference.Rows("colorchecker-ohta-d65-2deg.csv");
        int worst = 0;
        for (int p = 1; p <= 24; p++)
        {
            int id = names.IndexOf($"patch-{p:00}") + 1;
            int pixel = Enumerable.Range(0, ids.Width * ids.Height).First(i => ids.Samples[i] == id);
            for (int c = 0; c < 3; c++)
            {
                int got = preview.Samples[3 * pixel + c];
                int want = (int)rows[p - 1].D(new[] { "srgb8_r", "srgb8_g", "srgb8_b" }[c]);
                worst = Math.Max(worst, Math.Abs(got - want));
                Assert.True(Math.Abs(got - want) <= 1, $"patch {p} channel {c}: {got} vs reference {want}");
            }
        }
    }

    [SkippableFact]
    [Trait("Category", "Models")]
    public void Paper_3_3_blue_LED_preview_clips_at_most_2_percent_of_the_statue()
    {
        var igea = ModelFiles.Require("igea.ply");
        var outDir = Path.Combine(Reference.TempDir(), "out");
        var (code, _, err) =
            CliRunner.Run("render", Repo("scenes/paper-3.3-statue-led-blue.json"), "-o", outDir, "--quiet", "--formats", "png,aov",
            "--models", Path.GetDirectoryName(igea)!);
        Assert.True(code == 0, err);
        var preview = PngReader.Read(Path.Combine(outDir, "preview.png"));
        var ids = PngReader.Read(Path.Combine(outDir, "object-id.png"));
        int statue = 0, clipped = 0;
        for (int i = 0; i < ids.Width * ids.Height; i++)
        {
            if (ids.Samples[i] == 0) continue;
            statue++;
            if (preview.Samples[3 * i] == 255 || preview.Samples[3 * i + 1] == 255 || preview.Samples[3 * i + 2] == 255) clipped++;
        }
        Assert.True(statue > 10000, $"{statue} statue pixels");
        Assert.True(clipped <= 0.02 * statue,
            $"{clipped} of {statue} statue pixels ({100.0 * clipped / statue:F2} %) have a channel at 255");
    }

    static (string Dir, JsonNode Json) RenderSmall(string radiometry)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, $$"""
        { "radiometry": "{{radiometry}}",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 16, "height": 12 },
          "materials": { "green": { "diffuse": "colorchecker:14" } },
          "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "radius": 1, "material": "green" } ] }
        """);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        Assert.True(code == 0, err);
        return (outDir, JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "render.json")))!);
    }

    [Theory]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Files_state_the_radiometry_and_units_of_their_numbers(string radiometry)
    {
        var (dir, json) = RenderSmall(radiometry);
        bool physical = radiometry == "physical";
        Assert.Equal(radiometry, (string)json["radiometry"]!["mode"]!);
        Assert.Contains(physical ? "W.m^-2.sr^-1.nm^-1" : "relative", (string)json["radiometry"]!["band_values"]!);
        // EXR: emissiveUnits only when the S0 channels are in that unit.
        var exr = ExrReader.Read(Path.Combine(dir, "spectral.exr"));
        Assert.Equal(physical, exr.StringAttributes.ContainsKey("emissiveUnits"));
        Assert.StartsWith(radiometry, exr.StringAttributes["spectralRadiometry"]);
        // ENVI header.
        var hdr = File.ReadAllText(Path.Combine(dir, "spectral.hdr"));
        Assert.Contains($"radiometry = {radiometry}", hdr);
        Assert.Contains(physical ? "data units = W.m^-2.sr^-1.nm^-1" : "data units = relative", hdr);
        // Band PNGs: linear (gAMA 1.0) with the scale from samples to band values.
        var band = Directory.GetFiles(Path.Combine(dir, "bands"), "band-01-*.png").Single();
        var bytes = File.ReadAllBytes(band);
        int gama = IndexOf(bytes, "gAMA"u8);
        Assert.True(gama > 0, "no gAMA chunk");
        Assert.Equal(100000u, System.Buffers.Binary.BinaryPrimitives.ReadUInt32BigEndian(bytes.AsSpan(gama + 4)));
        var png = PngReader.Read(band);
        double scale = (double)json["bands"]!["band_image_scale"]!;
        Assert.Contains($"sample / 65535 * {(float)scale:R}", png.Text["Scale"]);
        Assert.Contains("380-400 nm", png.Text["Title"]);
    }

    static int IndexOf(byte[] haystack, ReadOnlySpan<byte> needle) => haystack.AsSpan().IndexOf(needle);

    [Fact]
    public void Colorcheck_refuses_a_shaded_sphere_with_the_reason_and_accepts_the_head_on_chart()
    {
        var (dir, _) = RenderSmall("paper");
        var (code, _, err) = CliRunner.Run("colorcheck", dir);
        Assert.Equal(2, code);
        Assert.Contains("is not a flat chart", err);
        Assert.Contains("patch 14", err);

        var chart = Path.Combine(Reference.TempDir(), "chart.json");
        File.WriteAllText(chart, """
        { "white": "D65", "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "fov": 16, "width": 72, "height": 48 },
          "lights": [ { "type": "directional", "direction": [0.2, 0, -1], "spectrum": "D65" } ],
          "objects": [ { "type": "colorchecker", "name": "patch" } ] }
        """);
        var slanted = Path.Combine(Path.GetDirectoryName(chart)!, "slanted");
        Assert.Equal(0, CliRunner.Run("render", chart, "-o", slanted, "--quiet").Exit);
        var (c2, _, e2) = CliRunner.Run("colorcheck", slanted);
        Assert.Equal(2, c2);
        Assert.Contains("is not lit head-on", e2);
        Assert.Contains("11.3°", e2);

        File.WriteAllText(chart, File.ReadAllText(chart).Replace("[0.2, 0, -1]", "[0, 0, -1]"));
        var headOn = Path.Combine(Path.GetDirectoryName(chart)!, "head-on");
        Assert.Equal(0, CliRunner.Run("render", chart, "-o", headOn, "--quiet").Exit);
        var (c3, o3, e3) = CliRunner.Run("colorcheck", headOn);
        Assert.True(c3 == 0, e3);
        Assert.Contains("max 0.0", o3);
    }
}
