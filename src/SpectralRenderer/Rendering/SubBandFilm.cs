using System.Diagnostics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A path render's film on its sub-band grid (issue 24, the camera's exact route): per pixel the mean over its camera samples
/// of the sub-band radiance L_f (W·m⁻²·sr⁻¹·nm⁻¹, one value per sub-band of <see cref="SubBandGrid"/>) that the film reduces to
/// the output bands (their sub-bands' means) and to XYZ (Σ_f L_f·κ∫_f x̄ dλ). A sensor channel's signal is then
/// Σ_f L_f · ∫_f η_c(λ)·λ/(hc) dλ, as the film integrates colour. Formed from the render's lights/ (L_f = F_f + Σ_k T_k,f·E_k,f,
/// no rays) or traced again: the render's camera samples, bit for bit (every random number is the sample's own), summed
/// with the film's weights 1/spp. Nothing of it is kept at render time; <see cref="Bytes"/> is what it holds.
/// </summary>
[CompiledAtFirstCall]
public sealed class SubBandFilm
{
    public required int Width { get; init; }
    public required int Height { get; init; }
    /// <summary>Sub-bands per output band of a uniform grid (an output band is the mean of its sub-bands), 0 when adaptive.</summary>
    public required int PerBand { get; init; }
    /// <summary>Output band b's sub-bands are [BandStart[b], BandStart[b + 1]).</summary>
    public required int[] BandStart { get; init; }
    /// <summary>The sub-bands' edges (nm).</summary>
    public required double[] Lower { get; init; }
    public required double[] Upper { get; init; }
    /// <summary>[pixel (row-major)][sub-band f]: L_f, W·m⁻²·sr⁻¹·nm⁻¹.</summary>
    public required float[] Data { get; init; }
    public int SubBands => Lower.Length;

    /// <summary>Bytes of a sub-band film of <paramref name="width"/> × <paramref name="height"/> pixels and
    /// <paramref name="subBands"/> sub-bands (4 per pixel and sub-band).</summary>
    public static long Bytes(int width, int height, int subBands) => 4L * width * height * subBands;

    /// <summary>The film of <paramref name="data"/> ([pixel][sub-band]) on <paramref name="grid"/>.</summary>
    internal static SubBandFilm Of(SubBandGrid grid, int width, int height, float[] data) => new()
    {
        Width = width,
        Height = height,
        PerBand = grid.PerBand,
        BandStart = grid.BandStart,
        Lower = grid.Lower,
        Upper = grid.Upper,
        Data = data,
    };
}
