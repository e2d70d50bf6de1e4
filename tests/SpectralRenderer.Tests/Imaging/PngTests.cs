using System.Buffers.Binary;
using System.Text;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Imaging;

public class PngTests
{
    const int W = Synthetic.W, H = Synthetic.H;

    internal static byte[] Rgb()
    {
        var rgb = new byte[W * H * 3];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 3; c++)
                    rgb[(y * W + x) * 3 + c] = (byte)(c == 0 ? x * 7 : c == 1 ? (x * y * 3 + 11) : (y < 5 ? 255 : (x ^ y) * 9));
        return rgb;
    }

    internal static ushort[] Gray16()
    {
        var g = new ushort[W * H];
        for (int i = 0; i < g.Length; i++) g[i] = (ushort)(i % 5 == 0 ? 0 : i % 7 == 0 ? 65535 : (i * 2654435761u) >> 16);
        return g;
    }

    internal static byte[] Gray8()
    {
        var g = new byte[W * H];
        for (int y = 0; y < H; y++) for (int x = 0; x < W; x++) g[y * W + x] = (byte)(x * 6 + y * 3);
        return g;
    }

    [Fact]
    public void Crc32_matches_the_standard_check_values()
    {
        Assert.Equal(0xCBF43926u, Crc32.Compute("123456789"u8));
        Assert.Equal(0xAE426082u, Crc32.Compute("IEND"u8));   // the CRC every PNG ends with
        Assert.Equal(0u, Crc32.Compute([]));
    }

    [Theory]
    [InlineData(PngFilter.None)]
    [InlineData(PngFilter.Sub)]
    [InlineData(PngFilter.Up)]
    [InlineData(PngFilter.Average)]
    [InlineData(PngFilter.Paeth)]
    [InlineData(PngFilter.Adaptive)]
    public void Rgb8_round_trips_with_every_filter(PngFilter filter)
    {
        var rgb = Rgb();
        var ms = new MemoryStream();
        PngWriter.WriteRgb8(ms, W, H, rgb,
            new Dictionary<string, string> { ["Software"] = "SpectralRenderer", ["Comment"] = "bands 380:780:20" }, filter);
        var png = PngReader.Read(new MemoryStream(ms.ToArray()));
        Assert.Equal((W, H, 8, 2, 3), (png.Width, png.Height, png.BitDepth, png.ColourType, png.Channels));
        Assert.Equal(rgb.Select(b => (ushort)b).ToArray(), png.Samples);
        Assert.Equal("SpectralRenderer", png.Text["Software"]);
        Assert.Equal("bands 380:780:20", png.Text["Comment"]);
        var types = FilterTypes(ms.ToArray(), W * 3);
        if (filter != PngFilter.Adaptive) Assert.All(types, t => Assert.Equal((int)filter, t));
        else Assert.True(types.Distinct().Count() >= 2, $"adaptive filtering used only {string.Join(",", types.Distinct())}");
    }

    [Fact]
    public void Gray16_is_big_endian_and_round_trips()
    {
        var g = Gray16();
        var ms = new MemoryStream();
        PngWriter.WriteGray16(ms, W, H, g, filter: PngFilter.None);
        var bytes = ms.ToArray();
        var png = PngReader.Read(new MemoryStream(bytes));
        Assert.Equal((16, 0, 1), (png.BitDepth, png.ColourType, png.Channels));
        Assert.Equal(g, png.Samples);
        // With filter None the first row, after its filter byte, is the samples big-endian.
        var raw = Inflate(bytes);
        Assert.Equal(0, raw[0]);
        Assert.Equal(g[1], BinaryPrimitives.ReadUInt16BigEndian(raw.AsSpan(3)));
        Assert.Equal(H * (1 + 2 * W), raw.Length);
    }

    [Fact]
    public void Rgb16_round_trips()
    {
        var rgb = new ushort[W * H * 3];
        for (int i = 0; i < rgb.Length; i++) rgb[i] = (ushort)(i % 3 == 0 ? i * 97 : i % 3 == 1 ? 65535 - i : (i * 40503) & 0xffff);
        var ms = new MemoryStream();
        PngWriter.WriteRgb16(ms, W, H, rgb);
        var png = PngReader.Read(new MemoryStream(ms.ToArray()));
        Assert.Equal((16, 2, 3), (png.BitDepth, png.ColourType, png.Channels));
        Assert.Equal(rgb, png.Samples);
    }

    [Fact]
    public void Gray8_round_trips()
    {
        var g = Gray8();
        var ms = new MemoryStream();
        PngWriter.WriteGray8(ms, W, H, g);
        var png = PngReader.Read(new MemoryStream(ms.ToArray()));
        Assert.Equal((8, 0, 1), (png.BitDepth, png.ColourType, png.Channels));
        Assert.Equal(g.Select(b => (ushort)b).ToArray(), png.Samples);
    }

    [Fact]
    public void File_has_signature_IHDR_first_and_IEND_last()
    {
        var dir = Reference.TempDir();
        var path = Path.Combine(dir, "rgb.png");
        PngWriter.WriteRgb8(path, W, H, Rgb());
        var b = File.ReadAllBytes(path);
        Assert.Equal(new byte[] { 0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A }, b[..8]);
        Assert.Equal(13, BinaryPrimitives.ReadInt32BigEndian(b.AsSpan(8)));
        Assert.Equal("IHDR", Encoding.ASCII.GetString(b, 12, 4));
        Assert.Equal(W, BinaryPrimitives.ReadInt32BigEndian(b.AsSpan(16)));
        Assert.Equal(H, BinaryPrimitives.ReadInt32BigEndian(b.AsSpan(20)));
        Assert.Equal(new byte[] { 0, 0, 0, 0, (byte)'I', (byte)'E', (byte)'N', (byte)'D', 0xAE, 0x42, 0x60, 0x82 }, b[^12..]);
        Assert.Single(Directory.GetFiles(dir));   // no temporary file left behind
    }

    [Fact]
    public void Corrupt_png_is_an_input_error()
    {
        var ms = new MemoryStream();
        PngWriter.WriteGray8(ms, W, H, Gray8());
        var b = ms.ToArray();
        b[40] ^= 0xff;
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => PngReader.Read(new MemoryStream(b)));
        Assert.Contains("CRC", e.Message);
        Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => PngReader.Read(new MemoryStream(b[..50])));
        // A valid chunk structure around a cut zlib stream.
        var cut = new MemoryStream();
        PngWriter.WriteGray8(cut, W, H, Gray8(), filter: PngFilter.None);
        var c = cut.ToArray();
        int len = BinaryPrimitives.ReadInt32BigEndian(c.AsSpan(33));
        var idat = c.AsSpan(41, len / 2).ToArray();
        var forged = new MemoryStream();
        forged.Write(c, 0, 33);
        var head = new byte[8];
        BinaryPrimitives.WriteInt32BigEndian(head, idat.Length);
        "IDAT"u8.CopyTo(head.AsSpan(4));
        forged.Write(head);
        forged.Write(idat);
        var crc = new byte[4];
        BinaryPrimitives.WriteUInt32BigEndian(crc, Crc32.Update(Crc32.Compute("IDAT"u8), idat));
        forged.Write(crc);
        forged.Write(c.AsSpan(c.Length - 12));
        Assert.Contains("truncated or corrupt",
            Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => PngReader.Read(new MemoryStream(forged.ToArray()))).Message);
    }

    static byte[] Inflate(byte[] png)
    {
        var idat = new MemoryStream();
        for (int pos = 8; pos < png.Length;)
        {
            int len = BinaryPrimitives.ReadInt32BigEndian(png.AsSpan(pos));
            if (Encoding.ASCII.GetString(png, pos + 4, 4) == "IDAT") idat.Write(png, pos + 8, len);
            pos += 12 + len;
        }
        idat.Position = 0;
        var outp = new MemoryStream();
        using (var z = new System.IO.Compression.ZLibStream(idat, System.IO.Compression.CompressionMode.Decompress)) z.CopyTo(outp);
        return outp.ToArray();
    }

    /// <summary>§9.2 filters and §9.4 Paeth written out as the standard gives them, byte by byte, the row above as zeros when
    /// absent.</summary>
    static byte[] ReferenceFilter(int type, byte[] x, byte[]? above, int bpp)
    {
        var b = above ?? new byte[x.Length];
        var o = new byte[x.Length + 1];
        o[0] = (byte)type;
        for (int i = 0; i < x.Length; i++)
        {
            int a = i >= bpp ? x[i - bpp] : 0, c = i >= bpp ? b[i - bpp] : 0;
            int p = a + b[i] - c, pa = Math.Abs(p - a), pb = Math.Abs(p - b[i]), pc = Math.Abs(p - c);
            int paeth = pa <= pb && pa <= pc ? a : pb <= pc ? b[i] : c;
            o[i + 1] = (byte)(x[i] - type switch { 0 => 0, 1 => a, 2 => b[i], 3 => (a + b[i]) / 2, _ => paeth });
        }
        return o;
    }

    [Fact]
    public void Vector_filters_equal_the_standard_byte_by_byte()
    {
        var rng = new Random(9);
        foreach (int bpp in new[] { 1, 2, 3, 4, 6, 8 })
            foreach (int n in new[] { bpp, 5 * bpp, 31 * bpp, 64 * bpp, 100 * bpp + bpp })
            {
                var x = new byte[n]; var above = new byte[n];
                rng.NextBytes(x); rng.NextBytes(above);
                for (int i = 0; i < n / 3; i++) x[rng.Next(n)] = (byte)(rng.Next(2) * 255);   // some 0 / 255 extremes
                for (int type = 0; type < 5; type++)
                    foreach (var b in new[] { above, null })
                    {
                        var o = new byte[n + 2];
                        o[^1] = 0x5A;
                        PngWriter.FilterRow(type, x, b ?? ReadOnlySpan<byte>.Empty, bpp, o);
                        Assert.True(ReferenceFilter(type, x, b, bpp).AsSpan().SequenceEqual(o.AsSpan(0, n + 1)),
                            $"filter {type}, bpp {bpp}, {n} bytes, first row {b is null}");
                        Assert.Equal(0x5A, o[^1]);
                        long sum = 0;
                        for (int i = 1; i <= n; i++) sum += Math.Abs((int)(sbyte)o[i]);
                        Assert.Equal(sum, PngWriter.SignedAbsSum(o.AsSpan(1, n)));
                    }
            }
        var big = new byte[100_000];
        Array.Fill(big, (byte)0x80);   // |−128| everywhere: the 16-bit lanes must not wrap
        Assert.Equal(128L * big.Length, PngWriter.SignedAbsSum(big));
    }

    [Fact]
    public void Adaptive_rows_are_the_least_signed_sum_filter_of_each_row()
    {
        var rgb = Rgb();
        var ms = new MemoryStream();
        PngWriter.WriteRgb8(ms, W, H, rgb);
        var raw = Inflate(ms.ToArray());
        int rowBytes = 3 * W;
        byte[]? above = null;
        var counts = new int[5];
        for (int y = 0; y < H; y++)
        {
            var x = rgb.AsSpan(y * rowBytes, rowBytes).ToArray();
            byte[] best = null!;
            long bestSum = long.MaxValue;
            for (int f = 0; f < 5; f++)
            {
                var o = ReferenceFilter(f, x, above, 3);
                long sum = o.Skip(1).Sum(v => (long)Math.Abs((int)(sbyte)v));
                if (sum < bestSum) { bestSum = sum; best = o; }
            }
            Assert.Equal(best, raw.AsSpan(y * (rowBytes + 1), rowBytes + 1).ToArray());
            counts[best[0]]++;
            above = x;
        }
        Assert.True(counts.Count(c => c > 0) >= 2, "the test image should exercise more than one filter");
    }

    [Fact]
    public void Slicing_by_8_crc_equals_the_bitwise_definition_at_every_length_and_split()
    {
        static uint Bitwise(ReadOnlySpan<byte> data)
        {
            uint c = 0xFFFFFFFF;
            foreach (byte v in data) { c ^= v; for (int k = 0; k < 8; k++) c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1; }
            return ~c;
        }
        var rng = new Random(4);
        var data = new byte[300];
        rng.NextBytes(data);
        for (int n = 0; n <= data.Length; n++)
        {
            Assert.Equal(Bitwise(data.AsSpan(0, n)), Crc32.Compute(data.AsSpan(0, n)));
            int split = n / 3;
            Assert.Equal(Bitwise(data.AsSpan(0, n)), Crc32.Update(Crc32.Compute(data.AsSpan(0, split)), data.AsSpan(split, n - split)));
        }
    }

    static int[] FilterTypes(byte[] png, int rowBytes)
    {
        var raw = Inflate(png);
        return Enumerable.Range(0, raw.Length / (rowBytes + 1)).Select(r => (int)raw[r * (rowBytes + 1)]).ToArray();
    }
}
