using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>Sixteen floats, one per lane of a <see cref="RayPacket"/>.</summary>
[InlineArray(RayPacket.Size)]
public struct PacketFloats { float _lane0; }

/// <summary>Sixteen ints, one per lane of a <see cref="RayPacket"/>.</summary>
[InlineArray(RayPacket.Size)]
public struct PacketInts { int _lane0; }

/// <summary>
/// Up to 16 rays traced together through a <see cref="Bvh"/> (Wald, Slusallek, Benthin &amp; Wagner, "Interactive
/// rendering with coherent ray tracing", 2001): each ray is one SIMD lane, stored as structure of arrays, and
/// <see cref="Active"/> says which lanes hold one. A closest-hit query fills <see cref="TMax"/> (shortened to the
/// hit), <see cref="Primitive"/>, <see cref="U"/> and <see cref="V"/> as <see cref="Hit"/> does for one ray; the
/// answer of every lane is the answer its ray gets alone, bit for bit (the same IEEE operations in the same order).
/// A value type of 1.7 KB: a caller keeps one and refills it; nothing is allocated per packet.
/// </summary>
[SkipLocalsInit]
public struct RayPacket
{
    public const int Size = 16;

    /// <summary>Bit i set when lane i holds a ray.</summary>
    public uint Active;
    public PacketFloats OriginX, OriginY, OriginZ, DirectionX, DirectionY, DirectionZ, TMax;
    /// <summary>Closest-hit results: the primitive (position in BVH order) and barycentric (u, v), as in <see cref="Hit"/>.</summary>
    public PacketInts Primitive;
    public PacketFloats U, V;

    // Per lane, what the slab and watertight tests precompute for a single ray (SlabRay, ShearedRay).
    internal PacketFloats InverseX, InverseY, InverseZ;
    internal PacketFloats NegativeX, NegativeY, NegativeZ;   // all bits set where the direction's sign bit is set
    internal PacketFloats RowXx, RowXy, RowXz, RowYx, RowYy, RowYz, RowZx, RowZy, RowZz;

    /// <summary>Empties the packet.</summary>
    public void Clear() => Active = 0;

    /// <summary>Puts <paramref name="ray"/> into lane <paramref name="lane"/> and prepares it for traversal.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Set(int lane, in Ray ray)
    {
        Active |= 1u << lane;
        OriginX[lane] = ray.Origin.X; OriginY[lane] = ray.Origin.Y; OriginZ[lane] = ray.Origin.Z;
        DirectionX[lane] = ray.Direction.X; DirectionY[lane] = ray.Direction.Y; DirectionZ[lane] = ray.Direction.Z;
        TMax[lane] = ray.TMax;
        Primitive[lane] = -1; U[lane] = 0; V[lane] = 0;
        // As SlabRay: 1/d lane by lane (1/±0 = ±∞), the sign bit of d as a mask.
        var inverse = Vector128<float>.One / ray.Direction.AsVector128();
        InverseX[lane] = inverse.GetElement(0); InverseY[lane] = inverse.GetElement(1); InverseZ[lane] = inverse.GetElement(2);
        NegativeX[lane] = SignMask(ray.Direction.X); NegativeY[lane] = SignMask(ray.Direction.Y); NegativeZ[lane] = SignMask(ray.Direction.Z);
        var s = new ShearedRay(ray);
        RowXx[lane] = s.RowX.X; RowXy[lane] = s.RowX.Y; RowXz[lane] = s.RowX.Z;
        RowYx[lane] = s.RowY.X; RowYy[lane] = s.RowY.Y; RowYz[lane] = s.RowY.Z;
        RowZx[lane] = s.RowZ.X; RowZy[lane] = s.RowZ.Y; RowZz[lane] = s.RowZ.Z;
    }

    /// <summary>The ray of lane <paramref name="lane"/>, with its current TMax.</summary>
    public readonly Ray Ray(int lane) =>
        new(new Vector3(OriginX[lane], OriginY[lane], OriginZ[lane]), new Vector3(DirectionX[lane], DirectionY[lane], DirectionZ[lane]), TMax[lane]);

    /// <summary>Bit a set when most active lanes run towards −a (a = x, y, z): the packet visits that side's child first.</summary>
    internal readonly int NegativeAxes()
    {
        int axes = 0, half = BitOperations.PopCount(Active);
        if (2 * CountNegative(NegativeX) > half) axes |= 1;
        if (2 * CountNegative(NegativeY) > half) axes |= 2;
        if (2 * CountNegative(NegativeZ) > half) axes |= 4;
        return axes;
    }

    readonly int CountNegative(in PacketFloats negative)
    {
        int n = 0;
        for (uint m = Active; m != 0; m &= m - 1)
            if (BitConverter.SingleToInt32Bits(negative[BitOperations.TrailingZeroCount(m)]) != 0) n++;
        return n;
    }

    static float SignMask(float x) => BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(x) >> 31);
}

/// <summary>The SIMD width the packet kernels run at on this machine, chosen once at start-up.</summary>
public static class PacketLanes
{
    /// <summary>16 with AVX-512, 8 with AVX2, 4 with SSE/NEON, else 1 (DOTNET_PreferredVectorBitWidth and DOTNET_EnableAVX… lower it).</summary>
    public static int Width { get; } =
        Vector512.IsHardwareAccelerated ? 16 : Vector256.IsHardwareAccelerated ? 8 : Vector128.IsHardwareAccelerated ? 4 : 1;
}
