using System.Buffers.Binary;
using System.IO.Compression;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Imaging;

public class ExrTests
{
    static byte[] Write(ExrOptions options)
    {
        var ms = new MemoryStream();
        ExrWriter.Write(ms, Synthetic.Image(), options with { Colorimeter = Synthetic.Colorimeter });
        return ms.ToArray();
    }

    [Theory]
    [InlineData(ExrCompression.Zip)]
    [InlineData(ExrCompression.None)]
    public void Float_round_trip_is_bit_exact(ExrCompression compression)
    {
        var img = Synthetic.Image();
        var f = ExrReader.Read(Write(new ExrOptions { Compression = compression, Xyz = true }));
        Assert.Equal((Synthetic.W, Synthetic.H), (f.Image.Width, f.Image.Height));
        Assert.Equal(BandGrid.Default, f.Image.Grid);
        Synthetic.AssertBitExact(img.Data, f.Image.Data, $"{compression} FLOAT");
        Assert.Equal((int)compression, f.Compression);
        Assert.False(f.Reflective);
        Assert.Equal(Synthetic.Colorimeter.Kappa, f.Kappa);
        Assert.Equal("1.0", f.StringAttributes["spectralLayoutVersion"]);
        Assert.Equal("W.m^-2.sr^-1", f.StringAttributes["emissiveUnits"]);
        Assert.StartsWith("380,400,420,", f.StringAttributes["spectralBandEdges"]);
        Assert.StartsWith("exact", f.StringAttributes["spectralIntegration"]);
        Assert.Equal(["B", "G", "R", "X", "Y", "Z"], f.OtherChannels.Keys.Order(StringComparer.Ordinal));

        // R, G, B are linear sRGB of each pixel's XYZ; X, Y, Z its eq. 3 tristimulus values.
        foreach (var (x, y) in new[] { (0, 0), (5, 3), (36, 22), (17, 11) })
        {
            var xyz = Synthetic.Colorimeter.ToXyz((ReadOnlySpan<float>)img.Pixel(x, y));
            var (r, g, b) = RgbSpace.Srgb.Linear(xyz);
            int i = y * Synthetic.W + x;
            Assert.Equal((float)r, f.OtherChannels["R"][i]);
            Assert.Equal((float)g, f.OtherChannels["G"][i]);
            Assert.Equal((float)b, f.OtherChannels["B"][i]);
            Assert.Equal((float)xyz.Y, f.OtherChannels["Y"][i]);
        }
    }

    [Theory]
    [InlineData(true)]
    [InlineData(false)]
    public void Uneven_grid_round_trips_with_or_without_the_edges_attribute(bool keepEdges)
    {
        var grid = new BandGrid(400, 700, 31);       // 9.677… nm bands, centres like 404,838710
        var img = Synthetic.Image(grid);
        var ms = new MemoryStream();
        ExrWriter.Write(ms, img, new ExrOptions { Rgb = false });
        var bytes = ms.ToArray();
        Assert.Equal("S0.404,838710nm", ExrWriter.SpectralChannelName(grid.Centre(0)));
        if (!keepEdges)
        {   // Rename the attribute so the reader must infer the grid from the channel names.
            int at = ExrTests.IndexOf(bytes, "spectralBandEdges\0"u8);
            bytes[at] = (byte)'x';
        }
        var f = ExrReader.Read(bytes);
        Assert.Equal(keepEdges, f.StringAttributes.ContainsKey("spectralBandEdges"));
        Assert.Equal(grid, f.Image.Grid);
        Synthetic.AssertBitExact(img.Data, f.Image.Data, "31 bands");
    }

