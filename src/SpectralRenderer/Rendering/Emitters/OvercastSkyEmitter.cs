using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// The CIE standard overcast sky (<see cref="SkyDistribution.CieOvercast"/>; Moon &amp; Spencer 1942, CIE S 011/E:2003 sky
/// type 1 in its traditional form): an escaping ray in direction ω sees L(ω) = L_z·g(cos θ), g(μ) = (1 + 2μ)/3 for μ = z·ω > 0
/// (θ from the zenith z) and 0 below the horizon, <see cref="Emitter.Radiance"/> the zenith's L_z. The factor g is what
/// <see cref="Emitted"/> and a sample's factor carry. Next-event estimation draws half its samples ∝ g over the upper
/// hemisphere, p_g(ω) = (1 + 2μ)/(4π) (∫g dω = 4π/3; the marginal of μ is (1 + 2μ)/2, inverted as μ = (√(1 + 8u) − 1)/2,
/// the azimuth uniform), and half cosine-weighted about the front shading normal n (p = max(0, n·ω)/π, the uniform sky's),
/// one sample from the mixture p = ½p_g + ½p_cos (the sky's luminance and the receiver's cosine each importance-sampled);
/// from a point without a surface (n = 0: in a medium) the draw is p_g alone.
/// </summary>
internal sealed class OvercastSkyEmitter(float[] zenithRadiance, Vector3 zenith) : Emitter(zenithRadiance)
{
    readonly Vector3 _zenith = Vector3.Normalize(zenith);

    public override bool IsDelta => false;

    /// <summary>g(μ) = (1 + 2μ)/3 above the horizon (μ = cos θ > 0), 0 below: L(θ)/L_z.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static float Gradation(float cosTheta) => cosTheta > 0 ? (1 + 2 * cosTheta) / 3 : 0;

    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        sample = default;
        bool surface = front != Vector3.Zero;
        Vector3 wi;
        if (!surface || u.X < 0.5f)
        {
            // ∝ g over the upper hemisphere: F(μ) = (μ + μ²)/2 = u.
            float ux = surface ? 2 * u.X : u.X;
            float mu = 0.5f * (MathF.Sqrt(1 + 8 * ux) - 1), sin = MathF.Sqrt(MathF.Max(0, 1 - mu * mu));
            float phi = 2 * MathF.PI * u.Y;
            var (t, b) = Bsdf.Frame(_zenith);
            wi = sin * MathF.Cos(phi) * t + sin * MathF.Sin(phi) * b + mu * _zenith;
        }
        else wi = Bsdf.CosineHemisphere(front, new Vector2(2 * u.X - 1, u.Y));
        float factor = Gradation(Vector3.Dot(_zenith, wi)), pdf = Density(front, wi);
        if (!(factor > 0) || !(pdf > 0)) return false;
        sample = new EmitterSample(wi, float.PositiveInfinity, factor, pdf, false);
        return true;
    }

    /// <summary>Φ/L_z = ∫g dω·πR² = (4π/3)·πR²: the sky's radiance through the disc of the scene's bounding sphere.</summary>
    public override double PowerPerRadiance(double sceneRadius) => 4 * Math.PI * Math.PI * sceneRadius * sceneRadius / 3;

    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx) => Density(front, wi);

    /// <summary>g of the direction the escaping ray left in (−<paramref name="wo"/>).</summary>
    public override float Emitted(Vector3 n, Vector3 wo) => Gradation(-Vector3.Dot(_zenith, wo));

    public override string Describe() => "sky (CIE standard overcast)";

    /// <summary>The mixture's solid-angle density ½p_g + ½p_cos about <paramref name="front"/> (p_g alone when it is 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    float Density(Vector3 front, Vector3 wi)
    {
        float mu = Vector3.Dot(_zenith, wi);
        float sky = mu > 0 ? (1 + 2 * mu) / (4 * MathF.PI) : 0;
        if (front == Vector3.Zero) return sky;
        return 0.5f * sky + 0.5f * MathF.Max(0, Vector3.Dot(front, wi)) / MathF.PI;
    }
}
