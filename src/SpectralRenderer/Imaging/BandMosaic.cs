using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>All band images side by side on one common scale — the paper's Fig. 2.</summary>
public static class BandMosaic
{
    const int Gap = 4;

    /// <summary>An 8-bit grey mosaic (sRGB-encoded for viewing), bands in reading order, each thumbnail at most 256 px wide.</summary>
    public static (int Width, int Height, byte[] Pixels) Build(SpectralImage image, float scale, int maxThumb = 256) =>
        Build(image.Width, image.Height, image.BandPlanes(), scale, maxThumb);

    /// <summary>As <see cref="Build(SpectralImage, float, int)"/>, from band-sequential planes (<see cref="SpectralImage.CopyBands"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static (int Width, int Height, byte[] Pixels) Build(int width, int height, float[] bands, float scale, int maxThumb = 256)
    {
        int plane = width * height, n = bands.Length / plane;
        int cols = (int)Math.Ceiling(Math.Sqrt(n * 1.25));
        int rows = (n + cols - 1) / cols;
        int step = Math.Max(1, (int)Math.Ceiling(Math.Max(width, height) / (double)maxThumb));
        int tw = (width + step - 1) / step, th = (height + step - 1) / step;
        int w = cols * tw + (cols + 1) * Gap, h = rows * th + (rows + 1) * Gap;
        var px = new byte[w * h];
        Array.Fill(px, (byte)40);
        // Bands fill disjoint thumbnails: one task each.
        Parallel.For(0, n, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (b) =>
        {
            var band = bands.AsSpan(b * plane, plane);
            int ox = Gap + b % cols * (tw + Gap), oy = Gap + b / cols * (th + Gap);
            for (int ty = 0; ty < th; ty++)
            {
                int y0 = ty * step, y1 = Math.Min(height, y0 + step);
                for (int tx = 0; tx < tw; tx++)
                {
                    // box filter over the step × step block, summed row by row as before
                    int x0 = tx * step, x1 = Math.Min(width, x0 + step);
                    double sum = 0;
                    for (int y = y0; y < y1; y++)
                        for (int x = y * width + x0; x < y * width + x1; x++) sum += band[x];
                    int count = (y1 - y0) * (x1 - x0);
                    // Dividing by a power of two is exact, so multiplying by its reciprocal gives the same double.
                    double average = (count & (count - 1)) == 0 ? sum * (1.0 / count) : sum / count;
                    double mean = scale > 0 ? average / scale : 0;
                    px[(oy + ty) * w + ox + tx] = RgbSpace.Srgb.Encode8(mean);   // = To8(SrgbCurve(clamp(mean, 0, 1)))
                }
            }
        });
        return (w, h, px);
    }
}
