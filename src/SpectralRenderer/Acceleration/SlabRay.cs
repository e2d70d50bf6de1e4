using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// A ray prepared for slab tests against many boxes (Kay &amp; Kajiya 1986; Williams et al., "An efficient and
/// robust ray–box intersection algorithm", JGT 2005): the inverse direction and, per axis, which box side is
/// entered first, chosen by the direction's sign bit. A zero component gives 1/±0 = ±∞, so the slab distances are
/// ±∞ (inside or outside the slab) or, for an origin exactly on the slab's plane, 0·∞ = NaN, which the
/// comparisons below ignore: such a ray runs inside the slab.
/// </summary>
readonly struct SlabRay
{
    /// <summary>Widening of the exit distance, 1 + 2γ₃, so rounding never culls a box the ray touches (Ize 2013; pbrt-v4 §6.8.2).</summary>
    internal const float ExitScale = 1 + 2 * (3 * UnitRoundoff) / (1 - 3 * UnitRoundoff);
    const float UnitRoundoff = 5.96046448e-8f; // 2^-24

    readonly Vector128<float> _origin;
    readonly Vector128<float> _inverse;
    readonly Vector128<float> _negative; // all ones in lanes whose direction has the sign bit set (−0 included)

    public SlabRay(in Ray ray)
    {
        _origin = ray.Origin.AsVector128();
        // Lane 3 is NaN, so whatever the node holds beside its corners (Offset, Count) drops out of the test below.
        _inverse = (Vector128<float>.One / ray.Direction.AsVector128()).WithElement(3, float.NaN);
        _negative = Vector128.ShiftRightArithmetic(ray.Direction.AsVector128().AsInt32(), 31).AsSingle();
        NegativeAxes = (int)(Vector128.ExtractMostSignificantBits(ray.Direction.AsVector128()) & 7);
    }

    /// <summary>Bit a is set when the direction's component a is negative (sign bit).</summary>
    public int NegativeAxes { get; }

    /// <summary>Whether the ray's interval [0, tMax] overlaps the node's box.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Hits(in BvhNode node, float tMax) => Hits(node, tMax, out _);

    /// <summary>As <see cref="Hits(in BvhNode, float)"/>, also giving the distance at which the ray enters the box.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Hits(in BvhNode node, float tMax, out float entry)
    {
        // One 16-byte load per corner: Min with Offset, Max with Count and Axis in lane 3 (BvhNode's layout).
        ref float at = ref Unsafe.As<BvhNode, float>(ref Unsafe.AsRef(in node));
        var min = Unsafe.ReadUnaligned<Vector128<float>>(ref Unsafe.As<float, byte>(ref at));
        var max = Unsafe.ReadUnaligned<Vector128<float>>(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref at, 4)));
        var near = (Vector128.ConditionalSelect(_negative, max, min) - _origin) * _inverse;
        var far = (Vector128.ConditionalSelect(_negative, min, max) - _origin) * _inverse * Vector128.Create(ExitScale);
        if (Sse.IsSupported)
        {
            // maxps/minps return the second operand when the first is NaN: NaN slabs (a ray in a face's plane)
            // and the unused fourth lane drop out, as in the scalar form below.
            var e = Sse.Max(near, Vector128<float>.Zero);
            var x = Sse.Min(far, Vector128.Create(tMax));
            e = Sse.Max(e, Sse.Shuffle(e, e, 0b01_00_11_10));
            e = Sse.Max(e, Sse.Shuffle(e, e, 0b10_11_00_01));
            x = Sse.Min(x, Sse.Shuffle(x, x, 0b01_00_11_10));
            x = Sse.Min(x, Sse.Shuffle(x, x, 0b10_11_00_01));
            entry = e.ToScalar();
            return entry <= x.ToScalar();
        }
        // "candidate > current ? candidate : current" keeps current when the candidate is NaN.
        float exit = tMax;
        entry = 0;
        float n = near.GetElement(0); if (n > entry) entry = n;
        n = near.GetElement(1); if (n > entry) entry = n;
        n = near.GetElement(2); if (n > entry) entry = n;
        float f = far.GetElement(0); if (f < exit) exit = f;
        f = far.GetElement(1); if (f < exit) exit = f;
        f = far.GetElement(2); if (f < exit) exit = f;
        return entry <= exit;
    }
}
