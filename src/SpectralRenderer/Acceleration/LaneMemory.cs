using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// Lane structures (<see cref="RayPacket"/>, <see cref="PacketFloats"/> and the structs made of them) placed on a 64-byte
/// boundary in stack or pinned memory, so that no SIMD load or store of lanes splits a cache line. A struct on the stack is
/// only 8- or 16-byte aligned, and where its 32-byte lanes fell depended on the depth of the stack: a lane written by one
/// call and read at once by the next then missed the store forwarding whenever it split a line, and the same machine code
/// ran up to 2× slower from one build (or one process) to the next. Callers reserve <see cref="Bytes{T}"/> bytes with
/// <c>stackalloc</c> (in a <c>SkipLocalsInit</c> method: not zeroed) and take the struct with <see cref="At{T}"/>.
/// </summary>
internal static class LaneMemory
{
    /// <summary>The cache line, and the boundary the structs are placed on.</summary>
    public const int Line = 64;

    /// <summary>Bytes to reserve for <paramref name="count"/> values of <typeparamref name="T"/> on a line boundary.</summary>
    public static int Bytes<T>(int count = 1) where T : unmanaged => count * Unsafe.SizeOf<T>() + Line - 1;

    /// <summary>The first value of <typeparamref name="T"/> on a line boundary inside <paramref name="memory"/> (stack or
    /// pinned: it must not move).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static unsafe ref T At<T>(Span<byte> memory) where T : unmanaged
    {
        nint start = (nint)Unsafe.AsPointer(ref MemoryMarshal.GetReference(memory));
        return ref Unsafe.AsRef<T>((void*)((start + Line - 1) & ~(nint)(Line - 1)));
    }

    /// <summary><paramref name="count"/> values of <typeparamref name="T"/> from a line boundary inside
    /// <paramref name="memory"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Span<T> Span<T>(Span<byte> memory, int count) where T : unmanaged =>
        MemoryMarshal.CreateSpan(ref At<T>(memory), count);
}

/// <summary>
/// <see cref="Length"/> floats from a cache-line boundary in a pinned array: a worker's spectra that SIMD loops fill whole (a
/// managed array starts 16 bytes past a boundary or not, by chance, and a 32- or 64-byte store that splits a line costs two).
/// </summary>
internal readonly struct LineFloats
{
    readonly float[] _array;
    readonly int _first;
    public readonly int Length;

    public LineFloats(int length)
    {
        _array = GC.AllocateArray<float>(length + LaneMemory.Line / sizeof(float), pinned: true);
        ref byte at = ref LaneMemory.At<byte>(MemoryMarshal.AsBytes(_array.AsSpan()));
        _first = (int)Unsafe.ByteOffset(ref Unsafe.As<float, byte>(ref _array[0]), ref at) / sizeof(float);
        Length = length;
    }

    public Span<float> Span => _array.AsSpan(_first, Length);
}

