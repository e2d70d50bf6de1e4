using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A participating medium: what the space inside an object (the object's <c>"medium"</c>, its interior) or around the
/// objects (the scene's <c>"medium"</c>) does to light along a ray. The walk asks it for the transmittance of a segment,
/// T(t) = exp(−∫₀ᵗ σ_t(x + sω) ds) per band (for a homogeneous medium Beer–Lambert's exp(−σ_t·t)), and multiplies
/// it into a path's throughput between two vertices and into a light sample's contribution along its shadow ray
/// (the path walk's media slot, Rendering/PathTracing/PathIntegrator.Media.cs). A medium that scatters also answers
/// <see cref="Scattering"/>: its coefficients and phase function, which the path tracer's free-flight sampling reads.
/// A kind of medium is one class plus one registration in Scenes/Loading/MediumTypes.cs (ARCHITECTURE.md, "Extending").
/// Coefficients are per scene length unit (docs/scene-format.md, "Participating media").
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

    /// <summary>
    /// Its scattering (null: a medium that only absorbs, whose every segment is Beer–Lambert by <see cref="Attenuate"/>; the
    /// path tracer then samples no distance in it).
    /// </summary>
    public virtual MediumScattering? Scattering => null;
}

/// <summary>
/// What free-flight sampling reads of a homogeneous scattering medium (Kutz et al. 2017, §5): per band the absorption and
/// scattering coefficients σ_a, σ_s (per scene unit, padded arrays, 0 in the padding), one majorant for every band
/// σ̄ = max_λ σ_t(λ), the null coefficient σ_n = σ̄ − σ_t ≥ 0 per band, and the phase function. A heterogeneous medium
/// (<see cref="GridMedium"/>) scales them by a <see cref="Density"/>: then σ_a, σ_s are the coefficients at density 1, the
/// majorant is max d · max_λ σ_t(λ) and σ_n(x) = σ̄ − d(x)·σ_t is formed at each tentative collision.
/// </summary>
public sealed class MediumScattering
{
    public MediumScattering(float[] sigmaA, float[] sigmaS, HenyeyGreenstein phase, int count, DensityGrid? density = null)
    {
        SigmaA = sigmaA;
        SigmaS = sigmaS;
        Phase = phase;
        Density = density;
        float majorant = 0;
        for (int i = 0; i < count; i++) majorant = MathF.Max(majorant, sigmaA[i] + sigmaS[i]);
        if (density is not null) majorant *= density.Maximum;
        Majorant = majorant;
        SigmaN = new float[sigmaA.Length];
        for (int i = 0; i < count; i++) SigmaN[i] = MathF.Max(0, majorant - sigmaA[i] - sigmaS[i]);
    }

    public float[] SigmaA { get; }
    public float[] SigmaS { get; }
    /// <summary>σ̄ − σ_t per band (0 in the padding).</summary>
    public float[] SigmaN { get; }
    /// <summary>σ̄ = max over the bands of σ_t.</summary>
    public float Majorant { get; }
    public HenyeyGreenstein Phase { get; }
    /// <summary>The density scaling σ_a and σ_s in space (null: homogeneous).</summary>
    public DensityGrid? Density { get; }
}
