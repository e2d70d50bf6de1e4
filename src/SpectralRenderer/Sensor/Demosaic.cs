namespace SpectralRenderer.Sensor;

public enum DemosaicMethod { Bilinear, Malvar }

/// <summary>
/// A mosaic frame (one value per pixel) to every channel at every pixel. Values at a channel's own sites are kept.
/// <list type="bullet">
/// <item><b>Bilinear</b>, for any periodic pattern: each missing value is the tent-weighted mean of the channel's sites
/// within one pattern period, weight (1 − |dx|/P)(1 − |dy|/P) — on a Bayer pattern exactly the classic bilinear
/// interpolation (mean of 2 or 4 neighbours), on a 4 × 4 mosaic bilinear interpolation on the channel's lattice.</item>
/// <item><b>Malvar–He–Cutler</b> (ICASSP 2004), Bayer only: bilinear plus a gradient correction from the Laplacian of
/// the channel measured at the pixel, the paper's eight 5 × 5 kernels (gains α = 1/2, β = 5/8, γ = 3/4).</item>
/// </list>
/// At the borders bilinear uses the sites inside the frame (weights renormalised); Malvar mirrors the frame about the
/// edge pixel (−1 → 1), which keeps the Bayer parity.
/// </summary>
public static class Demosaic
{
    public static float[] Run(SensorModel sensor, ReadOnlySpan<float> mosaic, int width, int height, DemosaicMethod method)
    {
        if (sensor.Arrangement != Arrangement.Mosaic) throw new ArgumentException("only a mosaic frame needs demosaicking");
        var input = mosaic.ToArray();
        var output = new float[width * height * sensor.ChannelCount];
        if (method == DemosaicMethod.Malvar && sensor.IsBayer)
            Parallel.For(0, height, y => MalvarRow(sensor, input, output, width, height, y));
        else
        {
            var taps = BilinearTaps.Of(sensor, width);
            Parallel.For(0, height, y => BilinearRow(sensor, taps, input, output, width, height, y));
        }
        return output;
    }

    /// <summary>
    /// Per phase of the pattern (a pixel's position modulo the period), the neighbours bilinear interpolation reads away
    /// from the borders — their offset in the frame, channel and tent weight, in the order the border loop visits them
    /// — and each channel's total weight, so interior pixels skip the per-neighbour pattern lookups and bounds tests
    /// (the same sums in the same order: the same bits).
    /// </summary>
    sealed class BilinearTaps
    {
        public required int[][] Offset, Channel;
        public required double[][] Weight, Total;

        public static BilinearTaps Of(SensorModel sensor, int w)
        {
            int ph = sensor.Pattern!.GetLength(0), pw = sensor.Pattern.GetLength(1), cc = sensor.ChannelCount, phases = ph * pw;
            var t = new BilinearTaps
            {
                Offset = new int[phases][],
                Channel = new int[phases][],
                Weight = new double[phases][],
                Total = new double[phases][]
            };
            for (int py = 0; py < ph; py++)
                for (int px = 0; px < pw; px++)
                {
                    // An interior pixel of this phase: (px + pw, py + ph) has the period's whole neighbourhood at non-negative sites.
                    int x = px + pw, y = py + ph, own = sensor.ChannelAt(x, y);
                    List<int> offsets = [], channels = [];
                    List<double> weights = [];
                    var total = new double[cc];
                    for (int dy = -ph + 1; dy < ph; dy++)
                        for (int dx = -pw + 1; dx < pw; dx++)
                        {
                            int c = sensor.ChannelAt(x + dx, y + dy);
                            if (c == own) continue;
                            double wt = (1 - Math.Abs(dx) / (double)pw) * (1 - Math.Abs(dy) / (double)ph);
                            offsets.Add(dy * w + dx); channels.Add(c); weights.Add(wt);
                            total[c] += wt;
                        }
                    int k = py * pw + px;
                    t.Offset[k] = [.. offsets]; t.Channel[k] = [.. channels]; t.Weight[k] = [.. weights]; t.Total[k] = total;
                }
            return t;
        }
    }

    static int Mirror(int i, int n) => n == 1 ? 0 : i < 0 ? Math.Min(-i, n - 1) : i >= n ? Math.Max(2 * (n - 1) - i, 0) : i;

