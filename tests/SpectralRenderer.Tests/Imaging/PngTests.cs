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
        PngWriter.WriteRgb8(ms, W, H, rgb, new Dictionary<string, string> { ["Software"] = "SpectralRenderer", ["Comment"] = "bands 380:780:20" }, filter);
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
        Assert.Contains("truncated or corrupt", Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => PngReader.Read(new MemoryStream(forged.ToArray()))).Message);
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

    static int[] FilterTypes(byte[] png, int rowBytes)
    {
        var raw = Inflate(png);
        return Enumerable.Range(0, raw.Length / (rowBytes + 1)).Select(r => (int)raw[r * (rowBytes + 1)]).ToArray();
    }
}
