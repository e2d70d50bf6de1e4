using System.Globalization;
using System.Net;
using System.Text.Json.Nodes;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Imaging;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// The viewer in a real browser: Debian's Chromium, headless, driven by playwright-core (tests/browser, installed by
/// .ci/run with npm). It loads viewer.html, hovers a pixel and reads the plotted spectrum back from the page, switches
/// the lights and reads a pixel's colour, and fails on any console error. The values it reads are checked against the
/// render's own files (spectral.npy) and against `spectral relight` (preview.png): the page computes them itself.
/// </summary>
[Trait("Category", "Browser")]
[Trait("Category", "Interop")]   // a real browser: not part of the fast core (README)
public class ViewerBrowserTests(ITestOutputHelper output)
{
    static string Repo()
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
            if (File.Exists(Path.Combine(d.FullName, "tests", "browser", "viewer-check.mjs"))) return d.FullName;
        throw new DirectoryNotFoundException("tests/browser");
    }

    internal static string Script()
    {
        var node = Tool.Find("node");
        Skip.If(node is null, "node is not installed (Debian package nodejs); skipping the browser test");
        Skip.If(Tool.Find("chromium") is null, "chromium is not installed (Debian package chromium); skipping the browser test");
        var dir = Path.Combine(Repo(), "tests", "browser");
        Skip.If(!Directory.Exists(Path.Combine(dir, "node_modules", "playwright-core")),
            "playwright-core is not installed: run 'npm ci' in tests/browser (.ci/run does)");
        return Path.Combine(dir, "viewer-check.mjs");
    }

    JsonNode Check(string target, string plan) => Check(output, target, plan);

    internal static JsonNode Check(ITestOutputHelper output, string target, string plan)
    {
        var (code, stdout, stderr) = Tool.Run(Tool.Find("node")!, [Script(), target, plan], timeoutMs: 120000);
        output.WriteLine(stdout.Length > 2000 ? stdout[..2000] + "…" : stdout);
        Assert.True(code == 0, $"browser check failed ({code}): {stdout} {stderr}");
        var r = JsonNode.Parse(stdout.Trim().Split('\n')[^1])!;
        Assert.Empty(r["errors"]!.AsArray());
        return r;
    }

    internal static void Run(params string[] args)
    {
        var (code, _, err) = CliRunner.Run(args);
        Assert.True(code == 0, err);
    }

    static float[] PixelOf(string npy, int x, int y)
    {
        using var s = File.OpenRead(npy);
        var (shape, data) = NpyReader.Read(s);
        return data.AsSpan((y * shape[1] + x) * shape[2], shape[2]).ToArray();
    }

    [SkippableFact]
    public void Viewer_plots_the_hovered_pixel_and_relights_to_the_colour_relight_writes()
    {
        Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, RelightTests.TwoLightScene("A", "A"));
        Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "png,npy,aov,lights");
        Run("view", Path.Combine(dir, "r"));
        Assert.DoesNotContain("http", File.ReadAllText(Path.Combine(dir, "r", "viewer.html")).Replace("http://127.0.0.1", ""));
        // The pixel at the centre of the green ball (48×36 camera).
        int x = 14, y = 20;
        var r = Check(Path.Combine(dir, "r", "viewer.html"),
            $$"""{"hover":[{{x}},{{y}}],"light":"key","preset":"D65","intensity":1,"read":[{{x}},{{y}}],"canvas":true}""");
        var plotted = r["plotted"]!.AsArray().Select(v => (double)v!).ToArray();
        var truth = PixelOf(Path.Combine(dir, "r", "spectral.npy"), x, y);
        Assert.Equal(truth.Length, plotted.Length);
        for (int b = 0; b < truth.Length; b++) Assert.Equal(truth[b], plotted[b], Math.Abs(truth[b]) * 1e-5 + 1e-12);
        Assert.Contains("ball", (string)r["where"]!);
        // The ground truth of the green ball: ColorChecker #14's band means.
        var reflectance = r["reflectance"]!.AsArray().Select(v => (double)v!).ToArray();
        var cm = new SpectralRenderer.Color.Colorimeter(SpectralRenderer.Spectra.BandGrid.Parse("380:780:20"),
            SpectralRenderer.Color.Observer.Cie1931, SpectralRenderer.Spectra.SpectrumLibrary.Resolve("D65"));
        var expected = cm.Project(SpectralRenderer.Spectra.SpectrumLibrary.Resolve("colorchecker:14"));
        for (int b = 0; b < expected.Length; b++) Assert.Equal(expected[b], reflectance[b], 1e-6);

        // The page's relit colour of the pixel equals preview.png of `spectral relight` with the same light.
        Run("relight", Path.Combine(dir, "r"), "--light", "key=D65", "-o", Path.Combine(dir, "relit"), "--quiet");
        var png = PngReader.Read(Path.Combine(dir, "relit", "preview.png"));
        int i = (y * png.Width + x) * png.Channels;
        var rgb = r["rgb"]!.AsArray().Select(v => (int)v!).ToArray();
        for (int c = 0; c < 3; c++) Assert.InRange(rgb[c], png.Samples[i + c] - 1, png.Samples[i + c] + 1);
        // And so does every pixel the page drew: diffuse, highlights, the coloured mirror and the glass (whose colour is
        // eq. 3 on band values), the background — relight and display encoding in the page against the C# writer.
        AssertCanvasIs(r, png);
    }

    [SkippableFact]
    public void Dragging_a_light_slider_past_the_old_limit_of_4_relights_to_what_relight_writes()
    {
        // The spot "blue" has intensity 3: its slider reaches 12 (4× the render's own value), beyond the old fixed 4.
        Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, RelightTests.TwoLightScene("A", "A", 3));
        Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "png,npy,aov,lights");
        Run("view", Path.Combine(dir, "r"));
        int x = 14, y = 20;
        var r = Check(Path.Combine(dir, "r", "viewer.html"),
            $$"""{"light":"blue","preset":"render: A (blue)","drag":1,"read":[{{x}},{{y}}]}""");
        Assert.Equal(12, (double)r["sliderMax"]!, 9);
        double dragged = (double)r["dragged"]!;
        Assert.True(dragged > 4, $"the slider stopped at {dragged}");
        Run("relight", Path.Combine(dir, "r"), "--intensity",
            $"blue={dragged.ToString("R", System.Globalization.CultureInfo.InvariantCulture)}",
            "-o", Path.Combine(dir, "relit"), "--quiet");
        var png = PngReader.Read(Path.Combine(dir, "relit", "preview.png"));
        int i = (y * png.Width + x) * png.Channels;
        var rgb = r["rgb"]!.AsArray().Select(v => (int)v!).ToArray();
        for (int c = 0; c < 3; c++) Assert.InRange(rgb[c], png.Samples[i + c] - 1, png.Samples[i + c] + 1);
    }

    /// <summary>
    /// Issue 27's photometric scene: a white diffuser (ρ = 1) facing the camera, a point lamp of 1000 cd at 2 m on the axis
    /// and a sun of 100 lx head-on; the 9 × 9 film's centre pixel looks along the axis (E = I/r² + E⊥, L = ρE/π).
    /// </summary>
    static string PhotometricScene(string lampSpectrum = "D65", string lampValue = "\"luminous_intensity\": 1000") => $$"""
        { "radiometry": "physical", "scaling": "absolute", "white": "D65", "bands": "380:780:20",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 20, "width": 9, "height": 9, "spp": 1 },
          "materials": { "diffuser": { "diffuse": 1 } },
          "lights": [ { "type": "point", "name": "lamp", "position": [0, 0, 2], "spectrum": "{{lampSpectrum}}", {{lampValue}} },
                      { "type": "directional", "name": "sun", "direction": [0, 0, -1], "spectrum": "D65", "illuminance": 100 } ],
          "objects": [ { "type": "quad", "center": [0, 0, 0], "size": 4, "material": "diffuser" } ] }
        """;

    static void Near(string what, double expected, double actual, double rel)
        => Assert.True(Math.Abs(actual - expected) <= rel * Math.Abs(expected), $"{what}: page {actual:G9}, expected {expected:G9}");

    [SkippableFact]
    public void The_cursor_readout_gives_lux_and_cd_per_m2_that_follow_the_lights_and_the_maps_are_views()
    {
        Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, PhotometricScene());
        Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "png,lights,photometry");
        Run("view", Path.Combine(dir, "r"));
        var page = Path.Combine(dir, "r", "viewer.html");
        var exr = SpectralRenderer.Tests.Output.PhotometryOutputTests.ReadExr(Path.Combine(dir, "r", "photometry.exr"));

        // As rendered: E = 1000/2² + 100 = 350 lx, L = 350/π cd/m² at the centre (the bar's 0.1 %), and photometry.exr's values.
        var r = Check(page, """{"readout":[4,4],"view":"illuminance"}""");
        Near("illuminance (lx)", 350, (double)r["illuminance"]!, 1e-3);
        Near("luminance (cd/m²)", 350 / Math.PI, (double)r["luminance"]!, 1e-3);
        Near("illuminance vs photometry.exr", exr.Channels["illuminance"][4 * 9 + 4], (double)r["illuminance"]!, 1e-6);
        Near("luminance vs photometry.exr", exr.Channels["luminance"][4 * 9 + 4], (double)r["luminance"]!, 1e-5);
        Assert.Contains("lx", (string)r["readoutText"]!);
        Assert.Contains("cd/m²", (string)r["readoutText"]!);
        // The illuminance view is illuminance.png (same scale), with its legend.
        var png = PngReader.Read(Path.Combine(dir, "r", "illuminance.png"));
        var canvas = r["viewCanvas"]!.AsArray().Select(v => (int)v!).ToArray();
        for (int p = 0; p < 81; p++)
            for (int c = 0; c < 3; c++) Assert.InRange(canvas[4 * p + c], png.Samples[3 * p + c] - 1, png.Samples[3 * p + c] + 1);
        Assert.Contains("data-unit=\"lx\"", (string)r["legend"]!);

        // The lamp's log slider dragged to the middle of its 4 decades: the same spectrum, so E = I/r² + 100 with
        // I = 1000 cd × (new scale / render's scale), and the text beside the slider says I in cd.
        double scale0 = (double)JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "r", "render.json")))!["lights"]![0]!["intensity"]!;
        r = Check(page, """{"light":"sun","preset":"render: D65 (sun)","logDrag":0,"logTo":0.5,"readout":[4,4]}""");
        double intensity = (double)r["intensity"]!;
        var log = r["logSlider"]!.AsArray().Select(v => (double)v!).ToArray();
        Assert.Equal(Math.Log10(4 * scale0), log[2], 9);
        Assert.Equal(Math.Pow(10, log[0]), intensity, intensity * 1e-12);
        Assert.True(intensity < 0.1 * scale0 && intensity > 1e-3 * scale0, $"log slider at {log[0]} gives {intensity} (scale {scale0})");
        double cd = 1000 * intensity / scale0;
        Assert.Contains($"= {cd.ToString("G4", CultureInfo.InvariantCulture)} cd", (string)r["intensityText"]!);
        Near("illuminance after the log drag (lx)", cd / 4 + 100, (double)r["illuminance"]!, 1e-3);
        Near("luminance after the log drag (cd/m²)", (cd / 4 + 100) / Math.PI, (double)r["luminance"]!, 1e-3);

        // Another spectrum: the lamp to A at twice the render's scale, against photometry.exr of that scene rendered.
        double x = 2 * scale0;
        r = Check(page,
            $$"""{"light":"lamp","preset":"A","intensity":{{x.ToString("R", CultureInfo.InvariantCulture)}},"readout":[4,4]}""");
        File.WriteAllText(scene, PhotometricScene("A", $"\"intensity\": {x.ToString("R", CultureInfo.InvariantCulture)}"));
        Run("render", scene, "-o", Path.Combine(dir, "a"), "--quiet", "--formats", "png,photometry");
        var a = SpectralRenderer.Tests.Output.PhotometryOutputTests.ReadExr(Path.Combine(dir, "a", "photometry.exr"));
        output.WriteLine($"A at ×{x:G6}: page {(double)r["illuminance"]!:G7} lx, {(double)r["luminance"]!:G7} cd/m²; render "
            + $"{a.Channels["illuminance"][40]:G7} lx, {a.Channels["luminance"][40]:G7} cd/m²");
        Near("illuminance under A vs its render", a.Channels["illuminance"][40], (double)r["illuminance"]!, 1e-5);
        Near("luminance under A vs its render", a.Channels["luminance"][40], (double)r["luminance"]!, 1e-4);
        Assert.True((double)r["illuminance"]! > 400, "the lamp under A at twice its scale should light the centre more than before");
    }

    /// <summary>Every pixel the page drew is within one code of <paramref name="png"/>, and 99 % of the codes are equal.</summary>
    static void AssertCanvasIs(JsonNode r, PngImage png)
    {
        var canvas = r["canvas"]!.AsArray().Select(v => (int)v!).ToArray();
        Assert.Equal(png.Width * png.Height * 4, canvas.Length);
        int exact = 0;
        for (int p = 0; p < png.Width * png.Height; p++)
            for (int c = 0; c < 3; c++)
            {
                int page = canvas[4 * p + c], file = png.Samples[p * png.Channels + c];
                Assert.True(Math.Abs(page - file) <= 1,
                    $"pixel {p % png.Width},{p / png.Width} channel {c}: page {page}, preview.png {file}");
                if (page == file) exact++;
            }
        Assert.True(exact >= 0.99 * 3 * png.Width * png.Height, $"only {exact} of {3 * png.Width * png.Height} codes equal preview.png");
    }

    /// <summary>
    /// The glass-mirror scene: dispersive glass (one-band components behind it), a mirror ball, two unnamed lights. The
    /// page relit to FL11 draws what `spectral relight` writes.
    /// </summary>
    [SkippableFact]
    public void Viewer_relights_the_dispersive_glass_scene_to_the_colours_relight_writes()
    {
        Script();
        var dir = Reference.TempDir();
        Run("render", Path.Combine(Repo(), "scenes", "glass-mirror.json"), "-o", Path.Combine(dir, "r"), "--quiet", "--formats",
            "png,npy,lights", "--width", "64", "--height", "48");
        Run("view", Path.Combine(dir, "r"));
        var r = Check(Path.Combine(dir, "r", "viewer.html"),
            """{"light":"light-0","preset":"FL11","intensity":1,"read":[32,24],"canvas":true}""");
        Run("relight", Path.Combine(dir, "r"), "--light", "light-0=FL11", "-o", Path.Combine(dir, "relit"), "--quiet");
        AssertCanvasIs(r, PngReader.Read(Path.Combine(dir, "relit", "preview.png")));
    }

    /// <summary>
    /// The ΔE00 map: the page's CIEDE2000 reproduces Sharma, Wu &amp; Dalal's 34 pairs (data/reference), and its value at
    /// a pixel between state A and the current state equals the C# CIEDE2000 of the two colours the page shows there.
    /// </summary>
    [SkippableFact]
    public void The_delta_E00_map_reproduces_Sharma_pairs_and_each_pixels_difference()
    {
        Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, RelightTests.TwoLightScene("A", "A"));
        Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "npy,lights");
        Run("view", Path.Combine(dir, "r"));
        var rows = Reference.Rows("ciede2000-sharma-2005.csv");
        string pairs = "["
            + string.Join(",",
                rows.Select(q => "[" + string.Join(",", new[] { "L1", "a1", "b1", "L2", "a2", "b2" }.Select(k => q[k])) + "]"))
            + "]";
        int x = 14, y = 20;
        var r = Check(Path.Combine(dir, "r", "viewer.html"),
            $$"""{"light":"key","preset":"D65","intensity":1,"read":[{{x}},{{y}}],"storeA":true,"dePairs":{{pairs}}}""");
        var page = r["dePairs"]!.AsArray().Select(v => (double)v!).ToArray();
        Assert.Equal(34, page.Length);
        for (int k = 0; k < rows.Count; k++)
            Assert.True(Math.Abs(page[k] - double.Parse(rows[k]["dE00"], CultureInfo.InvariantCulture)) <= 1e-4,
                $"pair {rows[k]["pair"]}: page {page[k]:F6}, Sharma {rows[k]["dE00"]}");

        var white = JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "r", "render.json")))!["colour"]!["white_xyz"]!.AsArray()
            .Select(v => (double)v!).ToArray();
        var w = new SpectralRenderer.Color.Xyz(white[0], white[1], white[2]);
        SpectralRenderer.Color.Xyz Xyz(string key)
        {
            var a = r[key]!.AsArray().Select(v => (double)v!).ToArray();
            return new(a[0], a[1], a[2]);
        }
        double expected = SpectralRenderer.Color.DeltaE2000.Between(SpectralRenderer.Color.Lab.FromXyz(Xyz("xyzA"), w),
            SpectralRenderer.Color.Lab.FromXyz(Xyz("xyz"), w));
        Assert.True(expected > 1, $"A → D65 should change the ball's colour visibly (ΔE00 {expected})");
        Assert.Equal(expected, (double)r["pixelDe"]!, 1e-6 * expected);
        Assert.InRange((double)r["de"]!["max"]!, expected, double.MaxValue);
    }

    [SkippableFact]
    public void Served_viewer_works_over_loopback_and_serves_nothing_outside_the_folder()
    {
        Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, RelightTests.TwoLightScene("A", "A"));
        Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "npy,lights");
        File.WriteAllText(Path.Combine(dir, "secret.txt"), "not served");
        var stdout = new StringWriter();
        var serving = Task.Run(() =>
            SpectralRenderer.Cli.CommandLine.Run(["view", Path.Combine(dir, "r"), "--serve", "--for", "60"], stdout, new StringWriter()));
        string? url = null;
        for (int t = 0; t < 200 && url is null; t++)
        {
            Thread.Sleep(50);
            var line = stdout.ToString().Split('\n').FirstOrDefault(l => l.Contains("http://127.0.0.1:"));
            if (line is not null) url = line[line.IndexOf("http", StringComparison.Ordinal)..].Trim();
        }
        Assert.NotNull(url);
        using var http = new HttpClient();
        Assert.Equal(HttpStatusCode.OK, http.GetAsync(url).Result.StatusCode);
        var root = url![..url.LastIndexOf('/')];
        Assert.NotEqual(HttpStatusCode.OK, http.GetAsync(root + "/%2e%2e/secret.txt").Result.StatusCode);
        Assert.Equal(HttpStatusCode.NotFound, http.GetAsync(root + "/nothing-here.bin").Result.StatusCode);
        var r = Check(url, """{"light":"blue","preset":"led-green","intensity":2,"read":[10,30]}""");
        Assert.Equal(["key", "blue"], r["lights"]!.AsArray().Select(v => (string)v!).ToArray());
    }
}

