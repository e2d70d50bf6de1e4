namespace SpectralRenderer.Color;

/// <summary>Bradford chromatic adaptation (Lam 1985; the linearised form of ICC v4 Annex E / CIE 159).</summary>
public static class ChromaticAdaptation
{
    static readonly double[,] Bradford =
    {
        { 0.8951, 0.2664, -0.1614 },
        { -0.7502, 1.7135, 0.0367 },
        { 0.0389, -0.0685, 1.0296 },
    };

    /// <summary>The 3×3 matrix that maps XYZ seen under <paramref name="from"/> white to <paramref name="to"/> white.</summary>
    public static double[,] BradfordMatrix(Xyz from, Xyz to)
    {
        var s = Matrix3.Apply(Bradford, from);
        var d = Matrix3.Apply(Bradford, to);
        var scale = new double[3, 3];
        scale[0, 0] = d.X / s.X; scale[1, 1] = d.Y / s.Y; scale[2, 2] = d.Z / s.Z;
        return Matrix3.Multiply(Matrix3.Inverse(Bradford), Matrix3.Multiply(scale, Bradford));
    }
}
