using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// Issue 24's exact route: each channel integrated at full spectral resolution per eq. 2 term, as exact colour is, so
/// the signals do not depend on the band count; checked against the render's own exact XYZ and CIE 015's 1 nm sum here.
/// </summary>
public class ExactSignalsTests(ITestOutputHelper output)
{
    const int Width = 90, Height = 60;

    /// <summary>The §3.1 chart (head-on D65, so a patch's radiance is ρ·E·intensity, /π physical) at a band grid, radiometry and
    /// intensity.</summary>
    internal static string Chart(string bands, string radiometry = "paper", double intensity = 1, string formats = "exr,aov",
        string light = "D65")
    {
        var dir = Reference.TempDir();
        var text = File.ReadAllText(Repo.PathOf("scenes", "paper-3.1-colorchecker-d65.json"))
            .Replace("\"spectrum\": \"D65\"", $"\"spectrum\": \"{light}\"", StringComparison.Ordinal)
            .Replace("\"radiometry\": \"paper\"", $"\"radiometry\": \"{radiometry}\"", StringComparison.Ordinal)
            .Replace("\"intensity\": 1 }", string.Create(CultureInfo.InvariantCulture, $"\"intensity\": {intensity:R} }}"),
                StringComparison.Ordinal);
        var scene = Path.Combine(dir, "chart.json");
        File.WriteAllText(scene, text);
        var outDir = Path.Combine(dir, "render");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--width", $"{Width}", "--height", $"{Height}", "--bands", bands,
            "--formats", formats, "--quiet");
        Assert.True(code == 0, err);
        return outDir;
    }

    internal static (float[] Raw, JsonObject Manifest) Camera(string render, string sensor, params string[] extra)
    {
        var outDir = Path.Combine(render, $"cam-{sensor}-{string.Join("", extra)}");
        // A flat lens (no cos⁴, no blur): these tests compare the spectral integration pixel by pixel; the lens is OpticsTests'.
        var (code, _, err) = CliRunner.Run(
            new[] { "camera", render, "--sensor", sensor, "--noise", "off", "-o", outDir, "--off-axis", "none", "--psf", "none" }
            .Concat(extra).ToArray());
        Assert.True(code == 0, err);
        var (_, raw) = NpyReader.Read(File.OpenRead(Path.Combine(outDir, "raw.npy")));
        return (raw, (JsonObject)JsonNode.Parse(File.ReadAllText(Path.Combine(outDir, "camera.json")))!);
    }

    /// <summary>
    /// The chart under a light at 20 and 5 bands (D65 the white): cie-xyz's raw is proportional to the render's exact XYZ — one
    /// summation rule (CIE 015's 1 nm sum) for colour and the camera — and every patch's XYZ is within ΔE00 0.01 of the CIE 1 nm
    /// summation written out here (<see cref="Cie015.Of"/>; issue 42's bar under the narrow blue LED at its built-in flux).
    /// </summary>
    [Theory]
    [InlineData("380:780:20", "D65")]
    [InlineData("380:780:5", "D65")]
    [InlineData("380:780:20", "led-blue")]
    [InlineData("380:780:5", "led-blue")]
    public void CieXyz_RawIsProportionalToTheRendersExactXyz(string bands, string light)
    {
        var render = Chart(bands, light: light);
        var (raw, manifest) = Camera(render, "cie-xyz");
        Assert.StartsWith("exact", (string)manifest["simulation"]!["signal_route"]!, StringComparison.Ordinal);
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
                    double q = raw[i * 3 + c] / xyz[c][i];
                    ratio ??= q;
                    worst = Math.Max(worst, Math.Abs(q / ratio.Value - 1));
                }
        output.WriteLine($"cie-xyz raw / exact XYZ at {bands} under {light}: largest relative deviation {worst:E3}");
        Assert.True(worst <= 1e-5, $"cie-xyz raw / exact XYZ varies by {worst:E3} relative at {bands} under {light}");

        var white = SpectrumLibrary.Resolve("D65");
        var refWhite = Cie015.White(white);
        double de = 0;
        foreach (var p in scene.Patches)
        {
            int i = p.Pixels[p.Pixels.Length / 2];
            var reference = Cie015.Of(ColorChecker.Patch(p.Number), [(SpectrumLibrary.Resolve(light), 1)], white);
            de = Math.Max(de, DeltaE2000.Between(Lab.FromXyz(new Xyz(xyz[0][i], xyz[1][i], xyz[2][i]), refWhite),
                Lab.FromXyz(reference, refWhite)));
        }
        output.WriteLine($"render's XYZ vs the CIE 1 nm summation at {bands} under {light}: max ΔE00 {de:F5}");
        Assert.True(de <= 0.01, $"render's XYZ vs the CIE 1 nm summation at {bands} under {light}: max ΔE00 {de:F4}");
    }

    [Theory]
    [InlineData("nikon-d5100")]
    [InlineData("wheel-6")]
    [InlineData("mosaic-16")]
    public void Signals_AtFiveBands_EqualThoseAt401Bands(string sensor)
    {
        var (coarse, _) = Camera(Chart("380:780:5"), sensor);
        var (fine, _) = Camera(Chart("380:780:401"), sensor);
        Assert.Equal(fine.Length, coarse.Length);
        double peak = fine.Max(), worst = 0;
        Assert.True(peak > 0 && peak < 4095, $"peak {peak} DN: the test wants an unclipped, lit chart");
        for (int i = 0; i < fine.Length; i++)
            if (fine[i] > 1e-3 * peak) worst = Math.Max(worst, Math.Abs(coarse[i] / fine[i] - 1));
        output.WriteLine($"{sensor}: 5 bands vs 401 bands, largest relative difference {worst:E3}");
        Assert.True(worst <= 1e-5, $"{sensor}: 5 bands vs 401 bands differ by {worst:E3} relative");
    }

    /// <summary>
    /// Issue 26: a fluorescent paper's diffuse term is its re-radiation matrix applied to the light, so the exact route's
    /// channels integrate the shifted emission too. The optically brightened paper beside a plain white under D50 with UV
    /// (bands from 300 nm): cie-xyz's raw is proportional to the render's exact XYZ (the colour of the matrix's emission
    /// cells, CIE 015) on both papers — without the shift the brightened paper's Z would fall ~10 % short — and the
    /// camera's colour correction trains on the ColorChecker beyond its 380–780 nm tables.
    /// </summary>
    [Fact]
    public void CieXyz_OnAFluorescentPaper_IsProportionalToTheRendersExactXyz()
    {
        var dir = Reference.TempDir();
        var render = Path.Combine(dir, "render");
        var (code, _, err) = CliRunner.Run("render", Repo.PathOf("scenes", "fluorescence-paper-m1.json"), "-o", render,
            "--width", "60", "--height", "30", "--formats", "exr,aov", "--quiet");
        Assert.True(code == 0, err);
        var (raw, manifest) = Camera(render, "cie-xyz");
        Assert.StartsWith("exact", (string)manifest["simulation"]!["signal_route"]!, StringComparison.Ordinal);
        var exr = ExrReader.Read(Path.Combine(render, "spectral.exr"));
        var xyz = new[] { exr.OtherChannels["X"], exr.OtherChannels["Y"], exr.OtherChannels["Z"] };
        // The left quad is the brightened paper, the right one the plain white: one pixel of each sets the scale apart.
        int left = 15 * 60 + 15, right = 15 * 60 + 45;
        Assert.True(xyz[2][left] > 1.03 * xyz[2][right] * xyz[1][left] / xyz[1][right],
            "the brightened paper should be bluer than the plain white");
        double ratio = raw[right * 3 + 1] / xyz[1][right], worst = 0;
        int lit = 0;
        for (int i = 0; i < 60 * 30; i++)
        {
            if (!(xyz[1][i] > 0)) continue;
            lit++;
            for (int c = 0; c < 3; c++) worst = Math.Max(worst, Math.Abs(raw[i * 3 + c] / xyz[c][i] / ratio - 1));
        }
        output.WriteLine($"fluorescent paper: cie-xyz raw / exact XYZ over {lit} pixels, largest relative deviation {worst:E3}");
        Assert.True(lit > 500, $"only {lit} lit pixels");
        Assert.True(worst <= 1e-5, $"cie-xyz raw / exact XYZ varies by {worst:E3} relative on the fluorescent paper scene");
    }

    /// <summary>
    /// Every preset, noise off: a patch pixel's DN − black against K·t·A·ff·πT/(1+4N²)·Σ ρ(λ)·E(λ)·η_c(λ)·λ/(hc), the sum
    /// CIE 015's at 1 nm (trapezoidal form, <see cref="Cie015.Sum"/>) of linear interpolants of the data tables (ρ: Ohta,
    /// E: D65), here.
    /// </summary>
    [Fact]
    public void NoiseFreeSignals_MatchTheCie1nmSum_ForEveryChannelOfEveryPreset()
    {
        var render = Chart("380:780:20");
        var scene = CameraScene.Open(render);
        var d65 = Table("illuminants.csv", "D65");
        var header = File.ReadLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "colorchecker-ohta.csv")).First().Split(',');
        const double h = 6.62607015e-34, c0 = 299792458;
        foreach (var name in SensorPresets.Names)
        {
            var sensor = SensorPresets.Get(name);
            var (raw, manifest) = Camera(render, name);
            var exposures = manifest["sensor"]!["channels"]!.AsArray().Select(ch => (double)ch!["exposure_s"]!).ToArray();
            double worst = 0;
            foreach (var p in scene.Patches)
            {
                var rho = Table("colorchecker-ohta.csv", header[p.Number]);
                int i = p.Pixels[p.Pixels.Length / 2], x = i % Width, y = i / Width;
                for (int c = 0; c < sensor.ChannelCount; c++)
                {
                    if (sensor.Arrangement == Arrangement.Mosaic && sensor.ChannelAt(x, y) != c) continue;
                    var ch = sensor.Channels[c];
                    var qe = (ch.QuantumEfficiency.Wavelengths.ToArray(), ch.QuantumEfficiency.Values.ToArray());
                    bool zero = ch.QuantumEfficiency.Extrapolation == SpectralRenderer.Spectra.Extrapolation.Zero;
                    // Over the wavelengths the tables give: a zero-extrapolated sensitivity's own range within 380–780 nm.
                    int first = zero ? Math.Max(380, (int)Math.Ceiling(qe.Item1[0])) : 380;
                    int last = zero ? Math.Min(780, (int)Math.Floor(qe.Item1[^1])) : 780;
                    double integral = Cie015.Sum(wl =>
                    {
                        double eta = ch.PerEnergy ? Lerp(qe, wl) * 555 / wl : Lerp(qe, wl);
                        return Lerp(rho, wl) * Lerp(d65, wl) * eta * wl * 1e-9 / (h * c0);
                    }, first, last);
                    double expected = sensor.SystemGain * exposures[c] * sensor.Etendue * integral;
                    double dn = sensor.Arrangement == Arrangement.Mosaic ? raw[i] : raw[i * sensor.ChannelCount + c];
                    worst = Math.Max(worst, Math.Abs((dn - sensor.BlackLevel) / expected - 1));
                }
            }
            output.WriteLine($"{name}: noise-free signal vs the 1 nm sum, largest relative difference {worst:E3}");
            Assert.True(worst <= 1e-4, $"{name}: noise-free signal vs the 1 nm sum: {worst:E3} relative");
        }
    }

    /// <summary>
    /// Issue 24's radiometry bar: the chart in physical radiometry (a white diffuser returns intensity·E/π) at intensities
    /// 0.01, 1 and 100 gives, with noise off, the ΔE00 of every patch in patches.csv within 0.01 and the Wiener recovery's
    /// ColorChecker RMSE (rawtoaces-190 training, 400–700 nm) within 1e-4 of the same chart in the paper's radiometry.
    /// </summary>
    [Fact]
    public void PhysicalRadiometry_AtAnyIntensity_ColourAndRecoveryEqualThePapers()
    {
        var (paperDe, paperRmse) = ColourAndRecovery(Chart("380:780:20", formats: "npy,aov"));
        Assert.True(paperDe.Average() < 2 && paperRmse < 0.05, $"paper radiometry: mean ΔE00 {paperDe.Average()}, RMSE {paperRmse}");
        foreach (var intensity in new[] { 0.01, 1, 100 })
        {
            var (de, rmse) = ColourAndRecovery(Chart("380:780:20", "physical", intensity, "npy,aov"));
            output.WriteLine($"intensity {intensity}: largest |ΔE00 − paper's| {de.Zip(paperDe, (x, y) => Math.Abs(x - y)).Max():E2} " +
                $"(paper mean {paperDe.Average():F3}), Wiener RMSE {rmse:F6} vs paper {paperRmse:F6}");
            for (int p = 0; p < de.Length; p++)
                Assert.True(Math.Abs(de[p] - paperDe[p]) <= 0.01,
                    $"intensity {intensity}, patch {p + 1}: ΔE00 {de[p]} vs paper {paperDe[p]}");
            Assert.True(Math.Abs(rmse - paperRmse) <= 1e-4, $"intensity {intensity}: Wiener RMSE {rmse} vs paper {paperRmse}");
        }
    }

    /// <summary>
    /// Issue 24: recovery calibrated on a white board (§3.4: <c>recover --white-object</c>, here the chart's white patch 19)
    /// works in physical radiometry: at intensities 0.01 and 100 its Wiener ColorChecker RMSE (400–700 nm) is the paper
    /// radiometry's within 1e-4, and the calibration scales the model (its figure differs from the uncalibrated one).
    /// </summary>
    [Fact]
    public void WhiteBoardCalibration_InPhysicalRadiometry_GivesThePapersRecovery()
    {
        var paperRender = Chart("380:780:20", formats: "npy,aov");
        double paper = Wiener(paperRender, "--white-object", "patch-19"), plain = Wiener(paperRender);
        Assert.True(Math.Abs(paper - plain) > 1e-4, $"calibrated {paper} vs uncalibrated {plain}: the calibration did nothing");
        foreach (var intensity in new[] { 0.01, 100 })
        {
            double rmse = Wiener(Chart("380:780:20", "physical", intensity, "npy,aov"), "--white-object", "patch-19");
            output.WriteLine($"white-board calibrated Wiener RMSE: physical at intensity {intensity} {rmse:F6}, paper {paper:F6}");
            Assert.True(Math.Abs(rmse - paper) <= 1e-4, $"intensity {intensity}: calibrated RMSE {rmse} vs paper {paper}");
        }
    }

    /// <summary>wheel-6, noise off, default lens; the Wiener ColorChecker RMSE over 400–700 nm (rawtoaces-190).</summary>
    static double Wiener(string render, params string[] extra)
    {
        var cam = Path.Combine(render, "cam-board");
        if (!Directory.Exists(cam))
        {
            var (c, _, e) = CliRunner.Run("camera", render, "--sensor", "wheel-6", "--noise", "off", "-o", cam);
            Assert.True(c == 0, e);
        }
        var (code, csv, err) = CliRunner.Run(["recover", cam, "--method", "wiener", "--training", "rawtoaces-190", "--range", "400:700",
            "--csv", .. extra]);
        Assert.True(code == 0, err);
        var line = csv.Split('\n').Single(l => l.StartsWith("wiener,colorchecker,", StringComparison.Ordinal)).Split(',');
        return double.Parse(line[3], CultureInfo.InvariantCulture);
    }

    /// <summary>
    /// The command line's integrator decides the route: a scene that names the path integrator rendered with
    /// --integrator whitted (render.json's run.integrator) takes the Whitted exact route (path renders: PathExactSignalsTests).
    /// </summary>
    [Fact]
    public void PathScene_RenderedByWhitted_TakesTheWhittedExactRoute()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, File.ReadAllText(Repo.PathOf("scenes", "path-colorchecker-booth.json")));
        var render = Path.Combine(dir, "render");
        var (code, _, err) =
            CliRunner.Run("render", scene, "-o", render, "--width", "24", "--height", "16", "--spp", "1", "--bands", "380:780:10",
            "--formats", "npy,aov", "--quiet", "--integrator", "whitted");
        Assert.True(code == 0, err);
        Assert.Equal("whitted", (string?)JsonNode.Parse(File.ReadAllText(Path.Combine(render, "render.json")))!["run"]!["integrator"]);
        var cam = Path.Combine(dir, "cam");
        (code, _, err) =
            CliRunner.Run("camera", render, "--sensor", "wheel-6", "--noise", "off", "-o", cam, "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);
        var manifest = JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!;
        string used = (string)manifest["simulation"]!["signal_route"]!;
        Assert.StartsWith("exact: ", used, StringComparison.Ordinal);
    }

    /// <summary>
    /// The band route (--signals bands) sees the render's radiometry too: the chart in physical radiometry at intensities
    /// 0.01, 1 and 100 gives the ΔE00 of every patch within 0.01, and the Wiener recovery's RMSE within 1e-4, of the same
    /// chart in the paper's radiometry on the band route (before, its white was the light's band values: ΔE00 ≈ 20 at
    /// intensity 1, where a white diffuser returns E/π).
    /// </summary>
    [Fact]
    public void BandRoute_PhysicalRadiometry_AtAnyIntensity_ColourAndRecoveryEqualThePapers()
    {
        var (paperDe, paperRmse) = ColourAndRecovery(Chart("380:780:20", formats: "npy,aov"), "--signals", "bands");
        Assert.True(paperDe.Average() < 3 && paperRmse < 0.05,
            $"paper radiometry, band route: mean ΔE00 {paperDe.Average()}, RMSE {paperRmse}");
        foreach (var intensity in new[] { 0.01, 1, 100 })
        {
            var (de, rmse) = ColourAndRecovery(Chart("380:780:20", "physical", intensity, "npy,aov"), "--signals", "bands");
            output.WriteLine(
                $"band route, intensity {intensity}: largest |ΔE00 − paper's| {de.Zip(paperDe, (x, y) => Math.Abs(x - y)).Max():E2} " +
                $"(paper mean {paperDe.Average():F3}), Wiener RMSE {rmse:F6} vs paper {paperRmse:F6}");
            for (int p = 0; p < de.Length; p++)
                Assert.True(Math.Abs(de[p] - paperDe[p]) <= 0.01,
                    $"intensity {intensity}, patch {p + 1}: ΔE00 {de[p]} vs paper {paperDe[p]}");
            Assert.True(Math.Abs(rmse - paperRmse) <= 1e-4, $"intensity {intensity}: Wiener RMSE {rmse} vs paper {paperRmse}");
        }
    }

    static (double[] DeltaE, double Rmse) ColourAndRecovery(string render, params string[] extra)
    {
        var cam = Path.Combine(render, "cam-wheel" + string.Join("", extra));
        var (code, _, err) = CliRunner.Run(["camera", render, "--sensor", "wheel-6", "--noise", "off", "-o", cam, .. extra]);
        Assert.True(code == 0, err);
        var rows = File.ReadAllLines(Path.Combine(cam, "patches.csv"));
        int col = Array.IndexOf(rows[0].Split(','), "dE00");
        var de = rows.Skip(1).Select(r => double.Parse(r.Split(',')[col], CultureInfo.InvariantCulture)).ToArray();
        Assert.Equal(24, de.Length);
        (code, var csv, err) =
            CliRunner.Run("recover", cam, "--method", "wiener", "--training", "rawtoaces-190", "--range", "400:700", "--csv");
        Assert.True(code == 0, err);
        var line = csv.Split('\n').Single(l => l.StartsWith("wiener,colorchecker,", StringComparison.Ordinal)).Split(',');
        return (de, double.Parse(line[3], CultureInfo.InvariantCulture));
    }

    internal static (double[] Wl, double[] V) Table(string file, string column)
    {
        var lines = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, file));
        int col = Array.IndexOf(lines[0].Split(','), column);
        var rows = lines.Skip(1).Where(l => l.Length > 0 && !l.StartsWith('#')).Select(l => l.Split(',')).ToArray();
        return (rows.Select(r => double.Parse(r[0], CultureInfo.InvariantCulture)).ToArray(),
            rows.Select(r => double.Parse(r[col], CultureInfo.InvariantCulture)).ToArray());
    }

    internal static double Lerp((double[] Wl, double[] V) t, double x)
    {
        if (x <= t.Wl[0]) return t.V[0];
        if (x >= t.Wl[^1]) return t.V[^1];
        int i = Array.BinarySearch(t.Wl, x);
        if (i >= 0) return t.V[i];
        i = ~i - 1;
        return t.V[i] + (x - t.Wl[i]) / (t.Wl[i + 1] - t.Wl[i]) * (t.V[i + 1] - t.V[i]);
    }
}
