namespace SpectralRenderer.Scenes;

/// <summary>
/// Light a surface emits (an area light): spectral radiance L_e in W·m⁻²·sr⁻¹·nm⁻¹ as padded band values (spectrum ×
/// "radiance"; its tabulated spectrum is in <see cref="Scene.Spectra"/>), the same in every direction of the side its
/// geometric normal points to, or of both sides when <see cref="TwoSided"/>. Path tracing only (<c>"integrator": "path"</c>).
/// A textured emission (<see cref="Texture"/>: texels of spectral radiance, "radiance" k applied) has the texture's mean as
/// <see cref="Radiance"/>.
/// </summary>
public sealed record Emission(float[] Radiance, bool TwoSided)
{
    /// <summary>The spectral radiance as a texture over the surface's (u, v), or null.</summary>
    public Textures.TextureBinding? Texture { get; init; }
}