/// <summary>
/// The relight timing the issue asks for: a 1024 × 768, 20-band render relit in the page, reported (the bar is under
/// 100 ms; the figure goes to BENCHMARKS.md). A wall-clock figure is not a pass/fail condition of a unit test on shared
/// machines, so this test reports it and checks what the timed page computed; it runs alone (no other test class in
/// parallel) so the figure it prints is the page's own.
/// </summary>
[Trait("Category", "Browser")]
[Trait("Category", "Interop")]
[Collection("Alone")]
public class ViewerTimingTests(ITestOutputHelper output)
{
    [SkippableFact]
    public void Relighting_1024_by_768_in_the_page_is_timed_and_reported()
    {
        ViewerBrowserTests.Script();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "s.json");
        File.WriteAllText(scene, RelightTests.TwoLightScene("A", "A").Replace("\"spp\": 2", "\"spp\": 1"));
        ViewerBrowserTests.Run("render", scene, "-o", Path.Combine(dir, "r"), "--quiet", "--formats", "lights", "--width", "1024",
            "--height", "768");
        ViewerBrowserTests.Run("view", Path.Combine(dir, "r"));
        var r = ViewerBrowserTests.Check(output, Path.Combine(dir, "r", "viewer.html"),
            """{"light":"key","preset":"FL11","intensity":1.5,"read":[512,400],"storeA":true,"timeRuns":9}""");
        double relight = (double)r["relightMs"]!, draw = (double)r["drawMs"]!;
        output.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"viewer relight 1024x768x20: {relight:0.0} ms (XYZ of every pixel, bar < 100 ms), {draw:0.0} ms (full redraw: relight, "
                + $"display encoding, putImageData), median of 9, components "
                + $"{JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "r", "lights", "lights.json")))!["components"]!.AsArray().Count}"));
        Assert.Equal([1024, 768, 20], r["size"]!.AsArray().Select(v => (int)v!).ToArray());
        Assert.True(relight > 0 && draw > 0, $"timings {relight} ms, {draw} ms");
        Assert.True((double)r["de"]!["max"]! > 0, "the ΔE00 map between A and FL11 should not be zero");
    }
}
