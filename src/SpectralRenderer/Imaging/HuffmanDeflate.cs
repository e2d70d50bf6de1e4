using System.Buffers;
using System.Buffers.Binary;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Imaging;

/// <summary>
/// A zlib stream (RFC 1950) of deflate blocks that hold literals only (RFC 1951 §3.2.7, dynamic Huffman codes; no LZ77
/// matches), each block with the Huffman code of its own byte histogram. For filtered image rows, whose bytes are
/// residuals with no long repeats, this is what zlib's Z_HUFFMAN_ONLY strategy does and what fpnge (Wassenberg &amp;
/// Versari's fast PNG encoder) builds on: a histogram pass and a table-lookup pass per byte, several times faster than
/// LZ77 at level 1 and about as small (smaller on 16-bit band images, BENCHMARKS.md). Any inflater reads it.
/// The output depends on the input bytes and their split into blocks only, never on timing or threads.
/// </summary>
public sealed class HuffmanDeflate : IDisposable
{
    /// <summary>RFC 1951 §3.2.7: literal/length code lengths are at most 15 bits, code-length code lengths at most 7.</summary>
    const int MaxLitBits = 15, MaxCodeLengthBits = 7;

    /// <summary>§3.2.7: the order in which the code-length code's lengths are sent.</summary>
    static ReadOnlySpan<byte> CodeLengthOrder => [16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15];

    byte[] _out;             // the stream's bytes since the last block returned them (rented, reused)
    int _length;
    ulong _bits;             // bits not yet in a whole byte (fewer than 8 between blocks)
    int _bitCount;
    uint _s1 = 1, _s2;       // RFC 1950 §8.2 Adler-32 of the uncompressed bytes
    bool _finished;

    readonly int[] _freq = new int[257];
    readonly byte[] _litLength = new byte[257];
    readonly uint[] _litCode = new uint[257];     // bit-reversed canonical code | length << 16

    public HuffmanDeflate()
    {
        _out = ArrayPool<byte>.Shared.Rent(1 << 16);
        // RFC 1950 §2.2: CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (FLEVEL 0 "fastest", no dictionary; 0x7801 is a multiple of 31).
        _out[0] = 0x78; _out[1] = 0x01;
        _length = 2;
    }

    /// <summary>Returns the buffer to the pool.</summary>
    public void Dispose()
    {
        ArrayPool<byte>.Shared.Return(_out);
        _out = [];
    }

    /// <summary>
    /// Compresses <paramref name="data"/> as one deflate block with its own Huffman code; <paramref name="final"/> marks the
    /// stream's last block (and appends the Adler-32). Returns the stream's next whole bytes (the zlib header first), valid
    /// until the next call; a block's last few bits may come with the next block's bytes.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public ReadOnlySpan<byte> Block(ReadOnlySpan<byte> data, bool final)
    {
        if (_finished) throw new InvalidOperationException("the zlib stream is finished");
        if (_out.Length == 0) throw new ObjectDisposedException(nameof(HuffmanDeflate));
        Histogram(data);
        _freq[256] = 1;   // end of block
        BuildCode(_freq, _litLength, MaxLitBits);
        Codes(_litLength, _litCode);

        // Block header: BFINAL, BTYPE = 10 (dynamic Huffman codes).
        Reserve(1024);
        PutBits(final ? 1u : 0u, 1);
        PutBits(2, 2);
        Header();

        // Worst case 15 bits a byte: reserve it all once (and 8 bytes of slack for the 64-bit stores), then write two
        // codes per step (at most 2 × 15 bits on top of the < 8 pending) and store the whole bytes of the accumulator.
        Reserve(data.Length * 2 + 64);
        ref uint codes = ref MemoryMarshal.GetArrayDataReference(_litCode);
        ref byte o = ref MemoryMarshal.GetArrayDataReference(_out);
        ref byte src = ref MemoryMarshal.GetReference(data);
        nint at = _length;
        ulong bits = _bits;
        int count = _bitCount;
        int i = 0;
        for (; i + 2 <= data.Length; i += 2)
        {
            uint c0 = Unsafe.Add(ref codes, Unsafe.Add(ref src, i)), c1 = Unsafe.Add(ref codes, Unsafe.Add(ref src, i + 1));
            bits |= (ulong)(c0 & 0xffff) << count;
            count += (int)(c0 >> 16);
            bits |= (ulong)(c1 & 0xffff) << count;
            count += (int)(c1 >> 16);
            Unsafe.WriteUnaligned(ref Unsafe.Add(ref o, at), BitConverter.IsLittleEndian ? bits : BinaryPrimitives.ReverseEndianness(bits));
            int whole = count >> 3;
            at += whole;
            bits >>= whole << 3;
            count &= 7;
        }
        for (; i < data.Length; i++)
        {
            uint c = Unsafe.Add(ref codes, Unsafe.Add(ref src, i));
            bits |= (ulong)(c & 0xffff) << count;
            count += (int)(c >> 16);
            Unsafe.WriteUnaligned(ref Unsafe.Add(ref o, at), BitConverter.IsLittleEndian ? bits : BinaryPrimitives.ReverseEndianness(bits));
            int whole = count >> 3;
            at += whole;
            bits >>= whole << 3;
            count &= 7;
        }
        _length = (int)at; _bits = bits; _bitCount = count;
        uint eob = _litCode[256];
        PutBits(eob & 0xffff, (int)(eob >> 16));
        if (final) Finish();
        var bytes = _out.AsSpan(0, _length);
        _length = 0;
        return bytes;
    }

