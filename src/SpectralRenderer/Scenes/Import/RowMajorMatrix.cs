namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// 4×4 affine matrices as 16 doubles, row-major, acting on column vectors (p' = M·p): our scene file's "matrix" layout,
/// which every importer composes its transforms in.
/// </summary>
static class RowMajorMatrix
{
    public static double[] Identity => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

    /// <summary>The product a·b (b applied first).</summary>
    public static double[] Multiply(double[] a, double[] b)
    {
        var m = new double[16];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
            {
                double s = 0;
                for (int k = 0; k < 4; k++) s += a[4 * r + k] * b[4 * k + c];
                m[4 * r + c] = s;
            }
        return m;
    }
}
