using System.Runtime.CompilerServices;
using System.Numerics;

namespace SpectralRenderer.Scenes;

public enum LightKind { Point, Spot, Directional }

/// <summary>
/// A light of eq. 2: its spectral intensity I_k (band values, spectrum × intensity), its ambient
/// contribution I_amb,k, distance attenuation d = 1/(c0 + c1·r + c2·r²) and, for spots, the factor
/// c_spot = (cos θ)^e inside the cone and 0 outside.
/// </summary>
public sealed class Light
{
    public required string Name { get; init; }
    public required LightKind Kind { get; init; }
    public Vector3 Position { get; init; }
    /// <summary>Unit direction the light shines towards (spot, directional).</summary>
    public Vector3 Direction { get; init; }
    public required float[] Intensity { get; init; }
    public required float[] Ambient { get; init; }
    public bool HasAmbient { get; init; }
    public float C0 { get; init; } = 1;
    public float C1 { get; init; }
    public float C2 { get; init; }
    /// <summary>cos of the spot's cutoff half-angle.</summary>
    public float CosCutoff { get; init; } = -1;
    public float SpotExponent { get; init; }
    /// <summary>The light's spectrum as given (for reports and the reference white).</summary>
    public Spectra.TabulatedSpectrum? Spectrum { get; init; }

    /// <summary>d_k of eq. 2.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Attenuation(float r) => Kind == LightKind.Directional ? 1f : 1f / (C0 + C1 * r + C2 * r * r);

    /// <summary>c_spot,k of eq. 2 for the unit direction from the light to the point.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float SpotFactor(Vector3 fromLight)
    {
        if (Kind != LightKind.Spot) return 1f;
        float c = Vector3.Dot(fromLight, Direction);
        return c < CosCutoff ? 0f : MathF.Pow(Math.Max(c, 0f), SpotExponent);
    }
}
