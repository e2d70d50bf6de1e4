using System.Buffers.Binary;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>The vector 16-bit band quantisation gives the samples of To16(clamp(v / scale, 0, 1)), big-endian.</summary>
public class BandSamplesTests
{
    static void AssertSameAsFormula(float[] plane, float scale)
    {
        var got = new byte[2 * plane.Length + 2];
        got[^1] = 0xA5;
        RenderOutputWriter.BandSamples16(plane, scale, got);
        for (int i = 0; i < plane.Length; i++)
        {
            ushort want = scale > 0 ? RgbSpace.To16(Math.Clamp(plane[i] / scale, 0, 1)) : (ushort)0;
            ushort actual = BinaryPrimitives.ReadUInt16BigEndian(got.AsSpan(2 * i));
            if (want != actual)
                Assert.Fail($"v = {plane[i]:R} ({BitConverter.SingleToInt32Bits(plane[i]):x8}), scale {scale:R}: {actual}, formula {want}");
        }
        Assert.Equal(0xA5, got[^1]);   // nothing written past the samples
    }

    [Fact]
    public void Every_61st_float_in_0_to_1_and_the_ties_match_the_formula()
    {
        int one = BitConverter.SingleToInt32Bits(1f);
        var plane = new float[one / 61 + 2];
        for (int i = 0; i < plane.Length - 2; i++) plane[i] = BitConverter.Int32BitsToSingle(i * 61);
        plane[^2] = 1f;
        plane[^1] = 0.5f;                  // 65535 · 0.5 = 32767.5: the one exact tie, rounds away from zero to 32768
        AssertSameAsFormula(plane, 1f);
        var tie = new byte[2];
        RenderOutputWriter.BandSamples16([0.5f], 1f, tie);
        Assert.Equal(32768, BinaryPrimitives.ReadUInt16BigEndian(tie));
    }

    [Fact]
    public void Random_values_special_values_and_scales_match_the_formula()
    {
        var rng = new Random(12);
        foreach (int n in new[] { 0, 1, 15, 16, 17, 33, 1000, 4099 })
            foreach (float scale in new[] { 1f, 0.37f, 3.3e-5f, 2.5e7f, 0f, -1f, float.NaN })
            {
                var plane = new float[n];
                for (int i = 0; i < n; i++)
                    plane[i] = rng.Next(8) switch
                    {
                        0 => float.NaN,
                        1 => rng.Next(2) == 0 ? float.PositiveInfinity : float.NegativeInfinity,
                        2 => -(float)rng.NextDouble(),
                        3 => (float)(rng.NextDouble() * 2 * scale),           // above the scale: clipped to 65535
                        4 => (float)(Math.Round(rng.NextDouble() * 65535) + 0.5) / 65535f * scale,   // near ties
                        _ => (float)(rng.NextDouble() * scale),
                    };
                AssertSameAsFormula(plane, scale);
            }
    }
}
