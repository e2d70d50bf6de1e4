using System.Buffers.Binary;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Owen-scrambled Sobol points by hashing (B. Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020): a
/// dimension pair's points are the first two Sobol dimensions — a (0, 2)-sequence in base 2, so every 2^k consecutive
/// aligned points stratify the square in every elementary interval — at a sample index shuffled by a nested uniform
/// scramble of its bits, then each coordinate Owen-scrambled, both seeded by a hash of (pixel, dimension, seed). The
/// shuffle maps the first 2^k indices onto an aligned block of 2^k, so every prefix of power-of-two length is a
/// (0, k, 2)-net: the sequence stays progressive (adaptive sampling may stop at any sample). Pairs of other
/// dimensions are decorrelated by their independent shuffles ("padding", Kollig &amp; Keller 2002).
/// </summary>
public static class OwenSobol
{
    /// <summary>Generator matrix columns of Sobol dimension 1 (primitive polynomial x + 1): v_i = v_{i−1} ⊕ (v_{i−1} ≫ 1).</summary>
    static readonly uint[] Dimension1 = MakeDimension1();

    /// <summary>
    /// The same matrix applied a byte at a time: entry 256·k + b is the XOR of the columns v_{8k+j} for the set bits j of b, so
    /// x = T[b₀] ⊕ T[256 + b₁] ⊕ T[512 + b₂] ⊕ T[768 + b₃] (the product is linear over GF(2)). Four loads instead of a branch per
    /// index bit: the scrambled indices use all 32 bits, and that loop's mispredicted branches were a tenth of a path's time.
    /// </summary>
    static readonly uint[] Dimension1Bytes = MakeDimension1Bytes();

    static uint[] MakeDimension1()
    {
        var v = new uint[32];
        v[0] = 1u << 31;
        for (int i = 1; i < 32; i++) v[i] = v[i - 1] ^ (v[i - 1] >> 1);
        return v;
    }

    static uint[] MakeDimension1Bytes()
    {
        var t = new uint[4 * 256];
        for (int k = 0; k < 4; k++)
            for (int b = 0; b < 256; b++)
            {
                uint x = 0;
                for (int j = 0; j < 8; j++)
                    if ((b >> j & 1) != 0) x ^= Dimension1[8 * k + j];
                t[256 * k + b] = x;
            }
        return t;
    }

    /// <summary>
    /// The bit reversal of Sobol dimension 1, R(Sobol1(i)), as the byte tables of the reversed columns (R is linear over
    /// GF(2) too): what the scramble of the v coordinate works on, without reversing it.
    /// </summary>
    static readonly uint[] Dimension1BytesReversed = Array.ConvertAll(Dimension1Bytes, ReverseBits);

    /// <summary>Sobol dimension 1 of <paramref name="index"/> as a 32-bit fraction (dimension 0 is the bit reversal).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint Sobol1(uint index)
    {
        var t = Dimension1Bytes;
        return t[index & 0xFF] ^ t[256 + (index >> 8 & 0xFF)] ^ t[512 + (index >> 16 & 0xFF)] ^ t[768 + (index >> 24)];
    }

    /// <summary>R(<see cref="Sobol1"/>(index)).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint Sobol1Reversed(uint index)
    {
        var t = Dimension1BytesReversed;
        return t[index & 0xFF] ^ t[256 + (index >> 8 & 0xFF)] ^ t[512 + (index >> 16 & 0xFF)] ^ t[768 + (index >> 24)];
    }

    /// <summary>Laine–Karras-style hash permutation (Burley 2020, §4): each bit flipped by the seed and the bits below it.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint LaineKarras(uint x, uint seed)
    {
        x += seed;
        x ^= x * 0x6c50b47cu;
        x ^= x * 0xb82f1e52u;
        x ^= x * 0xc7afe638u;
        x ^= x * 0x8d22f6e6u;
        return x;
    }

    /// <summary>Owen's nested uniform scramble of a 32-bit fraction: each bit flipped by the seed and the bits above it.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint Scramble(uint x, uint seed) => ReverseBits(LaineKarras(ReverseBits(x), seed));

    /// <summary>The bits of x in reverse order: the bytes swapped (one instruction), then each byte's bits.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint ReverseBits(uint x)
    {
        x = BinaryPrimitives.ReverseEndianness(x);
        x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
        x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
        return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    }

    /// <summary>A 32-bit fraction to [0, 1): its top 24 bits, so 1 is never reached in float.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float ToUnit(uint x) => (x >> 8) * (1f / (1 << 24));

    /// <summary>Mixes a seed with a constant (lowbias32): the seeds of a pair's shuffle and of its two coordinates.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint Mix(uint h, uint salt)
    {
        h ^= salt * 0x9E3779B9u;
        h ^= h >> 16; h *= 0x7FEB352Du; h ^= h >> 15; h *= 0x846CA68Bu; h ^= h >> 16;
        return h;
    }

    /// <summary>The 2D point of sample <paramref name="index"/> for a dimension pair seeded <paramref name="seed"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static (float U, float V) Sample2D(uint index, uint seed) => Sample2DReversed(ReverseBits(index), seed);

    /// <summary>The 1D point (Owen-scrambled van der Corput) of sample <paramref name="index"/> for a dimension seeded
    /// <paramref name="seed"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float Sample1D(uint index, uint seed) => Sample1DReversed(ReverseBits(index), seed);

    // The same points with fewer bit reversals (R): the shuffled index is i = Scramble(index) = R(LK(R(index))), and
    // u = Scramble(R(i)) = R(LK(i)) since R(R(x)) = x; v = Scramble(Sobol1(i)) = R(LK(R(Sobol1(i)))), R(Sobol1(i)) from the
    // reversed tables. R(index) is the caller's, once per camera sample (Sampler). Bit for bit the points above.

    /// <summary><see cref="Sample2D"/> given R(index).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static (float U, float V) Sample2DReversed(uint reversedIndex, uint seed)
    {
        uint i = ReverseBits(LaineKarras(reversedIndex, Mix(seed, 1)));
        uint u = ReverseBits(LaineKarras(i, Mix(seed, 2)));
        uint v = ReverseBits(LaineKarras(Sobol1Reversed(i), Mix(seed, 3)));
        return (ToUnit(u), ToUnit(v));
    }

    /// <summary><see cref="Sample1D"/> given R(index).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float Sample1DReversed(uint reversedIndex, uint seed)
    {
        uint i = ReverseBits(LaineKarras(reversedIndex, Mix(seed, 1)));
        return ToUnit(ReverseBits(LaineKarras(i, Mix(seed, 2))));
    }
}
