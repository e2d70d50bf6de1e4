using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Color;

/// <summary>How spectra become band values and band values become XYZ (eq. 3).</summary>
public enum BandIntegration
{
    /// <summary>
    /// Exact at the tables' full resolution (default): every term of eq. 2 is a scalar × a light spectrum ×
    /// a material spectrum, so its band value is the scalar × the band mean of the product E·m, and its colour
    /// the scalar × κΣx̄·E·m — the band mean the exact integral of the piecewise-linear tables, the colour CIE 015's
    /// 1 nm sum of them (<see cref="Spectra.CieSummation"/>), precomputed per (light, material component). The cube
    /// is the band average of the true spectral radiance; a pixel's XYZ is the exact colour of its spectrum, not eq. 3
    /// on its bands. The cube's own colour weights are the <see cref="Weighted"/> ones.
    /// </summary>
    Exact,
    /// <summary>
    /// Spectral prefiltering (the former default; Ward &amp; Eydelberg-Vileshin 2002, the paper's ref. [4]):
    /// a spectrum's band value is its exact mean over the band, a term's the product of its factors' band means, and its colour weight is
    /// Σ_b x̄·E / ∫_b E dλ · Δλ, the CMF averaged under the reference light E at full resolution (CIE 015's 1 nm sum).
    /// Right for narrow-band lights.
    /// </summary>
    Weighted,
    /// <summary>
    /// The paper's scheme: X = κ Σ_b x̄_b E_b R_b Δλ, every factor the mean of its 1 nm samples
    /// in the band [lo, hi) (last band closed) — as in data/reference. Fine for smooth lights only.
    /// </summary>
    Paper,
}

/// <summary>The names of <see cref="BandIntegration"/> in scene files, on the command line and in render.json.</summary>
public static class BandIntegrations
{
    public static string Name(BandIntegration scheme) => scheme switch
    {
        BandIntegration.Paper => "paper",
        BandIntegration.Weighted => "weighted",
        _ => "exact",
    };

    /// <summary>The scheme named <paramref name="name"/> (any case); bad input naming <paramref name="where"/> otherwise.</summary>
    public static BandIntegration Parse(string name, string where) => name.ToLowerInvariant() switch
    {
        "exact" => BandIntegration.Exact,
        "weighted" => BandIntegration.Weighted,
        "paper" => BandIntegration.Paper,
        _ => throw new InputException(where, $"unknown band integration '{name}'", "use exact (default), weighted or paper"),
    };
}
