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

    /// <summary>As <see cref="Build(SpectralImage, float, int)"/>, from band-sequential planes
    /// (<see cref="SpectralImage.CopyBands"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static (int Width, int Height, byte[] Pixels) Build(int width, int height, float[] bands, float scale, int maxThumb = 256) =>
        Build(width, height, bands, scale, maxThumb, null);

    /// <summary>
    /// As above, each thumbnail with its band's wavelengths ("380-400 nm") written in a strip above it in a 3 × 5 pixel
    /// font (twice the size when the thumbnail is wide enough), white on the mosaic's dark grey.
    /// </summary>
    internal static (int Width, int Height, byte[] Pixels) Build(int width, int height, float[] bands, float scale, int maxThumb,
        Spectra.BandGrid? labels)
    {
        int plane = width * height, n = bands.Length / plane;
        var mosaic = Blank(width, height, n, maxThumb, labels);
        // Bands fill disjoint thumbnails: one task each.
        Parallel.For(0, n, b => Draw(mosaic, width, height, n, b, bands.AsSpan(b * plane, plane), scale, maxThumb, labels));
        return mosaic;
    }

    /// <summary>
    /// The mosaic of <paramref name="n"/> bands of a width × height image before any band is drawn: the background grey,
    /// and each band's wavelengths in the strip above its thumbnail when <paramref name="labels"/> is given.
    /// </summary>
    internal static (int Width, int Height, byte[] Pixels) Blank(int width, int height, int n, int maxThumb = 256,
        Spectra.BandGrid? labels = null)
    {
        var (cols, rows, _, tw, th, strip, glyph) = Layout(width, height, n, maxThumb, labels);
        int w = cols * tw + (cols + 1) * Gap, h = rows * (th + strip) + (rows + 1) * Gap;
        var px = new byte[w * h];
        Array.Fill(px, (byte)40);
        if (labels is not null)
            for (int b = 0; b < n; b++)
                DrawText(px, w, Gap + b % cols * (tw + Gap), Gap + b / cols * (th + Gap + strip), tw, Label(labels, b), glyph);
        return (w, h, px);
    }

    /// <summary>Columns, rows, the box-filter step, a thumbnail's size, the label strip's height and the glyph scale.</summary>
    static (int Cols, int Rows, int Step, int ThumbW, int ThumbH, int Strip, int Glyph) Layout(int width, int height, int n, int maxThumb,
        Spectra.BandGrid? labels)
    {
        int cols = (int)Math.Ceiling(Math.Sqrt(n * 1.25));
        int rows = (n + cols - 1) / cols;
        int step = Math.Max(1, (int)Math.Ceiling(Math.Max(width, height) / (double)maxThumb));
        int tw = (width + step - 1) / step, th = (height + step - 1) / step;
        int glyph = 1, strip = 0;
        if (labels is not null)
        {
            int longest = Enumerable.Range(0, n).Max(b => Label(labels, b).Length);
            glyph = longest * 8 <= tw ? 2 : 1;
            strip = 5 * glyph + 2;
        }
        return (cols, rows, step, tw, th, strip, glyph);
    }

    /// <summary>Draws band b's thumbnail (its row-major width × height plane) into the mosaic from <see cref="Blank"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void Draw((int Width, int Height, byte[] Pixels) mosaic, int width, int height, int n, int b, ReadOnlySpan<float> band,
        float scale, int maxThumb = 256, Spectra.BandGrid? labels = null)
    {
        var (cols, _, step, tw, th, strip, _) = Layout(width, height, n, maxThumb, labels);
        int w = mosaic.Width;
        var px = mosaic.Pixels;
        int ox = Gap + b % cols * (tw + Gap), oy = Gap + b / cols * (th + Gap + strip) + strip;
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

    static string Label(Spectra.BandGrid g, int b) =>
        string.Create(System.Globalization.CultureInfo.InvariantCulture, $"{g.Lower(b):0.#}-{g.Upper(b):0.#} nm");

    // 3 × 5 glyphs, one row of 3 bits per entry (bit 2 = left column).
    static readonly Dictionary<char, byte[]> Font = new()
    {
        ['0'] = [7, 5, 5, 5, 7],
        ['1'] = [2, 6, 2, 2, 7],
        ['2'] = [7, 1, 7, 4, 7],
        ['3'] = [7, 1, 3, 1, 7],
        ['4'] = [5, 5, 7, 1, 1],
        ['5'] = [7, 4, 7, 1, 7],
        ['6'] = [7, 4, 7, 5, 7],
        ['7'] = [7, 1, 1, 2, 2],
        ['8'] = [7, 5, 7, 5, 7],
        ['9'] = [7, 5, 7, 1, 7],
        ['-'] = [0, 0, 7, 0, 0],
        ['.'] = [0, 0, 0, 0, 2],
        ['n'] = [0, 6, 5, 5, 5],
        ['m'] = [0, 7, 7, 5, 5],
        [' '] = [0, 0, 0, 0, 0],
    };

    /// <summary>Writes <paramref name="text"/> at (x0, y0), clipped to <paramref name="maxWidth"/> pixels.</summary>
    static void DrawText(byte[] px, int stride, int x0, int y0, int maxWidth, string text, int size)
    {
        int x = x0;
        foreach (char ch in text)
        {
            if (!Font.TryGetValue(ch, out var rows)) rows = Font[' '];
            for (int r = 0; r < 5; r++)
                for (int c = 0; c < 3; c++)
                {
                    if ((rows[r] >> (2 - c) & 1) == 0) continue;
                    for (int dy = 0; dy < size; dy++)
                        for (int dx = 0; dx < size; dx++)
                        {
                            int xx = x + c * size + dx;
                            if (xx < x0 + maxWidth) px[(y0 + r * size + dy) * stride + xx] = 230;
                        }
                }
            x += 4 * size;
        }
    }
}
