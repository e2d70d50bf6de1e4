using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>Issue 24's honest reports: clipping warned with its share, a monochrome image neutral, the real peak QE, units from the
/// radiometry.</summary>
public class HonestReportTests
{
    static readonly Lazy<string> Chart = new(() => ExactSignalsTests.Chart("380:780:20"));

    [Fact]
    public void Overexposure_PrintsTheClippedShare_AndTheHint_AndSnrLeavesClippedSitesOut()
    {
        var cam = Path.Combine(Chart.Value, "cam-over");
        var (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", "nikon-d5100", "--exposure", "0.5", "-o", cam);
        Assert.True(code == 0, err);
        var (_, dn) = NpyReader.Read(File.OpenRead(Path.Combine(cam, "raw.npy")));
        // At least the sites at the 12-bit white level are clipped (the full well, 10⁴ e⁻ × 0.4095 DN/e⁻, is at white too).
        double atWhite = dn.Count(v => v >= 4095) / (double)dn.Length;
        Assert.True(atWhite > 0.01, $"the test wants more than 1 % clipped, got {atWhite}");
        var line = err.Split('\n').Single(l => l.StartsWith("warning:", StringComparison.Ordinal));
        var manifest = (JsonObject)JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!;
        double clipped = (double)manifest["simulation"]!["clipped_at_white_fraction"]!;
        Assert.InRange(clipped, atWhite, 1.0);
        Assert.Contains(string.Create(CultureInfo.InvariantCulture, $"{clipped * 100:0.##} % of photosites clipped"), line);
        Assert.Contains("--exposure auto", line);
        // A patch clipped in every site has no SNR (empty), not the 64 dB of 4095 DN over the read noise of a full well.
        var rows = File.ReadAllLines(Path.Combine(cam, "patches.csv"));
        var white = rows.Single(r => r.StartsWith("19,", StringComparison.Ordinal)).Split(',');
        Assert.All(white[^3..], v => Assert.Equal("", v));

        var auto = Path.Combine(Chart.Value, "cam-auto");
        (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", "nikon-d5100", "--noise", "off", "-o", auto);
        Assert.True(code == 0, err);
        Assert.DoesNotContain("warning:", err);
    }

    [Fact]
    public void MonochromeSensor_ProcessedGreyIsNeutral()
    {
        var sensor = Path.Combine(Chart.Value, "mono.json");
        File.WriteAllText(sensor, """{ "name": "mono", "arrangement": "full", "channels": [ { "name": "L", "box": [400, 700] } ] }""");
        var cam = Path.Combine(Chart.Value, "cam-mono");
        var (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", sensor, "--noise", "off", "-o", cam);
        Assert.True(code == 0, err);
        var rows = File.ReadAllLines(Path.Combine(cam, "patches.csv"));
        var head = rows[0].Split(',');
        // The D65 white from the CIE tables at 1 nm here (Y = 1), and CIELAB (CIE 015) of the grey patches' camera XYZ.
        var white = WhiteXyz();
        foreach (var row in rows.Skip(1).Select(r => r.Split(','))
            .Where(f => int.Parse(f[0], CultureInfo.InvariantCulture) is >= 19 and <= 24))
        {
            double X = D(row, head, "camera_X"), Y = D(row, head, "camera_Y"), Z = D(row, head, "camera_Z");
            static double F(double t) => t > 216.0 / 24389 ? Math.Cbrt(t) : (24389.0 / 27 * t + 16) / 116;
            double a = 500 * (F(X / white[0]) - F(Y / white[1])), b = 200 * (F(Y / white[1]) - F(Z / white[2]));
            Assert.True(Math.Abs(a) <= 0.5 && Math.Abs(b) <= 0.5, $"patch {row[0]}: a* {a}, b* {b}");
        }
        // processed.png itself: the grey patches' centre pixels, sRGB decoded (IEC 61966-2-1: its curve, its RGB → XYZ matrix
        // and D65 white, written out here) to CIELAB, have a* and b* within 0.5.
        var png = PngReader.Read(Path.Combine(cam, "processed.png"));
        double[,] m = { { 0.4124, 0.3576, 0.1805 }, { 0.2126, 0.7152, 0.0722 }, { 0.0193, 0.1192, 0.9505 } };
        static double Linear(double v) => v <= 0.04045 ? v / 12.92 : Math.Pow((v + 0.055) / 1.055, 2.4);
        static double Fl(double t) => t > 216.0 / 24389 ? Math.Cbrt(t) : (24389.0 / 27 * t + 16) / 116;
        double[] Xyz(double[] rgb) => Enumerable.Range(0, 3).Select(r => m[r, 0] * rgb[0] + m[r, 1] * rgb[1] + m[r, 2] * rgb[2]).ToArray();
        var d65 = Xyz([1, 1, 1]);
        foreach (var p in CameraScene.Open(Chart.Value).Patches.Where(p => p.Number is >= 19 and <= 23))
        {
            int i = p.Pixels[p.Pixels.Length / 2] * png.Channels;
            var xyz = Xyz(Enumerable.Range(0, 3).Select(c => Linear(png.Samples[i + c] / 255.0)).ToArray());
            double a = 500 * (Fl(xyz[0] / d65[0]) - Fl(xyz[1] / d65[1])), b = 200 * (Fl(xyz[1] / d65[1]) - Fl(xyz[2] / d65[2]));
            Assert.True(Math.Abs(a) <= 0.5 && Math.Abs(b) <= 0.5, $"processed.png, patch {p.Number}: a* {a}, b* {b}");
        }
    }

    [Fact]
    public void CameraJson_StatesTheDnScale_AndThePeakQeTheChannelsUse()
    {
        var cam = Path.Combine(Chart.Value, "cam-xyz-json");
        var (code, _, err) = CliRunner.Run("camera", Chart.Value, "--sensor", "cie-xyz", "--noise", "off", "-o", cam);
        Assert.True(code == 0, err);
        var m = (JsonObject)JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!;
        Assert.Contains("2^bits", (string)m["sensor"]!["dn_scale"]!);
        // η = CMF·555 nm/λ × one factor that puts the highest table peak (z̄) at SensorPresets.DefaultPeakQe: its peak from the CIE table,
        // here.
        var lines = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "cie1931-2deg-cmf.csv"));
        var cols = lines[0].Split(',');
        var channels = m["sensor"]!["channels"]!.AsArray();
        var rows = lines.Skip(1).Where(l => l.Length > 0)
            .Select(l => l.Split(',').Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray()).ToArray();
        double scale = SpectralRenderer.Sensor.SensorPresets.DefaultPeakQe / rows.Max(r => Math.Max(r[1], Math.Max(r[2], r[3])));
        foreach (var (name, col) in new[] { ("X", "xbar"), ("Y", "ybar"), ("Z", "zbar") })
        {
            int j = Array.IndexOf(cols, col);
            double peak = rows.Max(r => r[j] * scale * 555 / r[0]);
            var ch = channels.Single(c => (string)c!["name"]! == name)!;
            Assert.Equal(peak, (double)ch["peak_qe"]!, 9);
        }
    }

    [Fact]
    public void Probe_OfAPhysicalRender_SaysItsUnits()
    {
        var render = ExactSignalsTests.Chart("380:780:5", "physical", 1, "npy");
        var (code, stdout, err) = CliRunner.Run("probe", render, "--pixel", "45,30");
        Assert.True(code == 0, err);
        Assert.Contains("W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry", stdout);
        Assert.DoesNotContain("relative", stdout);
        Assert.Contains("physical radiometry", File.ReadAllText(Path.Combine(render, "probe.svg")));
    }

    [Fact]
    public void SnrDb_IsTwentyLog10OfMeanOverSampleDeviation_AndMinusInfinityWithoutSignal()
    {
        // Hand-computed: {1, 2, 3} has mean 2 and sample deviation 1 → 20 log10 2; {4, 4.5} mean 4.25, s = 0.5/√2.
        static double Of(params double[] v) => CameraPatchMetrics.SnrDb(v.Sum(), v.Sum(x => x * x), v.Length);
        Assert.Equal(20 * Math.Log10(2), Of(1, 2, 3), 12);
        Assert.Equal(20 * Math.Log10(4.25 / (0.5 / Math.Sqrt(2))), Of(4, 4.5), 12);
        Assert.Equal(20 * Math.Log10(0.5), Of(-0.5, 0.5, 1.5), 12);   // mean 0.5 below σ = 1: a true SNR under 1 (−6 dB)
        Assert.Equal(double.NegativeInfinity, Of(-1, 0, 1));           // mean 0: no signal above black
        Assert.Equal(double.NegativeInfinity, Of(-3, -2, -1.5));       // a shaded patch whose sites read below black
        Assert.Equal(double.PositiveInfinity, Of(3, 3));
        Assert.True(double.IsNaN(Of(5)));
    }

    [Fact]
    public void Camera_OnPatchesWithoutSignal_PrintsADash_NotANegativeThousandsOfDb()
    {
        // A black level of 64 DN and an exposure of 0.11 ns (~1/20000 of the auto exposure, 2.4 µs): every patch's expected
        // signal is ~0.15 DN, so its sites read black ± read noise and the mean of DN − black is ≤ 0 for some patches (SNR 0).
        var sensor = Path.Combine(Chart.Value, "black64.json");
        File.WriteAllText(sensor, """{ "preset": "nikon-d5100", "name": "black64", "black_level_dn": 64 }""");
        var cam = Path.Combine(Chart.Value, "cam-black64");
        var (code, stdout, err) = CliRunner.Run("camera", Chart.Value, "--sensor", sensor, "--exposure", "1.1e-10", "-o", cam);
        Assert.True(code == 0, err);
        var rows = File.ReadAllLines(Path.Combine(cam, "patches.csv")).Skip(1).Select(r => r.Split(',')).ToList();
        var snr = rows.SelectMany(r => r[^3..]).ToList();
        Assert.Contains("-inf", snr);
        // A positive mean of whole DN over n sites is at least 1/n DN and σ < 4096 DN, so a finite SNR is above −200 dB
        // (20 log10 1/(4096 n) for n < 10⁶): −6000 dB (the logarithm of a clamped 1e-300) cannot appear.
        Assert.All(snr, v => Assert.True(v == "-inf" || double.Parse(v, CultureInfo.InvariantCulture) > -200, v));
        var table = stdout.Split('\n').Where(l => l.Length > 5 && int.TryParse(l[..5], out _)).ToList();
        Assert.Equal(rows.Count, table.Count);
        for (int i = 0; i < rows.Count; i++)
        {
            var printed = table[i].Split(' ', StringSplitOptions.RemoveEmptyEntries)[^3..];
            var csv = rows[i][^3..];
            for (int c = 0; c < 3; c++)
                Assert.Equal(csv[c] == "-inf"
                    ? "—"
                    : double.Parse(csv[c], CultureInfo.InvariantCulture).ToString("F1", CultureInfo.InvariantCulture),
                    printed[c]);
        }
    }

    static double D(string[] row, string[] head, string column) =>
        double.Parse(row[Array.IndexOf(head, column)], CultureInfo.InvariantCulture);

    static double[] WhiteXyz()
    {
        var cmf = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "cie1931-2deg-cmf.csv"));
        var ill = File.ReadAllLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "illuminants.csv"));
        int d65 = Array.IndexOf(ill[0].Split(','), "D65");
        var e = ill.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(','))
            .ToDictionary(f => double.Parse(f[0], CultureInfo.InvariantCulture), f => double.Parse(f[d65], CultureInfo.InvariantCulture));
        var xyz = new double[3];
        foreach (var f in cmf.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')))
        {
            double wl = double.Parse(f[0], CultureInfo.InvariantCulture);
            if (wl < 380 || wl > 780 || !e.TryGetValue(wl, out var ev)) continue;
            for (int k = 0; k < 3; k++) xyz[k] += double.Parse(f[k + 1], CultureInfo.InvariantCulture) * ev;
        }
        return [xyz[0] / xyz[1], 1, xyz[2] / xyz[1]];
    }
}
