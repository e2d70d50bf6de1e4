using System.Runtime.CompilerServices;
using System.Buffers.Binary;
using System.IO.Compression;
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
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        Check(width, height, rgb.Length, 3);
        Write(stream, width, height, 8, 2, 3, rgb, text, filter);
    }

    /// <summary>8-bit greyscale, one byte per pixel.</summary>
    public static void WriteGray8(Stream stream, int width, int height, ReadOnlySpan<byte> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        Check(width, height, gray.Length, 1);
        Write(stream, width, height, 8, 0, 1, gray, text, filter);
    }

    /// <summary>16-bit greyscale; samples are stored big-endian as §7.1 requires.</summary>
    public static void WriteGray16(Stream stream, int width, int height, ReadOnlySpan<ushort> gray,
        IReadOnlyDictionary<string, string>? text = null, PngFilter filter = PngFilter.Adaptive)
    {
        Check(width, height, gray.Length, 1);
        Write(stream, width, height, 16, 0, 2, BigEndian(gray), text, filter);
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
        for (int i = 0; i < samples.Length; i++) BinaryPrimitives.WriteUInt16BigEndian(bytes.AsSpan(2 * i), samples[i]);
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
        ReadOnlySpan<byte> pixels, IReadOnlyDictionary<string, string>? text, PngFilter filter)
    {
        stream.Write(Signature);

        // §11.2.1 IHDR: width, height, bit depth, colour type, compression 0, filter 0, interlace 0.
        Span<byte> ihdr = stackalloc byte[13];
        BinaryPrimitives.WriteInt32BigEndian(ihdr, width);
        BinaryPrimitives.WriteInt32BigEndian(ihdr[4..], height);
        ihdr[8] = bitDepth; ihdr[9] = colourType; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
        WriteChunk(stream, "IHDR", ihdr);

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
        int rowBytes = checked(width * bpp);
        var zlibData = new MemoryStream();
        using (var z = new ZLibStream(zlibData, CompressionLevel.Fastest, leaveOpen: true))
        {
            var prior = new byte[rowBytes];                    // §9.2: the row above the first is all zeros
            var candidates = new byte[5][];
            for (int f = 0; f < 5; f++) candidates[f] = new byte[rowBytes + 1];
            for (int y = 0; y < height; y++)
            {
                var row = pixels.Slice(y * rowBytes, rowBytes);
                byte[] best;
                if (filter == PngFilter.Adaptive)
                {
                    best = candidates[0];
                    long bestSum = long.MaxValue;
                    for (int f = 0; f < 5; f++)
                    {
                        FilterRow(f, row, prior, bpp, candidates[f]);
                        long sum = 0;
                        for (int i = 1; i <= rowBytes; i++) sum += Math.Abs((int)(sbyte)candidates[f][i]);
                        if (sum < bestSum) { bestSum = sum; best = candidates[f]; }
                    }
                }
                else
                {
                    best = candidates[(int)filter];
                    FilterRow((int)filter, row, prior, bpp, best);
                }
                z.Write(best);
                row.CopyTo(prior);
            }
        }
        var data = zlibData.GetBuffer().AsSpan(0, (int)zlibData.Length);
        int at = 0;
        do
        {
            WriteChunk(stream, "IDAT", data.Slice(at, Math.Min(IdatSize, data.Length - at)));
            at += IdatSize;
        } while (at < data.Length);
        WriteChunk(stream, "IEND", []);
    }

    /// <summary>§9.2: filter types 0–4 on one row; out[0] receives the type byte.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void FilterRow(int type, ReadOnlySpan<byte> x, ReadOnlySpan<byte> b, int bpp, Span<byte> output)
    {
        output[0] = (byte)type;
        var o = output[1..];
        switch (type)
        {
            case 0:
                x.CopyTo(o);
                break;
            case 1: // Sub: x − a
                for (int i = 0; i < x.Length; i++) o[i] = (byte)(x[i] - (i >= bpp ? x[i - bpp] : 0));
                break;
            case 2: // Up: x − b
                for (int i = 0; i < x.Length; i++) o[i] = (byte)(x[i] - b[i]);
                break;
            case 3: // Average: x − floor((a + b) / 2)
                for (int i = 0; i < x.Length; i++) o[i] = (byte)(x[i] - ((i >= bpp ? x[i - bpp] : 0) + b[i]) / 2);
                break;
            case 4: // Paeth: x − PaethPredictor(a, b, c)
                for (int i = 0; i < x.Length; i++)
                {
                    int a = i >= bpp ? x[i - bpp] : 0, c = i >= bpp ? b[i - bpp] : 0;
                    o[i] = (byte)(x[i] - Paeth(a, b[i], c));
                }
                break;
        }
    }

    /// <summary>§9.4: the Paeth predictor, ties broken in the order a, b, c.</summary>
    internal static int Paeth(int a, int b, int c)
    {
        int p = a + b - c;
        int pa = Math.Abs(p - a), pb = Math.Abs(p - b), pc = Math.Abs(p - c);
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
