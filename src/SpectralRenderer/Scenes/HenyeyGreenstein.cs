using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>
/// The Henyey–Greenstein phase function (Henyey &amp; Greenstein 1941), the same in every band: the density of scattering by the
/// angle θ between the propagation directions before and after, p(cos θ) = (1 − g²) / (4π·(1 + g² − 2g·cos θ)^{3/2}), with
/// ∫p dω = 1 and mean cosine g (g = 0: isotropic, 1/4π; g &gt; 0: forward). Directions follow the BSDF convention: ωo points
/// back along the ray that arrived (towards the previous vertex), ωi along the ray that leaves, so cos θ = −ωo·ωi.
/// Sampled exactly by inverting its cumulative distribution in cos θ, so f/pdf = 1.
/// </summary>
public sealed class HenyeyGreenstein(float g)
{
    /// <summary>The asymmetry g = ⟨cos θ⟩, |g| &lt; 1.</summary>
    public float G { get; } = g;

    /// <summary>p for the directions ωo (back along the arriving ray) and ωi (the leaving one): also the sampling density.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Evaluate(Vector3 wo, Vector3 wi) => Density(-Vector3.Dot(wo, wi));

    /// <summary>p(cos θ).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Density(float cosTheta)
    {
        float g2 = G * G, d = 1 + g2 - 2 * G * cosTheta;
        return (1 - g2) / (4 * MathF.PI * d * MathF.Sqrt(MathF.Max(d, 1e-12f)));
    }

    /// <summary>A direction ωi drawn with density p(ωo, ωi) from <paramref name="u"/> ∈ [0, 1)².</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3 Sample(Vector3 wo, Vector2 u)
    {
        // cos θ from P(cos θ ≤ c) = u.X: for g ≠ 0 the inverse (1 + g² − ((1 − g²)/(1 − g + 2g·u))²)/(2g), else uniform.
        float cos;
        if (MathF.Abs(G) < 1e-3f) cos = 1 - 2 * u.X;
        else
        {
            float s = (1 - G * G) / (1 - G + 2 * G * u.X);
            cos = (1 + G * G - s * s) / (2 * G);
        }
        cos = Math.Clamp(cos, -1, 1);
        float sin = MathF.Sqrt(MathF.Max(0, 1 - cos * cos)), phi = 2 * MathF.PI * u.Y;
        var axis = -wo;   // the propagation direction of the arriving ray
        var (t, b) = Bsdf.Frame(axis);
        return Vector3.Normalize(sin * MathF.Cos(phi) * t + sin * MathF.Sin(phi) * b + cos * axis);
    }
}
