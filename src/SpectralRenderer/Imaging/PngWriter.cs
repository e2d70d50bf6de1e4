using System.Buffers;
using System.Buffers.Binary;
using System.IO.Compression;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;

namespace SpectralRenderer.Imaging;

/// <summary>The per-row filter (PNG spec, 3rd ed., §9.2); <see cref="Adaptive"/> picks one per row.</summary>
public enum PngFilter
{
    None = 0,
    Sub = 1,
    Up = 2,
    Average = 3,
    Paeth = 4,
    /// <summary>Per row, the filter whose output has the smallest sum of absolute values taken as signed bytes (§12.7 heuristic).</summary>
    Adaptive = 5,
}

/// <summary>
/// A minimal PNG encoder (W3C PNG Specification, 3rd edition): non-interlaced 8- and 16-bit RGB (colour type 2),
/// 8- and 16-bit greyscale (colour type 0), chunks IHDR, optional tEXt, IDAT, IEND.
/// </summary>
public static class PngWriter
{
    /// <summary>§5.2: the eight-byte PNG signature.</summary>
    internal static ReadOnlySpan<byte> Signature => [0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A];

    /// <summary>IDAT payloads are split at this size (§11.2.4: any split is allowed).</summary>
    const int IdatSize = 1 << 20;

    /// <summary>8-bit RGB, <paramref name="rgb"/> is width·height·3 bytes, rows top to bottom.</summary>
    public static void WriteRgb8(Stream stream, int width, int height, ReadOnlySpan<byte> rgb,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive, bool huffmanOnly = false)
    {
        Check(width, height, rgb.Length, 3);
        Write(stream, width, height, 8, 2, 3, rgb, text, filter, huffmanOnly: huffmanOnly);
    }

    /// <summary>8-bit greyscale, one byte per pixel.</summary>
    public static void WriteGray8(Stream stream, int width, int height, ReadOnlySpan<byte> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive, bool huffmanOnly = false)
    {
        Check(width, height, gray.Length, 1);
        Write(stream, width, height, 8, 0, 1, gray, text, filter, huffmanOnly: huffmanOnly);
    }

    /// <summary>16-bit greyscale; samples are stored big-endian as §7.1 requires.</summary>
    public static void WriteGray16(Stream stream, int width, int height, ReadOnlySpan<ushort> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive, bool huffmanOnly = false)
    {
        Check(width, height, gray.Length, 1);
        Write(stream, width, height, 16, 0, 2, BigEndian(gray), text, filter, huffmanOnly: huffmanOnly);
    }

    /// <summary>
    /// 16-bit greyscale from samples already big-endian (§7.1), two bytes per pixel; with <paramref name="gamma"/> a gAMA
    /// chunk (§11.3.3.2: the encoding exponent × 100000; 1 = linear samples) and with <paramref name="text"/> tEXt chunks.
    /// </summary>
    internal static void WriteGray16BigEndian(Stream stream, int width, int height, ReadOnlySpan<byte> samples, PngFilter filter,
        IReadOnlyDictionary<string, string>? text = null, double? gamma = null, bool huffmanOnly = false)
    {
        Check(width, height, samples.Length, 2);
        Write(stream, width, height, 16, 0, 2, samples, text, filter, gamma, huffmanOnly);
    }

    /// <summary>16-bit RGB, width·height·3 samples, stored big-endian (§7.1).</summary>
    public static void WriteRgb16(Stream stream, int width, int height, ReadOnlySpan<ushort> rgb,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        Check(width, height, rgb.Length, 3);
        Write(stream, width, height, 16, 2, 6, BigEndian(rgb), text, filter);
    }

    static byte[] BigEndian(ReadOnlySpan<ushort> samples)
    {
        var bytes = new byte[samples.Length * 2];
        if (BitConverter.IsLittleEndian) BinaryPrimitives.ReverseEndianness(samples, MemoryMarshal.Cast<byte, ushort>(bytes.AsSpan()));
        else samples.CopyTo(MemoryMarshal.Cast<byte, ushort>(bytes.AsSpan()));
        return bytes;
    }

    public static void WriteRgb16(string path, int width, int height, ReadOnlySpan<ushort> rgb,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        var ms = new MemoryStream();
        WriteRgb16(ms, width, height, rgb, text, filter);
        AtomicFile.Write(path, ms.WriteTo);
    }

    public static void WriteRgb8(string path, int width, int height, ReadOnlySpan<byte> rgb,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        var ms = new MemoryStream();
        WriteRgb8(ms, width, height, rgb, text, filter);
        AtomicFile.Write(path, ms.WriteTo);
    }

