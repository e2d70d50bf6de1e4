using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// What a light gives a surface point for eq. 2: the unit direction l towards the light, the distance
/// along it (∞ for a directional light), the spot factor c_spot,k and the distance attenuation d_k.
/// </summary>
public readonly struct LightSample
{
    public readonly Vector3 Direction;
    public readonly float Distance;
    public readonly float Spot;
    public readonly float Attenuation;

    public LightSample(Vector3 direction, float distance, float spot, float attenuation)
    {
        Direction = direction; Distance = distance; Spot = spot; Attenuation = attenuation;
    }
}

/// <summary>
/// What every light of eq. 2 emits, whatever its kind: its name, spectral intensity I_k (band values, spectrum ×
/// intensity), ambient contribution I_amb,k, the scene's "intensity" factor and the spectrum as given.
/// </summary>
public readonly record struct LightEmission(string Name, float[] Intensity, float[] Ambient, bool HasAmbient, float Scale = 1,
    Spectra.TabulatedSpectrum? Spectrum = null, LightPhotometry? Photometric = null);

/// <summary>
/// A light's strength given photometrically (physical radiometry): the quantity ("luminous_flux", "luminous_intensity",
/// "illuminance", "luminance"), its value in <paramref name="Unit"/> (lm, cd, lx, cd/m²), the radiometric scale it gives
/// (the factor on the spectrum, what "intensity" would be) and K_m ∫V·S dλ of the spectrum (photometric per unit scale).
/// </summary>
public sealed record LightPhotometry(string Quantity, double Value, string Unit, double RadiometricScale, double LuminousPerUnit);

/// <summary>
/// A light of eq. 2: its spectral intensity I_k (band values, spectrum × intensity) and its ambient
/// contribution I_amb,k. Each kind of light (one file each) answers <see cref="Illuminate"/>;
/// the integrator never asks which kind it has.
/// </summary>
public abstract class Light(LightEmission emission)
{
    public string Name { get; } = emission.Name;
    public float[] Intensity { get; } = emission.Intensity;
    public float[] Ambient { get; } = emission.Ambient;
    public bool HasAmbient { get; } = emission.HasAmbient;
    /// <summary>The scene's "intensity": the factor on <see cref="Spectrum"/> in <see cref="Intensity"/>.</summary>
    public float Scale { get; } = emission.Scale;
    /// <summary>The light's spectrum as given (for reports and the reference white).</summary>
    public Spectra.TabulatedSpectrum? Spectrum { get; } = emission.Spectrum;
    /// <summary>The photometric value the scene gave instead of "intensity", or null.</summary>
    public LightPhotometry? Photometric { get; } = emission.Photometric;

    /// <summary>The scene-file name of this kind of light ("point", "spot", "directional").</summary>
    public abstract string Type { get; }

    /// <summary>
    /// Direction, distance, c_spot,k and d_k of eq. 2 at point <paramref name="p"/>; false when the light
    /// cannot reach it at all (the point is at the light, or outside its cone), so it adds nothing, not even ambient.
    /// </summary>
    public abstract bool Illuminate(Vector3 p, out LightSample sample);

    /// <summary>The light as an isotropic point light that packets evaluate in SIMD lanes, or null when it is not one.</summary>
    public virtual LanePointLight? LaneForm => null;

    // ---- sampling: a scene light is a delta light --------------------------------------------------------------

    /// <summary>
    /// True: every scene light is concentrated in a point or a direction (point, spot, directional, goniometric), so no ray
    /// can hit it and the path tracer's emitter set (Rendering/Emitters) gives it pdf and emitted radiance 0. A light with
    /// extent is an emitting object (a material's <c>emission</c> on any shape kind), not a <see cref="Light"/>.
    /// </summary>
    public bool IsDelta => true;

