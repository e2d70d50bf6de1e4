using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>The mosaic (the paper's Fig. 2) from band planes gives the bytes of the per-pixel definition.</summary>
public class BandMosaicTests
{
    /// <summary>The definition: each thumbnail pixel the box mean of its step × step block (rows, then columns), over the scale,
    /// sRGB-encoded.</summary>
    static byte[] Reference(SpectralImage image, float scale, int maxThumb, out int w, out int h)
    {
        int n = image.Bands, gap = 4;
        int cols = (int)Math.Ceiling(Math.Sqrt(n * 1.25)), rows = (n + cols - 1) / cols;
        int step = Math.Max(1, (int)Math.Ceiling(Math.Max(image.Width, image.Height) / (double)maxThumb));
        int tw = (image.Width + step - 1) / step, th = (image.Height + step - 1) / step;
        w = cols * tw + (cols + 1) * gap; h = rows * th + (rows + 1) * gap;
        var px = new byte[w * h];
        Array.Fill(px, (byte)40);
        for (int b = 0; b < n; b++)
        {
            int ox = gap + b % cols * (tw + gap), oy = gap + b / cols * (th + gap);
            for (int ty = 0; ty < th; ty++)
                for (int tx = 0; tx < tw; tx++)
                {
                    double sum = 0; int count = 0;
                    for (int y = ty * step; y < Math.Min(image.Height, (ty + 1) * step); y++)
                        for (int x = tx * step; x < Math.Min(image.Width, (tx + 1) * step); x++) { sum += image[x, y, b]; count++; }
                    double v = scale > 0 ? sum / count / scale : 0;
                    px[(oy + ty) * w + ox + tx] = RgbSpace.To8(RgbSpace.SrgbCurve(Math.Clamp(v, 0, 1)));
                }
        }
        return px;
    }

    [Theory]
    [InlineData(37, 23, 256)]     // step 1: blocks of one pixel
    [InlineData(64, 40, 32)]      // step 2: blocks of 4 (a power of two)
    [InlineData(100, 53, 34)]     // step 3: blocks of 9, edge blocks of 3 and 6 pixels
    [InlineData(70, 70, 18)]      // step 4, edge blocks of 2 × 4, 4 × 2 and 2 × 2
    public void Mosaic_equals_the_per_pixel_definition(int width, int height, int maxThumb)
    {
        var rng = new Random(width * height);
        var img = new SpectralImage(width, height, BandGrid.Default);
        for (int i = 0; i < img.Data.Length; i++) img.Data[i] = (float)(rng.NextDouble() * rng.NextDouble() * 3);
        float scale = img.Max();
        foreach (float s in new[] { scale, 0f, scale / 3 })
        {
            var want = Reference(img, s, maxThumb, out int w, out int h);
            var (gw, gh, got) = BandMosaic.Build(img, s, maxThumb);
            Assert.Equal((w, h), (gw, gh));
            Assert.Equal(want, got);
            if (s > 0) Assert.True(got.Distinct().Count() > 50, "the test image should cover many grey levels");
        }
    }
}
