using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>Eq. 3 over whole planes gives each pixel's ToXyz bit for bit, and the preview made from it the same bytes.</summary>
public class XyzPlanesTests
{
    [Theory]
    [InlineData(37, 23)]     // 851 pixels: vector body and scalar tail
    [InlineData(64, 70)]     // 4480 pixels: several 2048-pixel blocks
    public void Xyz_planes_equal_ToXyz_of_every_pixel_bit_for_bit(int w, int h)
    {
        var rng = new Random(w + h);
        var img = new SpectralImage(w, h, BandGrid.Default);
        for (int i = 0; i < img.Data.Length; i++)
            img.Data[i] = rng.Next(10) == 0 ? 0f : (float)(rng.NextDouble() * Math.Pow(10, rng.Next(-6, 4)));
        var cm = Synthetic.Colorimeter;
        var xyz = XyzPlanes.Compute(cm, img.BandPlanes(), w * h);
        var fromCube = XyzPlanes.Compute(cm, img);   // the preview's path when no band planes are written
        Assert.Equal(xyz.X, fromCube.X);
        Assert.Equal(xyz.Y, fromCube.Y);
        Assert.Equal(xyz.Z, fromCube.Z);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
            {
                var want = cm.ToXyz((ReadOnlySpan<float>)img.Pixel(x, y));
                var got = xyz[y * w + x];
                Assert.True(BitConverter.DoubleToInt64Bits(want.X) == BitConverter.DoubleToInt64Bits(got.X)
                    && BitConverter.DoubleToInt64Bits(want.Y) == BitConverter.DoubleToInt64Bits(got.Y)
                    && BitConverter.DoubleToInt64Bits(want.Z) == BitConverter.DoubleToInt64Bits(got.Z),
                        $"pixel ({x}, {y}): {got} != {want}");
            }
        Assert.True(xyz.Y.Max() > 0);

        // The preview from the planes: the bytes of the per-pixel encoder, in both RGB modes, with exposure and adaptation.
        foreach (
            var encoder in new[] { new DisplayEncoder(cm, RgbSpace.Srgb, 3.5, adapt: true), new DisplayEncoder(cm, RgbSpace.Paper, 0.7) })
        {
            var rgb = RenderOutputWriter.Preview(img, encoder);
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                {
                    // The definition: eq. 3, exposure, the matrix, then clip, curve and round (RgbSpace.Encode, To8).
                    var (lr, lg, lb) = encoder.Linear(img.Pixel(x, y));
                    var s = encoder.Space;
                    var (r, g, b) = (RgbSpace.To8(s.Encode(lr)), RgbSpace.To8(s.Encode(lg)), RgbSpace.To8(s.Encode(lb)));
                    int o = 3 * (y * w + x);
                    Assert.Equal((r, g, b), (rgb[o], rgb[o + 1], rgb[o + 2]));
                }
            Assert.Contains(rgb, v => v is > 0 and < 255);
        }
    }
}
