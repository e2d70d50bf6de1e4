using System.Globalization;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Distributed;

namespace SpectralRenderer.Tests.Relight;

/// <summary>
/// Everything downstream of a render works on path renders (issue 23): colorcheck, the camera stage, recovery, the viewer
/// and sweeps. The chart is the paper's §3.1 scene in physical radiometry under the path integrator: one directional light
/// head-on and nothing else, so every patch point sees the light and the radiance is E·ρ/π exactly (a flat chart returns
/// no light to itself) — the independent references are the 1 nm tables and that analytic white.
/// </summary>
public class PathDownstreamTests
{
    static readonly Lazy<string> Chart = new(() =>
    {
        var dir = Reference.TempDir();
        var text = File.ReadAllText(ShardMergeTests.Scene("paper-3.1-colorchecker-d65.json"))
            .Replace("\"radiometry\": \"paper\"", "\"radiometry\": \"physical\", \"integrator\": { \"type\": \"path\" }");
        Assert.Contains("\"path\"", text);
        var scene = Path.Combine(dir, "chart.json");
        File.WriteAllText(scene, text);
        var render = Path.Combine(dir, "chart");
        ShardMergeTests.Render(scene, render, "--width", "60", "--height", "40", "--spp", "1", "--formats", "npy,aov,lights");
        return render;
    });

    static double D(JsonNode? n) => n!.GetValue<double>();

    [Fact]
    public void Colorcheck_matches_the_1nm_colours_of_the_patches()
    {
        var (code, csv, err) = CliRunner.Run("colorcheck", Chart.Value, "--csv");
        Assert.True(code == 0, err);
        var lines = csv.Trim().Split('\n');
        int de = Array.IndexOf(lines[0].Trim().Split(','), "dE00");
        Assert.Equal(25, lines.Length);
        // The path tracer integrates colour on its 5 nm grid: within 0.05 ΔE00 of the 1 nm integral (Whitted's exact route: 0.002).
        foreach (var l in lines.Skip(1))
            Assert.True(double.Parse(l.Split(',')[de], CultureInfo.InvariantCulture) <= 0.05, l);
    }

