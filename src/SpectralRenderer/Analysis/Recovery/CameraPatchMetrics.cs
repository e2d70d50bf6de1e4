using SpectralRenderer.Color;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// One ColorChecker patch through the camera: the processed (corrected) colour against the patch's exact colour
/// (1 nm CIE XYZ under the scene light, white Y = 1 — exact for a chart lit like the white, as in §3.1), and per
/// channel the raw signal-to-noise ratio over the patch's unclipped sites (below the full well and white, above 0 DN), SNR = mean(DN −
/// black) / std(DN), in dB (20 log10; <see cref="CameraPatchMetrics.SnrDb"/>): −∞ when the mean signal is not above the black level
/// (SNR 0: no signal, e.g. a shaded object), +∞ when the sites do not vary, NaN when fewer than two sites are unclipped.
/// </summary>
public sealed record PatchMetrics(int Patch, string Object, int Pixels, Xyz Camera, Xyz Exact, double DeltaE00, double[] SnrDb);

public static class CameraPatchMetrics
{
    public static List<PatchMetrics> Compute(CameraScene scene, RawFrame raw, ProcessedImage image, ColourCorrection colour)
    {
        var sensor = raw.Sensor;
        var rows = new List<PatchMetrics>();
        foreach (var p in scene.Patches)
        {
            double x = 0, y = 0, z = 0;
            foreach (int i in p.Pixels) { x += image.Xyz[i].X; y += image.Xyz[i].Y; z += image.Xyz[i].Z; }
            var cam = new Xyz(x / p.Pixels.Length, y / p.Pixels.Length, z / p.Pixels.Length);
            var exact = colour.Targets[p.Number - 1];
            double de = DeltaE2000.Between(Lab.FromXyz(cam, colour.White), Lab.FromXyz(exact, colour.White));
            var snr = new double[sensor.ChannelCount];
            for (int c = 0; c < sensor.ChannelCount; c++)
            {
                double sum = 0, sum2 = 0;
                int n = 0;
                foreach (int i in p.Pixels)
                {
                    int px = i % raw.Width, py = i / raw.Width;
                    double v;
                    int site = sensor.Arrangement == Arrangement.Mosaic ? i : i * raw.Planes + c;
                    if (sensor.Arrangement == Arrangement.Mosaic && sensor.ChannelAt(px, py) != c) continue;
                    v = raw.Dn[site];
                    if (raw.Clipped(site) || v <= 0) continue;   // clipped: its noise is not the sensor's
                    sum += v - sensor.BlackLevel; sum2 += (v - sensor.BlackLevel) * (v - sensor.BlackLevel); n++;
                }
                snr[c] = SnrDb(sum, sum2, n);
            }
            rows.Add(new PatchMetrics(p.Number, p.Object, p.Pixels.Length, cam, exact, de, snr));
        }
        return rows;
    }

    /// <summary>
    /// 20 log10(mean/s) of n signals (DN − black) from their sum and sum of squares, s the sample standard deviation: NaN for
    /// n &lt; 2; −∞ when the mean is ≤ 0 (no signal above black: SNR 0, not the logarithm of a negative or tiny ratio); +∞ when
    /// s = 0 and the mean is positive.
    /// </summary>
    public static double SnrDb(double sum, double sumOfSquares, int n)
    {
        if (n < 2) return double.NaN;
        double mean = sum / n, variance = Math.Max(0, (sumOfSquares - sum * sum / n) / (n - 1));
        if (!(mean > 0)) return double.NegativeInfinity;
        return variance > 0 ? 20 * Math.Log10(mean / Math.Sqrt(variance)) : double.PositiveInfinity;
    }
}
