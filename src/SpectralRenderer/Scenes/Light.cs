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
public readonly record struct LightEmission(string Name, float[] Intensity, float[] Ambient, bool HasAmbient, float Scale = 1, Spectra.TabulatedSpectrum? Spectrum = null);

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

    /// <summary>The scene-file name of this kind of light ("point", "spot", "directional").</summary>
    public abstract string Type { get; }

    /// <summary>
    /// Direction, distance, c_spot,k and d_k of eq. 2 at point <paramref name="p"/>; false when the light
    /// cannot reach it at all (the point is at the light, or outside its cone), so it adds nothing, not even ambient.
    /// </summary>
    public abstract bool Illuminate(Vector3 p, out LightSample sample);

    /// <summary>The light as an isotropic point emitter that packets evaluate in SIMD lanes, or null when it is not one.</summary>
    public virtual PointEmitter? LaneForm => null;
}

/// <summary>An isotropic point emitter (c_spot = 1) at <paramref name="Position"/> with distance falloff d_k.</summary>
public readonly record struct PointEmitter(Vector3 Position, DistanceFalloff Falloff);

/// <summary>Distance attenuation d = 1/(c0 + c1·r + c2·r²) of eq. 2.</summary>
public readonly record struct DistanceFalloff(float C0, float C1, float C2)
{
    public static readonly DistanceFalloff None = new(1, 0, 0);

    public float At(float r) => 1f / (C0 + C1 * r + C2 * r * r);
}
