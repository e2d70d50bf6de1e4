using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Rendering;

namespace SpectralRenderer.Imaging;

/// <summary>All band images side by side on one common scale — the paper's Fig. 2.</summary>
public static class BandMosaic
{
    const int Gap = 4;

    /// <summary>An 8-bit grey mosaic (sRGB-encoded for viewing), bands in reading order, each thumbnail at most 256 px wide.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static (int Width, int Height, byte[] Pixels) Build(SpectralImage image, float scale, int maxThumb = 256)
    {
        int n = image.Bands;
        int cols = (int)Math.Ceiling(Math.Sqrt(n * 1.25));
        int rows = (n + cols - 1) / cols;
        int step = Math.Max(1, (int)Math.Ceiling(Math.Max(image.Width, image.Height) / (double)maxThumb));
        int tw = (image.Width + step - 1) / step, th = (image.Height + step - 1) / step;
        int w = cols * tw + (cols + 1) * Gap, h = rows * th + (rows + 1) * Gap;
        var px = new byte[w * h];
        Array.Fill(px, (byte)40);
        for (int b = 0; b < n; b++)
        {
            int ox = Gap + b % cols * (tw + Gap), oy = Gap + b / cols * (th + Gap);
            for (int ty = 0; ty < th; ty++)
            for (int tx = 0; tx < tw; tx++)
            {
                // box filter over the step × step block
                double sum = 0; int count = 0;
                for (int y = ty * step; y < Math.Min(image.Height, (ty + 1) * step); y++)
                for (int x = tx * step; x < Math.Min(image.Width, (tx + 1) * step); x++) { sum += image[x, y, b]; count++; }
                double v = scale > 0 ? sum / count / scale : 0;
                px[(oy + ty) * w + ox + tx] = RgbSpace.To8(RgbSpace.SrgbCurve(Math.Clamp(v, 0, 1)));
            }
        }
        return (w, h, px);
    }
}