    [Fact]
    public void The_camera_reads_the_white_off_the_chart_and_recovery_sees_every_chart_pixel_lit()
    {
        var cam = Path.Combine(Chart.Value, "cam-xyz");
        var (code, stdout, err) = CliRunner.Run("camera", Chart.Value, "--sensor", "cie-xyz", "--noise", "off", "-o", cam,
            "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);
        Assert.DoesNotContain("band cube", err);   // a path render's channels come from its fine grid (here its lights/)
        // The white diffuser's radiance under a head-on directional light of intensity 1 in physical radiometry: E/π.
        var json = JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!;
        Assert.StartsWith("exact (path)", (string)json["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        Assert.Contains("from the render's lights/", (string)json["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        double white = D(json["simulation"]?["white_radiance_scale"]);
        Assert.True(Math.Abs(white * Math.PI - 1) <= 2e-3, $"white radiance scale {white} × π = {white * Math.PI}");
        var m = Regex.Match(stdout, @"mean ΔE00 (\d+\.\d+), max (\d+\.\d+)");
        Assert.True(m.Success, stdout);
        // The sub-band grid's signals against the 1 nm colours (the Whitted render of the paper's scene, band route: mean 0.13, max 0.28).
        Assert.True(double.Parse(m.Groups[2].Value, CultureInfo.InvariantCulture) <= 0.5, m.Value);

        (code, var csv, err) = CliRunner.Run("recover", cam, "--csv");
        Assert.True(code == 0, err);
        var rows = csv.Trim().Split('\n').Skip(1).Select(l => l.Split(',')).ToList();
        Assert.DoesNotContain(rows, r => r[1] == "shadow");
        int lit = rows.Where(r => r[1] == "lit").Select(r => int.Parse(r[2], CultureInfo.InvariantCulture)).First();
        Assert.Equal(rows.First(r => r[1] == "all")[2], lit.ToString(CultureInfo.InvariantCulture));
        // mask-lit-0.png: 255 wherever the centre ray sees the chart (object id > 0), 0 on the background.
        using var ids = File.OpenRead(Path.Combine(Chart.Value, "lights", "ids.npy"));
        var (shape, data) = NpyReader.Read(ids);
        Assert.Equal([40, 60, 3], shape);
        int onChart = Enumerable.Range(0, 40 * 60).Count(i => data[3 * i] > 0);
        Assert.True(Enumerable.Range(0, 40 * 60).All(i => data[3 * i + 1] == (data[3 * i] > 0 ? 1 : 0)),
            "lit mask bit 0 where the chart is seen");
        Assert.True(onChart >= lit, $"{onChart} chart pixels, {lit} lit surface pixels");
    }

    [Fact]
    public void The_viewer_shows_a_path_render()
    {
        var (code, _, err) = CliRunner.Run("view", Chart.Value);
        Assert.True(code == 0, err);
        var data = File.ReadAllText(Path.Combine(Chart.Value, "viewer-data.js"));
        Assert.Contains("patch-01", data);
    }

    [Fact]
    public void A_sweep_of_a_path_scene_renders_each_job_as_the_render_of_its_scene_and_a_relight_agrees()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "scene.json"), """
            { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
              "camera": { "position": [0, 1, 5], "look_at": [0, 0.6, 0], "width": 24, "height": 16, "spp": 2 },
              "materials": { "ball": { "type": "lambertian", "reflectance": "colorchecker:14" },
                             "floor": { "type": "lambertian", "reflectance": "colorchecker:neutral-6.5" } },
              "lights": [ { "type": "point", "name": "key", "position": [2, 4, 3], "spectrum": "D65", "intensity": 5 } ],
              "objects": [ { "type": "sphere", "name": "sphere", "center": [0, 0.7, 0], "radius": 0.7, "material": "ball" },
                           { "type": "plane", "name": "floor", "material": "floor" } ] }
            """);
        File.WriteAllText(Path.Combine(dir, "plan.json"), """
            { "scene": "scene.json", "formats": ["npy", "lights"],
              "axes": [ { "name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"] } ] }
            """);
        var outDir = Path.Combine(dir, "sweep");
        var (code, _, err) = CliRunner.Run("sweep", Path.Combine(dir, "plan.json"), "-o", outDir, "--quiet");
        Assert.True(code == 0, err);
        var jobA = Path.Combine(outDir, "jobs", "0001");
        var direct = Path.Combine(dir, "direct");
        ShardMergeTests.Render(Path.Combine(jobA, "scene.json"), direct, "--formats", "npy,lights");
        Assert.Equal(File.ReadAllBytes(Path.Combine(direct, "spectral.npy")), File.ReadAllBytes(Path.Combine(jobA, "spectral.npy")));
        // Job 0000 (D65) relit to A is job 0001 up to float rounding.
        var relit = Path.Combine(dir, "relit");
        (code, _, err) = CliRunner.Run("relight", Path.Combine(outDir, "jobs", "0000"), "-o", relit, "--light", "key=A", "--quiet");
        Assert.True(code == 0, err);
        float[] Read(string d) { using var s = File.OpenRead(Path.Combine(d, "spectral.npy")); return NpyReader.Read(s).Data; }
        var (a, b) = (Read(jobA), Read(relit));
        double worst = a.Zip(b).Max(p => p.First == p.Second ? 0 : Math.Abs(p.First - p.Second) / Math.Max(Math.Abs(p.First), 1e-30));
        Assert.True(worst <= 1e-5, $"relit D65 job differs from the A job by {worst:E2}");
        double change = a.Zip(Read(Path.Combine(outDir, "jobs", "0000")))
            .Max(p => Math.Abs(p.First - p.Second) / Math.Max(Math.Abs(p.First), 1e-30));
        Assert.True(change > 1e-2, $"the A and D65 jobs differ by only {change:E2}");
    }
}
