using System.Buffers.Binary;
using System.Globalization;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Writes a <see cref="SpectralImage"/> as a NumPy .npy file, format version 1.0 (NEP 1 / numpy.lib.format):
/// magic "\x93NUMPY", major 1, minor 0, a little-endian uint16 header length, then an ASCII Python dict literal
/// {'descr': '&lt;f4', 'fortran_order': False, 'shape': (H, W, N), } padded with spaces and ended by '\n' so that
/// magic + length + header is a multiple of 64 bytes, then the float32 data in C order (the image's own layout).
/// </summary>
public static class NpyWriter
{
    internal static ReadOnlySpan<byte> Magic => [0x93, (byte)'N', (byte)'U', (byte)'M', (byte)'P', (byte)'Y'];

    public static void Write(string path, SpectralImage image) => AtomicFile.Write(path, s => Write(s, image));

    /// <summary>A C-order float32 array of <paramref name="shape"/> to <paramref name="path"/>.</summary>
    public static void Write(string path, float[] data, int[] shape) => AtomicFile.Write(path, s => Write(s, shape, data));

    public static void Write(Stream stream, SpectralImage image) =>
        Write(stream, [image.Height, image.Width, image.Bands], image.Data);

    /// <summary>
    /// Magic, version 1.0, header length and the header dict of a C-order float32 array of this shape: the bytes before
    /// the data (a multiple of 64), which the data follows as they are in memory.
    /// </summary>
    public static byte[] Preamble(ReadOnlySpan<int> shape) => Preamble(shape, "<f4");

    /// <summary>The preamble of a C-order array of this shape whose elements have NumPy type <paramref name="descr"/> (e.g. <c>&lt;f4</c>,
    /// <c>&lt;i4</c>).</summary>
    public static byte[] Preamble(ReadOnlySpan<int> shape, string descr)
    {
        string dims =
            shape.Length == 1 ? $"{shape[0]}," : string.Join(", ", shape.ToArray().Select(d => d.ToString(CultureInfo.InvariantCulture)));
        string dict = $"{{'descr': '{descr}', 'fortran_order': False, 'shape': ({dims}), }}";
        int preamble = Magic.Length + 2 + 2;
        int total = (preamble + dict.Length + 1 + 63) / 64 * 64;
        string header = dict.PadRight(total - preamble - 1) + "\n";
        if (header.Length > ushort.MaxValue) throw new ArgumentException("NPY header too long for format 1.0");
        var bytes = new byte[preamble + header.Length];
        Magic.CopyTo(bytes);
        bytes[6] = 1;  // major version
        bytes[7] = 0;  // minor version
        BinaryPrimitives.WriteUInt16LittleEndian(bytes.AsSpan(8), (ushort)header.Length);
        Encoding.ASCII.GetBytes(header, bytes.AsSpan(preamble));
        return bytes;
    }

    /// <summary>Any C-order float32 array.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static void Write(Stream stream, ReadOnlySpan<int> shape, ReadOnlySpan<float> data)
    {
        long count = 1;
        foreach (int d in shape) count *= d;
        if (count != data.Length) throw new ArgumentException($"shape holds {count} values, data {data.Length}");
        stream.Write(Preamble(shape));
        if (BitConverter.IsLittleEndian) { stream.Write(MemoryMarshal.AsBytes(data)); return; }  // '<f4' is the memory layout: one write
        var buffer = new byte[4 * Math.Min(data.Length, 1 << 16)];
        for (int at = 0; at < data.Length; at += buffer.Length / 4)
        {
            int n = Math.Min(buffer.Length / 4, data.Length - at);
            for (int i = 0; i < n; i++) BinaryPrimitives.WriteSingleLittleEndian(buffer.AsSpan(4 * i), data[at + i]);
            stream.Write(buffer, 0, 4 * n);
        }
    }
}
