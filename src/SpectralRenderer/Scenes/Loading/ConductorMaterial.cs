using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// The "conductor" material model: a metal of measured complex index n(λ) + ik(λ), smooth or GGX-rough
/// (<see cref="ConductorBsdf"/>). <c>"conductor"</c> names a metal of data/ (<see cref="Metals"/>) or gives
/// <c>{"n": spectrum, "k": spectrum}</c>; <c>"roughness"</c> is GGX α ∈ [0, 1] (0, the default: the smooth Fresnel mirror).
/// For the Whitted integrator, which knows only eq. 2's lobes, the metal is its normal-incidence reflectance
/// R₀ = ((n − 1)² + k²)/((n + 1)² + k²) per band: as k_r when smooth, else as m_spec with a Blinn–Phong lobe of shininess
/// 2/α² − 2 (the correspondence of Walter et al. 2007, §5.2) — an approximation; the path integrator uses the BSDF.
/// </summary>
public static class ConductorMaterial
{
    public static readonly string[] Keys = ["conductor", "roughness"];

    /// <summary>The built-in metals: symbol, other names, the table in data/ (columns symbol_n and symbol_k) and its source.</summary>
    public static readonly (string Symbol, string[] Names, string File, string Source)[] Metals =
    [
        ("Au", ["gold"], "metals-johnson-christy-1972.csv", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972)"),
        ("Ag", ["silver"], "metals-johnson-christy-1972.csv", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972)"),
        ("Cu", ["copper"], "metals-johnson-christy-1972.csv", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972)"),
        ("Al", ["aluminium", "aluminum"], "aluminium-rakic-1995.csv", "Rakić, Appl. Opt. 34, 4755 (1995)"),
    ];

    /// <summary>The metal's (n, k) tables, by symbol or name (any case); false when it is not built in.</summary>
    public static bool TryFind(string name, out TabulatedSpectrum n, out TabulatedSpectrum k)
    {
        foreach (var m in Metals)
            if (string.Equals(m.Symbol, name, StringComparison.OrdinalIgnoreCase)
                || m.Names.Any(x => string.Equals(x, name, StringComparison.OrdinalIgnoreCase)))
            {
                var table = SpectrumLibrary.DataTable(m.File);
                n = table[m.Symbol + "_n"];
                k = table[m.Symbol + "_k"];
                return true;
            }
        n = k = null!;
        return false;
    }

    public static Material Make(SceneLoader.MaterialSource s)
    {
        TabulatedSpectrum n, k;
        if (s.IsString("conductor"))
        {
            var name = s.String("conductor").Trim();
            if (!TryFind(name, out n, out k))
                throw s.Error("conductor", $"unknown metal {Diagnostics.MessageText.Quote(name)}",
                    $"built in: {string.Join(", ", Metals.Select(m => $"{m.Symbol} ({m.Names[0]})"))}; or give "
                        + $"{{\"n\": spectrum, \"k\": spectrum}}");
        }
        else
        {
            var nk = s.Object("conductor", "n", "k");
            n = nk.Spectrum("n");
            k = nk.Spectrum("k");
        }
        float alpha = Roughness(s);
        var nBands = s.Bands(n, "conductor");
        var kBands = s.Bands(k, "conductor");
        for (int i = 0; i < s.Grid.Count; i++)
            if (nBands[i] == 0 && kBands[i] == 0)
                throw s.Error("conductor",
                    $"n and k are both 0 in band {i} ({s.Grid.Lower(i):0.#}–{s.Grid.Upper(i):0.#} nm): that is no medium, not a metal",
                    "give the metal's measured n and k (k > 0 absorbs), or name a built-in metal such as \"Au\"");
        var r0 = s.Zero();
        for (int i = 0; i < r0.Length; i++)
        {
            float ni = nBands[i], ki = kBands[i];
            r0[i] = ni == 0 && ki == 0 ? 0 : ((ni - 1) * (ni - 1) + ki * ki) / ((ni + 1) * (ni + 1) + ki * ki);
        }
        return new Material
        {
            Name = s.Name,
            Ambient = s.Zero(),
            Diffuse = s.Zero(),
            Specular = alpha > 0 ? r0 : s.Zero(),
            Shininess = alpha > 0 ? MathF.Max(0, 2 / (alpha * alpha) - 2) : 32,
            Mirror = alpha > 0 ? s.Zero() : r0,
            Transmit = s.Zero(),
            Ior = s.Ior().Ior,
            Bsdf = new ConductorBsdf(nBands, kBands, alpha),
        };
    }

    /// <summary>"roughness": GGX α, 0 (smooth, the default) to 1.</summary>
    internal static float Roughness(SceneLoader.MaterialSource s)
    {
        if (!s.Has("roughness")) return 0;
        double alpha = s.Number("roughness", 0, double.MinValue, double.MaxValue);
        if (!(alpha >= 0 && alpha <= 1))
            throw s.Error("roughness",
                $"roughness {alpha.ToString(System.Globalization.CultureInfo.InvariantCulture)} is out of range: GGX α lies in [0, 1]",
                "0 is a smooth surface, 0.05–0.3 a polished to brushed one, 1 the roughest");
        return (float)alpha;
    }
}
