using SpectralRenderer.Color;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// One ColorChecker patch through the camera: the processed (corrected) colour against the patch's exact colour
/// (1 nm CIE XYZ under the scene light, white Y = 1 — exact for a chart lit like the white, as in §3.1), and per
/// channel the raw signal-to-noise ratio over the patch's unclipped sites (below the full well and white, above 0 DN), SNR = mean(DN −
/// black) / std(DN), in dB (20 log10); NaN when fewer than two sites are unclipped.
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
                double mean = n > 0 ? sum / n : 0, variance = n > 1 ? Math.Max(0, (sum2 - sum * sum / n) / (n - 1)) : 0;
                snr[c] = n < 2
                    ? double.NaN
                    : variance > 0
                    ? 20 * Math.Log10(Math.Max(mean, 1e-300) / Math.Sqrt(variance))
                    : double.PositiveInfinity;
            }
            rows.Add(new PatchMetrics(p.Number, p.Object, p.Pixels.Length, cam, exact, de, snr));
        }
        return rows;
    }
}
