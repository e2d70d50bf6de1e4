namespace SpectralRenderer.Scenes;

/// <summary>The specular lobe of eq. 2.</summary>
public enum SpecularModel
{
    /// <summary>max(0, n·h)^shininess with the half-vector h (default).</summary>
    BlinnPhong,
    /// <summary>max(0, r·v)^shininess with the mirrored light direction r.</summary>
    Phong,
}

/// <summary>
/// A surface's spectral reflectances as band values (padded for SIMD): ambient m_amb, diffuse m_diff,
/// specular m_spec of eq. 2, the Whitted mirror weight k_r and transmittance k_t, and the index of
/// refraction per band (constant, or Cauchy n(λ) = A + B/λ² which makes refraction dispersive).
/// </summary>
public sealed class Material
{
    public required string Name { get; init; }
    public required float[] Ambient { get; init; }
    public required float[] Diffuse { get; init; }
    public required float[] Specular { get; init; }
    public float Shininess { get; init; } = 32;
    public SpecularModel Model { get; init; } = SpecularModel.BlinnPhong;
    public required float[] Mirror { get; init; }
    public required float[] Transmit { get; init; }
    /// <summary>Index of refraction per band.</summary>
    public required float[] Ior { get; init; }
    public bool Dispersive { get; init; }
    /// <summary>Scale k_r by the dielectric Fresnel reflectance and k_t by its complement.</summary>
    public bool Fresnel { get; init; }
    /// <summary>The tabulated diffuse reflectance (ground truth for analysis), when it was a spectrum.</summary>
    public Spectra.TabulatedSpectrum? DiffuseSpectrum { get; init; }

    public bool HasSpecular { get; init; }
    public bool HasMirror { get; init; }
    public bool HasTransmission { get; init; }
    public bool HasAmbient { get; init; }
}
