using System.Collections.Concurrent;
using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Imaging;
using SpectralRenderer.Sensor;
using SpectralRenderer.Tests.Cli;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// Issue 24's exact route for path renders: each channel integrated from the render's sub-band grid (each sub-band's
/// mean radiance × ∫ η·λ/(hc) over the sub-band at the sensitivity's full resolution), as the path film integrates XYZ;
/// checked against the render's own XYZ, across output band counts with the same sub-band grid and samples, and against a
/// 0.1 nm integral of ρ·E·η·λ/(hc) for direct light, where the radiance is ρ/π·E analytically.
/// </summary>
public class PathExactSignalsTests(ITestOutputHelper output)
{
    static readonly ConcurrentDictionary<string, string> Renders = new();

    /// <summary>A render of a scene file edited by <paramref name="edit"/>, once per key for the class.</summary>
    static string Render(string key, string sceneFile, Func<string, string> edit, params string[] args) => Renders.GetOrAdd(key, _ =>
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, edit(File.ReadAllText(Repo.PathOf("scenes", sceneFile))));
        var outDir = Path.Combine(dir, "render");
        var (code, _, err) = CliRunner.Run(["render", scene, "-o", outDir, "--quiet", .. args]);
        Assert.True(code == 0, err);
        return outDir;
    });

    /// <summary>
    /// The light booth (path-colorchecker-booth.json: the chart lit by an emitter and the white walls' bounces, Monte Carlo
    /// noise and all) at 60 × 40, 4 samples per pixel, its sub-band grid <paramref name="grid"/> nm wide.
    /// </summary>
    internal static string Booth(string bands, double grid, string formats = "exr,aov") =>
        Render($"booth {bands} {grid} {formats}", "path-colorchecker-booth.json",
            t => t.Replace("\"integrator\": \"path\"",
                string.Create(CultureInfo.InvariantCulture, $"\"integrator\": {{ \"type\": \"path\", \"spectral_grid\": {grid} }}"),
                StringComparison.Ordinal),
            "--width", "60", "--height", "40", "--spp", "4", "--bands", bands, "--formats", formats);

    /// <summary>The §3.1 chart head-on under D65 in physical radiometry by the path integrator (max_depth 1: direct light, L =
    /// ρ/π·E).</summary>
    internal static string DirectChart(string bands, double grid, string formats = "exr,aov") =>
        Render($"chart {bands} {grid} {formats}", "paper-3.1-colorchecker-d65.json",
            t => t.Replace("\"radiometry\": \"paper\"", "\"radiometry\": \"physical\"", StringComparison.Ordinal)
                .Replace("\"max_depth\": 2,",
                    string.Create(CultureInfo.InvariantCulture,
                        $"\"integrator\": {{ \"type\": \"path\", \"max_depth\": 1, \"spectral_grid\": {grid} }},"),
                    StringComparison.Ordinal),
            "--width", "90", "--height", "60", "--bands", bands, "--formats", formats);

    [Theory]
    [InlineData("380:780:20")]
    [InlineData("380:780:5")]
    public void CieXyz_RawIsProportionalToThePathRendersXyz(string bands)
    {
        var render = Booth(bands, 5);
        var (raw, manifest) = ExactSignalsTests.Camera(render, "cie-xyz");
        Assert.StartsWith("exact (path)", (string)manifest["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        var exr = ExrReader.Read(Path.Combine(render, "spectral.exr"));
        var xyz = new[] { exr.OtherChannels["X"], exr.OtherChannels["Y"], exr.OtherChannels["Z"] };
        var scene = CameraScene.Open(render);
        Assert.Equal(24, scene.Patches.Count);
        double? ratio = null;
        double worst = 0;
        foreach (var p in scene.Patches)
            foreach (int i in p.Pixels)
                for (int c = 0; c < 3; c++)
                {
                    Assert.True(xyz[c][i] > 0, $"pixel {i} channel {c}: the booth's chart is lit");
                    double q = raw[i * 3 + c] / xyz[c][i];
                    ratio ??= q;
                    worst = Math.Max(worst, Math.Abs(q / ratio.Value - 1));
                }
        output.WriteLine($"path booth, cie-xyz raw / the film's XYZ at {bands}: largest relative deviation {worst:E3}");
        Assert.True(worst <= 1e-5, $"cie-xyz raw / the path film's XYZ varies by {worst:E3} relative at {bands}");
    }

    /// <summary>
    /// 5 output bands of 80 nm and 400 of 1 nm with a 1 nm sub-band grid (and 5 against 80 bands on the default 5 nm grid) are
    /// the same 400 (80) sub-bands, so the booth's paths are the same and each band count's signals must agree. (401 bands
    /// cannot share a sub-band grid with 5: 401 is no multiple of 5, so their sub-bands differ and so do the paths.)
    /// </summary>
    [Theory]
    [InlineData("nikon-d5100", "380:780:400", 1)]
    [InlineData("wheel-6", "380:780:400", 1)]
    [InlineData("mosaic-16", "380:780:400", 1)]
    [InlineData("wheel-6", "380:780:80", 5)]
    public void Signals_AtFiveBands_EqualThoseAtOneBandPerSubBand(string sensor, string many, double grid)
    {
        var (coarse, m) = ExactSignalsTests.Camera(Booth("380:780:5", grid, "npy,aov"), sensor);
        var (fine, _) = ExactSignalsTests.Camera(Booth(many, grid, "npy,aov"), sensor);
        Assert.StartsWith("exact (path)", (string)m["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        Assert.Equal(fine.Length, coarse.Length);
        double peak = fine.Max(), worst = 0;
        Assert.True(peak > 0, "the booth is lit");
        int compared = 0;
        for (int i = 0; i < fine.Length; i++)
            if (fine[i] > 1e-3 * peak && fine[i] < 0.99 * 4095) { worst = Math.Max(worst, Math.Abs(coarse[i] / fine[i] - 1)); compared++; }
        Assert.True(compared > fine.Length / 4, $"only {compared} of {fine.Length} photosites lit and unclipped");
        output.WriteLine(
            $"{sensor}: 5 bands vs {many} on a {grid} nm fine grid, largest relative difference {worst:E3} over {compared} photosites");
        Assert.True(worst <= 1e-5, $"{sensor}: 5 bands vs {many} differ by {worst:E3} relative");
    }

    /// <summary>
    /// Direct light only (max_depth 1), head-on D65 in physical radiometry: a patch's radiance is ρ(λ)·E(λ)/π, and its
    /// noise-free DN − black is K·t·A·ff·πT/(1+4N²)·∫ ρ·E/π·η_c·λ/(hc) dλ. On a 1 nm sub-band grid every channel of every
    /// preset meets the 0.1 nm integral (midpoint rule on the tables' linear interpolants, here) within 1e-4. On the default
    /// 5 nm grid the path carries ρ and E as their sub-band means, so the bound is the grid's own: the signals meet
    /// Σ_f ρ̄_f·Ē_f/π·∫_f η·λ/(hc) dλ (the same 0.1 nm sums per sub-band) within 1e-5, and the 5 nm grid's distance from the
    /// continuous integral is printed.
    /// </summary>
    [Theory]
    [InlineData(1, false, 3e-4)]
    [InlineData(1, true, 1e-5)]
    [InlineData(5, false, 1e-2)]
    [InlineData(5, true, 1e-5)]
    public void NoiseFreeSignals_MatchATenthNanometreIntegral_ForEveryChannelOfEveryPreset(double grid, bool subBandMeans, double bound)
    {
        var render = DirectChart("380:780:20", grid);
        var scene = CameraScene.Open(render);
        Assert.Equal(24, scene.Patches.Count);
        var d65 = ExactSignalsTests.Table("illuminants.csv", "D65");
        var header = File.ReadLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "colorchecker-ohta.csv")).First().Split(',');
        const double h = 6.62607015e-34, c0 = 299792458;
        int steps = (int)Math.Round(grid / 0.1);
        double overall = 0;
        foreach (var name in SensorPresets.Names)
        {
            var sensor = SensorPresets.Get(name);
            var (raw, manifest) = ExactSignalsTests.Camera(render, name);
            Assert.StartsWith("exact (path)", (string)manifest["simulation"]!["signal_route"]!, StringComparison.Ordinal);
            var exposures = manifest["sensor"]!["channels"]!.AsArray().Select(ch => (double)ch!["exposure_s"]!).ToArray();
            double worst = 0;
            foreach (var p in scene.Patches)
            {
                var rho = ExactSignalsTests.Table("colorchecker-ohta.csv", header[p.Number]);
                int i = p.Pixels[p.Pixels.Length / 2], x = i % 90, y = i / 90;
                for (int c = 0; c < sensor.ChannelCount; c++)
                {
                    if (sensor.Arrangement == Arrangement.Mosaic && sensor.ChannelAt(x, y) != c) continue;
                    var ch = sensor.Channels[c];
                    var qe = (ch.QuantumEfficiency.Wavelengths.ToArray(), ch.QuantumEfficiency.Values.ToArray());
                    bool zero = ch.QuantumEfficiency.Extrapolation == SpectralRenderer.Spectra.Extrapolation.Zero;
                    double integral = 0;
                    // Per sub-band [380 + k·grid, 380 + (k+1)·grid]: the 0.1 nm sums of ρ, E and η·λ/(hc).
                    for (int k = 0; k * grid < 400 - 1e-9; k++)
                    {
                        double sr = 0, se = 0, sg = 0, sreg = 0;
                        for (int j = 0; j < steps; j++)
                        {
                            double wl = 380 + k * grid + (j + 0.5) * 0.1;
                            double r = ExactSignalsTests.Lerp(rho, wl), e = ExactSignalsTests.Lerp(d65, wl);
                            double eta = zero && (wl < qe.Item1[0] || wl > qe.Item1[^1])
                                ? 0
                                : ch.PerEnergy
                                ? ExactSignalsTests.Lerp(qe, wl) * 555 / wl
                                : ExactSignalsTests.Lerp(qe, wl);
                            double g = eta * wl * 1e-9 / (h * c0) * 0.1;
                            sr += r; se += e; sg += g; sreg += r * e * g;
                        }
                        integral += subBandMeans ? sr / steps * (se / steps) * sg : sreg;
                    }
                    double expected = sensor.SystemGain * exposures[c] * sensor.Etendue * integral / Math.PI;
                    double dn = sensor.Arrangement == Arrangement.Mosaic ? raw[i] : raw[i * sensor.ChannelCount + c];
                    worst = Math.Max(worst, Math.Abs((dn - sensor.BlackLevel) / expected - 1));
                }
            }
            overall = Math.Max(overall, worst);
            output.WriteLine($"{name}: {grid} nm fine grid vs the 0.1 nm {(subBandMeans ? "sums of sub-band means" : "integral")}, largest "
                + $"relative difference {worst:E3}");
            Assert.True(worst <= bound,
                $"{name}: {grid} nm grid vs the 0.1 nm {(subBandMeans ? "sub-band means" : "integral")}: {worst:E3} relative");
        }
        output.WriteLine($"all presets: {overall:E3}");
    }

    /// <summary>
    /// A path render's sub-band film formed two ways gives the same signals: from its lights/ (L_f = F_f + Σ_k T_k,f·E_k,f, no
    /// rays) and traced again from render.json (the render's samples) — within float rounding (1e-5), and camera.json says which.
    /// </summary>
    [Fact]
    public void LightsTransfer_AndTracingAgain_GiveTheSameSignals()
    {
        var withLights = DirectChart("380:780:20", 5, "npy,aov,lights");
        var plain = DirectChart("380:780:20", 5, "npy,aov");
        var (a, ma) = ExactSignalsTests.Camera(withLights, "nikon-d5100");
        var (b, mb) = ExactSignalsTests.Camera(plain, "nikon-d5100");
        Assert.Contains("from the render's lights/", (string)ma["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        Assert.Contains("traced again", (string)mb["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        double peak = a.Max(), worst = 0;
        for (int i = 0; i < a.Length; i++) if (b[i] > 1e-3 * peak) worst = Math.Max(worst, Math.Abs(a[i] / b[i] - 1));
        output.WriteLine($"lights/ vs traced again: largest relative difference {worst:E3}");
        Assert.True(worst <= 1e-5, $"lights/ vs traced again differ by {worst:E3}");
    }

    /// <summary>The path route's signals (the samples traced again, the lens applied per band) are the same on 1 and 2 threads, bit for
    /// bit.</summary>
    [Fact]
    public void Signals_AreTheSameOnAnyThreadCount()
    {
        var render = Booth("380:780:20", 5, "npy,aov");
        var raws = new[] { "1", "2" }.Select(t =>
        {
            var cam = Path.Combine(render, $"cam-threads-{t}");
            var (code, _, err) = CliRunner.Run("camera", render, "--sensor", "mosaic-16", "--noise", "off", "-o", cam, "--threads", t);
            Assert.True(code == 0, err);
            return File.ReadAllBytes(Path.Combine(cam, "raw.npy"));
        }).ToArray();
        Assert.Equal(raws[0], raws[1]);
    }

    /// <summary>
    /// A path render takes the exact route, whichever way the path integrator was chosen (the scene, or --integrator path
    /// for a scene that names none), with no band-route note; --signals bands still gives the band cube.
    /// </summary>
    [Theory]
    [InlineData("path-colorchecker-booth.json", null, null)]
    [InlineData("paper-3.1-colorchecker-d65.json", "path", null)]
    [InlineData("paper-3.1-colorchecker-d65.json", "path", "bands")]
    public void PathRender_TakesTheExactRoute(string sceneFile, string? integrator, string? signals)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, File.ReadAllText(Repo.PathOf("scenes", sceneFile))
            .Replace("\"radiometry\": \"paper\"", "\"radiometry\": \"physical\"", StringComparison.Ordinal));
        var render = Path.Combine(dir, "render");
        string[] args = ["render", scene, "-o", render, "--width", "24", "--height", "16", "--spp", "1", "--bands", "380:780:10",
            "--formats", "npy,aov", "--quiet"];
        var (code, _, err) = CliRunner.Run(integrator is null ? args : [.. args, "--integrator", integrator]);
        Assert.True(code == 0, err);
        var cam = Path.Combine(dir, "cam");
        string[] camArgs = ["camera", render, "--sensor", "wheel-6", "--noise", "off", "-o", cam, "--off-axis", "none", "--psf", "none"];
        (code, _, err) = CliRunner.Run(signals is null ? camArgs : [.. camArgs, "--signals", signals]);
        Assert.True(code == 0, err);
        Assert.DoesNotContain("note:", err, StringComparison.Ordinal);
        string used = (string)JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!["simulation"]!["signal_route"]!;
        if (signals == "bands") Assert.Equal(RadianceCube.BandRoute, used);
        else Assert.StartsWith("exact (path)", used, StringComparison.Ordinal);
        var (_, raw) = NpyReader.Read(File.OpenRead(Path.Combine(cam, "raw.npy")));
        Assert.True(raw.Max() > 100, $"peak {raw.Max()} DN: the scene is lit");
    }
}
