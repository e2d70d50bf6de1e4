using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// One scene material as the path integrator walks it, on its sub-band grid (<see cref="SubBandGrid"/>): the BSDF, the emitted
/// radiance, the fluorescent shift with the albedos its lobe choice weighs, the lobe flags and the smooth lobes' channel
/// share, whether it disperses, and its textures. Built once per render; read by every thread.
/// </summary>
sealed class PathMaterial
{
    /// <summary>The material's index in the scene (what a shifted bounce keeps: PathIntegrator.Fluorescence.cs).</summary>
    public readonly int Index;
    public readonly Bsdf Bsdf;
    /// <summary>The radiance it emits (null: none), on one side or both.</summary>
    public readonly float[]? Emission;
    public readonly bool TwoSided;
    /// <summary>A fluorescent material's shifted diffuse lobe (FluorescentShift.cs), and its m_diff and m_spec (its lobe choice).</summary>
    public readonly FluorescentShift? Shift;
    public readonly float[]? AlbedoDiffuse, AlbedoSpecular;
    /// <summary>Has it a diffuse or glossy lobe (next-event estimation), a delta lobe (mirror, transmission)?</summary>
    public readonly bool Smooth, Delta;
    /// <summary>A transmitting material with a dispersive index: a path splits its bands there (PathIntegrator.Dispersion.cs).</summary>
    public readonly bool Dispersive;
    /// <summary>The smooth lobes' share in the lobe choice: the channel value of m_diff + m_spec (their albedo at most).</summary>
    public readonly float SmoothChannel;
    /// <summary>Its textures on the sub-band grid (null: its spectrum), and the plain m_diff, m_spec channel values beside a
    /// texel.</summary>
    public readonly SubBandTexture? DiffuseTexture, SpecularTexture, EmissionTexture;
    public readonly float DiffuseChannel, SpecularChannel;

    /// <summary>
    /// Scene material <paramref name="index"/> on <paramref name="grid"/>, or bad input naming what the path integrator
    /// cannot carry.
    /// </summary>
    public PathMaterial(Scene scene, int index, SubBandGrid grid)
    {
        var material = scene.Materials[index];
        string where = $"{scene.SourcePath}: {material.JsonPath}";
        Index = index;
        Dispersive = material.Dispersive && material.HasTransmission;
        Bsdf = material.Bsdf.Resampled(grid.Resample)
            ?? throw new InputException($"{scene.SourcePath}: $.materials.{material.Name}",
                $"material '{material.Name}' ({material.Bsdf.GetType().Name}) cannot be carried to the path integrator's spectral grid",
                "use a material type the path integrator knows (eq2, lambertian), or the whitted integrator");
        Smooth = (Bsdf.Lobes & (BsdfFlags.Diffuse | BsdfFlags.Glossy)) != 0;
        Delta = (Bsdf.Lobes & BsdfFlags.Delta) != 0;
        if (Smooth)
        {
            var albedo = grid.Resample(material.Diffuse);
            var spec = grid.Resample(material.Specular);
            for (int i = 0; i < albedo.Length; i++) albedo[i] += spec[i];
            SmoothChannel = Math.Max(grid.Luminance(albedo), 1e-6f);
        }
        if (material.Fluorescence is { HasShift: true } fl)
        {
            Shift = new FluorescentShift(fl, grid);
            AlbedoDiffuse = grid.Resample(material.Diffuse);
            AlbedoSpecular = grid.Resample(material.Specular);
        }
        if (material.Emission is { } e) { Emission = grid.Resample(e.Radiance); TwoSided = e.TwoSided; }
        if ((material.DiffuseTexture is not null || material.SpecularTexture is not null) && !Bsdf.TakesTextures)
            throw new InputException($"{where}.diffuse",
                $"material '{material.Name}' ({material.Bsdf.GetType().Name}) is textured: "
                + "the path integrator textures eq. 2 and lambertian materials only",
                "give this material a spectrum, or use an eq2 or lambertian material for the texture");
        if (material.DiffuseTexture is { } d) DiffuseTexture = new SubBandTexture(d, grid);
        if (material.SpecularTexture is { } s) SpecularTexture = new SubBandTexture(s, grid);
        if (material.Emission?.Texture is { } t) EmissionTexture = new SubBandTexture(t, grid);
        if (Textured)
        {
            DiffuseChannel = grid.Luminance(grid.Resample(material.Diffuse));
            SpecularChannel = grid.Luminance(grid.Resample(material.Specular));
        }
    }

    /// <summary>Has it any texture?</summary>
    public bool Textured => DiffuseTexture is not null || SpecularTexture is not null || EmissionTexture is not null;
}
