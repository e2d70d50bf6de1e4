using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Color;

/// <summary>How spectra become band values and band values become XYZ (eq. 3).</summary>
public enum BandIntegration
{
    /// <summary>
    /// Spectral prefiltering (default; Ward &amp; Eydelberg-Vileshin 2002, the paper's ref. [4]):
    /// a band's value is the exact mean of the spectrum over the band, and its colour weight is
    /// ∫_b x̄·E dλ / ∫_b E dλ · Δλ, the CMF averaged under the reference light E at full resolution.
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
    public static string Name(BandIntegration scheme) => scheme == BandIntegration.Paper ? "paper" : "weighted";

    /// <summary>The scheme named <paramref name="name"/> (any case); bad input naming <paramref name="where"/> otherwise.</summary>
    public static BandIntegration Parse(string name, string where) => name.ToLowerInvariant() switch
    {
        "weighted" => BandIntegration.Weighted,
        "paper" => BandIntegration.Paper,
        _ => throw new InputException(where, $"unknown band integration '{name}'", "use weighted or paper"),
    };
}
