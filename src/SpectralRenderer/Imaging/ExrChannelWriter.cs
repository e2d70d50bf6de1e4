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
    public static void Write(string path, int width, int height, IReadOnlyList<(string Name, float[] Plane)> channels,
        IReadOnlyDictionary<string, string> attributes, int dataX = 0, int dataY = 0, int displayWidth = 0, int displayHeight = 0)
    {
        var sorted = channels.OrderBy(c => c.Name, StringComparer.Ordinal).ToArray();
        foreach (var c in sorted)
            if (c.Plane.Length != width * height) throw new ArgumentException($"channel {c.Name} holds {c.Plane.Length} values, {width}×{height} expected");
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
            ("displayWindow", "box2i", displayWidth > 0 ? Box(0, 0, displayWidth - 1, displayHeight - 1) : Box(0, 0, width - 1, height - 1)),
            ("lineOrder", "lineOrder", [0]),                                       // INCREASING_Y
            ("pixelAspectRatio", "float", BitConverter.GetBytes(1f)),
            ("screenWindowCenter", "v2f", new byte[8]),
            ("screenWindowWidth", "float", BitConverter.GetBytes(1f)),
        };
        foreach (var (k, v) in attributes) attrs.Add((k, "string", Encoding.UTF8.GetBytes(v)));
        attrs.Sort((a, b) => string.CompareOrdinal(a.Name, b.Name));
        bool longNames = sorted.Any(c => Encoding.UTF8.GetByteCount(c.Name) > 31) || attrs.Any(a => Encoding.UTF8.GetByteCount(a.Name) > 31);

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
