using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// A group of float SIMD lanes for the ray-packet kernels, so one kernel is written once and compiled for
/// the widths the machine has: <see cref="Lanes512"/> (AVX-512, 16 lanes), <see cref="Lanes256"/> (8),
/// <see cref="Lanes128"/> (4) and <see cref="Lanes1"/> (scalar). A comparison gives a mask in the same type
/// (all bits set in true lanes). Every operation is the IEEE single-precision operation of the scalar
/// code, lane by lane (no fused multiply-add), so a packet computes exactly what a single ray does.
/// </summary>
internal interface ILanes<T> where T : struct, ILanes<T>
{
    static abstract int Count { get; }
    static abstract T Load(ref float source);
    static abstract void Store(T value, ref float destination);
    static abstract T Splat(float value);
    static abstract T operator +(T a, T b);
    static abstract T operator -(T a, T b);
    static abstract T operator *(T a, T b);
    static abstract T operator /(T a, T b);
    /// <summary>The correctly rounded square root (IEEE 754), as MathF.Sqrt.</summary>
    static abstract T Sqrt(T a);
    /// <summary>−a: the sign bit flipped (−0 for +0), as float and Vector3 negation.</summary>
    static abstract T Negate(T a);
    /// <summary>candidate &gt; current ? candidate : current (x86 maxps): a NaN candidate leaves current.</summary>
    static abstract T Max(T candidate, T current);
    /// <summary>candidate &lt; current ? candidate : current (x86 minps): a NaN candidate leaves current.</summary>
    static abstract T Min(T candidate, T current);
    static abstract T Less(T a, T b);
    static abstract T LessOrEqual(T a, T b);
    static abstract T Greater(T a, T b);
    static abstract T Equal(T a, T b);
    static abstract T And(T a, T b);
    static abstract T Or(T a, T b);
    /// <summary>a and not b, bitwise.</summary>
    static abstract T AndNot(T a, T b);
    /// <summary>All bits set in lanes whose sign bit is set (−0 included), else zero.</summary>
    static abstract T SignFill(T a);
    /// <summary>mask ? a : b, lane by lane.</summary>
    static abstract T Select(T mask, T a, T b);
    /// <summary>Bit i set when lane i of the mask is true.</summary>
    static abstract uint Bits(T mask);
    /// <summary>The mask whose lane i is true when bit i is set.</summary>
    static abstract T FromBits(uint bits);
}