    /// <summary>
    /// One pass over the block: the byte histogram (four sub-histograms, so repeated bytes do not wait on each other's
    /// counts) and the running Adler-32 (RFC 1950 §8.2: s1 = 1 + Σ bytes, s2 = Σ s1, both mod 65521, reduced every
    /// 5552 bytes, the most that cannot overflow 32 bits).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Histogram(ReadOnlySpan<byte> data)
    {
        Span<int> hist = stackalloc int[4 * 256];
        hist.Clear();
        ref int h = ref MemoryMarshal.GetReference(hist);
        ref byte src = ref MemoryMarshal.GetReference(data);
        uint s1 = _s1, s2 = _s2;
        int i = 0;
        while (i < data.Length)
        {
            int end = Math.Min(data.Length, i + 5552);
            for (; i + 4 <= end; i += 4)
            {
                uint b0 = Unsafe.Add(ref src, i), b1 = Unsafe.Add(ref src, i + 1), b2 = Unsafe.Add(ref src, i + 2),
                    b3 = Unsafe.Add(ref src, i + 3);
                Unsafe.Add(ref h, b0)++; Unsafe.Add(ref h, 256 + b1)++; Unsafe.Add(ref h, 512 + b2)++; Unsafe.Add(ref h, 768 + b3)++;
                s2 += 4 * s1 + 4 * b0 + 3 * b1 + 2 * b2 + b3;
                s1 += b0 + b1 + b2 + b3;
            }
            for (; i < end; i++) { hist[data[i]]++; s1 += data[i]; s2 += s1; }
            s1 %= 65521; s2 %= 65521;
        }
        _s1 = s1; _s2 = s2;
        for (int s = 0; s < 256; s++) _freq[s] = hist[s] + hist[256 + s] + hist[512 + s] + hist[768 + s];
    }

    /// <summary>
    /// §3.2.7 dynamic block header: HLIT = 257 literal/length codes (the literals and end of block), HDIST = 2 distance codes
    /// of one bit each (a complete code no symbol uses), HCLEN code-length codes, then the run-length coded lengths.
    /// </summary>
    void Header()
    {
        const int Hdist = 2;
        Span<byte> lengths = stackalloc byte[257 + Hdist];
        _litLength.CopyTo(lengths);
        lengths[257] = 1; lengths[258] = 1;

        // §3.2.7 run-length symbols: 0–15 a length; 16 repeats the previous length 3–6 times (2 extra bits);
        // 17 repeats zero 3–10 times (3 bits); 18 repeats zero 11–138 times (7 bits).
        Span<byte> symbols = stackalloc byte[lengths.Length];
        Span<byte> extra = stackalloc byte[lengths.Length];
        int count = 0;
        for (int i = 0; i < lengths.Length;)
        {
            byte l = lengths[i];
            int run = 1;
            while (i + run < lengths.Length && lengths[i + run] == l) run++;
            if (l == 0 && run >= 3)
            {
                int r = Math.Min(run, 138);
                if (r >= 11) { symbols[count] = 18; extra[count++] = (byte)(r - 11); }
                else { symbols[count] = 17; extra[count++] = (byte)(r - 3); }
                i += r;
            }
            else if (l != 0 && run >= 4)
            {
                symbols[count++] = l;          // the length once, then 16 for 3–6 repeats of it
                int r = Math.Min(run - 1, 6);
                symbols[count] = 16; extra[count++] = (byte)(r - 3);
                i += 1 + r;
            }
            else { symbols[count++] = l; i++; }
        }

        var freq = new int[19];
        for (int i = 0; i < count; i++) freq[symbols[i]]++;
        var clLength = new byte[19];
        var clCode = new uint[19];
        BuildCode(freq, clLength, MaxCodeLengthBits);
        Codes(clLength, clCode);
        int hclen = 19;
        while (hclen > 4 && clLength[CodeLengthOrder[hclen - 1]] == 0) hclen--;

        PutBits(257 - 257, 5);
        PutBits(Hdist - 1, 5);
        PutBits((uint)(hclen - 4), 4);
        for (int i = 0; i < hclen; i++) PutBits(clLength[CodeLengthOrder[i]], 3);
        for (int i = 0; i < count; i++)
        {
            uint c = clCode[symbols[i]];
            PutBits(c & 0xffff, (int)(c >> 16));
            if (symbols[i] == 16) PutBits(extra[i], 2);
            else if (symbols[i] == 17) PutBits(extra[i], 3);
            else if (symbols[i] == 18) PutBits(extra[i], 7);
        }
    }

