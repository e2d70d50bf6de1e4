using System.Buffers.Binary;
using System.IO.Compression;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>A decoded PNG: samples row by row (1 or 3 per pixel), 8-bit values widened to ushort.</summary>
public sealed record PngImage(int Width, int Height, int BitDepth, int ColourType, int Channels,
    ushort[] Samples, IReadOnlyDictionary<string, string> Text);

/// <summary>
/// A minimal PNG decoder for the files <see cref="PngWriter"/> writes (round-trip tests): non-interlaced,
/// colour types 0 (greyscale, 8/16 bit) and 2 (RGB, 8/16 bit), all five filter types, CRCs checked.
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
                    if (type is not (0 or 2) || depth is not (8 or 16))
                        throw new InputException($"{where}: chunk IHDR", $"colour type {type} at {depth} bits is not supported",
                            "only 8/16-bit grey and RGB");
                    break;
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
        int channels = type == 2 ? 3 : 1, bpp = channels * depth / 8;
        // Declared sizes against the data, before allocating: zlib inflates at most 1032:1 (RFC 1950/1951).
        long rowBytesLong = (long)width * bpp;
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
        var samples = new ushort[(long)width * height * channels];
        for (int i = 0; i < samples.Length; i++)
            samples[i] = depth == 8 ? raw[i] : BinaryPrimitives.ReadUInt16BigEndian(raw.AsSpan(2 * i));
        return new PngImage(width, height, depth, type, channels, samples, text);
    }
}
