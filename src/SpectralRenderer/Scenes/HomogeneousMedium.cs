using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A homogeneous medium: absorption σ_a and scattering σ_s per band (per scene length unit), constant in space, and a
/// Henyey–Greenstein phase function. Its transmittance is Beer–Lambert, T(t) = exp(−σ_t·t) with σ_t = σ_a + σ_s, exact per
/// band; a medium with σ_s = 0 in every band only absorbs (<see cref="Medium.Scattering"/> null). The scene file gives either
/// σ_a and σ_s, or the single-scattering albedo α and σ_t (σ_s = α·σ_t, σ_a = (1 − α)·σ_t); the medium keeps the two spectra
/// it was given, so another band grid resamples exactly those (<see cref="Resampled"/>).
/// </summary>
public sealed class HomogeneousMedium : Medium
{
    readonly float[] _first, _second;   // σ_a and σ_s, or α and σ_t, as given (padded band values)
    readonly bool _albedoForm;
    readonly float[] _sigmaT;
    readonly int _count;

    /// <param name="first">σ_a, or α when <paramref name="albedoForm"/>.</param>
    /// <param name="second">σ_s, or σ_t when <paramref name="albedoForm"/>.</param>
    /// <param name="count">The bands (the arrays may be padded beyond them).</param>
    public HomogeneousMedium(float[] first, float[] second, bool albedoForm, HenyeyGreenstein phase, int count)
    {
        _first = first; _second = second; _albedoForm = albedoForm; _count = count;
        Phase = phase;
        int n = first.Length;
        SigmaA = new float[n]; SigmaS = new float[n]; _sigmaT = new float[n];
        for (int i = 0; i < count; i++)
        {
            SigmaA[i] = albedoForm ? (1 - first[i]) * second[i] : first[i];
            SigmaS[i] = albedoForm ? first[i] * second[i] : second[i];
            _sigmaT[i] = albedoForm ? second[i] : first[i] + second[i];
        }
        bool scatters = false;
        for (int i = 0; i < count; i++) scatters |= SigmaS[i] > 0;
        Scattering = scatters ? new MediumScattering(SigmaA, SigmaS, phase, count) : null;
    }

    /// <summary>σ_a, σ_s per band (padded; 0 in the padding).</summary>
    public float[] SigmaA { get; }
    public float[] SigmaS { get; }
    public HenyeyGreenstein Phase { get; }

    public override MediumScattering? Scattering { get; }

    /// <summary>values ⊙= exp(−σ_t·t) per band (σ_t = 0: T = 1, also for t = ∞).</summary>
    public override void Attenuate(Vector3 origin, Vector3 direction, float distance, Span<float> values)
    {
        var sigma = _sigmaT;
        for (int i = 0; i < _count && i < values.Length; i++)
            if (sigma[i] > 0) values[i] *= MathF.Exp(-sigma[i] * distance);
    }

    public override Medium Resampled(Func<float[], float[]> resample)
    {
        var first = resample(_first);   // (every entry: the padding is 0 in each array, T = 1 there, and β is 0 there)
        return new HomogeneousMedium(first, resample(_second), _albedoForm, Phase, first.Length);
    }
}