    public static void WriteGray8(string path, int width, int height, ReadOnlySpan<byte> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        var ms = new MemoryStream();
        WriteGray8(ms, width, height, gray, text, filter);
        AtomicFile.Write(path, ms.WriteTo);
    }

    public static void WriteGray16(string path, int width, int height, ReadOnlySpan<ushort> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        var ms = new MemoryStream();
        WriteGray16(ms, width, height, gray, text, filter);
        AtomicFile.Write(path, ms.WriteTo);
    }

    static void Check(int width, int height, int length, int samples)
    {
        // §11.2.1: width and height are 1 … 2³¹−1.
        if (width < 1 || height < 1) throw new ArgumentOutOfRangeException(nameof(width), $"image size {width}×{height} is empty");
        if ((long)width * height * samples != length)
            throw new ArgumentException($"pixel buffer has {length} samples, {width}×{height}×{samples} expected");
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Write(Stream stream, int width, int height, byte bitDepth, byte colourType, int bpp,
        ReadOnlySpan<byte> pixels, IReadOnlyDictionary<string, string>? text, PngFilter filter, double? gamma = null,
            bool huffmanOnly = false)
    {
        stream.Write(Signature);

        // §11.2.1 IHDR: width, height, bit depth, colour type, compression 0, filter 0, interlace 0.
        Span<byte> ihdr = stackalloc byte[13];
        BinaryPrimitives.WriteInt32BigEndian(ihdr, width);
        BinaryPrimitives.WriteInt32BigEndian(ihdr[4..], height);
        ihdr[8] = bitDepth; ihdr[9] = colourType; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
        WriteChunk(stream, "IHDR", ihdr);

        // §11.3.3.2 gAMA (before IDAT): the image gamma × 100000 as a 4-byte unsigned integer.
        if (gamma is { } gm)
        {
            Span<byte> g = stackalloc byte[4];
            BinaryPrimitives.WriteUInt32BigEndian(g, (uint)Math.Round(gm * 100000));
            WriteChunk(stream, "gAMA", g);
        }

        // §11.3.3.2 tEXt: Latin-1 keyword (1–79 bytes), a null separator, Latin-1 text.
        if (text is not null)
            foreach (var (key, value) in text)
            {
                if (key.Length is < 1 or > 79 || key.Any(c => c < 32 || c > 255) || key.StartsWith(' ') || key.EndsWith(' '))
                    throw new ArgumentException($"PNG tEXt keyword '{key}' must be 1–79 printable Latin-1 characters");
                var latin1 = Encoding.Latin1;
                var payload = new byte[key.Length + 1 + latin1.GetByteCount(value)];
                latin1.GetBytes(key, payload);
                latin1.GetBytes(value, payload.AsSpan(key.Length + 1));
                WriteChunk(stream, "tEXt", payload);
            }

        // §7.3 / §9: each scanline is a filter-type byte followed by the filtered row;
        // §10: the filtered scanlines form one zlib datastream (RFC 1950) split over IDAT chunks.
        // Rows are filtered in batches of about 1 MiB, each handed to zlib in one call.
        int rowBytes = checked(width * bpp), stride = rowBytes + 1;
        int batchRows = Math.Clamp((1 << 20) / stride, 1, height);
        var batch = ArrayPool<byte>.Shared.Rent(checked(batchRows * stride));
        var scratch = filter == PngFilter.Adaptive ? ArrayPool<byte>.Shared.Rent(2 * stride) : null;
        var zlibData = huffmanOnly ? null : new MemoryStream((int)Math.Min(int.MaxValue / 2, (long)height * stride / 4 + 256));
        var huffman = huffmanOnly ? new HuffmanDeflate() : null;
        try
        {
            using (var z = zlibData is null ? null : new ZLibStream(zlibData, CompressionLevel.Fastest, leaveOpen: true))
            {
                for (int y0 = 0; y0 < height; y0 += batchRows)
                {
                    int rows = Math.Min(batchRows, height - y0);
                    for (int r = 0; r < rows; r++)
                    {
                        int y = y0 + r;
                        var row = pixels.Slice(y * rowBytes, rowBytes);
                        // §9.2: the row above the first is all zeros
                        var prior = y == 0 ? ReadOnlySpan<byte>.Empty : pixels.Slice((y - 1) * rowBytes, rowBytes);
                        var output = batch.AsSpan(r * stride, stride);
                        if (filter == PngFilter.Adaptive) FilterAdaptive(row, prior, bpp, output, scratch!);
                        else FilterRow((int)filter, row, prior, bpp, output);
                    }
                    if (z is not null) z.Write(batch, 0, rows * stride);
                    else
                    {
                        // One deflate block of its own Huffman code per batch, its bytes one IDAT chunk (§11.2.4: any split is allowed).
                        var bytes = huffman!.Block(batch.AsSpan(0, rows * stride), final: y0 + rows == height);
                        if (bytes.Length > 0) WriteChunk(stream, "IDAT", bytes);
                    }
                }
            }
        }
        finally
        {
            ArrayPool<byte>.Shared.Return(batch);
            if (scratch is not null) ArrayPool<byte>.Shared.Return(scratch);
            huffman?.Dispose();
        }
        if (zlibData is not null)
        {
            var data = zlibData.GetBuffer().AsSpan(0, (int)zlibData.Length);
            int at = 0;
            do
            {
                WriteChunk(stream, "IDAT", data.Slice(at, Math.Min(IdatSize, data.Length - at)));
                at += IdatSize;
            } while (at < data.Length);
        }
        WriteChunk(stream, "IEND", []);
    }

    /// <summary>
    /// §12.7 heuristic: the filter whose output has the least sum of absolute values, bytes taken as signed; the first
    /// of equal sums wins (None, Sub, Up, Average, Paeth). The best so far is kept in <paramref name="output"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void FilterAdaptive(ReadOnlySpan<byte> row, ReadOnlySpan<byte> prior, int bpp, Span<byte> output, byte[] scratch)
    {
        int stride = row.Length + 1;
        FilterRow(0, row, prior, bpp, output);
        long bestSum = SignedAbsSum(output[1..]);
        var candidate = scratch.AsSpan(0, stride);
        for (int f = 1; f < 5; f++)
        {
            FilterRow(f, row, prior, bpp, candidate);
            long sum = SignedAbsSum(candidate[1..]);
            if (sum < bestSum) { bestSum = sum; candidate.CopyTo(output); }
        }
    }

    /// <summary>Σ |(sbyte) b|.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static long SignedAbsSum(ReadOnlySpan<byte> bytes)
    {
        long sum = 0;
        int i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var signed = MemoryMarshal.Cast<byte, sbyte>(bytes);
            var acc = Vector<ushort>.Zero;   // each step adds at most 2 · 128 per lane: flush every 255 steps
            for (int steps = 0; i + Vector<sbyte>.Count <= signed.Length; i += Vector<sbyte>.Count)
            {
                // |−128| = 128 still fits the byte read as unsigned
                Vector.Widen(Vector.AsVectorByte(Vector.Abs(new Vector<sbyte>(signed[i..]))), out var lo, out var hi);
                acc += lo + hi;
                if (++steps == 255) { sum += Total(acc); acc = Vector<ushort>.Zero; steps = 0; }
            }
            sum += Total(acc);
        }
        for (; i < bytes.Length; i++) sum += Math.Abs((int)(sbyte)bytes[i]);
        return sum;

        static long Total(Vector<ushort> v)
        {
            Vector.Widen(v, out var lo, out var hi);
            return Vector.Sum(lo + hi);
        }
    }

