using System.Numerics;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// One sample of an emitter seen from a point (<see cref="Emitter.Sample"/>): the unit direction ω_i towards it, the
/// distance (∞ at infinity), the factor on its spectrum <see cref="Emitter.Radiance"/> (1 for radiance, d_k·c_spot,k of a
/// delta light), the solid-angle pdf p_ω (1 for a delta light), whether it is a delta emitter, and on a surface the point x,
/// its normal n_x and the face (parallelogram or triangle) it lies on, for a textured emission.
/// </summary>
internal readonly record struct EmitterSample(Vector3 Direction, float Distance, float Factor, float Pdf, bool IsDelta,
    Vector3 Point = default, Vector3 Normal = default, int Face = 0);

/// <summary>
/// A light source as the path tracer sees it, whatever its kind (Mitsuba 3's <c>Emitter</c>, pbrt-v4's <c>Light</c>): it
/// answers sample, pdf, emitted radiance, is-delta and describe, and lives in the scene's one <see cref="EmitterSet"/>.
/// Next-event estimation draws from <see cref="Sample"/>; a BSDF-sampled ray that hits the emitter (or escapes, for the
/// sky) is weighted by multiple importance sampling with <see cref="Pdf"/>, the density of the same draw (Veach 1997, §9.2).
/// The kinds: a scene light (<see cref="SceneLightEmitter"/>: point, spot, directional, goniometric — delta, never hit),
/// an emitting object (<see cref="ShapeEmitter"/>: any shape kind) and the sky (<see cref="SkyEmitter"/>, uniform;
/// <see cref="OvercastSkyEmitter"/>, the CIE overcast sky, whose <see cref="Emitted"/> of an escaping ray's direction is the
/// factor on its radiance; or <see cref="EnvironmentEmitter"/>, an image whose radiance the caller looks up per direction).
/// </summary>
internal abstract class Emitter(float[] radiance, SubBandTexture? texture = null)
{
    /// <summary>The emitted spectrum on the path tracer's sub-band grid: radiance L_e, or a delta light's intensity I_k.</summary>
    public float[] Radiance { get; } = radiance;

    /// <summary>True for an emitter concentrated in a point or a direction: no ray can hit it; its pdf is 1 by convention.</summary>
    public abstract bool IsDelta { get; }

    /// <summary>
    /// Its radiant power per unit of <see cref="Radiance"/>'s spectral integral (Φ = this × ∫L dλ; <see cref="EmitterSet.Power"/>),
    /// a light at infinity's through the sphere of radius <paramref name="sceneRadius"/> about the scene.
    /// </summary>
    public abstract double PowerPerRadiance(double sceneRadius);

    /// <summary>Where it is and where it shines, for a light tree (<see cref="LightTree"/>), or null for an emitter at infinity
    /// (the sky, a directional light).</summary>
    public virtual EmitterBounds? Bounds => null;

    /// <summary>The scene light this emitter is (its index in <c>Scene.Lights</c>, whose transfer a relight keeps apart), or −1.</summary>
    public virtual int SceneLight => -1;

    /// <summary>
    /// One sample of the emitter seen from <paramref name="p"/> (front shading normal <paramref name="front"/>) for
    /// <paramref name="u"/> ∈ [0, 1)²; false when it sends nothing towards p for these numbers.
    /// </summary>
    public abstract bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample);

    /// <summary>
    /// The solid-angle density with which <see cref="Sample"/> from <paramref name="p"/> (front normal
    /// <paramref name="front"/>) picks direction <paramref name="wi"/>, reaching the emitter at <paramref name="x"/> with
    /// normal <paramref name="nx"/> (unused at infinity); 0 for a delta emitter.
    /// </summary>
    public abstract float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx);

    /// <summary>
    /// The factor on <see cref="Radiance"/> of what a ray that reaches the emitter at surface normal <paramref name="n"/>
    /// travelling back along <paramref name="wo"/> (towards its origin) sees: 1 or 0 (a one-sided emitter seen from behind;
    /// a delta emitter, never hit).
    /// </summary>
    public abstract float Emitted(Vector3 n, Vector3 wo);

    /// <summary>L_e as a texture on the sub-band grid (<see cref="TexCoord"/> places a sample's point on it), or null.</summary>
    public SubBandTexture? Texture { get; } = texture;

    /// <summary>
    /// The (u, v) of point <paramref name="x"/> on <paramref name="face"/> and the mapping's density (a textured emitter).
    /// </summary>
    public virtual Vector2 TexCoord(int face, Vector3 x, out float uvPerLength) =>
        throw new NotSupportedException($"{Describe()} has no texture");

    /// <summary>The emitter in words, for messages and tests: its kind and name.</summary>
    public abstract string Describe();
}
