using System.Buffers.Binary;
using System.IO.Compression;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>
/// The PNG reader on the colour types textures come in besides ours (ISO/IEC 15948): palette images with PLTE and tRNS at
/// 1–8 bits, grey at 1–4 bits, grey + alpha and RGBA at 8 and 16 bits, and tRNS on grey and RGB. Each file is assembled here
/// byte by byte from scanlines packed by hand (the bits written out literally), so the expected pixels are the values put in.
/// </summary>
public class PngPaletteAlphaTests
{
    static byte[] Chunk(string type, byte[] data)
    {
        var o = new byte[12 + data.Length];
        BinaryPrimitives.WriteInt32BigEndian(o, data.Length);
        Encoding.ASCII.GetBytes(type).CopyTo(o, 4);
        data.CopyTo(o, 8);
        BinaryPrimitives.WriteUInt32BigEndian(o.AsSpan(8 + data.Length), Crc32.Compute(o.AsSpan(4, 4 + data.Length)));
        return o;
    }

    /// <summary>A PNG of the given scanlines (each starting with its filter byte) and extra chunks before IDAT.</summary>
    static PngImage Png(int w, int h, int depth, int type, byte[][] rows, params (string Type, byte[] Data)[] extra)
    {
        var ihdr = new byte[13];
        BinaryPrimitives.WriteInt32BigEndian(ihdr, w);
        BinaryPrimitives.WriteInt32BigEndian(ihdr.AsSpan(4), h);
        ihdr[8] = (byte)depth;
        ihdr[9] = (byte)type;
        var z = new MemoryStream();
        using (var zs = new ZLibStream(z, CompressionLevel.Optimal, true)) foreach (var r in rows) zs.Write(r);
        var file = new MemoryStream();
        file.Write([0x89, (byte)'P', (byte)'N', (byte)'G', 13, 10, 26, 10]);
        file.Write(Chunk("IHDR", ihdr));
        foreach (var (t, d) in extra) file.Write(Chunk(t, d));
        file.Write(Chunk("IDAT", z.ToArray()));
        file.Write(Chunk("IEND", []));
        file.Position = 0;
        return PngReader.Read(file, "test.png");
    }

    [Fact]
    public void A_4_bit_palette_image_with_tRNS_expands_to_rgb_and_alpha()
    {
        // 3 × 2 pixels, 4 bits: row 0 indices 0 1 2 (0x01, 0x20), row 1 indices 2 2 0 with the Sub filter on bytes: raw
        // 0x22, 0x00 → written 0x22, 0x00 − 0x22 = 0xDE.
        byte[] plte = [255, 0, 0, 0, 128, 0, 10, 20, 30];
        byte[] trns = [0, 200];   // index 0 transparent, 1 at 200, 2 (absent) opaque
        var png = Png(3, 2, 4, 3, [[0, 0x01, 0x20], [1, 0x22, 0xDE]], ("PLTE", plte), ("tRNS", trns));
        Assert.Equal((3, 8, 3), (png.Channels, png.BitDepth, png.ColourType));
        ushort[] rgb = [255, 0, 0, 0, 128, 0, 10, 20, 30, 10, 20, 30, 10, 20, 30, 255, 0, 0];
        Assert.Equal(rgb, png.Samples);
        Assert.Equal(new ushort[] { 0, 200, 255, 255, 255, 0 }, png.Alpha);
    }

    [Fact]
    public void One_bit_palette_and_two_bit_grey_unpack_from_the_high_bit()
    {
        // 10 pixels of 1 bit: 1011001110 → 0b10110011, 0b10000000.
        var palette = Png(10, 1, 1, 3, [[0, 0b1011_0011, 0b1000_0000]], ("PLTE", new byte[] { 0, 0, 0, 255, 255, 255 }));
        Assert.Equal(new[] { 1, 0, 1, 1, 0, 0, 1, 1, 1, 0 }, Enumerable.Range(0, 10).Select(i => palette.Samples[3 * i] / 255));
        Assert.Null(palette.Alpha);
        // 5 pixels of 2 bits: 3 0 2 1 3 → 0b11_00_10_01, 0b11_000000; grey keeps its depth (codes 0 … 3).
        var grey = Png(5, 1, 2, 0, [[0, 0b1100_1001, 0b1100_0000]]);
        Assert.Equal((1, 2), (grey.Channels, grey.BitDepth));
        Assert.Equal(new ushort[] { 3, 0, 2, 1, 3 }, grey.Samples);
    }

    [Fact]
    public void Alpha_channels_and_tRNS_colours_give_the_alpha_plane()
    {
        var ga = Png(2, 1, 8, 4, [[0, 50, 255, 60, 0]]);
        Assert.Equal(1, ga.Channels);
        Assert.Equal(new ushort[] { 50, 60 }, ga.Samples);
        Assert.Equal(new ushort[] { 255, 0 }, ga.Alpha);
        var rgba16 = Png(1, 1, 16, 6, [[0, 0x12, 0x34, 0, 1, 0xFF, 0xFF, 0x80, 0x00]]);
        Assert.Equal(new ushort[] { 0x1234, 1, 0xFFFF }, rgba16.Samples);
        Assert.Equal(new ushort[] { 0x8000 }, rgba16.Alpha);
        // tRNS on RGB: the colour (1, 2, 3) (16-bit fields) is transparent, any other opaque.
        var keyed = Png(2, 1, 8, 2, [[0, 1, 2, 3, 1, 2, 4]], ("tRNS", new byte[] { 0, 1, 0, 2, 0, 3 }));
        Assert.Equal(new ushort[] { 0, 255 }, keyed.Alpha);
    }

    [Fact]
    public void A_palette_index_past_the_palette_and_an_invalid_depth_are_one_line()
    {
        var ex = Assert.Throws<InputException>(() => Png(1, 1, 8, 3, [[0, 5]], ("PLTE", new byte[] { 1, 2, 3 })));
        Assert.Contains("palette index 5 past the 1 entries", ex.Message);
        ex = Assert.Throws<InputException>(() => Png(1, 1, 4, 2, [[0, 0]]));
        Assert.Contains("colour type 2 at 4 bits", ex.Message);
        ex = Assert.Throws<InputException>(() => Png(1, 1, 8, 3, [[0, 0]]));
        Assert.Contains("without a PLTE chunk", ex.Message);
    }
}
