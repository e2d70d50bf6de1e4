using System.Buffers;
using System.IO.Compression;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;

namespace SpectralRenderer.Imaging;

/// <summary>
/// OpenEXR ZIP(S)_COMPRESSION of one chunk, as OpenEXR's ImfZip.cpp does it: split the bytes into
/// the even-indexed then the odd-indexed half, replace each byte after the first by
/// (t[i] − t[i−1] + 128) mod 256, and deflate the result as a zlib (RFC 1950) stream.
/// </summary>
static class ExrZip
{
    /// <summary>
    /// A chunk is deflated when at least this fraction of its samples equal the sample before them. Measured on
    /// 512² renders (16 lines × 26 float channels per chunk): piecewise-constant chunks (ground truth, background)
    /// shrink 50–100× at level 1 in well under 1 ms; chunks of noisy radiance (repeat fraction ≈ 0) cost 5–10 ms each
    /// to deflate for a file only a sixth smaller (20.1 → 16.8 MB at 512², 26 channels), so they are stored raw unless
    /// <see cref="ExrOptions.DeflateEveryChunk"/> (--exr-compression zip-all) asks for the smallest file.
    /// </summary>
    public const double MinRepeatFraction = 0.3;

    /// <summary>The most deflate can shrink data (RFC 1951: a 258-byte match per ≥ 2 bits), with room for headers: 1032:1.</summary>
    public const long MaxRatio = 1032;

    /// <summary>
    /// The chunk's ZIP payload, or null when it should be stored raw (OpenEXR reads a chunk whose size equals its
    /// raw size as uncompressed): deflated when <paramref name="always"/> or when its samples repeat
    /// (<see cref="MinRepeatFraction"/>), and kept only if smaller than raw.
    /// </summary>
    public static byte[]? CompressChunk(ReadOnlySpan<byte> raw, int sampleBytes, bool always)
    {
        if (!always && RepeatFraction(raw, sampleBytes) < MinRepeatFraction) return null;
        var z = Compress(raw);
        return z.Length < raw.Length ? z : null;
    }

    /// <summary>The fraction of <paramref name="sampleBytes"/>-byte samples bit-equal to the one before them.</summary>
    public static double RepeatFraction(ReadOnlySpan<byte> raw, int sampleBytes)
    {
        if (raw.Length < 2 * sampleBytes) return 0;
        long repeats = sampleBytes == 4 ? Repeats(MemoryMarshal.Cast<byte, uint>(raw))
            : sampleBytes == 2 ? Repeats(MemoryMarshal.Cast<byte, ushort>(raw))
            : throw new ArgumentOutOfRangeException(nameof(sampleBytes));
        return repeats / (double)(raw.Length / sampleBytes - 1);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static long Repeats<T>(ReadOnlySpan<T> s) where T : unmanaged, IBinaryInteger<T>
    {
        long count = 0;
        int i = 1;
        if (Vector.IsHardwareAccelerated)
        {
            // Equal lanes of Vector.Equals are all ones (−1): subtracting counts them; flush before a 16-bit lane could wrap.
            var acc = Vector<T>.Zero;
            for (int inAcc = 0; i + Vector<T>.Count <= s.Length; i += Vector<T>.Count)
            {
                acc -= Vector.Equals(new Vector<T>(s[i..]), new Vector<T>(s[(i - 1)..]));
                if (++inAcc == 1 << 15) { count += Total(acc); acc = Vector<T>.Zero; inAcc = 0; }
            }
            count += Total(acc);
        }
        for (; i < s.Length; i++) if (s[i] == s[i - 1]) count++;
        return count;

        static long Total(Vector<T> v)
        {
            long t = 0;
            for (int k = 0; k < Vector<T>.Count; k++) t += long.CreateTruncating(v[k]);
            return t;
        }
    }

    /// <summary>Predictor and deflate (level 1, default strategy: its LZ77 matches catch repeated pixels, whose bytes recur every other
    /// byte after the reordering).</summary>
    public static byte[] Compress(ReadOnlySpan<byte> raw)
    {
        var t = ArrayPool<byte>.Shared.Rent(Math.Max(1, raw.Length));
        try
        {
            Predict(raw, t.AsSpan(0, raw.Length));
            var ms = new MemoryStream(raw.Length / 16 + 256);
            using (var z = new ZLibStream(ms, CompressionLevel.Fastest, leaveOpen: true)) z.Write(t, 0, raw.Length);
            return ms.ToArray();
        }
        finally { ArrayPool<byte>.Shared.Return(t); }
    }

    /// <summary>
    /// Reorder and delta in one pass: t = bytes 0, 2, 4, … then 1, 3, 5, …; d[0] = t[0], d[i] = t[i] − t[i−1] + 128 (mod 256).
    /// Byte j of the first half is raw[2j], byte k of the second half raw[2k + 1]; their predecessors are raw[2j − 2] and
    /// raw[2k − 1], except the second half's first byte, which follows the first half's last.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static void Predict(ReadOnlySpan<byte> raw, Span<byte> d)
    {
        int n = raw.Length;
        if (n == 0) return;
        int half = (n + 1) / 2, pairs = n / 2;   // pairs: whole (even, odd) byte pairs; the second half has `pairs` bytes
        d = d[..n];
        d[0] = raw[0];
        if (pairs > 0) d[half] = (byte)(raw[1] - raw[2 * half - 2] + 128);
        int j = 1;
        if (Vector128.IsHardwareAccelerated && BitConverter.IsLittleEndian)
        {
            // 16 pairs at a time: a pair read as a little-endian ushort holds the even byte low, the odd byte high.
            var words = MemoryMarshal.Cast<byte, ushort>(raw[..(2 * pairs)]);
            var bias = Vector128.Create((byte)128);
            var low = Vector128.Create((ushort)0xff);
            for (; j + 16 <= pairs; j += 16)
            {
                var a0 = Vector128.Create(words.Slice(j, 8)); var a1 = Vector128.Create(words.Slice(j + 8, 8));
                var p0 = Vector128.Create(words.Slice(j - 1, 8)); var p1 = Vector128.Create(words.Slice(j + 7, 8));
                var even = Vector128.Narrow(a0 & low, a1 & low) - Vector128.Narrow(p0 & low, p1 & low) + bias;
                var odd = Vector128.Narrow(a0 >>> 8, a1 >>> 8) - Vector128.Narrow(p0 >>> 8, p1 >>> 8) + bias;
                even.CopyTo(d.Slice(j, 16));
                odd.CopyTo(d.Slice(half + j, 16));
            }
        }
        for (int e = j; e < half; e++) d[e] = (byte)(raw[2 * e] - raw[2 * e - 2] + 128);
        for (int k = j; k < pairs; k++) d[half + k] = (byte)(raw[2 * k + 1] - raw[2 * k - 1] + 128);
    }

    /// <summary>Inverse of <see cref="Compress"/>; returns false when the stream does not inflate to exactly
    /// <paramref name="output"/>.Length bytes.</summary>
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
        // ZLibException is an IOException (found by fuzzing)
        catch (Exception e) when (e is InvalidDataException or EndOfStreamException or IOException)
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