    static void BilinearRow(SensorModel sensor, BilinearTaps taps, float[] input, float[] output, int w, int h, int y)
    {
        int ph = sensor.Pattern!.GetLength(0), pw = sensor.Pattern.GetLength(1), cc = sensor.ChannelCount;
        Span<double> sum = stackalloc double[cc];
        Span<double> weight = stackalloc double[cc];
        bool interiorRow = y >= ph - 1 && y <= h - ph;
        for (int x = 0; x < w; x++)
        {
            sum.Clear(); weight.Clear();
            int own = sensor.ChannelAt(x, y);
            if (interiorRow && x >= pw - 1 && x <= w - pw)
            {
                int k = (y % ph) * pw + x % pw, at = y * w + x;
                var offsets = taps.Offset[k]; var channels = taps.Channel[k]; var weights = taps.Weight[k];
                for (int j = 0; j < offsets.Length; j++) sum[channels[j]] += weights[j] * input[at + offsets[j]];
                var total = taps.Total[k];
                for (int c = 0; c < cc; c++) output[at * cc + c] = c == own ? input[at] : total[c] > 0 ? (float)(sum[c] / total[c]) : 0;
                continue;
            }
            for (int dy = -ph + 1; dy < ph; dy++)
                for (int dx = -pw + 1; dx < pw; dx++)
                {
                    int sx = x + dx, sy = y + dy;
                    if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;   // normalised convolution: missing sites drop out
                    int c = sensor.ChannelAt(sx, sy);
                    if (c == own) continue;
                    double wt = (1 - Math.Abs(dx) / (double)pw) * (1 - Math.Abs(dy) / (double)ph);
                    sum[c] += wt * input[sy * w + sx];
                    weight[c] += wt;
                }
            int o = (y * w + x) * cc;
            for (int c = 0; c < cc; c++) output[o + c] = c == own ? input[y * w + x] : weight[c] > 0 ? (float)(sum[c] / weight[c]) : 0;
        }
    }

    // Malvar–He–Cutler kernels (×1/8), rows dy = −2…2, columns dx = −2…2.
    static readonly double[,] GreenAtRedOrBlue =
    {
        { 0, 0, -1, 0, 0 }, { 0, 0, 2, 0, 0 }, { -1, 2, 4, 2, -1 }, { 0, 0, 2, 0, 0 }, { 0, 0, -1, 0, 0 },
    };
    /// <summary>Red (blue) at a green site in a red (blue) row: neighbours left and right.</summary>
    static readonly double[,] AtGreenRowNeighbours =
    {
        { 0, 0, 0.5, 0, 0 }, { 0, -1, 0, -1, 0 }, { -1, 4, 5, 4, -1 }, { 0, -1, 0, -1, 0 }, { 0, 0, 0.5, 0, 0 },
    };
    /// <summary>Red (blue) at a green site in a blue (red) row: neighbours above and below.</summary>
    static readonly double[,] AtGreenColumnNeighbours =
    {
        { 0, 0, -1, 0, 0 }, { 0, -1, 4, -1, 0 }, { 0.5, 0, 5, 0, 0.5 }, { 0, -1, 4, -1, 0 }, { 0, 0, -1, 0, 0 },
    };
    /// <summary>Red at blue, blue at red: diagonal neighbours.</summary>
    static readonly double[,] Diagonal =
    {
        { 0, 0, -1.5, 0, 0 }, { 0, 2, 0, 2, 0 }, { -1.5, 0, 6, 0, -1.5 }, { 0, 2, 0, 2, 0 }, { 0, 0, -1.5, 0, 0 },
    };

    static void MalvarRow(SensorModel sensor, float[] input, float[] output, int w, int h, int y)
    {
        const int R = 0, G = 1, B = 2;
        for (int x = 0; x < w; x++)
        {
            int own = sensor.ChannelAt(x, y);
            double v = input[y * w + x];
            double r, g, b;
            if (own == G)
            {
                // Which of red and blue shares this row?
                int rowMate = sensor.ChannelAt(x + 1, y);
                double horizontal =
                    Apply(AtGreenRowNeighbours, input, w, h, x, y), vertical = Apply(AtGreenColumnNeighbours, input, w, h, x, y);
                g = v;
                if (rowMate == R) { r = horizontal; b = vertical; } else { b = horizontal; r = vertical; }
            }
            else
            {
                g = Apply(GreenAtRedOrBlue, input, w, h, x, y);
                double other = Apply(Diagonal, input, w, h, x, y);
                if (own == R) { r = v; b = other; } else { b = v; r = other; }
            }
            int o = (y * w + x) * 3;
            output[o + R] = (float)r; output[o + G] = (float)g; output[o + B] = (float)b;
        }
    }

    static double Apply(double[,] kernel, float[] input, int w, int h, int x, int y)
    {
        double s = 0;
        for (int dy = -2; dy <= 2; dy++)
            for (int dx = -2; dx <= 2; dx++)
            {
                double k = kernel[dy + 2, dx + 2];
                if (k != 0) s += k * input[Mirror(y + dy, h) * w + Mirror(x + dx, w)];
            }
        return s / 8;
    }
}
