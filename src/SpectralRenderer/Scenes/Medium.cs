using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A participating medium: what the space inside an object (the object's <c>"medium"</c>, its interior) or around the
/// objects (the scene's <c>"medium"</c>) does to light along a ray. The walk asks it for the transmittance of a segment,
/// T(t) = exp(−∫₀ᵗ σ_t(x + sω) ds) per band (for a homogeneous absorbing medium Beer–Lambert's exp(−σ_a·t)), and multiplies
/// it into a path's throughput between two vertices and into a light sample's contribution along its shadow ray
/// (the path walk's media slot, Rendering/PathTracing). A kind of medium is one class plus one registration in
/// Scenes/Loading/MediumTypes.cs (ARCHITECTURE.md, "Extending"); the engine registers none yet (issue 41 adds the
/// homogeneous and grid media, and scattering: free-flight sampling against a majorant and a phase function, here).
/// </summary>
public abstract class Medium
{
    /// <summary>
    /// values ⊙= T per band: the transmittance along the segment from <paramref name="origin"/> along the unit
    /// <paramref name="direction"/> for <paramref name="distance"/> scene units (+∞: a ray that leaves the scene; T is then
    /// 0 in a band that attenuates and 1 in one that does not). Called per path segment and shadow ray: no allocation.
    /// </summary>
    public abstract void Attenuate(Vector3 origin, Vector3 direction, float distance, Span<float> values);

    /// <summary>
    /// The medium on another band grid (the path tracer's sub-band grid, <c>SubBandGrid.Resample</c>): each of its band spectra
    /// through <paramref name="resample"/>, as <see cref="Bsdf.Resampled"/>.
    /// </summary>
    public abstract Medium Resampled(Func<float[], float[]> resample);
}