    /// <summary>
    /// One sample of the light seen from <paramref name="p"/> for the random numbers <paramref name="u"/> ∈ [0, 1)²:
    /// <see cref="Illuminate"/>'s direction and distance, whatever <paramref name="u"/>, the factor d_k·c_spot,k on its
    /// spectrum <see cref="Intensity"/> (as eq. 2 uses it), the pdf 1 (its one direction is chosen with certainty) and
    /// <see cref="IsDelta"/>. False when it cannot reach <paramref name="p"/>.
    /// </summary>
    public bool Sample(Vector3 p, Vector2 u, out LightIncidence sample)
    {
        if (!Illuminate(p, out var ls)) { sample = default; return false; }
        sample = new LightIncidence(ls.Direction, ls.Distance, ls.Attenuation * ls.Spot, 1f, IsDelta);
        return true;
    }

    /// <summary>
    /// The radiant power per unit of the spectrum <see cref="Intensity"/> (the factor Φ_λ/I_λ): the solid-angle integral
    /// ∫c_spot dω of a light at a point (4π for an isotropic one, the kinds override it), πR² for a light at infinity (the
    /// irradiance through the disc of the scene's bounding sphere of radius <paramref name="sceneRadius"/>, as pbrt-v4's
    /// <c>DirectionalLight::Phi</c>). A point's distance falloff d_k is taken as the physical 1/r² (the power of a c0 or
    /// c1 falloff is not defined).
    /// </summary>
    public virtual double PowerPerIntensity(double sceneRadius) => 4 * Math.PI;

    /// <summary>
    /// Where the light is and the cone it shines into, for a light tree's bounds (Rendering/Emitters/LightTree), or null for a
    /// light at infinity (directional). The kinds at a point override it.
    /// </summary>
    public virtual LightExtent? Extent => null;

    /// <summary>The light as render.json lists it (its kind, what its intensity is in, where it is and how it falls off).</summary>
    public virtual LightDescription Describe(Radiometry radiometry) =>
        new(Type, LightDescription.UnitOf(radiometry, LightDescription.RadiantIntensity));
}

/// <summary>
/// One sample of a light seen from a point (<see cref="Light.Sample"/>): unit direction towards the light, the distance
/// (∞ at infinity), the factor on the light's spectrum (radiance, or d_k·c_spot,k of a delta light), the solid-angle
/// pdf (1 for a delta light) and whether the light is a delta light.
/// </summary>
public readonly record struct LightIncidence(Vector3 Direction, float Distance, float Factor, float Pdf, bool IsDelta);

/// <summary>
/// A light as the manifest describes it: its kind, the unit of its spectrum × intensity, and the parameters of its kind
/// (position, direction it shines towards, attenuation [c0, c1, c2]); null where the kind has none.
/// </summary>
public sealed record LightDescription(string Type, string Unit,
    double[]? Position = null, double[]? Direction = null, double[]? Attenuation = null)
{
    public const string Relative = "relative (paper radiometry)";
    public const string RadiantIntensity = "W.sr^-1.nm^-1 (radiant intensity) per unit of the spectrum";
    public const string Irradiance = "W.m^-2.nm^-1 (irradiance facing the light) per unit of the spectrum";

    /// <summary>The unit text: relative under paper radiometry, else <paramref name="physical"/>.</summary>
    public static string UnitOf(Radiometry radiometry, string physical) => radiometry != Radiometry.Physical ? Relative : physical;

    public static double[] Of(Vector3 v) => [v.X, v.Y, v.Z];
    public static double[] Of(DistanceFalloff f) => [f.C0, f.C1, f.C2];
}

/// <summary>An isotropic point light in its lane form (c_spot = 1) at <paramref name="Position"/> with distance falloff d_k.</summary>
public readonly record struct LanePointLight(Vector3 Position, DistanceFalloff Falloff);

/// <summary>Distance attenuation d = 1/(c0 + c1·r + c2·r²) of eq. 2.</summary>
public readonly record struct DistanceFalloff(float C0, float C1, float C2)
{
    public static readonly DistanceFalloff None = new(1, 0, 0);

    public float At(float r) => 1f / (C0 + C1 * r + C2 * r * r);
}

/// <summary>
/// A light at a point: its <paramref name="Position"/> and the cone it can shine into, about the unit
/// <paramref name="Axis"/> with half-angle θ_c (<paramref name="CosHalfAngle"/> = cos θ_c; −1 for every direction).
/// </summary>
public readonly record struct LightExtent(Vector3 Position, Vector3 Axis, float CosHalfAngle);
