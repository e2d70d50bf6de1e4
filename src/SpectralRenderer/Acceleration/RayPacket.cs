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
/// A value type of 1.6 KB: a caller keeps one and refills it; nothing is allocated per packet.
/// </summary>
[SkipLocalsInit]
public struct RayPacket
{
    public const int Size = 16;

    // The lane arrays first, each a multiple of 64 bytes from the start: a packet placed on a cache-line boundary
    // (LaneMemory) keeps every SIMD load of lanes inside one line.
    public PacketFloats OriginX, OriginY, OriginZ, DirectionX, DirectionY, DirectionZ, TMax;
    /// <summary>Closest-hit results: the primitive (position in BVH order) and barycentric (u, v), as in <see cref="Hit"/>.</summary>
    public PacketInts Primitive;
    public PacketFloats U, V;

    // Per lane, what the slab and watertight tests precompute for a single ray (SlabRay, ShearedRay).
    internal PacketFloats InverseX, InverseY, InverseZ;
    internal PacketFloats NegativeX, NegativeY, NegativeZ;   // all bits set where the direction's sign bit is set
    internal PacketFloats RowXx, RowXy, RowXz, RowYx, RowYy, RowYz, RowZx, RowZy, RowZz;

    /// <summary>Bit i set when lane i holds a ray.</summary>
    public uint Active;

    /// <summary>Empties the packet.</summary>
    public void Clear() => Active = 0;

    /// <summary>Puts <paramref name="ray"/> into lane <paramref name="lane"/> (the traversal prepares all lanes at once,
    /// <see cref="Prepare{L}"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Set(int lane, in Ray ray)
    {
        Active |= 1u << lane;
        OriginX[lane] = ray.Origin.X; OriginY[lane] = ray.Origin.Y; OriginZ[lane] = ray.Origin.Z;
        DirectionX[lane] = ray.Direction.X; DirectionY[lane] = ray.Direction.Y; DirectionZ[lane] = ray.Direction.Z;
        TMax[lane] = ray.TMax;
        Primitive[lane] = -1; U[lane] = 0; V[lane] = 0;
    }

    /// <summary>
    /// Computes for all lanes at once what SlabRay and ShearedRay compute for one ray: 1/d, the sign masks of d,
    /// and the watertight test's shear (dominant axis k_z of |d|, k_x and k_y swapped when d[k_z] &lt; 0,
    /// S = (d[k_x]/d[k_z], d[k_y]/d[k_z], 1/d[k_z]) folded into the rows Unit(k_x) − S_x·Unit(k_z),
    /// Unit(k_y) − S_y·Unit(k_z), S_z·Unit(k_z)), with the same operations, so the same bits. Called by the traversal.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal void Prepare<L>() where L : struct, ILanes<L>
    {
        var one = L.Splat(1);
        var zero = L.Splat(0);
        var all = L.Equal(zero, zero);
        var magnitude = L.Splat(BitConverter.Int32BitsToSingle(0x7FFFFFFF));
        for (int c = 0; c < Size; c += L.Count)
        {
            var dx = L.Load(ref DirectionX[c]); var dy = L.Load(ref DirectionY[c]); var dz = L.Load(ref DirectionZ[c]);
            L.Store(one / dx, ref InverseX[c]); L.Store(one / dy, ref InverseY[c]); L.Store(one / dz, ref InverseZ[c]);
            L.Store(L.SignFill(dx), ref NegativeX[c]); L.Store(L.SignFill(dy), ref NegativeY[c]); L.Store(L.SignFill(dz), ref NegativeZ[c]);
            var ax = L.And(dx, magnitude); var ay = L.And(dy, magnitude); var az = L.And(dz, magnitude);
            var xy = L.Greater(ax, ay);
            var zx = L.And(xy, L.Greater(ax, az));            // k_z = x
            var zy = L.AndNot(L.Greater(ay, az), xy);         // k_z = y
            var zz = L.AndNot(all, L.Or(zx, zy));             // k_z = z
            var dkz = L.Select(zx, dx, L.Select(zy, dy, dz));
            // k_x = k_z + 1, k_y = k_x + 1 (mod 3), swapped when d[k_z] < 0.
            var swap = L.Less(dkz, zero);
            var xx = L.Select(swap, zy, zz); var xyM = L.Select(swap, zz, zx); var xz = L.Select(swap, zx, zy);   // k_x = x, y, z
            var yx = L.Select(swap, zz, zy); var yy = L.Select(swap, zx, zz); var yz = L.Select(swap, zy, zx);    // k_y = x, y, z
            var dkx = L.Select(xx, dx, L.Select(xyM, dy, dz));
            var dky = L.Select(yx, dx, L.Select(yy, dy, dz));
            var sz = one / dkz;
            var sx = dkx * sz; var sy = dky * sz;
            var ux = L.And(zx, one); var uy = L.And(zy, one); var uz = L.And(zz, one);   // Unit(k_z)
            L.Store(L.And(xx, one) - sx * ux, ref RowXx[c]);
            L.Store(L.And(xyM, one) - sx * uy, ref RowXy[c]);
            L.Store(L.And(xz, one) - sx * uz, ref RowXz[c]);
            L.Store(L.And(yx, one) - sy * ux, ref RowYx[c]);
            L.Store(L.And(yy, one) - sy * uy, ref RowYy[c]);
            L.Store(L.And(yz, one) - sy * uz, ref RowYz[c]);
            L.Store(sz * ux, ref RowZx[c]); L.Store(sz * uy, ref RowZy[c]); L.Store(sz * uz, ref RowZz[c]);
        }
    }

    /// <summary>The ray of lane <paramref name="lane"/>, with its current TMax.</summary>
    public readonly Ray Ray(int lane) =>
        new(new Vector3(OriginX[lane], OriginY[lane], OriginZ[lane]), new Vector3(DirectionX[lane], DirectionY[lane], DirectionZ[lane]),
            TMax[lane]);

    /// <summary>Bit a set when most active lanes run towards −a (a = x, y, z): the packet visits that side's child first.</summary>
    internal int NegativeAxes()
    {
        int half = BitOperations.PopCount(Active);
        int axes = 0;
        if (2 * BitOperations.PopCount(SignBits(ref NegativeX) & Active) > half) axes |= 1;
        if (2 * BitOperations.PopCount(SignBits(ref NegativeY) & Active) > half) axes |= 2;
        if (2 * BitOperations.PopCount(SignBits(ref NegativeZ) & Active) > half) axes |= 4;
        return axes;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint SignBits(ref PacketFloats lanes)
    {
        ref float first = ref lanes[0];
        if (Vector512.IsHardwareAccelerated) return (uint)Vector512.LoadUnsafe(ref first).ExtractMostSignificantBits();
        uint bits = 0;
        for (int i = 0; i < Size; i++) bits |= (uint)BitConverter.SingleToInt32Bits(Unsafe.Add(ref first, i)) >> 31 << i;
        return bits;
    }

    static float SignMask(float x) => BitConverter.Int32BitsToSingle(BitConverter.SingleToInt32Bits(x) >> 31);
}

/// <summary>The SIMD width the packet kernels run at on this machine, chosen once at start-up.</summary>
public static class PacketLanes
{
    /// <summary>16 with AVX-512, 8 with AVX2, 4 with SSE/NEON, else 1 (DOTNET_PreferredVectorBitWidth and DOTNET_EnableAVX… lower
    /// it).</summary>
    public static int Width { get; } =
        Vector512.IsHardwareAccelerated ? 16 : Vector256.IsHardwareAccelerated ? 8 : Vector128.IsHardwareAccelerated ? 4 : 1;
}
