using System.Buffers.Binary;
using System.IO.Compression;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>
/// A decoded PNG: colour samples row by row (1 grey or 3 RGB per pixel), 8-bit values widened to ushort; a palette image
/// (colour type 3) is expanded to RGB at 8 bits. <see cref="Alpha"/>: one opacity per pixel (0 … 2^BitDepth − 1) from an alpha
/// channel (types 4, 6) or a tRNS chunk, else null.
/// </summary>
public sealed record PngImage(int Width, int Height, int BitDepth, int ColourType, int Channels,
    ushort[] Samples, IReadOnlyDictionary<string, string> Text)
{
    public ushort[]? Alpha { get; init; }
}

/// <summary>
/// A PNG decoder (ISO/IEC 15948, PNG 2nd ed.) for the files <see cref="PngWriter"/> writes and for textures: non-interlaced;
/// colour types 0 (grey, 1/2/4/8/16 bit), 2 (RGB, 8/16), 3 (palette, 1/2/4/8, with PLTE and tRNS), 4 (grey + alpha, 8/16)
/// and 6 (RGBA, 8/16); all five filter types (on bytes, at least one per pixel, §9.2), CRCs checked.
/// </summary>
public static class PngReader
{
    public static PngImage Read(string path)
    {
        return Read(new MemoryStream(InputFile.ReadAllBytes(path, "PNG file")), path);
    }

    public static PngImage Read(Stream stream, string where = "PNG")
    {
        var ms = new MemoryStream();
        stream.CopyTo(ms);
        var bytes = ms.ToArray().AsSpan();
        if (bytes.Length < 8 || !bytes[..8].SequenceEqual(PngWriter.Signature))
            throw new InputException($"{where}: byte 0", "not a PNG file (bad signature)",
                "is this a PNG image? it must start with 89 50 4E 47");
        int pos = 8, width = 0, height = 0, depth = 0, type = -1;
        byte[]? palette = null, trns = null;
        var idat = new MemoryStream();
        var text = new Dictionary<string, string>();
        bool end = false;
        while (!end)
        {
            if (pos + 12 > bytes.Length) throw new InputException($"{where}: byte {pos}", "file is truncated", "the PNG has no IEND chunk");
            int length = BinaryPrimitives.ReadInt32BigEndian(bytes[pos..]);
            if (length < 0 || pos + 12L + length > bytes.Length)
                throw new InputException($"{where}: byte {pos}", "file is truncated", "the file was cut short: write it again");
            var chunkType = Encoding.ASCII.GetString(bytes.Slice(pos + 4, 4));
            var data = bytes.Slice(pos + 8, length);
            uint crc = BinaryPrimitives.ReadUInt32BigEndian(bytes[(pos + 8 + length)..]);
            if (crc != Crc32.Compute(bytes.Slice(pos + 4, length + 4)))
                throw new InputException($"{where}: chunk {chunkType} at byte {pos}", $"CRC mismatch in chunk {chunkType}",
                    "the file is corrupt: write it again");
            switch (chunkType)
            {
                case "IHDR":
                    width = BinaryPrimitives.ReadInt32BigEndian(data);
                    height = BinaryPrimitives.ReadInt32BigEndian(data[4..]);
                    depth = data[8]; type = data[9];
                    if (data[12] != 0)
                        throw new InputException($"{where}: chunk IHDR", "interlaced PNG is not supported",
                            "save the image without interlacing");
                    bool allowed = type switch
                    {
                        0 => depth is 1 or 2 or 4 or 8 or 16,
                        3 => depth is 1 or 2 or 4 or 8,
                        2 or 4 or 6 => depth is 8 or 16,
                        _ => false,
                    };
                    if (!allowed)
                        throw new InputException($"{where}: chunk IHDR", $"colour type {type} at {depth} bits is not a valid PNG",
                            "PNG has grey (0: 1–16 bits), RGB (2), palette (3: 1–8 bits), grey + alpha (4) and RGBA (6: 8 or 16 bits)");
                    break;
                case "PLTE":
                    if (length % 3 != 0 || length == 0 || length > 768)
                        throw new InputException($"{where}: chunk PLTE", $"a palette of {length} bytes",
                            "a palette holds 1 to 256 RGB entries: write the file again");
                    palette = data.ToArray();
                    break;
                case "tRNS": trns = data.ToArray(); break;
                case "IDAT": idat.Write(data); break;
                case "tEXt":
                    int nul = data.IndexOf((byte)0);
                    if (nul > 0) text[Encoding.Latin1.GetString(data[..nul])] = Encoding.Latin1.GetString(data[(nul + 1)..]);
                    break;
                case "IEND": end = true; break;
            }
            pos += 12 + length;
        }
        if (type < 0)
            throw new InputException($"{where}: byte {pos}", "no IHDR chunk", "the file is not a complete PNG image: write it again");
        if (type == 3 && palette is null)
            throw new InputException($"{where}: chunk IHDR", "a palette image without a PLTE chunk", "write the file again");
        int stored = type switch { 2 => 3, 4 => 2, 6 => 4, _ => 1 };   // samples per pixel in the file
        int bpp = Math.Max(1, stored * depth / 8);                     // the filters' byte distance
        int channels = type is 2 or 3 or 6 ? 3 : 1;
        // Declared sizes against the data, before allocating: zlib inflates at most 1032:1 (RFC 1950/1951).
        long rowBytesLong = ((long)width * stored * depth + 7) / 8;
        if (width < 1 || height < 1 || (rowBytesLong + 1) * height > 1032L * idat.Length + 1024 || rowBytesLong * height > Array.MaxLength)
            throw new InputException($"{where}: chunk IHDR",
                $"IHDR declares {width}×{height} pixels, more than the {idat.Length} bytes of image data can hold",
                "the file is truncated or its header is damaged: write it again");
        int rowBytes = (int)rowBytesLong;
        var raw = new byte[(long)height * rowBytes];
        idat.Position = 0;
        try
        {
            using var z = new ZLibStream(idat, CompressionMode.Decompress);
            var prior = new byte[rowBytes];
            var line = new byte[rowBytes + 1];
            for (int y = 0; y < height; y++)
            {
                z.ReadExactly(line);
                var x = raw.AsSpan((int)((long)y * rowBytes), rowBytes);
                line.AsSpan(1).CopyTo(x);
                for (int i = 0; i < rowBytes; i++)
                {
                    int a = i >= bpp ? x[i - bpp] : 0, b = prior[i], c = i >= bpp ? prior[i - bpp] : 0;
                    x[i] += line[0] switch
                    {
                        0 => 0,
                        1 => (byte)a,
                        2 => (byte)b,
                        3 => (byte)((a + b) / 2),
                        4 => (byte)PngWriter.Paeth(a, b, c),
                        _ => throw new InputException($"{where}: row {y}", $"row {y} has unknown filter type {line[0]}",
                            "the file is corrupt: write it again"),
                    };
                }
                x.CopyTo(prior);
            }
        }
        catch (Exception e) when (e is EndOfStreamException or InvalidDataException)
        {
            throw new InputException($"{where}: chunk IDAT", "the image data is truncated or corrupt",
                "the file is corrupt or cut short: write it again");
        }
        if (type is 0 or 2 && trns is null && depth >= 8)
        {
            var plain = new ushort[(long)width * height * channels];
            for (int i = 0; i < plain.Length; i++)
                plain[i] = depth == 8 ? raw[i] : BinaryPrimitives.ReadUInt16BigEndian(raw.AsSpan(2 * i));
            return new PngImage(width, height, depth, type, channels, plain, text);
        }
        return Expand(raw, rowBytes, width, height, depth, type, stored, channels, palette, trns, text, where);
    }

