namespace SpectralRenderer.Color;

/// <summary>
/// Pixel spectra → display RGB: eq. 3 (band values → XYZ through the scene's <see cref="Colorimeter"/>),
/// exposure, optional Bradford adaptation from the scene white to the RGB space's white, then eq. 4
/// (paper) or sRGB, clipped and encoded.
/// </summary>
public sealed class DisplayEncoder
{
    readonly Colorimeter _colorimeter;
    readonly double[,] _toRgb;
    readonly double _exposure;

    public DisplayEncoder(Colorimeter colorimeter, RgbSpace space, double exposure = 1, bool adapt = false)
    {
        _colorimeter = colorimeter;
        Space = space;
        _exposure = exposure;
        // The scene white is taken at Y = 1 for the adaptation, so absolute scaling keeps its luminance.
        var white = colorimeter.White * (1 / colorimeter.White.Y);
        _toRgb = adapt ? Matrix3.Multiply(space.FromXyz, ChromaticAdaptation.BradfordMatrix(white, space.White)) : space.FromXyz;
    }

    public RgbSpace Space { get; }

    /// <summary>The colorimeter of eq. 3, whose <see cref="Colorimeter.ToXyz(ReadOnlySpan{float})"/> <see cref="Encode8(Xyz)"/> expects.</summary>
    public Colorimeter Colorimeter => _colorimeter;

    public Xyz Xyz(ReadOnlySpan<float> bands) => _colorimeter.ToXyz(bands) * _exposure;

    /// <summary>Linear RGB (unclipped) of a pixel spectrum.</summary>
    public (double R, double G, double B) Linear(ReadOnlySpan<float> bands)
    {
        var v = Matrix3.Apply(_toRgb, Xyz(bands));
        return (v.X, v.Y, v.Z);
    }

    /// <summary>8-bit display RGB of a pixel spectrum.</summary>
    public (byte R, byte G, byte B) Encode8(ReadOnlySpan<float> bands) => Encode8(_colorimeter.ToXyz(bands));

    /// <summary>8-bit display RGB of a pixel whose eq. 3 XYZ (before exposure) is <paramref name="xyz"/>: the same bytes as from its spectrum.</summary>
    public (byte R, byte G, byte B) Encode8(Xyz xyz)
    {
        var v = Matrix3.Apply(_toRgb, xyz * _exposure);
        return (Space.Encode8(v.X), Space.Encode8(v.Y), Space.Encode8(v.Z));
    }
}
