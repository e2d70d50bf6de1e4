namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// What a material emits as its integrator carries it (an area light of each object made of it): the spectral radiance on
/// the sub-band grid (padded), whether both sides emit, and its texture of radiance on that grid, or null. The integrator
/// builds it once per material, so an emitting object's texture is the one its camera rays look up.
/// </summary>
internal sealed record SurfaceEmission(float[] Radiance, bool TwoSided, SubBandTexture? Texture);
