using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Spectra;

/// <summary>
/// The framebuffer's streaming copy writes exactly the values a plain span copy writes, at every alignment of the
/// destination and every length (ragged ends included), and nothing outside the pixel.
/// </summary>
public class StreamBandsTests
{
    [Fact]
    public void Streaming_stores_write_the_plain_copy_and_nothing_else()
    {
        var rng = new Random(7);
        foreach (int n in new[] { 1, 20, SpectralMath.StreamMinBands - 1, SpectralMath.StreamMinBands, 129, 143, 160, 401, 1024 })
        {
            var padded = new float[n + 64];
            for (int i = 0; i < padded.Length; i++) padded[i] = (float)(rng.NextDouble() * 2 - 1);
            for (int start = 0; start < 32; start++)
            {
                var buffer = GC.AllocateArray<float>(n + 96, pinned: true);   // pinned: the alignment stays what it was
                Array.Fill(buffer, float.NaN);
                SpectralMath.StreamBands(padded, buffer.AsSpan(start, n));
                SpectralMath.StreamFence();
                for (int i = 0; i < buffer.Length; i++)
                {
                    if (i >= start && i < start + n)
                        Assert.Equal(BitConverter.SingleToInt32Bits(padded[i - start]), BitConverter.SingleToInt32Bits(buffer[i]));
                    else
                        Assert.True(float.IsNaN(buffer[i]), $"n {n}, start {start}: element {i} outside the pixel was written");
                }
            }
        }
    }
}
