using System.Numerics;

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

    public void Include(Vector3 p) { Min = Vector3.Min(Min, p); Max = Vector3.Max(Max, p); }
    public void Include(in Bounds3 b) { Min = Vector3.Min(Min, b.Min); Max = Vector3.Max(Max, b.Max); }
    public static Bounds3 Union(in Bounds3 a, in Bounds3 b) => new(Vector3.Min(a.Min, b.Min), Vector3.Max(a.Max, b.Max));

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
