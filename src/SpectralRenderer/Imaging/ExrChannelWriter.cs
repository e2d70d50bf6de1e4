using System.Buffers.Binary;
using System.Text;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Writes named FLOAT channels (not a spectrum) as a single-part scanline OpenEXR 2.0 file without compression ("The
/// OpenEXR File Layout": magic, version 2, header attributes sorted by name, one scanline per chunk, channels in
/// byte order of their names), with string attributes (units, method) and a crop as its data window.
/// </summary>
public static class ExrChannelWriter
{
    /// <summary>A data window: its first column and row and its size.</summary>
    public readonly record struct PixelWindow(int X0, int Y0, int Width, int Height);

    public static void Write(string path, int width, int height, IReadOnlyList<(string Name, float[] Plane)> channels,
        IReadOnlyDictionary<string, string> attributes, int dataX = 0, int dataY = 0, int displayWidth = 0, int displayHeight = 0)
    {
        var sorted = channels.OrderBy(c => c.Name, StringComparer.Ordinal).ToArray();
        foreach (var c in sorted)
            if (c.Plane.Length != width * height)
                throw new ArgumentException($"channel {c.Name} holds {c.Plane.Length} values, {width}×{height} expected");
        var chlist = new MemoryStream();
        using (var cw = new BinaryWriter(chlist, Encoding.UTF8, true))
        {
            foreach (var c in sorted)
            {
                cw.Write(Encoding.UTF8.GetBytes(c.Name)); cw.Write((byte)0);
                cw.Write(2);                 // FLOAT
                cw.Write(0);                 // pLinear + 3 reserved bytes
                cw.Write(1); cw.Write(1);    // x and y sampling
            }
            cw.Write((byte)0);
        }
        var attrs = new List<(string Name, string Type, byte[] Value)>
        {
            ("channels", "chlist", chlist.ToArray()),
            ("compression", "compression", [0]),                                   // NO_COMPRESSION
            ("dataWindow", "box2i", Box(dataX, dataY, dataX + width - 1, dataY + height - 1)),
            ("displayWindow", "box2i",
                displayWidth > 0 ? Box(0, 0, displayWidth - 1, displayHeight - 1) : Box(0, 0, width - 1, height - 1)),
            ("lineOrder", "lineOrder", [0]),                                       // INCREASING_Y
            ("pixelAspectRatio", "float", BitConverter.GetBytes(1f)),
            ("screenWindowCenter", "v2f", new byte[8]),
            ("screenWindowWidth", "float", BitConverter.GetBytes(1f)),
        };
        foreach (var (k, v) in attributes) attrs.Add((k, "string", Encoding.UTF8.GetBytes(v)));
        attrs.Sort((a, b) => string.CompareOrdinal(a.Name, b.Name));
        bool longNames =
            sorted.Any(c => Encoding.UTF8.GetByteCount(c.Name) > 31) || attrs.Any(a => Encoding.UTF8.GetByteCount(a.Name) > 31);

        AtomicFile.Write(path, stream =>
        {
            var bw = new BinaryWriter(stream, Encoding.UTF8, true);
            bw.Write(ExrWriter.Magic);
            bw.Write(2 | (longNames ? 0x400 : 0));
            foreach (var (name, type, value) in attrs)
            {
                bw.Write(Encoding.UTF8.GetBytes(name)); bw.Write((byte)0);
                bw.Write(Encoding.ASCII.GetBytes(type)); bw.Write((byte)0);
                bw.Write(value.Length);
                bw.Write(value);
            }
            bw.Write((byte)0);
            long headerEnd = stream.Position;
            int lineBytes = 4 * width * sorted.Length;
            // Offset table: one chunk per scanline, each 8 bytes of (y, size) then the line.
            for (int y = 0; y < height; y++) bw.Write((ulong)(headerEnd + 8L * height + (long)y * (8 + lineBytes)));
            Span<byte> f = stackalloc byte[4];
            for (int y = 0; y < height; y++)
            {
                bw.Write(dataY + y);
                bw.Write(lineBytes);
                foreach (var c in sorted)
                    for (int x = 0; x < width; x++) { BinaryPrimitives.WriteSingleLittleEndian(f, c.Plane[y * width + x]); bw.Write(f); }
            }
            bw.Flush();
        });
    }

    /// <summary>
    /// Reads back a file <see cref="Write"/> wrote (uncompressed FLOAT channels, one scanline per chunk): its data window
    /// and each channel as a row-major plane of it. Anything else is refused with the file and what differs.
    /// </summary>
    public static (PixelWindow Window, Dictionary<string, float[]> Channels) Read(string path)
    {
        var b = File.ReadAllBytes(path);
        Exception Bad(string what) =>
            new Diagnostics.InputException(path, what, "not a photometry.exr this version wrote: render it again");
        if (b.Length < 8 || BinaryPrimitives.ReadInt32LittleEndian(b) != ExrWriter.Magic) throw Bad("is not an OpenEXR file");
        int at = 8;
        string Z()
        {
            int e = Array.IndexOf(b, (byte)0, at);
            if (e < 0) throw Bad("its header is cut short");
            var s = Encoding.UTF8.GetString(b, at, e - at);
            at = e + 1;
            return s;
        }
        var names = new List<string>();
        int x0 = 0, y0 = 0, x1 = -1, y1 = -1, compression = -1;
        while (at < b.Length && b[at] != 0)
        {
            string name = Z(), type = Z();
            if (at + 4 > b.Length) throw Bad("its header is cut short");
            int size = BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(at));
            at += 4;
            if (size < 0 || at + size > b.Length) throw Bad($"attribute {name} is cut short");
            var v = b.AsSpan(at, size);
            if (type == "chlist")
                for (int p = 0; p < v.Length && v[p] != 0;)
                {
                    int e = v[p..].IndexOf((byte)0);
                    if (e < 0 || p + e + 17 > v.Length || BinaryPrimitives.ReadInt32LittleEndian(v[(p + e + 1)..]) != 2)
                        throw Bad("has a channel that is not FLOAT");
                    names.Add(Encoding.UTF8.GetString(v.Slice(p, e)));
                    p += e + 1 + 16;
                }
            else if (name == "compression" && size == 1) compression = v[0];
            else if (name == "dataWindow" && size == 16)
                (x0, y0, x1, y1) = (BinaryPrimitives.ReadInt32LittleEndian(v), BinaryPrimitives.ReadInt32LittleEndian(v[4..]),
                    BinaryPrimitives.ReadInt32LittleEndian(v[8..]), BinaryPrimitives.ReadInt32LittleEndian(v[12..]));
            at += size;
        }
        at++;
        int w = x1 - x0 + 1, h = y1 - y0 + 1, line = 4 * w * names.Count;
        if (compression != 0 || w <= 0 || h <= 0 || names.Count == 0) throw Bad("is not uncompressed FLOAT channels with a data window");
        if (at + 8L * h + (long)h * (8 + line) > b.Length) throw Bad("is cut short");
        var channels = names.ToDictionary(n => n, _ => new float[w * h]);
        for (int y = 0; y < h; y++)
        {
            long chunk = (long)BinaryPrimitives.ReadUInt64LittleEndian(b.AsSpan(at + 8 * y));
            if (chunk < 0 || chunk + 8 + line > b.Length || BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan((int)chunk)) != y0 + y)
                throw Bad($"scanline {y0 + y} is not where its offset table says");
            int p = (int)chunk + 8;
            foreach (var n in names)
                for (int x = 0; x < w; x++, p += 4) channels[n][y * w + x] = BinaryPrimitives.ReadSingleLittleEndian(b.AsSpan(p));
        }
        return (new PixelWindow(x0, y0, w, h), channels);
    }

    static byte[] Box(int xMin, int yMin, int xMax, int yMax)
    {
        var b = new byte[16];
        BinaryPrimitives.WriteInt32LittleEndian(b, xMin);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4), yMin);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8), xMax);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(12), yMax);
        return b;
    }
}
