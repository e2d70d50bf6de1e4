namespace SpectralRenderer.Scenes;

/// <summary>
/// Dispersion formulas for the index of refraction n(λ) of a transparent material ("ior" in a scene).
/// Cauchy (1836): n(λ) = A + B/λ², λ in nm (B in nm²). Sellmeier (1871), in the form of glass catalogues (Schott's
/// optical glass data sheets, refractiveindex.info): n²(λ) = 1 + Σ_{i=1..3} B_i·λ²/(λ² − C_i), λ in µm, C_i in µm²;
/// e.g. Schott N-BK7 gives n_d = 1.5168 at 587.56 nm.
/// </summary>
public static class RefractiveIndex
{
    /// <summary>Cauchy's n(λ) = A + B/λ² at <paramref name="nm"/> (B in nm²).</summary>
    public static double Cauchy(double a, double b, double nm) => a + b / (nm * nm);

    /// <summary>
    /// Sellmeier's n(λ) = √(1 + Σ B_i·λ²/(λ² − C_i)) at <paramref name="nm"/> (C_i in µm²); NaN where n² ≤ 0 (at or near
    /// a resonance C_i, where the formula does not describe a transparent material).
    /// </summary>
    public static double Sellmeier(ReadOnlySpan<double> b, ReadOnlySpan<double> c, double nm)
    {
        double l2 = nm * nm * 1e-6;   // λ² in µm²
        double n2 = 1;
        for (int i = 0; i < b.Length; i++) n2 += b[i] * l2 / (l2 - c[i]);
        return n2 > 0 && double.IsFinite(n2) ? Math.Sqrt(n2) : double.NaN;
    }
}
