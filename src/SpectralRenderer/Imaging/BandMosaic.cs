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
        var mosaic = Blank(width, height, n, maxThumb);
        // Bands fill disjoint thumbnails: one task each.
        Parallel.For(0, n, b => Draw(mosaic, width, height, n, b, bands.AsSpan(b * plane, plane), scale, maxThumb));
        return mosaic;
    }

    /// <summary>The mosaic of <paramref name="n"/> bands of a width × height image before any band is drawn: the background grey.</summary>
    internal static (int Width, int Height, byte[] Pixels) Blank(int width, int height, int n, int maxThumb = 256)
    {
        var (cols, rows, _, tw, th) = Layout(width, height, n, maxThumb);
        int w = cols * tw + (cols + 1) * Gap, h = rows * th + (rows + 1) * Gap;
        var px = new byte[w * h];
        Array.Fill(px, (byte)40);
        return (w, h, px);
    }

    static (int Cols, int Rows, int Step, int ThumbW, int ThumbH) Layout(int width, int height, int n, int maxThumb)
    {
        int cols = (int)Math.Ceiling(Math.Sqrt(n * 1.25));
        int rows = (n + cols - 1) / cols;
        int step = Math.Max(1, (int)Math.Ceiling(Math.Max(width, height) / (double)maxThumb));
        return (cols, rows, step, (width + step - 1) / step, (height + step - 1) / step);
    }

    /// <summary>Draws band b's thumbnail (its row-major width × height plane) into the mosaic from <see cref="Blank"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void Draw((int Width, int Height, byte[] Pixels) mosaic, int width, int height, int n, int b, ReadOnlySpan<float> band, float scale, int maxThumb = 256)
    {
        var (cols, _, step, tw, th) = Layout(width, height, n, maxThumb);
        int w = mosaic.Width;
        var px = mosaic.Pixels;
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
    }
}