    [Fact]
    public void Zip_and_uncompressed_files_read_back_identical()
    {
        var zip = Write(new ExrOptions { Compression = ExrCompression.Zip, DeflateEveryChunk = true });
        var none = Write(new ExrOptions { Compression = ExrCompression.None });
        Assert.True(zip.Length < 0.9 * none.Length, $"ZIP {zip.Length} B is not 10% smaller than NONE {none.Length} B");
        var a = ExrReader.Read(zip);
        var b = ExrReader.Read(none);
        Synthetic.AssertBitExact(b.Image.Data, a.Image.Data, "ZIP vs NONE");
        foreach (var c in b.OtherChannels.Keys) Synthetic.AssertBitExact(b.OtherChannels[c], a.OtherChannels[c], c);
    }

    [Fact]
    public void Half_round_trip_is_within_half_precision()
    {
        var img = Synthetic.Image();
        var f = ExrReader.Read(Write(new ExrOptions { PixelType = ExrPixelType.Half }));
        Assert.All(f.ChannelTypes.Values, t => Assert.Equal(ExrPixelType.Half, t));
        int normal = 0;
        for (int i = 0; i < img.Data.Length; i++)
        {
            float v = img.Data[i], h = f.Image.Data[i];
            Assert.Equal((float)(Half)v, h);                           // exactly the correctly rounded half
            if (v >= 6.103515625e-5f && v <= 65504f)
            {
                Assert.True(Math.Abs(h - v) <= v * Math.Pow(2, -11), $"{v} read back as {h}");
                normal++;
            }
            else if (v > 65520f) Assert.True(float.IsPositiveInfinity(h));
            else if (v < 2.98e-8f) Assert.Equal(0f, h);
            else Assert.True(Math.Abs(h - v) <= Math.Pow(2, -25), $"subnormal {v} read back as {h}");
        }
        Assert.True(normal > img.Data.Length / 2);
    }

    [Fact]
    public void Float_to_half_rounds_to_nearest_even()
    {
        // Ties to even at 2048 (spacing 2), overflow past 65504 + 16, subnormals at 2^-24.
        Assert.Equal(2048f, (float)(Half)2049f);
        Assert.Equal(2052f, (float)(Half)2051f);
        Assert.Equal(65504f, (float)(Half)65519.99f);
        Assert.True(float.IsPositiveInfinity((float)(Half)65520f));
        Assert.Equal(0f, (float)(Half)MathF.Pow(2, -25));                 // tie between 0 and 2^-24 → 0 (even)
        Assert.Equal(MathF.Pow(2, -23), (float)(Half)(3 * MathF.Pow(2, -25)));  // tie 2^-24·1.5 → 2^-23 (even)
        Assert.Equal(1f + 1f / 1024, (float)(Half)(1f + 1.5f / 2048));
    }

    [Fact]
    public void Channel_names_follow_the_JCGT_2021_layout_sorted_by_name()
    {
        Assert.Equal("S0.390,000000nm", ExrWriter.SpectralChannelName(390));
        Assert.Equal("S0.412,500000nm", ExrWriter.SpectralChannelName(412.5));
        Assert.Equal("T.770,000000nm", ExrWriter.SpectralChannelName(770, reflective: true));
        var names = ChannelNames(Write(new ExrOptions { Xyz = true }));
        var expected = new[] { "B", "G", "R" }
            .Concat(Enumerable.Range(0, 20).Select(b => $"S0.{390 + 20 * b},000000nm")).Concat(["X", "Y", "Z"]).ToArray();
        Assert.Equal(expected, names);
    }

    [Fact]
    public void Reflective_cube_uses_T_channels_and_no_emissive_units()
    {
        var f = ExrReader.Read(Write(new ExrOptions { Reflective = true, Rgb = false }));
        Assert.True(f.Reflective);
        Assert.False(f.StringAttributes.ContainsKey("emissiveUnits"));
        Assert.Empty(f.OtherChannels);
        Assert.Contains("T.390,000000nm", f.ChannelTypes.Keys);
        Synthetic.AssertBitExact(Synthetic.Image().Data, f.Image.Data, "reflective");
    }

