namespace SpectralRenderer.Rendering.Terms;

/// <summary>
/// The exact camera route of eq. 2's terms: a pixel's radiance is Σ_c F_c · P_c over components c (a light's term through
/// a chain of mirrors and glass, <see cref="TransferComponent"/>), each P_c a spectrum the camera integrates at its full
/// resolution. Implemented by the Whitted transfer.
/// </summary>
public interface ITermRoute : ILightTransfer
{
    int Width { get; }
    int Height { get; }
    int Bands { get; }
    TransferComponent[] Components { get; }
    /// <summary>Per component, its pixels (y·W + x, ascending) and the factors there.</summary>
    int[][] Pixels { get; }
    float[][] Factors { get; }
    /// <summary>Per component, a textured one's texel samples per entry (null for components of spectra).</summary>
    float[]?[]? Texels { get; }
}
