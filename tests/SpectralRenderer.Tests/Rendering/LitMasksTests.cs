using SpectralRenderer.Rendering;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>The compact lit masks hold each light's bit for every light count up to 32, in ⌈lights / 8⌉ bytes a pixel.</summary>
public class LitMasksTests
{
    [Theory]
    [InlineData(0, 1)]
    [InlineData(1, 1)]
    [InlineData(8, 1)]
    [InlineData(9, 2)]
    [InlineData(24, 3)]
    [InlineData(32, 4)]
    [InlineData(40, 4)]   // lights past the 32nd have no bit, as with a uint per pixel
    public void Every_lights_bit_survives_in_the_fewest_bytes(int lights, int bytes)
    {
        var rng = new Random(lights);
        int used = Math.Min(lights, LitMasks.MaxLights);
        uint valid = used == 32 ? uint.MaxValue : (1u << used) - 1;
        var truth = Enumerable.Range(0, 1000).Select(_ => (uint)rng.NextInt64(0, 1L << 32) & valid).ToArray();
        var masks = LitMasks.From(truth, lights);
        Assert.Equal(bytes, masks.BytesPerPixel);
        Assert.Equal(truth, masks.ToArray());
        for (int i = 0; i < truth.Length; i++)
            for (int k = 0; k < 40; k++)
                Assert.Equal(k < 32 && (truth[i] & (1u << k)) != 0, masks.IsLit(i, k));
    }
}
