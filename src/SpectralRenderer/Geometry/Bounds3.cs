using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;

namespace SpectralRenderer.Geometry;

/// <summary>An axis-aligned bounding box.</summary>
public struct Bounds3
{
    public Vector3 Min;
    public Vector3 Max;

    public Bounds3(Vector3 min, Vector3 max) { Min = min; Max = max; }

    public static Bounds3 Empty => new(new Vector3(float.PositiveInfinity), new Vector3(float.NegativeInfinity));

    public readonly bool IsEmpty => Min.X > Max.X || Min.Y > Max.Y || Min.Z > Max.Z;
    public readonly Vector3 Centre => 0.5f * (Min + Max);
    public readonly Vector3 Extent => Max - Min;

    // minps/maxps (MinNative/MaxNative): bounds hold no NaN, so IEEE NaN handling would only cost time.
    public void Include(Vector3 p) { Min = Lo(Min, p); Max = Hi(Max, p); }
    public void Include(in Bounds3 b) { Min = Lo(Min, b.Min); Max = Hi(Max, b.Max); }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector3 Lo(Vector3 a, Vector3 b) => Vector128.MinNative(a.AsVector128(), b.AsVector128()).AsVector3();
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector3 Hi(Vector3 a, Vector3 b) => Vector128.MaxNative(a.AsVector128(), b.AsVector128()).AsVector3();

    /// <summary>The box about the eight corners of this one under the affine <paramref name="m"/> (p·M, System.Numerics' row
    /// vectors): the world box of an object-space box.</summary>
    public readonly Bounds3 Transformed(Matrix4x4 m)
    {
        var b = Empty;
        for (int c = 0; c < 8; c++)
            b.Include(Vector3.Transform(new Vector3((c & 1) == 0 ? Min.X : Max.X, (c & 2) == 0 ? Min.Y : Max.Y,
                (c & 4) == 0 ? Min.Z : Max.Z), m));
        return b;
    }

    /// <summary>Half the surface area (the SAH only needs ratios).</summary>
    public readonly float HalfArea
    {
        get
        {
            if (IsEmpty) return 0;
            var e = Max - Min;
            return e.X * e.Y + e.Y * e.Z + e.Z * e.X;
        }
    }
}
