using System.Buffers.Binary;
using System.Text;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Sensor;

/// <summary>
/// A Bayer raw frame as a DNG 1.4 file (Adobe DNG Specification 1.4.0.0): little-endian TIFF, one IFD holding the
/// uncompressed 16-bit CFA image (PhotometricInterpretation 32803), CFARepeatPatternDim/CFAPattern (0 = red,
/// 1 = green, 2 = blue), BlackLevel and WhiteLevel in digital numbers, ColorMatrix1 (XYZ → camera, for the
/// calibration illuminant) and AsShotNeutral (the camera's response to the white, normalised to its maximum).
/// </summary>
public static class DngWriter
{
    const ushort Byte = 1, Ascii = 2, Short = 3, Long = 4, Rational = 5, SRational = 10;

    /// <summary>EXIF LightSource codes for CalibrationIlluminant1 (DNG 1.4 table): 21 D65, 17 standard light A, 23 D50, 0
    /// unknown.</summary>
    public static ushort IlluminantCode(string light) => light.ToUpperInvariant() switch
    {
        "D65" => 21,
        "A" => 17,
        "D50" => 23,
        _ => 0,
    };

    public static void Write(string path, RawFrame raw, double[,] xyzToCamera, double[] asShotNeutral, ushort illuminant,
        string software) =>
        AtomicFile.Write(path, s => Write(s, raw, xyzToCamera, asShotNeutral, illuminant, software));

    public static void Write(Stream stream, RawFrame raw, double[,] xyzToCamera, double[] asShotNeutral, ushort illuminant, string software)
    {
        var sensor = raw.Sensor;
        if (!sensor.IsBayer) throw new ArgumentException("a DNG is written for Bayer sensors only");
        int w = raw.Width, h = raw.Height;
        var p = sensor.Pattern!;
        var entries = new List<(ushort Tag, ushort Type, int Count, byte[] Value)>
        {
            (254, Long, 1, U32(0)),
            (256, Long, 1, U32((uint)w)),
            (257, Long, 1, U32((uint)h)),
            (258, Short, 1, U16(16)),
            (259, Short, 1, U16(1)),
            (262, Short, 1, U16(32803)),
            (271, Ascii, 0, Text("SpectralRenderer")),
            (272, Ascii, 0, Text(sensor.Name)),
            (273, Long, 1, U32(0)),            // strip offset, patched below
            (274, Short, 1, U16(1)),
            (277, Short, 1, U16(1)),
            (278, Long, 1, U32((uint)h)),
            (279, Long, 1, U32((uint)(w * h * 2))),
            (284, Short, 1, U16(1)),
            (305, Ascii, 0, Text(software)),
            (33421, Short, 2, [.. U16(2), .. U16(2)]),
            (33422, Byte, 4, [(byte)p[0, 0], (byte)p[0, 1], (byte)p[1, 0], (byte)p[1, 1]]),
            (50706, Byte, 4, [1, 4, 0, 0]),
            (50707, Byte, 4, [1, 1, 0, 0]),
            (50708, Ascii, 0, Text($"SpectralRenderer {sensor.Name}")),
            (50710, Byte, 3, [0, 1, 2]),
            (50711, Short, 1, U16(1)),
            (50713, Short, 2, [.. U16(1), .. U16(1)]),
            (50714, Long, 1, U32((uint)Math.Round(sensor.BlackLevel))),
            (50717, Long, 1, U32((uint)sensor.WhiteLevel)),
            (50721, SRational, 9, Rationals(Flatten(xyzToCamera), signed: true)),
            (50728, Rational, 3, Rationals(asShotNeutral, signed: false)),
            (50778, Short, 1, U16(illuminant)),
        };
        for (int i = 0; i < entries.Count; i++)
            if (entries[i].Type == Ascii) entries[i] = entries[i] with { Count = entries[i].Value.Length };

        // Layout: header (8) | IFD | out-of-line values | pixels.
        int ifdSize = 2 + entries.Count * 12 + 4;
        int dataOffset = 8 + ifdSize;
        var extra = new MemoryStream();
        var offsets = new int[entries.Count];
        for (int i = 0; i < entries.Count; i++)
        {
            if (entries[i].Value.Length <= 4) continue;
            offsets[i] = dataOffset + (int)extra.Length;
            extra.Write(entries[i].Value);
            if (extra.Length % 2 == 1) extra.WriteByte(0);
        }
        int pixelOffset = dataOffset + (int)extra.Length;
        int strip = entries.FindIndex(e => e.Tag == 273);
        entries[strip] = entries[strip] with { Value = U32((uint)pixelOffset) };

        var head = new byte[8 + ifdSize];
        head[0] = (byte)'I'; head[1] = (byte)'I';
        BinaryPrimitives.WriteUInt16LittleEndian(head.AsSpan(2), 42);
        BinaryPrimitives.WriteUInt32LittleEndian(head.AsSpan(4), 8);
        BinaryPrimitives.WriteUInt16LittleEndian(head.AsSpan(8), (ushort)entries.Count);
        for (int i = 0; i < entries.Count; i++)
        {
            var e = head.AsSpan(10 + 12 * i, 12);
            BinaryPrimitives.WriteUInt16LittleEndian(e, entries[i].Tag);
            BinaryPrimitives.WriteUInt16LittleEndian(e[2..], entries[i].Type);
            BinaryPrimitives.WriteUInt32LittleEndian(e[4..], (uint)entries[i].Count);
            if (entries[i].Value.Length <= 4) entries[i].Value.CopyTo(e[8..]);
            else BinaryPrimitives.WriteUInt32LittleEndian(e[8..], (uint)offsets[i]);
        }
        // next-IFD offset 0 is already in place
        stream.Write(head);
        stream.Write(extra.ToArray());
        var row = new byte[w * 2];
        for (int y = 0; y < h; y++)
        {
            for (int x = 0; x < w; x++)
                BinaryPrimitives.WriteUInt16LittleEndian(row.AsSpan(2 * x), (ushort)Math.Clamp(Math.Round(raw.Dn[y * w + x]), 0, 65535));
            stream.Write(row);
        }
    }

    static byte[] U16(ushort v) { var b = new byte[2]; BinaryPrimitives.WriteUInt16LittleEndian(b, v); return b; }
    static byte[] U32(uint v) { var b = new byte[4]; BinaryPrimitives.WriteUInt32LittleEndian(b, v); return b; }
    static byte[] Text(string s) => [.. Encoding.ASCII.GetBytes(s), 0];

    static double[] Flatten(double[,] m)
    {
        var v = new double[m.Length];
        int k = 0;
        foreach (var x in m) v[k++] = x;
        return v;
    }

    /// <summary>Each value as numerator / 1 000 000 (32-bit).</summary>
    static byte[] Rationals(double[] values, bool signed)
    {
        var b = new byte[values.Length * 8];
        for (int i = 0; i < values.Length; i++)
        {
            double v = Math.Clamp(values[i], signed ? -2000 : 0, 2000);
            if (signed) BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8 * i), (int)Math.Round(v * 1e6));
            else BinaryPrimitives.WriteUInt32LittleEndian(b.AsSpan(8 * i), (uint)Math.Round(v * 1e6));
            BinaryPrimitives.WriteUInt32LittleEndian(b.AsSpan(8 * i + 4), 1_000_000);
        }
        return b;
    }
}