    /// <summary>
    /// Huffman code lengths of at most <paramref name="maxBits"/> for <paramref name="freq"/> (zero: the symbol gets no code).
    /// Lengths come from the Huffman tree of the used symbols (at least two: an unused one is given a count of 1 if needed,
    /// since inflaters reject an incomplete code), then limited as miniz's tdefl_huffman_enforce_max_code_size does:
    /// over-long codes are shortened to the limit and codes lengthened until the Kraft sum is exactly 1 again;
    /// the most frequent symbols get the shortest codes. Ties are broken by symbol number: the result is deterministic.
    /// </summary>
    internal static void BuildCode(int[] freq, byte[] lengths, int maxBits)
    {
        int n = freq.Length;
        Array.Clear(lengths);
        int used = 0;
        for (int s = 0; s < n; s++) if (freq[s] > 0) used++;
        for (int s = 0; used < 2 && s < n; s++) if (freq[s] == 0) { freq[s] = 1; used++; }
        if (used > 1 << maxBits) throw new ArgumentException($"{used} symbols do not fit codes of at most {maxBits} bits");

        // Leaves in ascending (frequency, symbol) order; the two-queue construction of the tree.
        var sym = new int[used];
        var weight = new long[2 * used];
        var parent = new int[2 * used];
        for (int s = 0, k = 0; s < n; s++) if (freq[s] > 0) sym[k++] = s;
        Array.Sort(sym, (a, b) => freq[a] != freq[b] ? freq[a].CompareTo(freq[b]) : a.CompareTo(b));
        for (int k = 0; k < used; k++) weight[k] = freq[sym[k]];
        int leaf = 0, inner = used, next = used;
        int Take() => leaf < used && (inner >= next || weight[leaf] <= weight[inner]) ? leaf++ : inner++;
        for (; next < 2 * used - 1; next++)
        {
            int a = Take(), b = Take();
            weight[next] = weight[a] + weight[b];
            parent[a] = next; parent[b] = next;
        }
        // Depths: the root (last node) is at 0; a node's depth is its parent's plus one (parents come after children).
        var depth = new int[2 * used - 1];
        for (int k = 2 * used - 3; k >= 0; k--) depth[k] = depth[parent[k]] + 1;

        // Codes per length, the over-long ones folded onto the limit, then the Kraft sum restored (miniz).
        var perLength = new int[Math.Max(maxBits, 2 * used) + 1];
        for (int k = 0; k < used; k++) perLength[depth[k]]++;
        for (int l = maxBits + 1; l < perLength.Length; l++) { perLength[maxBits] += perLength[l]; perLength[l] = 0; }
        long total = 0;
        for (int l = maxBits; l > 0; l--) total += (long)perLength[l] << (maxBits - l);
        while (total != 1L << maxBits)
        {
            perLength[maxBits]--;
            for (int l = maxBits - 1; l > 0; l--)
                if (perLength[l] != 0) { perLength[l]--; perLength[l + 1] += 2; break; }
            total--;
        }
        // The least frequent symbols take the longest codes.
        for (int l = maxBits, k = 0; l > 0; l--)
            for (int c = perLength[l]; c > 0; c--) lengths[sym[k++]] = (byte)l;
    }

    /// <summary>RFC 1951 §3.2.2 canonical codes from the lengths, bit-reversed (deflate sends codes most significant bit first into an
    /// LSB-first stream), with the length in the high half.</summary>
    static void Codes(byte[] lengths, uint[] codes)
    {
        Span<int> perLength = stackalloc int[16];
        perLength.Clear();
        foreach (byte l in lengths) perLength[l]++;
        perLength[0] = 0;
        Span<int> nextCode = stackalloc int[16];
        int code = 0;
        for (int l = 1; l < 16; l++) { code = (code + perLength[l - 1]) << 1; nextCode[l] = code; }
        for (int s = 0; s < lengths.Length; s++)
        {
            int l = lengths[s];
            if (l == 0) { codes[s] = 0; continue; }
            uint c = (uint)nextCode[l]++, reversed = 0;
            for (int i = 0; i < l; i++) { reversed = (reversed << 1) | (c & 1); c >>= 1; }
            codes[s] = reversed | (uint)l << 16;
        }
    }

    void PutBits(uint value, int count)
    {
        _bits |= (ulong)value << _bitCount;
        _bitCount += count;
        while (_bitCount >= 8)
        {
            Reserve(1);
            _out[_length++] = (byte)_bits;
            _bits >>= 8; _bitCount -= 8;
        }
    }

    void Reserve(int more)
    {
        if (_length + more + 8 <= _out.Length) return;
        var bigger = ArrayPool<byte>.Shared.Rent(Math.Max(_out.Length * 2, _length + more + 8));
        _out.AsSpan(0, _length).CopyTo(bigger);
        ArrayPool<byte>.Shared.Return(_out);
        _out = bigger;
    }

    /// <summary>Pads the last byte and appends the Adler-32 (big-endian, RFC 1950 §2.2).</summary>
    void Finish()
    {
        if (_bitCount > 0) PutBits(0, 8 - _bitCount);
        Reserve(4);
        BinaryPrimitives.WriteUInt32BigEndian(_out.AsSpan(_length), (_s2 << 16) | _s1);
        _length += 4;
        _finished = true;
    }
}
