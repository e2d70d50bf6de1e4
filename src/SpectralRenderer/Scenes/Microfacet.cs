using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>
/// The isotropic GGX (Trowbridge–Reitz) microfacet distribution with Smith masking, in a local frame whose z axis is the
/// macro-surface normal: D(h) = α²/(π·((h_z)²(α² − 1) + 1)²) (Walter et al. 2007, eq. 33), Λ(ω) = (√(1 + α² tan²θ) − 1)/2
/// (Heitz 2014, eq. 72), G₁ = 1/(1 + Λ) and the height-correlated G₂ = 1/(1 + Λ(ωo) + Λ(ωi)) (Heitz 2014, eq. 99).
/// Normals are drawn from the distribution of visible normals D_ωo(h) = G₁(ωo)·max(0, ωo·h)·D(h)/cos θo (Heitz 2018,
/// JCGT 7(4)), so a reflected direction has the solid-angle density G₁(ωo)·D(h)/(4 cos θo).
/// </summary>
public static class Ggx
{
    /// <summary>D(h) for the cosine <paramref name="cosH"/> between h and the normal.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float D(float cosH, float alpha)
    {
        if (!(cosH > 0)) return 0;
        float a2 = alpha * alpha, t = cosH * cosH * (a2 - 1) + 1;
        return a2 / (MathF.PI * t * t);
    }

    /// <summary>Smith's Λ for a direction at cos θ from the normal.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float Lambda(float cos, float alpha)
    {
        float c2 = cos * cos;
        if (!(c2 > 0)) return float.PositiveInfinity;
        float tan2 = MathF.Max(0, 1 - c2) / c2;
        return (MathF.Sqrt(1 + alpha * alpha * tan2) - 1) / 2;
    }

    /// <summary>G₁(ω) = 1/(1 + Λ(ω)): the fraction of the microsurface visible from ω.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float G1(float cos, float alpha) => 1 / (1 + Lambda(cos, alpha));

    /// <summary>The height-correlated masking-shadowing G₂(ωo, ωi) = 1/(1 + Λ(ωo) + Λ(ωi)).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float G2(float cosO, float cosI, float alpha) => 1 / (1 + Lambda(cosO, alpha) + Lambda(cosI, alpha));

    /// <summary>
    /// A visible normal for the local view direction <paramref name="wo"/> (z > 0) and u ∈ [0, 1)² (Heitz 2018, listing 1):
    /// the view stretched to the hemisphere configuration, a point on the projected disk, unstretched.
    /// </summary>
    public static Vector3 SampleVisibleNormal(Vector3 wo, float alpha, Vector2 u)
    {
        var vh = Vector3.Normalize(new Vector3(alpha * wo.X, alpha * wo.Y, wo.Z));
        float lensq = vh.X * vh.X + vh.Y * vh.Y;
        var t1 = lensq > 0 ? new Vector3(-vh.Y, vh.X, 0) / MathF.Sqrt(lensq) : Vector3.UnitX;
        var t2 = Vector3.Cross(vh, t1);
        float r = MathF.Sqrt(u.X), phi = 2 * MathF.PI * u.Y;
        float p1 = r * MathF.Cos(phi), p2 = r * MathF.Sin(phi);
        float s = 0.5f * (1 + vh.Z);
        p2 = (1 - s) * MathF.Sqrt(MathF.Max(0, 1 - p1 * p1)) + s * p2;
        var nh = p1 * t1 + p2 * t2 + MathF.Sqrt(MathF.Max(0, 1 - p1 * p1 - p2 * p2)) * vh;
        return Vector3.Normalize(new Vector3(alpha * nh.X, alpha * nh.Y, MathF.Max(1e-7f, nh.Z)));
    }

    /// <summary>The solid-angle density of ωi = reflect(ωo, h) for h drawn by <see cref="SampleVisibleNormal"/>: G₁(ωo)·D(h)/(4 cos
    /// θo).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float ReflectionPdf(float cosO, float cosH, float alpha) => G1(cosO, alpha) * D(cosH, alpha) / (4 * cosO);

    /// <summary><paramref name="v"/> in the frame (t, b, n): its components along t, b and n.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3 ToLocal(Vector3 v, Vector3 t, Vector3 b, Vector3 n) =>
        new(Vector3.Dot(v, t), Vector3.Dot(v, b), Vector3.Dot(v, n));
}

/// <summary>
/// Fresnel reflectance of a conductor of complex index n + ik seen from a medium of index 1, for unpolarised light (Born &amp;
/// Wolf, Principles of Optics §14.2; the real form of pbrt-v3's FrConductor): with a² + b² = √((n² − k² − sin²θ)² + 4n²k²)
/// and a = √((a² + b² + n² − k² − sin²θ)/2), R_s = (a² + b² − 2a cos θ + cos²θ)/(a² + b² + 2a cos θ + cos²θ),
/// R_p = R_s·(a² + b²)cos²θ − 2a cos θ sin²θ + sin⁴θ over the same with +2a, and R = (R_s + R_p)/2. At normal incidence
/// R = ((n − 1)² + k²)/((n + 1)² + k²).
/// </summary>
public static class Conductor
{
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float Reflectance(float cos, float n, float k)
    {
        cos = Math.Clamp(cos, 0, 1);
        float cos2 = cos * cos, sin2 = 1 - cos2;
        float t0 = n * n - k * k - sin2;
        float a2b2 = MathF.Sqrt(t0 * t0 + 4 * n * n * k * k);
        float a = MathF.Sqrt(MathF.Max(0, (a2b2 + t0) / 2));
        float t1 = a2b2 + cos2, t2 = 2 * a * cos;
        float rs = (t1 - t2) / (t1 + t2);
        float t3 = a2b2 * cos2 + sin2 * sin2, t4 = t2 * sin2;
        float rp = rs * (t3 - t4) / (t3 + t4);
        float r = (rs + rp) / 2;
        return float.IsFinite(r) ? r : 1;
    }
}
