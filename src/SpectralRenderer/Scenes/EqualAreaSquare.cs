using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// Clarberg's equal-area octahedral mapping between the unit square and the sphere (P. Clarberg, "Fast Equal-Area Mapping of
/// the (Hemi)Sphere using SIMD", JGT 13(3), 2008), the layout of pbrt-v4's image <c>infinite</c> lights (pbrt-v4
/// util/math.cpp EqualAreaSquareToSphere/SphereToSquare; lights.cpp ImageInfiniteLight). With s = 2u − 1, t = 2v − 1, the
/// diamond |s| + |t| ≤ 1 holds the hemisphere z ≥ 0 and the four corner triangles z &lt; 0; r = 1 − |1 − |s| − |t|| is the
/// distance from the square's centre (the +z pole) or its corners (the −z pole) in the L1 sense, and 1 − |z| = r², so equal
/// areas of the square are equal solid angles: each of N × N pixels subtends 4π/N². The azimuth within a quadrant grows
/// linearly along the diamond's edge, φ = (π/4)·((|t| − |s|)/r + 1); u runs along +x, v along +y, the centre is +z.
/// </summary>
public static class EqualAreaSquare
{
    /// <summary>The unit direction of square point (u, v) ∈ [0, 1]².</summary>
    public static Vector3 ToSphere(double u, double v)
    {
        double s = 2 * u - 1, t = 2 * v - 1, a = Math.Abs(s), b = Math.Abs(t);
        double signed = 1 - (a + b);                 // > 0 inside the diamond (the upper hemisphere)
        double r = 1 - Math.Abs(signed);
        double phi = (r == 0 ? 1 : (b - a) / r + 1) * Math.PI / 4;
        double z = Math.CopySign(1 - r * r, signed);
        double rho = r * Math.Sqrt(Math.Max(0, 2 - r * r));   // sin θ = √(1 − z²) = r·√(2 − r²)
        return new Vector3((float)Math.CopySign(Math.Cos(phi) * rho, s), (float)Math.CopySign(Math.Sin(phi) * rho, t), (float)z);
    }

    /// <summary>The square point (u, v) ∈ [0, 1]² of direction <paramref name="d"/> (any length): the inverse of
    /// <see cref="ToSphere"/>.</summary>
    public static Vector2 ToSquare(Vector3 d)
    {
        d = Vector3.Normalize(d);
        float x = MathF.Abs(d.X), y = MathF.Abs(d.Y);
        float r = MathF.Sqrt(MathF.Max(0, 1 - MathF.Abs(d.Z)));
        // The azimuth in the quadrant as a fraction of π/2: the share of r that goes to the t axis.
        float share = x == 0 && y == 0 ? 0 : MathF.Atan2(y, x) * (2 / MathF.PI);
        float t = share * r, s = r - t;
        if (d.Z < 0) (s, t) = (1 - t, 1 - s);   // the lower hemisphere: the corner triangles, mirrored across the diamond's edge
        s = MathF.CopySign(s, d.X);
        t = MathF.CopySign(t, d.Y);
        return new Vector2(0.5f * (s + 1), 0.5f * (t + 1));
    }
}
