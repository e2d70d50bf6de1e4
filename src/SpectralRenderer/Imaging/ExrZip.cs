using System.Runtime.CompilerServices;
using System.IO.Compression;

namespace SpectralRenderer.Imaging;

/// <summary>
/// OpenEXR ZIP(S)_COMPRESSION of one chunk, as OpenEXR's ImfZip.cpp does it: split the bytes into
/// the even-indexed then the odd-indexed half, replace each byte after the first by
/// (t[i] − t[i−1] + 128) mod 256, and deflate the result as a zlib (RFC 1950) stream.
/// </summary>
static class ExrZip
{
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static byte[] Compress(ReadOnlySpan<byte> raw)
    {
        int n = raw.Length;
        var t = new byte[n];
        // Reorder: bytes 0, 2, 4, … into the first (n + 1) / 2, bytes 1, 3, 5, … after them.
        int half = (n + 1) / 2;
        for (int i = 0, j = 0; i < n; i += 2, j++) t[j] = raw[i];
        for (int i = 1, j = half; i < n; i += 2, j++) t[j] = raw[i];
        // Predictor: d[i] = (t[i] − t[i−1] + 128 + 256) & 0xff, walking forwards with the original t[i−1].
        int p = n > 0 ? t[0] : 0;
        for (int i = 1; i < n; i++)
        {
            int v = t[i];
            t[i] = (byte)((v - p + 128 + 256) & 0xff);
            p = v;
        }
        var ms = new MemoryStream(n / 2 + 64);
        // Level 1 with deflate's run-length strategy: after the predictor, float data compresses mostly by
        // entropy coding, and RLE matching is 40% faster than level 1's search for ~10% larger chunks.
        using (var z = new ZLibStream(ms, new ZLibCompressionOptions { CompressionLevel = 1, CompressionStrategy = ZLibCompressionStrategy.RunLengthEncoding }, leaveOpen: true)) z.Write(t);
        return ms.ToArray();
    }

    /// <summary>Inverse of <see cref="Compress"/>; returns false when the stream does not inflate to exactly <paramref name="output"/>.Length bytes.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static bool TryDecompress(ReadOnlySpan<byte> compressed, Span<byte> output)
    {
        int n = output.Length;
        var t = new byte[n];
        try
        {
            using var z = new ZLibStream(new MemoryStream(compressed.ToArray()), CompressionMode.Decompress);
            z.ReadExactly(t);
            if (z.ReadByte() != -1) return false;
        }
        catch (Exception e) when (e is InvalidDataException or EndOfStreamException)
        {
            return false;
        }
        for (int i = 1; i < n; i++) t[i] = (byte)(t[i - 1] + t[i] - 128);
        int half = (n + 1) / 2;
        for (int i = 0, j = 0; i < n; i += 2, j++) output[i] = t[j];
        for (int i = 1, j = half; i < n; i += 2, j++) output[i] = t[j];
        return true;
    }
}
