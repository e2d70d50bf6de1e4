using System.Globalization;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Sensor;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>`spectral recover` on the §3.1 chart: the issue's RMSE bars, multispectral against RGB, an exactly invertible sensor, white
/// calibration.</summary>
public class RecoveryTests
{
    static string Repo()
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
            if (File.Exists(Path.Combine(d.FullName, "scenes", "paper-3.1-colorchecker-d65.json"))) return d.FullName;
        throw new DirectoryNotFoundException("scenes/");
    }

    /// <summary>The §3.1 chart under D65 at 144 × 96 (patches of about 16 pixels), rendered once for the class.</summary>
    static readonly Lazy<string> Chart = new(() => RenderChart("chart"));

    /// <summary>
    /// The same chart with the band values as products of band means (R_b·E_b, <c>--integration weighted</c>): each band
    /// of the cube is then the band-mean reflectance times the light, the case box channels on the bands invert exactly.
    /// </summary>
    static readonly Lazy<string> ProductChart = new(() => RenderChart("chart-weighted", "--integration", "weighted"));

    static string RenderChart(string name, params string[] extra)
    {
        var dir = Path.Combine(Reference.TempDir(), name);
        var (code, _, err) = CliRunner.Run(["render", Path.Combine(Repo(), "scenes", "paper-3.1-colorchecker-d65.json"), "-o", dir,
            "--width", "144", "--height", "96", "--formats", "npy,aov", "--quiet", .. extra]);
        Assert.True(code == 0, err);
        return dir;
    }

    static Dictionary<(string Method, string Region), (double Rmse, double Gfc, double De)> Recover(string sensor, string noise,
        params string[] extra) =>
        RecoverOn("bands", sensor, noise, extra);

    static Dictionary<(string Method, string Region), (double Rmse, double Gfc, double De)> RecoverOn(string route, string sensor,
        string noise, params string[] extra)
    {
        var cam = Path.Combine(Chart.Value, route == "bands" ? $"camera-{sensor}-{noise}" : $"camera-{sensor}-{noise}-{route}");
        // The band route (--signals bands) unless asked: the figures these bars were set on; the exact route's bar is
        // ExactRoute_… (issue 24). A flat lens (no cos⁴ fall-off, no Airy blur): the bars are on the spectral chain, and the
        // recovery's forward model has no lens shading correction (docs/camera.md).
        var (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", sensor, "--noise", noise, "-o", cam, "--signals", route,
            "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);
        (code, var csv, err) = CliRunner.Run(["recover", cam, "--csv", .. extra]);
        Assert.True(code == 0, err);
        var lines = csv.Trim().Split('\n');
        Assert.Equal("method,region,count,rmse,gfc,dE00_D65,dE00_A,metric_range_nm", lines[0]);
        var inv = CultureInfo.InvariantCulture;
        return lines.Skip(1).Select(l => l.Split(',')).ToDictionary(f => (f[0], f[1]),
            f => (double.Parse(f[3], inv), double.Parse(f[4], inv), double.Parse(f[5], inv)));
    }

    static readonly string[] Methods = ["pinv", "wiener", "linear", "tikhonov", "wiener-local"];

    [Fact]
    public void NoiseOff_Wiener_MeetsTheBars_AndMultispectralBeatsRgbForEveryMethod()
    {
        var range = new[] { "--range", "400:700" };
        var rgb = Recover("nikon-d5100", "off", range);
        var wheel = Recover("wheel-6", "off", range);
        var mosaic = Recover("mosaic-16", "off", range);
        Assert.True(rgb[("wiener", "colorchecker")].Rmse <= 0.05, $"nikon-d5100 {rgb[("wiener", "colorchecker")].Rmse}");
        Assert.True(wheel[("wiener", "colorchecker")].Rmse <= 0.02, $"wheel-6 {wheel[("wiener", "colorchecker")].Rmse}");
        Assert.True(mosaic[("wiener", "colorchecker")].Rmse <= 0.005, $"mosaic-16 {mosaic[("wiener", "colorchecker")].Rmse}");
        var json = System.Text.Json.Nodes.JsonNode.Parse(
            File.ReadAllText(Path.Combine(Chart.Value, "camera-mosaic-16-off", "recovery.json")))!;
        Assert.Equal("bands", (string)json["forward_model"]!);   // a band-route capture keeps the band model
        foreach (var m in Methods)
        {
            Assert.True(wheel[(m, "colorchecker")].Rmse < rgb[(m, "colorchecker")].Rmse, $"{m}: wheel-6 vs RGB");
            Assert.True(mosaic[(m, "colorchecker")].Rmse < rgb[(m, "colorchecker")].Rmse, $"{m}: mosaic-16 vs RGB");
        }
    }

    /// <summary>
    /// Issue 24: on the exact route (a render's default) `recover` inverts a forward model at full spectral resolution (the
    /// training spectra's exact signals, recovered as band means), so mosaic-16's noise-free Wiener ColorChecker RMSE over
    /// 400–700 nm meets the bar 0.005 there too (0.0055 with the band model) and is no worse than the band route's;
    /// recovery.json records which model each route's capture got. Slow (two captures and recoveries, ~2 s): the fast test of
    /// the bar is ForwardModelTests', on the patches' exact signals without a render.
    /// </summary>
    [Fact]
    [Trait("Category", "Slow")]
    public void ExactRoute_MosaicMeetsTheBar_WithTheFullResolutionModel_AndRecordsIt()
    {
        var args = new[] { "--method", "wiener", "--range", "400:700" };
        double exact = RecoverOn("exact", "mosaic-16", "off", args)[("wiener", "colorchecker")].Rmse;
        double bands = RecoverOn("bands", "mosaic-16", "off", args)[("wiener", "colorchecker")].Rmse;
        Assert.True(exact <= 0.005 && exact <= bands, $"mosaic-16 exact route {exact}, band route {bands}");
        foreach (var (route, folder) in new[] { ("exact", "camera-mosaic-16-off-exact"), ("bands", "camera-mosaic-16-off") })
        {
            var json = System.Text.Json.Nodes.JsonNode.Parse(File.ReadAllText(Path.Combine(Chart.Value, folder, "recovery.json")))!;
            Assert.Equal(route, (string)json["forward_model"]!);
            Assert.StartsWith(route + ":", (string)json["forward_model_description"]!, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void NoiseOn_CostsAccuracy_ButTheMosaicStillBeatsRgb()
    {
        var off = Recover("mosaic-16", "off");
        var on = Recover("mosaic-16", "on");
        var rgb = Recover("nikon-d5100", "on");
        // The pseudo-inverse has no prior and amplifies noise through 16 narrow channels; the other methods do not.
        foreach (var m in Methods.Where(m => m != "pinv"))
            Assert.True(on[(m, "colorchecker")].Rmse < rgb[(m, "colorchecker")].Rmse, $"{m}: mosaic-16 vs RGB with noise");
        Assert.True(on[("wiener", "colorchecker")].Rmse >= off[("wiener", "colorchecker")].Rmse - 1e-4);
        // Wiener is the least-squares-optimal linear estimate: with noise it is not worse than the pseudo-inverse.
        Assert.True(on[("wiener", "colorchecker")].Rmse <= on[("pinv", "colorchecker")].Rmse);
    }

    /// <summary>
    /// Over all bands (380–780 nm, where no preset sees above ~720 nm) the locally weighted Wiener estimate beats the
    /// textbook one for every sensor, noise off and on — most for the wheel (0.051 → 0.024, bar 0.02) — and the
    /// multispectral sensors still beat RGB with it. The issue's full-range bars stay unmet (docs/camera.md); the limits
    /// asserted are the figures measured there.
    /// </summary>
    [Fact]
    public void WienerLocal_BeatsWiener_OverAllBands_NoiseOffAndOn()
    {
        var atMost = new Dictionary<string, double> { ["nikon-d5100"] = 0.065, ["wheel-6"] = 0.026, ["mosaic-16"] = 0.016 };
        foreach (var noise in new[] { "off", "on" })
        {
            var score = atMost.Keys.ToDictionary(s => s, s => Recover(s, noise, "--method", "wiener,wiener-local"));
            foreach (var (sensor, limit) in atMost)
            {
                double wiener = score[sensor][("wiener", "colorchecker")].Rmse,
                    local = score[sensor][("wiener-local", "colorchecker")].Rmse;
                Assert.True(local < wiener, $"{sensor}, noise {noise}: wiener-local {local} vs wiener {wiener}");
                if (noise == "off") Assert.True(local <= limit, $"{sensor}: wiener-local {local}");
            }
            Assert.True(score["wheel-6"][("wiener-local", "colorchecker")].Rmse < score["nikon-d5100"][("wiener-local", "colorchecker")]
                .Rmse);
            Assert.True(score["mosaic-16"][("wiener-local", "colorchecker")].Rmse < score["nikon-d5100"][("wiener-local", "colorchecker")]
                .Rmse);
        }
    }

    [Fact]
    public void BoxFiltersOnTheBands_AreInvertedExactly_ByPinvAndWiener()
    {
        // 20 box channels, one per band of 380:780:20, every channel at every pixel: A is diagonal and invertible, so the
        // pseudo-inverse returns every band of every reflectance exactly (an analytic case, whatever the prior).
        var sensor = Path.Combine(ProductChart.Value, "boxes.json");
        var channels = string.Join(",\n",
            Enumerable.Range(0, 20).Select(b => $$"""{ "name": "B{{b:00}}", "box": [{{380 + 20 * b}}, {{400 + 20 * b}}] }"""));
        File.WriteAllText(sensor, $$"""{ "name": "boxes", "arrangement": "full", "channels": [ {{channels}} ] }""");
        var cam = Path.Combine(ProductChart.Value, "camera-boxes");
        // A cube of band products read as values (--signals bands), the case of a cube that is not a render.
        var (code, _, err) =
            CliRunner.Run("camera", ProductChart.Value, "--sensor", sensor, "--noise", "off", "-o", cam, "--signals", "bands",
            "--off-axis", "none", "--psf", "none");   // each pixel its own band products: no lens
        Assert.True(code == 0, err);
        (code, var csv, err) = CliRunner.Run("recover", cam, "--method", "pinv,wiener", "--csv");
        Assert.True(code == 0, err);
        foreach (var line in csv.Trim().Split('\n').Skip(1).Where(l => l.Contains(",colorchecker,")))
        {
            var f = line.Split(',');
            Assert.True(double.Parse(f[3], CultureInfo.InvariantCulture) < 1e-5, line);
            Assert.True(double.Parse(f[5], CultureInfo.InvariantCulture) < 1e-3, line);
        }
    }

    [Fact]
    public void WhiteBoard_Calibration_FixesTheLightLevel_AndShadowsStayAScale()
    {
        // The ball and board of §3.4 under a point light: the board is not lit head-on, so the uncalibrated forward
        // model (a surface lit like the white) is off by the board's irradiance; calibrating on the board removes it.
        var root = Reference.TempDir();
        File.WriteAllText(Path.Combine(root, "scene.json"), AnalysisFolder.Scene);
        var dir = Path.Combine(root, "out");
        var (rc, _, rerr) = CliRunner.Run("render", Path.Combine(root, "scene.json"), "-o", dir, "--width", "96", "--height", "72",
            "--quiet", "--formats", "npy,aov");
        Assert.True(rc == 0, rerr);
        var cam = Path.Combine(dir, "cam");
        // no demosaicking across the ball's edge
        var (code, _, err) = CliRunner.Run("camera", dir, "--sensor", "wheel-6", "--noise", "off", "-o", cam);
        Assert.True(code == 0, err);
        var inv = CultureInfo.InvariantCulture;
        Dictionary<string, (double Rmse, double Gfc)> Rmse(params string[] extra)
        {
            var (c, csv, e) = CliRunner.Run(["recover", cam, "--method", "wiener", "--range", "400:700", "--csv", .. extra]);
            Assert.True(c == 0, e);
            return csv.Trim().Split('\n').Skip(1).Select(l => l.Split(','))
                .ToDictionary(f => f[1], f => (double.Parse(f[3], inv), double.Parse(f[4], inv)));
        }
        var plain = Rmse();
        var calibrated = Rmse("--white-object", "board");
        Assert.Contains("lit", calibrated.Keys);
        Assert.Contains("shadow", calibrated.Keys);
        Assert.True(calibrated["lit"].Rmse < plain["lit"].Rmse, $"lit: calibrated {calibrated["lit"]} vs plain {plain["lit"]}");
        // The ball's lit pixels see other irradiances than the board (n·l, distance): a per-pixel scale, so the shape is
        // nearly right (GFC) while the level is not; shadows (the flat ambient light only, on ball and board) are far off.
        Assert.True(calibrated["lit"].Gfc > 0.98, $"lit GFC {calibrated["lit"].Gfc}");
        Assert.True(calibrated["shadow"].Rmse > 3 * calibrated["lit"].Rmse);
        Assert.True(File.Exists(Path.Combine(cam, "recovery-wiener.svg")));
        Assert.True(File.Exists(Path.Combine(cam, "recovered-wiener.npy")));
        // A render's capture takes the exact route, and recover the forward model at full resolution for it.
        var json = System.Text.Json.Nodes.JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "recovery.json")))!;
        Assert.Equal("exact", (string)json["forward_model"]!);
        Assert.Equal("wiener", (string)json["methods"]![0]!);
    }

    [Fact]
    public void ReportComparison_HasEverySensorNoiseAndMethod_AndAgreesWithTheCommand()
    {
        var rows = SpectralRenderer.Analysis.Recovery.RecoveryComparison.Rows(Chart.Value);
        Assert.Equal(3 * 2 * 5, rows.Count);
        var mosaic = Recover("mosaic-16", "off", "--range", "400:700");
        var row = rows.Single(r => r.Sensor == "mosaic-16" && !r.Noise && r.Method == "wiener");
        // The report recovers each patch's mean signal; for the affine Wiener that is the command's mean of the pixels' estimates.
        Assert.Equal(mosaic[("wiener", "colorchecker")].Rmse, row.Rmse400To700, 6);
        Assert.Contains("<table>", SpectralRenderer.Analysis.Recovery.RecoveryComparison.HtmlSection(Chart.Value));
    }

    /// <summary>
    /// Issue 24: the report's comparison (`spectral experiments`) on the exact route — the signals each channel's full-resolution
    /// integral per eq. 2 term, recovered with the model at full resolution — is what `camera` (exact route, flat lens) and
    /// `recover` give for the same capture, and not the band route's figure. Slow (~25 s on a loaded machine: 30 estimators
    /// and three exact-route captures beside the command's two).
    /// </summary>
    [Fact]
    [Trait("Category", "Slow")]
    public void ReportComparison_OnTheExactRoute_AgreesWithTheCommand()
    {
        var rows = SpectralRenderer.Analysis.Recovery.RecoveryComparison.Rows(Chart.Value,
            SpectralRenderer.Relighting.ExactChannelSignals.Input);
        Assert.Equal(3 * 2 * 5, rows.Count);
        var args = new[] { "--method", "wiener", "--range", "400:700" };
        double exact = RecoverOn("exact", "mosaic-16", "off", args)[("wiener", "colorchecker")].Rmse;
        double bands = RecoverOn("bands", "mosaic-16", "off", args)[("wiener", "colorchecker")].Rmse;
        var row = rows.Single(r => r.Sensor == "mosaic-16" && !r.Noise && r.Method == "wiener");
        Assert.Equal(exact, row.Rmse400To700, 6);
        Assert.True(Math.Abs(exact - bands) > 1e-5,
            $"exact route {exact} vs band route {bands}: the routes differ, so the report took the exact one");
    }

    [Fact]
    public void RecoverySvg_DrawsEachRecoveredCurveInItsTruthsColour_SolidAgainstDashed()
    {
        Recover("nikon-d5100", "off", "--method", "wiener");
        System.Xml.Linq.XNamespace ns = "http://www.w3.org/2000/svg";
        var svg = System.Xml.Linq.XDocument.Load(Path.Combine(Chart.Value, "camera-nikon-d5100-off", "recovery-wiener.svg"));
        var lines = svg.Descendants(ns + "polyline").Select(p => (Title: p.Element(ns + "title")!.Value,
            Stroke: p.Attribute("stroke")!.Value, Dashed: p.Attribute("stroke-dasharray") is not null)).ToList();
        var truths = lines.Where(l => l.Title.StartsWith("truth: ", StringComparison.Ordinal)).ToList();
        Assert.True(truths.Count >= 2, $"{truths.Count} truth curves");
        Assert.Equal(lines.Count, 2 * truths.Count);
        foreach (var t in truths)
        {
            var recovered = lines.Single(l => l.Title == t.Title["truth: ".Length..]);
            Assert.True(t.Dashed && !recovered.Dashed, t.Title);
            Assert.Equal(t.Stroke, recovered.Stroke);
        }
        // Different curves in different colours, as far as the palette goes.
        Assert.Equal(Math.Min(truths.Count, SpectralRenderer.Imaging.SvgPlot.Palette.Length),
            truths.Select(t => t.Stroke).Distinct().Count());
    }

    [Theory]
    [InlineData("nikon-d5100")]
    [InlineData("mosaic-16")]
    public void PatchMeanSignals_OfTheAffineMethods_EqualTheMeanOfEveryPixelsEstimate_WithNoise(string sensor)
    {
        // Two ways to the ColorChecker figures: every patch pixel recovered and its estimates averaged (RecoveryEvaluation.Run),
        // and one estimate of each patch's mean signal. For an affine estimator r̂ = G·s + h they are the same number.
        var scene = CameraScene.Open(Chart.Value);
        var training = TrainingSet.Load("rawtoaces-190", scene.Grid);
        var capture = CameraCapture.Simulate(scene, SensorPresets.Get(sensor),
            new SimulationOptions { Noise = true, Seed = 3 });
        foreach (var method in new[] { RecoveryMethod.Pinv, RecoveryMethod.Wiener, RecoveryMethod.Linear, RecoveryMethod.Tikhonov })
        {
            var perPixel = RecoveryEvaluation.Run(capture, method, training, regions: false);
            var row = perPixel.Rows.Single(r => r.Region == "colorchecker");
            var (all, visible, de) = RecoveryEvaluation.PatchMeanSignals(capture, perPixel.Estimator, (400, 700));
            Assert.True(Math.Abs(all - row.Rmse) <= 1e-6 * Math.Max(1, row.Rmse), $"{sensor} {method}: RMSE {all} against {row.Rmse}");
            Assert.True(Math.Abs(de - row.DeltaE00D65) <= 1e-4, $"{sensor} {method}: ΔE00 {de} against {row.DeltaE00D65}");
            double pixelsVisible = RecoveryEvaluation.PatchRmse(scene, perPixel.Reflectance, (400, 700));
            Assert.True(Math.Abs(visible - pixelsVisible) <= 1e-6, $"{sensor} {method}: 400–700 nm RMSE {visible} against {pixelsVisible}");
        }
    }

    [Fact]
    public void BadMethodAndTraining_AreOneLineErrors()
    {
        var cam = Path.Combine(Chart.Value, "camera-bad");
        var (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", "wheel-6", "-o", cam);
        Assert.True(code == 0, err);
        (code, _, err) = CliRunner.Run("recover", cam, "--method", "wienr");
        Assert.Equal(2, code);
        Assert.Contains("did you mean 'wiener'", err);
        (code, _, err) = CliRunner.Run("recover", cam, "--training", "rawtoaces-19");
        Assert.Equal(2, code);
        Assert.Contains("did you mean", err);
        (code, _, err) = CliRunner.Run("recover", Chart.Value);
        Assert.Equal(2, code);
        Assert.Contains("camera.json", err);
    }
}