    [Fact]
    public void Layout_has_magic_version_offset_table_and_16_line_zip_chunks()
    {
        var b = Write(new ExrOptions());
        Assert.Equal(20000630, BinaryPrimitives.ReadInt32LittleEndian(b));
        Assert.Equal(2, BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(4)));
        var (tableAt, _) = HeaderEnd(b);
        long first = BinaryPrimitives.ReadInt64LittleEndian(b.AsSpan(tableAt));
        long second = BinaryPrimitives.ReadInt64LittleEndian(b.AsSpan(tableAt + 8));
        Assert.Equal(tableAt + 16, first);                              // 23 lines → 2 chunks
        Assert.Equal(0, BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)first)));
        Assert.Equal(16, BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)second)));
        int size1 = BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)first + 4));
        Assert.Equal(second, first + 8 + size1);
        Assert.Equal(b.Length, second + 8 + BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)second + 4)));

        var none = Write(new ExrOptions { Compression = ExrCompression.None });
        var (tableNone, _) = HeaderEnd(none);
        long c5 = BinaryPrimitives.ReadInt64LittleEndian(none.AsSpan(tableNone + 5 * 8));
        Assert.Equal(5, BinaryPrimitives.ReadInt32LittleEndian(none.AsSpan((int)c5)));
        Assert.Equal(23 * 4 * Synthetic.W, BinaryPrimitives.ReadInt32LittleEndian(none.AsSpan((int)c5 + 4)));  // 23 channels × W floats
        // Scanline 5, first channel (B), pixel 0, then the first spectral channel at offset 3·W.
        var img = Synthetic.Image();
        Assert.Equal(img[0, 5, 0], BinaryPrimitives.ReadSingleLittleEndian(none.AsSpan((int)c5 + 8 + 3 * Synthetic.W * 4)));
        Assert.Equal(img[4, 5, 1], BinaryPrimitives.ReadSingleLittleEndian(none.AsSpan((int)c5 + 8 + (4 * Synthetic.W + 4) * 4)));
    }

    [Fact]
    public void Zip_predictor_reorders_then_deltas_as_ImfZip()
    {
        byte[] raw = [1, 2, 3, 4, 250, 7];
        // Reorder → 1 3 250 | 2 4 7; delta d[i] = t[i] − t[i−1] + 128 (mod 256).
        byte[] expected = [1, 130, 119, 136, 130, 131];  // 250−3+128 = 375 → 119; 2−250+128+256 = 136
        var z = ExrZip.Compress(raw);
        var inflated = new MemoryStream();
        using (var s = new ZLibStream(new MemoryStream(z), CompressionMode.Decompress)) s.CopyTo(inflated);
        Assert.Equal(expected, inflated.ToArray());
        var back = new byte[raw.Length];
        Assert.True(ExrZip.TryDecompress(z, back));
        Assert.Equal(raw, back);
    }

    [Fact]
    public void Incompressible_zip_chunks_are_stored_raw_and_read_back()
    {
        var rng = new Random(7);
        var img = new global::SpectralRenderer.Spectra.SpectralImage(Synthetic.W, Synthetic.H, BandGrid.Default);
        for (int i = 0; i < img.Data.Length; i++) img.Data[i] = BitConverter.Int32BitsToSingle(rng.Next(0, 0x7f000000));
        var ms = new MemoryStream();
        ExrWriter.Write(ms, img, new ExrOptions { Rgb = false });
        var b = ms.ToArray();
        var (tableAt, _) = HeaderEnd(b);
        long first = BinaryPrimitives.ReadInt64LittleEndian(b.AsSpan(tableAt));
        Assert.Equal(16 * 20 * Synthetic.W * 4, BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)first + 4)));
        Synthetic.AssertBitExact(img.Data, ExrReader.Read(b).Image.Data, "raw chunks");
    }

    [Fact]
    public void Bad_files_are_input_errors()
    {
        var good = Write(new ExrOptions());
        var e = Assert.Throws<InputException>(() => ExrReader.Read("P6 not an exr"u8.ToArray(), "x.exr"));
        Assert.Contains("x.exr: byte 0: not an OpenEXR file", e.Message);
        e = Assert.Throws<InputException>(() => ExrReader.Read(good[..(good.Length - 100)], "t.exr"));
        Assert.Contains("truncated", e.Message);
        e = Assert.Throws<InputException>(() => ExrReader.Read(good[..300], "h.exr"));
        Assert.Contains("truncated", e.Message);
        var piz = (byte[])good.Clone();
        int at = IndexOf(piz, "compression\0compression\0"u8) + 24 + 4;
        piz[at] = 4;
        e = Assert.Throws<InputException>(() => ExrReader.Read(piz, "p.exr"));
        Assert.Contains("PIZ is not supported", e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }

    [Fact]
    public void Writing_a_file_is_atomic_and_validates_options()
    {
        var dir = Reference.TempDir();
        var path = Path.Combine(dir, "spectral.exr");
        ExrWriter.Write(path, Synthetic.Image(), new ExrOptions { Colorimeter = Synthetic.Colorimeter });
        Assert.Equal(new[] { path }, Directory.GetFiles(dir));
        Synthetic.AssertBitExact(Synthetic.Image().Data, ExrReader.Read(path).Image.Data, "file");
        Assert.Throws<ArgumentException>(() => ExrWriter.Write(Path.Combine(dir, "x.exr"), Synthetic.Image()));  // RGB needs a colorimeter
        Assert.Equal(new[] { path }, Directory.GetFiles(dir));
    }

    /// <summary>The predictor as ImfZip.cpp writes it: reorder into even then odd bytes, then delta + 128.</summary>
    static byte[] ReferencePredict(byte[] raw)
    {
        int n = raw.Length, half = (n + 1) / 2;
        var t = new byte[n];
        for (int i = 0; i < n; i++) t[i % 2 == 0 ? i / 2 : half + i / 2] = raw[i];
        var d = (byte[])t.Clone();
        for (int i = 1; i < n; i++) d[i] = (byte)(t[i] - t[i - 1] + 128);
        return d;
    }

    [Fact]
    public void Fused_vector_predictor_equals_the_reference_for_every_length()
    {
        var rng = new Random(11);
        foreach (int n in Enumerable.Range(0, 80).Concat([127, 128, 129, 1000, 1001, 4099]))
        {
            var raw = new byte[n];
            rng.NextBytes(raw);
            var d = new byte[n + 3];
            d.AsSpan().Fill(0xEE);
            ExrZip.Predict(raw, d);
            Assert.Equal(ReferencePredict(raw), d[..n]);
            Assert.All(d[n..], b => Assert.Equal(0xEE, b));   // nothing written past the chunk
            var back = new byte[n];
            Assert.True(ExrZip.TryDecompress(ExrZip.Compress(raw), back));
            Assert.Equal(raw, back);
        }
    }

    [Fact]
    public void Repeat_fraction_counts_samples_equal_to_the_one_before()
    {
        uint[] words = [1, 1, 2, 2, 2, 3];   // 3 of 5 follow an equal sample
        Assert.Equal(0.6, ExrZip.RepeatFraction(System.Runtime.InteropServices.MemoryMarshal.AsBytes(words.AsSpan()), 4), 12);
        Assert.Equal(0.0, ExrZip.RepeatFraction(new byte[] { 1, 0, 2, 0 }, 2));
        // Long buffers take the vector path: compare with a plain count, for 4- and 2-byte samples.
        var rng = new Random(3);
        var raw = new byte[4 * 100_003];
        for (int i = 0; i < raw.Length; i += 4) if (rng.Next(3) != 0) rng.NextBytes(raw.AsSpan(i, 4));
        else raw.AsSpan(i - (i > 0 ? 4 : 0), 4).CopyTo(raw.AsSpan(i));
        foreach (int size in new[] { 4, 2 })
        {
            int samples = raw.Length / size, repeats = 0;
            for (int i = 1; i < samples; i++) if (raw.AsSpan(i * size, size).SequenceEqual(raw.AsSpan((i - 1) * size, size))) repeats++;
            Assert.Equal(repeats / (double)(samples - 1), ExrZip.RepeatFraction(raw, size), 12);
            if (size == 4) Assert.InRange(repeats / (double)(samples - 1), 0.2, 0.5);   // a third of the floats copy their neighbour
        }
    }

    /// <summary>The pixel-data size of every chunk, by walking the offset table.</summary>
    static List<int> ChunkSizes(byte[] b)
    {
        var (tableAt, _) = HeaderEnd(b);
        long first = BinaryPrimitives.ReadInt64LittleEndian(b.AsSpan(tableAt));
        int count = (int)((first - tableAt) / 8);
        return Enumerable.Range(0, count)
            .Select(c => BinaryPrimitives.ReadInt32LittleEndian(
                b.AsSpan((int)BinaryPrimitives.ReadInt64LittleEndian(b.AsSpan(tableAt + 8 * c)) + 4)))
            .ToList();
    }

    [Fact]
    public void Zip_deflates_repetitive_chunks_and_stores_noisy_ones_and_both_read_back_exactly()
    {
        // 64 × 40: the top 32 rows constant per 16-pixel block (like ground truth over objects), the bottom 8 rows noise.
        const int w = 64, h = 40;
        var rng = new Random(5);
        var img = new global::SpectralRenderer.Spectra.SpectralImage(w, h, BandGrid.Default);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < 20; b++)
                    img[x, y, b] = y < 32 ? 0.05f * (x / 16 + 1) + 0.01f * b : (float)rng.NextDouble();
        int raw16 = 16 * 20 * w * 4;   // one full chunk: 16 lines × 20 channels × 64 floats
        foreach (bool everyChunk in new[] { false, true })
        {
            var ms = new MemoryStream();
            ExrWriter.Write(ms, img, new ExrOptions { Rgb = false, DeflateEveryChunk = everyChunk });
            var bytes = ms.ToArray();
            var sizes = ChunkSizes(bytes);
            Assert.Equal(3, sizes.Count);
            Assert.All(sizes.Take(2), size => Assert.True(size < raw16 / 20, $"constant chunk of {size} B not deflated"));
            // Noise does not deflate: stored raw either way (the 8-line last chunk), deflate tried only when asked.
            Assert.Equal(8 * 20 * w * 4, sizes[2]);
            var back = ExrReader.Read(bytes);
            Synthetic.AssertBitExact(img.Data, back.Image.Data, $"everyChunk {everyChunk}");
        }
    }

    internal static int IndexOf(byte[] hay, ReadOnlySpan<byte> needle) => hay.AsSpan().IndexOf(needle);

    /// <summary>Offset of the line offset table, and the channel list, by walking the header.</summary>
    internal static (int TableAt, List<string> Channels) HeaderEnd(byte[] b)
    {
        int pos = 8;
        var channels = new List<string>();
        while (b[pos] != 0)
        {
            string name = CString(b, ref pos), type = CString(b, ref pos);
            int size = BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(pos));
            pos += 4;
            if (type == "chlist")
                for (int p = pos; b[p] != 0; p += 16) channels.Add(CString(b, ref p));
            pos += size;
        }
        return (pos + 1, channels);
    }

    static List<string> ChannelNames(byte[] b) => HeaderEnd(b).Channels;

    static string CString(byte[] b, ref int pos)
    {
        int end = Array.IndexOf(b, (byte)0, pos);
        var s = System.Text.Encoding.ASCII.GetString(b, pos, end - pos);
        pos = end + 1;
        return s;
    }
}
