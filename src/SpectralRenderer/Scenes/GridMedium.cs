using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A heterogeneous medium: a homogeneous medium's coefficients scaled by a density grid, σ_a(x, λ) = d(x)·σ_a(λ) and
/// σ_s(x, λ) = d(x)·σ_s(λ) (<see cref="DensityGrid"/>: trilinear, 0 outside its box), with the unit-density medium's phase
/// function. Its transmittance T = exp(−σ_t(λ)·τ), τ = ∫ d(x + sω) ds, is exact (<see cref="DensityGrid.OpticalDepth"/>), so
/// Whitted's Beer–Lambert and the path tracer's shadow rays need no estimator (a zero-variance stand-in for ratio
/// tracking); free-flight sampling tracks against the majorant max d · max_λ σ_t(λ) with null collisions
/// (<see cref="MediumScattering.Density"/>).
/// </summary>
public sealed class GridMedium : Medium
{
    /// <param name="unit">The medium where the density is 1.</param>
    public GridMedium(HomogeneousMedium unit, DensityGrid density)
    {
        Unit = unit;
        Density = density;
        Scattering = unit.Scattering is null ? null
            : new MediumScattering(unit.SigmaA, unit.SigmaS, unit.Phase, unit.SigmaA.Length, density);
    }

    public HomogeneousMedium Unit { get; }
    public DensityGrid Density { get; }
    public override MediumScattering? Scattering { get; }

    /// <summary>values ⊙= exp(−σ_t·τ) per band, τ the density's exact integral along the segment (finite also for t = ∞).</summary>
    public override void Attenuate(Vector3 origin, Vector3 direction, float distance, Span<float> values)
    {
        double tau = Density.OpticalDepth(origin, direction, distance);
        if (tau > 0) Unit.Attenuate(origin, direction, (float)tau, values);
    }

    public override Medium Resampled(Func<float[], float[]> resample) =>
        new GridMedium((HomogeneousMedium)Unit.Resampled(resample), Density);
}