    /// <summary>§9.2: filter types 0–4 on one row (<paramref name="b"/>, the row above, is empty for the first row: zeros); out[0] receives
    /// the type byte.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void FilterRow(int type, ReadOnlySpan<byte> x, ReadOnlySpan<byte> b, int bpp, Span<byte> output)
    {
        output[0] = (byte)type;
        var o = output.Slice(1, x.Length);
        if (b.IsEmpty && type >= 2)
        {
            // First row: Up is None, Average is x − floor(a / 2), Paeth is Sub (the predictor of (a, 0, 0) is a).
            if (type == 2) { x.CopyTo(o); return; }
            if (type == 4) { Sub(x, bpp, o); return; }
            for (int i = 0; i < x.Length; i++) o[i] = (byte)(x[i] - (i >= bpp ? x[i - bpp] : 0) / 2);
            return;
        }
        int n = x.Length, v = 0;
        switch (type)
        {
            case 0:
                x.CopyTo(o);
                break;
            case 1: // Sub: x − a
                Sub(x, bpp, o);
                break;
            case 2: // Up: x − b
                if (Vector.IsHardwareAccelerated)
                    for (; v + Vector<byte>.Count <= n; v += Vector<byte>.Count)
                        (new Vector<byte>(x[v..]) - new Vector<byte>(b[v..])).CopyTo(o[v..]);
                for (int i = v; i < n; i++) o[i] = (byte)(x[i] - b[i]);
                break;
            case 3: // Average: x − floor((a + b) / 2); floor((a + b) / 2) = (a & b) + ((a ^ b) >> 1) without overflow
                for (int i = 0; i < Math.Min(bpp, n); i++) o[i] = (byte)(x[i] - b[i] / 2);
                v = bpp;
                if (Vector.IsHardwareAccelerated)
                    for (; v + Vector<byte>.Count <= n; v += Vector<byte>.Count)
                    {
                        Vector<byte> a = new(x[(v - bpp)..]), up = new(b[v..]);
                        (new Vector<byte>(x[v..]) - ((a & up) + Vector.ShiftRightLogical(a ^ up, 1))).CopyTo(o[v..]);
                    }
                for (int i = v; i < n; i++) o[i] = (byte)(x[i] - (x[i - bpp] + b[i]) / 2);
                break;
            case 4: // Paeth: x − PaethPredictor(a, b, c)
                for (int i = 0; i < Math.Min(bpp, n); i++) o[i] = (byte)(x[i] - b[i]);   // a = c = 0: the predictor is b
                v = bpp;
                if (Vector.IsHardwareAccelerated)
                    for (; v + Vector<byte>.Count <= n; v += Vector<byte>.Count)
                    {
                        Vector.Widen(new Vector<byte>(x[(v - bpp)..]), out var a0, out var a1);
                        Vector.Widen(new Vector<byte>(b[v..]), out var b0, out var b1);
                        Vector.Widen(new Vector<byte>(b[(v - bpp)..]), out var c0, out var c1);
                        var predictor = Vector.Narrow(PaethVector(a0, b0, c0), PaethVector(a1, b1, c1));
                        (new Vector<byte>(x[v..]) - predictor).CopyTo(o[v..]);
                    }
                for (int i = v; i < n; i++) o[i] = (byte)(x[i] - Paeth(x[i - bpp], b[i], b[i - bpp]));
                break;
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Sub(ReadOnlySpan<byte> x, int bpp, Span<byte> o)
    {
        int n = x.Length, v = Math.Min(bpp, n);
        x[..v].CopyTo(o);
        if (Vector.IsHardwareAccelerated)
            for (; v + Vector<byte>.Count <= n; v += Vector<byte>.Count)
                (new Vector<byte>(x[v..]) - new Vector<byte>(x[(v - bpp)..])).CopyTo(o[v..]);
        for (int i = v; i < n; i++) o[i] = (byte)(x[i] - x[i - bpp]);
    }

    /// <summary><see cref="Paeth"/> on 16-bit lanes holding bytes.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector<ushort> PaethVector(Vector<ushort> a, Vector<ushort> b, Vector<ushort> c)
    {
        Vector<short> sa = Vector.AsVectorInt16(a), sb = Vector.AsVectorInt16(b), sc = Vector.AsVectorInt16(c);
        Vector<short> dbc = sb - sc, dac = sa - sc;
        Vector<short> pa = Vector.Abs(dbc), pb = Vector.Abs(dac), pc = Vector.Abs(dbc + dac);
        var useA = Vector.LessThanOrEqual(pa, pb) & Vector.LessThanOrEqual(pa, pc);
        var useB = Vector.LessThanOrEqual(pb, pc);
        return Vector.AsVectorUInt16(Vector.ConditionalSelect(useA, sa, Vector.ConditionalSelect(useB, sb, sc)));
    }

    /// <summary>§9.4: the Paeth predictor, ties broken in the order a, b, c.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static int Paeth(int a, int b, int c)
    {
        int pa = b - c, pb = a - c, pc = pa + pb;      // p − a, p − b, p − c with p = a + b − c
        pa = pa < 0 ? -pa : pa; pb = pb < 0 ? -pb : pb; pc = pc < 0 ? -pc : pc;
        if (pa <= pb && pa <= pc) return a;
        return pb <= pc ? b : c;
    }

    /// <summary>§5.3: length (big-endian), type, data, CRC-32 over type and data.</summary>
    static void WriteChunk(Stream stream, string type, ReadOnlySpan<byte> data)
    {
        Span<byte> head = stackalloc byte[8];
        BinaryPrimitives.WriteInt32BigEndian(head, data.Length);
        Encoding.ASCII.GetBytes(type, head[4..]);
        stream.Write(head);
        stream.Write(data);
        uint crc = Crc32.Update(Crc32.Compute(head[4..]), data);
        Span<byte> tail = stackalloc byte[4];
        BinaryPrimitives.WriteUInt32BigEndian(tail, crc);
        stream.Write(tail);
    }
}
