using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Imaging;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>The blocked band transpose equals the per-band strided copy, value for value.</summary>
public class BandPlanesTests
{
    static SpectralImage Noise(int w, int h, BandGrid grid, int seed)
    {
        var rng = new Random(seed);
        var img = new SpectralImage(w, h, grid);
        for (int i = 0; i < img.Data.Length; i++) img.Data[i] = BitConverter.Int32BitsToSingle(rng.Next());  // any bits, NaNs included
        return img;
    }

    static float[] PerBand(SpectralImage img)
    {
        int n = img.Width * img.Height;
        var expected = new float[img.Data.Length];
        for (int b = 0; b < img.Bands; b++) img.CopyBand(b, expected.AsSpan(b * n, n));
        return expected;
    }

    [Theory]
    [InlineData(37, 23, 20)]    // 851 pixels: three whole 256-pixel blocks and a partial one
    [InlineData(300, 7, 31)]
    [InlineData(1, 1, 1)]
    [InlineData(256, 1, 3)]     // exactly one block
    public void CopyBands_equals_CopyBand_of_every_band(int w, int h, int count)
    {
        var img = Noise(w, h, new BandGrid(400, 700, count), w * 1000 + h);
        var expected = PerBand(img);
        var planes = new float[img.Data.Length];
        img.CopyBands(planes);
        Synthetic.AssertBitExact(expected, planes, "CopyBands");
        Synthetic.AssertBitExact(expected, img.BandPlanes(), "BandPlanes");
        Assert.Equal(img[w - 1, h - 1, count - 1], planes[(count - 1) * w * h + w * h - 1]);
    }

    [Fact]
    public void Max_is_the_largest_value_skipping_NaN_and_at_least_zero()
    {
        static float Scalar(float[] data) { float m = 0; foreach (var v in data) if (v > m) m = v; return m; }
        var img = Noise(37, 23, BandGrid.Default, 8);   // random non-negative bit patterns: NaNs among them
        Assert.Equal(Scalar(img.Data), img.Max());
        Assert.True(img.Max() > 1e38f);
        img.Data[100] = float.PositiveInfinity;
        Assert.Equal(float.PositiveInfinity, img.Max());
        var rng = new Random(1);
        for (int i = 0; i < img.Data.Length; i++) img.Data[i] = rng.Next(5) == 0 ? float.NaN : (float)(rng.NextDouble() - 0.3);
        img.Data[img.Data.Length - 1] = 0.75f;          // in the scalar tail
        Assert.Equal(Scalar(img.Data), img.Max());
        img.Data[3] = 0.9f;
        Assert.Equal(0.9f, img.Max());
        Array.Fill(img.Data, -1f);
        Assert.Equal(0f, img.Max());
    }

    [Fact]
    public void A_pixel_range_copies_that_range_of_every_band_only()
    {
        var img = Noise(37, 23, BandGrid.Default, 5);
        int n = 37 * 23;
        var expected = PerBand(img);
        var planes = new float[img.Data.Length];
        Array.Fill(planes, -7f);
        img.CopyBands(planes, 300, 400);
        for (int b = 0; b < img.Bands; b++)
            for (int i = 0; i < n; i++)
            {
                float want = i >= 300 && i < 700 ? expected[b * n + i] : -7f;
                Assert.Equal(BitConverter.SingleToInt32Bits(want), BitConverter.SingleToInt32Bits(planes[b * n + i]));
            }
        img.CopyBands(planes, 0, 300);
        img.CopyBands(planes, 700);
        Synthetic.AssertBitExact(expected, planes, "three ranges");
        Assert.Throws<ArgumentOutOfRangeException>(() => img.CopyBands(planes, 800, 100));
        Assert.Throws<ArgumentException>(() => img.CopyBands(new float[n], 0, 1));
    }

    [Fact]
    public void Ground_truth_planes_are_the_ground_truth_image_transposed()
    {
        var scene = SceneText.Load("""
        { "camera": { "position": [0, 1, 6], "look_at": [0, 0.5, 0], "width": 40, "height": 30 },
          "materials": { "a": { "diffuse": "colorchecker:14" }, "b": { "diffuse": "colorchecker:3" } },
          "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "a" },
                       { "type": "box", "center": [-1.5, 0.5, 0], "size": [1, 1, 1], "material": "b" } ] }
        """);
        var result = Integrators.Render(scene, 2);
        // The definition, pixel by pixel: m_diff of the material the centre ray hit, zero for the background.
        var truth = new SpectralImage(result.Image.Width, result.Image.Height, result.Image.Grid);
        for (int i = 0; i < result.ObjectIds.Length; i++)
            if (result.ObjectIds[i] >= 0)
                scene.Materials[scene.Objects[result.ObjectIds[i]].Material].Diffuse.AsSpan(0, truth.Bands)
                    .CopyTo(truth.Data.AsSpan(i * truth.Bands));
        var planes = AnalysisImages.GroundTruthBands(scene, result);
        Synthetic.AssertBitExact(PerBand(truth), planes, "ground truth planes");
        Assert.Contains(result.ObjectIds, id => id < 0);                       // background (0) and both objects are in view
        Assert.Contains(result.ObjectIds, id => id == 0);
        Assert.Contains(result.ObjectIds, id => id == 1);
        int at = Array.IndexOf(result.ObjectIds, 1);
        Assert.Equal(scene.Materials[scene.Objects[1].Material].Diffuse[7], planes[7 * 40 * 30 + at]);
    }
}