    /// <summary>Palette, sub-byte grey, alpha and tRNS images into colour samples and an alpha plane.</summary>
    static PngImage Expand(byte[] raw, int rowBytes, int width, int height, int depth, int type, int stored, int channels,
        byte[]? palette, byte[]? trns, Dictionary<string, string> text, string where)
    {
        long n = (long)width * height;
        int outDepth = type == 3 ? 8 : depth, max = (1 << outDepth) - 1;
        var samples = new ushort[n * channels];
        var alpha = type is 4 or 6 || trns is not null ? new ushort[n] : null;
        for (int y = 0; y < height; y++)
        {
            var row = raw.AsSpan(y * rowBytes, rowBytes);
            for (int x = 0; x < width; x++)
            {
                long i = (long)y * width + x;
                for (int c = 0; c < stored; c++)
                {
                    int v = Sample(row, x * stored + c, depth);
                    if (type == 3)
                    {
                        if (3 * v + 2 >= palette!.Length)
                            throw new InputException($"{where}: pixel ({x}, {y})", $"palette index {v} past the {palette.Length / 3} "
                                + "entries", "the file is corrupt: write it again");
                        for (int k = 0; k < 3; k++) samples[3 * i + k] = palette[3 * v + k];
                        if (alpha is not null) alpha[i] = v < trns!.Length ? trns[v] : (ushort)255;
                    }
                    else if (c < channels) samples[i * channels + c] = (ushort)v;
                    else alpha![i] = (ushort)v;
                }
                if (type is 0 or 2 && alpha is not null)
                {
                    // tRNS: the one fully transparent grey or RGB value (16-bit fields, §11.3.2.1).
                    bool match = trns!.Length >= 2 * channels;
                    for (int c = 0; c < channels && match; c++)
                        match = samples[i * channels + c] == BinaryPrimitives.ReadUInt16BigEndian(trns.AsSpan(2 * c));
                    alpha[i] = match ? (ushort)0 : (ushort)max;
                }
            }
        }
        return new PngImage(width, height, outDepth, type, channels, samples, text) { Alpha = alpha };
    }

    /// <summary>Sample <paramref name="k"/> of a row at <paramref name="depth"/> bits (1, 2, 4: packed from the high bit).</summary>
    static int Sample(ReadOnlySpan<byte> row, int k, int depth) => depth switch
    {
        16 => BinaryPrimitives.ReadUInt16BigEndian(row[(2 * k)..]),
        8 => row[k],
        _ => (row[k * depth / 8] >> (8 - depth - k * depth % 8)) & ((1 << depth) - 1),
    };
}
