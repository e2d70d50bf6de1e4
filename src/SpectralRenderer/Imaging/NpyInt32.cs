using System.Buffers.Binary;
using System.Globalization;
using System.Runtime.InteropServices;
using System.Text;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>
/// C-order little-endian int32 ('&lt;i4') NumPy .npy arrays, format version 1.0 (NEP 1, as <see cref="NpyWriter"/>):
/// magic, version, header length, the header dict padded so that the data start at a multiple of 64 bytes, the data.
/// </summary>
public static partial class NpyInt32
{
    static ReadOnlySpan<byte> Magic => [0x93, (byte)'N', (byte)'U', (byte)'M', (byte)'P', (byte)'Y'];

    [GeneratedRegex(@"'shape'\s*:\s*\(([^)]*)\)")]
    private static partial Regex ShapeRegex();

    public static void Write(Stream stream, ReadOnlySpan<int> shape, ReadOnlySpan<int> data)
    {
        long count = 1;
        foreach (int d in shape) count *= d;
        if (count != data.Length) throw new ArgumentException($"shape holds {count} values, data {data.Length}");
        stream.Write(Preamble(shape));
        if (BitConverter.IsLittleEndian) { stream.Write(MemoryMarshal.AsBytes(data)); return; }
        var b = new byte[4];
        foreach (int v in data) { BinaryPrimitives.WriteInt32LittleEndian(b, v); stream.Write(b); }
    }

    /// <summary>Magic, version 1.0, header length and the header dict of a C-order int32 array of this shape: the bytes before the data (a
    /// multiple of 64).</summary>
    public static byte[] Preamble(ReadOnlySpan<int> shape) => NpyWriter.Preamble(shape, "<i4");

    public static (int[] Shape, int[] Data) Read(Stream stream, string where = "NPY")
    {
        Span<byte> pre = stackalloc byte[10];
        try { stream.ReadExactly(pre); }
        catch (EndOfStreamException)
        {
            throw new InputException(where, "not a .npy file (too short)", "the file was cut short: save it again with numpy.save");
        }
        if (!pre[..6].SequenceEqual(Magic) || pre[6] != 1)
            throw new InputException(where, "not a version 1.0 .npy file", "save the array with numpy.save");
        var hb = new byte[BinaryPrimitives.ReadUInt16LittleEndian(pre[8..])];
        try { stream.ReadExactly(hb); }
        catch (EndOfStreamException)
        {
            throw new InputException(where, "file is truncated (in the header)", "the file was cut short: save it again with numpy.save");
        }
        var header = Encoding.Latin1.GetString(hb);
        if (!header.Contains("'descr': '<i4'") || header.Contains("'fortran_order': True"))
            throw new InputException(where, $"expected a C-order int32 array, header {header.Trim()}",
                "save a C-order int32 array with numpy.save");
        var s = ShapeRegex().Match(header);
        if (!s.Success) throw new InputException(where, "header has no shape", "save the array with numpy.save");
        var shape = s.Groups[1].Value.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries)
            .Select(t => int.TryParse(t, NumberStyles.Integer, CultureInfo.InvariantCulture, out int v) && v >= 0
                ? v
                : throw new InputException(where, $"bad shape entry '{t}'", "shape entries are non-negative integers"))
            .ToArray();
        long count = 1;
        foreach (int v in shape) count *= v;
        if (count > Array.MaxLength) throw new InputException(where, "array too large", $"at most {Array.MaxLength} values");
        var data = new int[count];
        try { stream.ReadExactly(MemoryMarshal.AsBytes(data.AsSpan())); }
        catch (EndOfStreamException)
        {
            throw new InputException(where, $"file is truncated: {count} int32 values expected",
                "the file was cut short: save it again with numpy.save");
        }
        if (!BitConverter.IsLittleEndian) for (int i = 0; i < data.Length; i++) data[i] = BinaryPrimitives.ReverseEndianness(data[i]);
        return (shape, data);
    }
}
