using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// The adaptive grid (issue 42). A product of sub-band means misses the covariance of the spectra inside a sub-band, and
// over many bounces it adds up: in a closed room of reflectance ρ lit by E the radiance is E·ρ/(1 − ρ) (the integrating
// sphere's series Σ ρⁿ), and its sub-band mean is not E_f·ρ_f/(1 − ρ_f) of the sub-band means where ρ changes fast — at
// 5 nm that is −0.8 % at 380–400 nm and −1.3 % at 400–420 nm for the ColorChecker's white under D65, what the path
// tracer shows in such a room. So the grid predicts, per output band and number of equal sub-bands n, the relative error
// of that worst case for every pair of a material's reflectance and an emitter's spectrum (or a flat light), against the
// 1 nm split; when the uniform grid's prediction exceeds AdaptiveThreshold in some band, the same number of sub-bands is
// handed out again, one at a time to the band whose predicted error is then largest (each band at least one sub-band,
// none finer than 1 nm). The cost per path is the same (as many lanes); only scenes that ask for it change.
internal sealed partial class SubBandGrid
{
    /// <summary>The uniform grid is kept while its predicted error is at most this (relative) in every band.</summary>
    internal const double AdaptiveThreshold = 5e-4;
    /// <summary>The finest sub-band the adaptive grid makes (nm), and the split its prediction compares against.</summary>
    const double FinestWidth = 1;
    /// <summary>The closed room's reflectance is capped here (ρ → 1 would make its radiance, not its error, diverge).</summary>
    const double AlbedoCap = 0.95;

    static readonly ConditionalWeakTable<Scene, StrongBox<(int PerBand, int[]? Counts)>> s_counts = new();

    /// <summary>
    /// Sub-bands per output band of <paramref name="scene"/>'s adaptive grid at the budget of <paramref name="perBand"/> per
    /// band, or null to keep the uniform grid (its predicted error is small, or the scene has spectra the prediction does not
    /// model: a dispersive glass, a fluorescent material or a medium keep the uniform grid).
    /// </summary>
    static int[]? AdaptiveCounts(Scene scene, int perBand)
    {
        if (s_counts.TryGetValue(scene, out var box) && box.Value.PerBand == perBand) return box.Value.Counts;
        var counts = Allocate(scene, perBand);
        s_counts.AddOrUpdate(scene, new StrongBox<(int, int[]?)>((perBand, counts)));
        return counts;
    }

    static int[]? Allocate(Scene scene, int perBand)
    {
        if (scene.Media.Count > 0 || scene.Materials.Any(m => m.Dispersive && m.HasTransmission || m.Fluorescence is not null))
            return null;
        var error = PredictedErrors(scene, perBand);
        if (error is null || error.All(e => e[perBand - 1] <= AdaptiveThreshold)) return null;
        int bands = error.Length, left = bands * perBand - bands;
        var counts = new int[bands];
        Array.Fill(counts, 1);
        for (; left > 0; left--)
        {
            int worst = -1;
            for (int b = 0; b < bands; b++)
                if (counts[b] < error[b].Length && (worst < 0 || error[b][counts[b] - 1] > error[worst][counts[worst] - 1])) worst = b;
            if (worst < 0) break;   // every band at its finest: the rest of the budget is not needed
            counts[worst]++;
        }
        return counts.All(n => n == perBand) ? null : counts;
    }

    /// <summary>
    /// Per output band b, for n = 1 … its finest count: the largest relative error, over the scene's reflectances ρ and
    /// emitter spectra E (and a flat light), of the band mean of E·g(ρ), g(ρ) = ρ/(1 − ρ), taken on n equal sub-bands
    /// from the sub-band means, against the same on 1 nm sub-bands. Null when no reflectance has a tabulated spectrum.
    /// </summary>
    static double[][]? PredictedErrors(Scene scene, int perBand)
    {
        var reflectances = new List<TabulatedSpectrum>();
        var emitters = new List<TabulatedSpectrum?> { null };
        foreach (var m in scene.Materials)
        {
            foreach (var r in (float[][])[m.Diffuse, m.Specular, m.Mirror])
                if (scene.Spectra.TryGetValue(r, out var s) && !reflectances.Contains(s)) reflectances.Add(s);
            if (m.Emission is { } e && scene.Spectra.TryGetValue(e.Radiance, out var es) && !emitters.Contains(es)) emitters.Add(es);
        }
        if (scene.Spectra.TryGetValue(scene.Background, out var sky) && !emitters.Contains(sky)) emitters.Add(sky);
        if (reflectances.Count == 0) return null;
        var grid = scene.Grid;
        var error = new double[grid.Count][];
        for (int b = 0; b < grid.Count; b++)
        {
            double lo = grid.Lower(b), width = grid.Upper(b) - lo;
            int finest = Math.Max(perBand, (int)Math.Floor(width / FinestWidth + 1e-9));
            error[b] = new double[finest];
            foreach (var rho in reflectances)
                foreach (var light in emitters)
                {
                    double reference = BandMean(rho, light, lo, width, finest);
                    if (!(reference > 0)) continue;
                    for (int n = 1; n < finest; n++)
                        error[b][n - 1] = Math.Max(error[b][n - 1], Math.Abs(BandMean(rho, light, lo, width, n) / reference - 1));
                }
        }
        return error;
    }

    /// <summary>(1/n)·Σ_j E_j·g(ρ_j) over n equal sub-bands of [lo, lo + width], E_j and ρ_j the exact sub-band means.</summary>
    static double BandMean(TabulatedSpectrum rho, TabulatedSpectrum? light, double lo, double width, int n)
    {
        double sum = 0, w = width / n;
        for (int j = 0; j < n; j++)
        {
            double a = lo + j * w, z = lo + (j + 1) * w;
            double r = Math.Clamp(rho.Mean(a, z), 0, AlbedoCap), e = light?.Mean(a, z) ?? 1;
            sum += e * r / (1 - r);
        }
        return sum / n;
    }
}