internal readonly struct Lanes512 : ILanes<Lanes512>
{
    readonly Vector512<float> _v;
    Lanes512(Vector512<float> v) => _v = v;
    static readonly Vector512<int> LaneBits = Vector512.Create(1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384, 32768);

    public static int Count => 16;
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Load(ref float source) => new(Vector512.LoadUnsafe(ref source));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Store(Lanes512 value, ref float destination) => value._v.StoreUnsafe(ref destination);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 Splat(float value) => new(Vector512.Create(value));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 operator +(Lanes512 a, Lanes512 b) => new(a._v + b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 operator -(Lanes512 a, Lanes512 b) => new(a._v - b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 operator *(Lanes512 a, Lanes512 b) => new(a._v * b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 operator /(Lanes512 a, Lanes512 b) => new(a._v / b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 Sqrt(Lanes512 a) => new(Vector512.Sqrt(a._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 Negate(Lanes512 a) => new(a._v ^ Vector512.Create(-0f));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Max(Lanes512 candidate, Lanes512 current) => new(Avx512F.Max(candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Min(Lanes512 candidate, Lanes512 current) => new(Avx512F.Min(candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Less(Lanes512 a, Lanes512 b) => new(Vector512.LessThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 LessOrEqual(Lanes512 a, Lanes512 b) => new(Vector512.LessThanOrEqual(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Greater(Lanes512 a, Lanes512 b) => new(Vector512.GreaterThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Equal(Lanes512 a, Lanes512 b) => new(Vector512.Equals(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 And(Lanes512 a, Lanes512 b) => new(a._v & b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes512 Or(Lanes512 a, Lanes512 b) => new(a._v | b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 AndNot(Lanes512 a, Lanes512 b) => new(Vector512.AndNot(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 SignFill(Lanes512 a) => new(Vector512.ShiftRightArithmetic(a._v.AsInt32(), 31).AsSingle());
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 Select(Lanes512 mask, Lanes512 a, Lanes512 b) => new(Vector512.ConditionalSelect(mask._v, a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static uint Bits(Lanes512 mask) => (uint)mask._v.ExtractMostSignificantBits();
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes512 FromBits(uint bits) => new(Vector512.Equals(Vector512.Create((int)bits) & LaneBits, LaneBits).AsSingle());
}

internal readonly struct Lanes256 : ILanes<Lanes256>
{
    readonly Vector256<float> _v;
    Lanes256(Vector256<float> v) => _v = v;
    static readonly Vector256<int> LaneBits = Vector256.Create(1, 2, 4, 8, 16, 32, 64, 128);

    public static int Count => 8;
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Load(ref float source) => new(Vector256.LoadUnsafe(ref source));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Store(Lanes256 value, ref float destination) => value._v.StoreUnsafe(ref destination);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 Splat(float value) => new(Vector256.Create(value));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 operator +(Lanes256 a, Lanes256 b) => new(a._v + b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 operator -(Lanes256 a, Lanes256 b) => new(a._v - b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 operator *(Lanes256 a, Lanes256 b) => new(a._v * b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 operator /(Lanes256 a, Lanes256 b) => new(a._v / b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 Sqrt(Lanes256 a) => new(Vector256.Sqrt(a._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 Negate(Lanes256 a) => new(a._v ^ Vector256.Create(-0f));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Max(Lanes256 candidate, Lanes256 current) =>
        Avx.IsSupported
            ? new(Avx.Max(candidate._v, current._v))
            : new(Vector256.ConditionalSelect(Vector256.GreaterThan(candidate._v, current._v), candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Min(Lanes256 candidate, Lanes256 current) =>
        Avx.IsSupported
            ? new(Avx.Min(candidate._v, current._v))
            : new(Vector256.ConditionalSelect(Vector256.LessThan(candidate._v, current._v), candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Less(Lanes256 a, Lanes256 b) => new(Vector256.LessThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 LessOrEqual(Lanes256 a, Lanes256 b) => new(Vector256.LessThanOrEqual(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Greater(Lanes256 a, Lanes256 b) => new(Vector256.GreaterThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Equal(Lanes256 a, Lanes256 b) => new(Vector256.Equals(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 And(Lanes256 a, Lanes256 b) => new(a._v & b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes256 Or(Lanes256 a, Lanes256 b) => new(a._v | b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 AndNot(Lanes256 a, Lanes256 b) => new(Vector256.AndNot(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 SignFill(Lanes256 a) => new(Vector256.ShiftRightArithmetic(a._v.AsInt32(), 31).AsSingle());
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 Select(Lanes256 mask, Lanes256 a, Lanes256 b) => new(Vector256.ConditionalSelect(mask._v, a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static uint Bits(Lanes256 mask) => mask._v.ExtractMostSignificantBits();
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes256 FromBits(uint bits) => new(Vector256.Equals(Vector256.Create((int)bits) & LaneBits, LaneBits).AsSingle());
}

internal readonly struct Lanes128 : ILanes<Lanes128>
{
    readonly Vector128<float> _v;
    Lanes128(Vector128<float> v) => _v = v;
    static readonly Vector128<int> LaneBits = Vector128.Create(1, 2, 4, 8);

    public static int Count => 4;
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Load(ref float source) => new(Vector128.LoadUnsafe(ref source));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Store(Lanes128 value, ref float destination) => value._v.StoreUnsafe(ref destination);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 Splat(float value) => new(Vector128.Create(value));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 operator +(Lanes128 a, Lanes128 b) => new(a._v + b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 operator -(Lanes128 a, Lanes128 b) => new(a._v - b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 operator *(Lanes128 a, Lanes128 b) => new(a._v * b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 operator /(Lanes128 a, Lanes128 b) => new(a._v / b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 Sqrt(Lanes128 a) => new(Vector128.Sqrt(a._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 Negate(Lanes128 a) => new(a._v ^ Vector128.Create(-0f));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Max(Lanes128 candidate, Lanes128 current) =>
        Sse.IsSupported
            ? new(Sse.Max(candidate._v, current._v))
            : new(Vector128.ConditionalSelect(Vector128.GreaterThan(candidate._v, current._v), candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Min(Lanes128 candidate, Lanes128 current) =>
        Sse.IsSupported
            ? new(Sse.Min(candidate._v, current._v))
            : new(Vector128.ConditionalSelect(Vector128.LessThan(candidate._v, current._v), candidate._v, current._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Less(Lanes128 a, Lanes128 b) => new(Vector128.LessThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 LessOrEqual(Lanes128 a, Lanes128 b) => new(Vector128.LessThanOrEqual(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Greater(Lanes128 a, Lanes128 b) => new(Vector128.GreaterThan(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Equal(Lanes128 a, Lanes128 b) => new(Vector128.Equals(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 And(Lanes128 a, Lanes128 b) => new(a._v & b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes128 Or(Lanes128 a, Lanes128 b) => new(a._v | b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 AndNot(Lanes128 a, Lanes128 b) => new(Vector128.AndNot(a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 SignFill(Lanes128 a) => new(Vector128.ShiftRightArithmetic(a._v.AsInt32(), 31).AsSingle());
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 Select(Lanes128 mask, Lanes128 a, Lanes128 b) => new(Vector128.ConditionalSelect(mask._v, a._v, b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static uint Bits(Lanes128 mask) => mask._v.ExtractMostSignificantBits();
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes128 FromBits(uint bits) => new(Vector128.Equals(Vector128.Create((int)bits) & LaneBits, LaneBits).AsSingle());
}

/// <summary>One lane: the scalar fallback (and the reference the wider groups must agree with).</summary>
internal readonly struct Lanes1 : ILanes<Lanes1>
{
    readonly float _v;
    Lanes1(float v) => _v = v;
    static float Mask(bool b) => b ? BitConverter.Int32BitsToSingle(-1) : 0f;

    public static int Count => 1;
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Load(ref float source) => new(source);
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Store(Lanes1 value, ref float destination) => destination = value._v;
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Splat(float value) => new(value);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 operator +(Lanes1 a, Lanes1 b) => new(a._v + b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 operator -(Lanes1 a, Lanes1 b) => new(a._v - b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 operator *(Lanes1 a, Lanes1 b) => new(a._v * b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 operator /(Lanes1 a, Lanes1 b) => new(a._v / b._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Sqrt(Lanes1 a) => new(MathF.Sqrt(a._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Negate(Lanes1 a) => new(-a._v);
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 Max(Lanes1 candidate, Lanes1 current) => candidate._v > current._v ? candidate : current;
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 Min(Lanes1 candidate, Lanes1 current) => candidate._v < current._v ? candidate : current;
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Less(Lanes1 a, Lanes1 b) => new(Mask(a._v < b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 LessOrEqual(Lanes1 a, Lanes1 b) => new(Mask(a._v <= b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Greater(Lanes1 a, Lanes1 b) => new(Mask(a._v > b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 Equal(Lanes1 a, Lanes1 b) => new(Mask(a._v == b._v));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 And(Lanes1 a, Lanes1 b) =>
        new(BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(a._v) & BitConverter.SingleToInt32Bits(b._v)));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 Or(Lanes1 a, Lanes1 b) =>
        new(BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(a._v) | BitConverter.SingleToInt32Bits(b._v)));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 AndNot(Lanes1 a, Lanes1 b) =>
        new(BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(a._v) & ~BitConverter.SingleToInt32Bits(b._v)));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 SignFill(Lanes1 a) => new(BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(a._v) >> 31));
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Lanes1 Select(Lanes1 mask, Lanes1 a, Lanes1 b) => BitConverter.SingleToInt32Bits(mask._v) < 0 ? a : b;
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint Bits(Lanes1 mask) => (uint)BitConverter.SingleToInt32Bits(mask._v) >> 31;
    [MethodImpl(MethodImplOptions.AggressiveInlining)] public static Lanes1 FromBits(uint bits) => new(Mask((bits & 1) != 0));
}
