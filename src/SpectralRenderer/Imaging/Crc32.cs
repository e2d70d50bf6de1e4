using System.Buffers.Binary;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Imaging;

/// <summary>
/// CRC-32 as PNG defines it (PNG spec, 3rd ed., §5.5 and Annex D): polynomial x³²+x²⁶+…+1
/// (reflected 0xEDB88320), register preset to all ones, result complemented.
/// </summary>
public static class Crc32
{
    /// <summary>Slicing-by-8 tables: T[0] is the classic byte table; T[k][n] is the CRC of byte n followed by k zero bytes.</summary>
    static readonly uint[] Table = MakeTable();

    static uint[] MakeTable()
    {
        var t = new uint[8 * 256];
        for (uint n = 0; n < 256; n++)
        {
            uint c = n;
            for (int k = 0; k < 8; k++) c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        for (int k = 1; k < 8; k++)
            for (int n = 0; n < 256; n++) t[k * 256 + n] = (t[(k - 1) * 256 + n] >> 8) ^ t[t[(k - 1) * 256 + n] & 0xff];
        return t;
    }

    /// <summary>Continues a running CRC (start with 0) over <paramref name="data"/>, eight bytes per step.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static uint Update(uint crc, ReadOnlySpan<byte> data)
    {
        uint c = ~crc;
        var t = Table.AsSpan();
        int i = 0;
        for (; i + 8 <= data.Length; i += 8)
        {
            uint lo = BinaryPrimitives.ReadUInt32LittleEndian(data[i..]) ^ c, hi = BinaryPrimitives.ReadUInt32LittleEndian(data[(i + 4)..]);
            c = t[7 * 256 + (int)(lo & 0xff)] ^ t[6 * 256 + (int)((lo >> 8) & 0xff)] ^ t[5 * 256 + (int)((lo >> 16) & 0xff)] ^ t[4 * 256
                + (int)(lo >> 24)]
              ^ t[3 * 256 + (int)(hi & 0xff)] ^ t[2 * 256 + (int)((hi >> 8) & 0xff)] ^ t[256
                  + (int)((hi >> 16) & 0xff)] ^ t[(int)(hi >> 24)];
        }
        for (; i < data.Length; i++) c = t[(int)((c ^ data[i]) & 0xff)] ^ (c >> 8);
        return ~c;
    }

    public static uint Compute(ReadOnlySpan<byte> data) => Update(0, data);
}
