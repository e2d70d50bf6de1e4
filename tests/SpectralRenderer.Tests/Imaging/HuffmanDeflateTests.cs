using System.IO.Compression;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>
/// <see cref="HuffmanDeflate"/>'s streams decoded by an independent inflater (the runtime's zlib, which also checks the
/// Adler-32 trailer), the Adler-32 against the published check value, and the code lengths against RFC 1951's limits.
/// </summary>
public class HuffmanDeflateTests
{
    static byte[] Compress(params byte[][] blocks)
    {
        var ms = new MemoryStream();
        using var d = new HuffmanDeflate();
        for (int i = 0; i < blocks.Length; i++) ms.Write(d.Block(blocks[i], final: i == blocks.Length - 1));
        return ms.ToArray();
    }

    static byte[] Inflate(byte[] zlib)
    {
        using var z = new ZLibStream(new MemoryStream(zlib), CompressionMode.Decompress);
        var ms = new MemoryStream();
        z.CopyTo(ms);
        return ms.ToArray();
    }

    public static TheoryData<string> Inputs => ["empty", "one byte", "one value repeated", "uniform random", "all 256 values once",
        "skewed (Fibonacci counts)", "image residuals"];

    static byte[] Input(string name)
    {
        var rng = new Random(7);
        switch (name)
        {
            case "empty": return [];
            case "one byte": return [42];
            case "one value repeated": return Enumerable.Repeat((byte)128, 100_000).ToArray();
            case "uniform random": { var b = new byte[300_000]; rng.NextBytes(b); return b; }
            case "all 256 values once": return Enumerable.Range(0, 256).Select(i => (byte)i).ToArray();
            case "skewed (Fibonacci counts)":
                {
                    // Counts 1, 1, 2, 3, 5, … for 25 symbols: the unconstrained Huffman code is 24 bits deep, over the 15-bit limit.
                    var list = new List<byte>();
                    long a = 1, b = 1;
                    for (int s = 0; s < 25; s++) { for (long k = 0; k < a; k++) list.Add((byte)(s * 10)); (a, b) = (b, a + b); }
                    return list.OrderBy(_ => rng.Next()).ToArray();
                }
            default:
                {
                    // Small signed residuals around 0 as a Sub-filtered smooth image gives, a few large ones.
                    var b = new byte[500_000];
                    for (int i = 0; i < b.Length; i++)
                        b[i] = (byte)(rng.Next(100) < 3 ? rng.Next(256) : (int)Math.Round(rng.NextDouble() * 6 - 3));
                    return b;
                }
        }
    }

    [Theory]
    [MemberData(nameof(Inputs))]
    public void Inflates_to_the_input(string name)
    {
        var data = Input(name);
        Assert.Equal(data, Inflate(Compress(data)));
    }

    [Theory]
    [MemberData(nameof(Inputs))]
    public void Several_blocks_with_their_own_codes_inflate_to_the_concatenation(string name)
    {
        var data = Input(name);
        int third = data.Length / 3;
        var parts = new[] { data[..third], Input("skewed (Fibonacci counts)"), data[third..], [], Input("one byte") };
        Assert.Equal(parts.SelectMany(p => p).ToArray(), Inflate(Compress(parts)));
    }

    [Fact]
    public void Adler32_trailer_is_the_published_check_value()
    {
        // RFC 1950 §9 example value used by every implementation: Adler-32("Wikipedia") = 0x11E60398.
        var z = Compress("Wikipedia"u8.ToArray());
        Assert.Equal(new byte[] { 0x11, 0xE6, 0x03, 0x98 }, z[^4..]);
        Assert.Equal(0x78, z[0]);
        Assert.Equal(0, (z[0] << 8 | z[1]) % 31);   // RFC 1950 §2.2: CMF·256 + FLG is a multiple of 31
        // Over the 5552-byte reduction interval: s1 and s2 by their definition, in 64 bits, mod 65521.
        var big = Input("uniform random");
        ulong s1 = 1, s2 = 0;
        foreach (byte b in big) { s1 += b; s2 += s1; }
        uint expected = (uint)((s2 % 65521) << 16 | (s1 % 65521));
        var zb = Compress(big[..100_000], big[100_000..]);
        Assert.Equal(expected, System.Buffers.Binary.BinaryPrimitives.ReadUInt32BigEndian(zb.AsSpan(zb.Length - 4)));
    }

    [Theory]
    [InlineData(15)]
    [InlineData(7)]
    public void Code_lengths_respect_the_limit_and_form_a_complete_prefix_code(int maxBits)
    {
        var rng = new Random(3);
        foreach (int symbols in new[] { 2, 19, 40, 128, 257 }.Where(n => n <= 1 << maxBits))
            for (int trial = 0; trial < 20; trial++)
            {
                var freq = new int[symbols];
                // Geometric-ish counts spanning many octaves make deep unconstrained trees.
                for (int s = 0; s < symbols; s++)
                    freq[s] = trial % 3 == 0 && s % 5 == 0 ? 0 : (int)Math.Min(int.MaxValue / 512, Math.Pow(1.9, rng.Next(0, 30)));
                var lengths = new byte[symbols];
                HuffmanDeflate.BuildCode(freq, lengths, maxBits);
                double kraft = 0;
                for (int s = 0; s < symbols; s++)
                {
                    Assert.InRange(lengths[s], 0, maxBits);
                    Assert.True(freq[s] == 0 ? lengths[s] == 0 : lengths[s] > 0, $"symbol {s}: count {freq[s]}, length {lengths[s]}");
                    if (lengths[s] > 0) kraft += Math.Pow(2, -lengths[s]);
                }
                Assert.Equal(1.0, kraft, 12);
                // A more frequent symbol never has a longer code.
                for (int a = 0; a < symbols; a++)
                    for (int b = 0; b < symbols; b++)
                        if (freq[a] > freq[b] && freq[b] > 0) Assert.True(lengths[a] <= lengths[b]);
            }
    }

    [Fact]
    public void Residuals_shrink_to_about_their_entropy()
    {
        var data = Input("image residuals");
        var hist = new long[256];
        foreach (byte b in data) hist[b]++;
        double bits = hist.Where(c => c > 0).Sum(c => -c * Math.Log2(c / (double)data.Length));
        int size = Compress(data).Length;
        // A Huffman code is within one bit per symbol of the entropy (and in practice within a few per cent).
        Assert.InRange(size, bits / 8, bits / 8 * 1.05 + 200);
    }
}
