using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// The sky: the scene's <c>background</c> (a uniform radiance, or a CIE daylight by <c>"sky"</c>) as the radiance of every
/// ray that escapes, sampled cosine-weighted about the front shading normal, p_ω = max(0, n·ω)/π.
/// </summary>
internal sealed class SkyEmitter(float[] radiance) : Emitter(radiance)
{
    public override bool IsDelta => false;

    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        var wi = Bsdf.CosineHemisphere(front, u);
        sample = new EmitterSample(wi, float.PositiveInfinity, 1, Density(front, wi), false);
        return true;
    }

    /// <summary>Φ/L = 4π·πR²: radiance L from every direction through the disc of the scene's bounding sphere (pbrt-v4's
    /// <c>UniformInfiniteLight::Phi</c>).</summary>
    public override double PowerPerRadiance(double sceneRadius) => 4 * Math.PI * Math.PI * sceneRadius * sceneRadius;

    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx) => Density(front, wi);

    /// <summary>Every escaping ray sees the sky.</summary>
    public override float Emitted(Vector3 n, Vector3 wo) => 1;
    public override string Describe() => "sky (uniform background)";

    /// <summary>The cosine-weighted density about <paramref name="front"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float Density(Vector3 front, Vector3 wi) => MathF.Max(0, Vector3.Dot(front, wi)) / MathF.PI;
}
