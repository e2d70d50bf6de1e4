namespace SpectralRenderer.Spectra;

/// <summary>
/// Sprague (1880) fifth-order interpolation of a uniformly tabulated spectrum, the method CIE 167:2005
/// recommends for uniform data (and colour-science's default): on [x_i, x_{i+1}] a quintic through the six
/// samples y_{i−2} … y_{i+3}; two extra samples at each end are extrapolated with Sprague's boundary
/// coefficients. Used where a standard's reference computation interpolates 5 nm data to 1 nm (CIE 13.3
/// Ra); the renderer itself takes tables as their linear interpolant.
/// </summary>
public static class Sprague
{
    static readonly double[,] Boundary =
    {
        { 884, -1960, 3033, -2648, 1080, -180 },
        { 508, -540, 488, -367, 144, -24 },
        { -24, 144, -367, 488, -540, 508 },
        { -180, 1080, -2648, 3033, -1960, 884 },
    };

    /// <summary>Is the table uniform (equal steps to 1e-9 nm) with at least six samples?</summary>
    public static bool Applies(TabulatedSpectrum s)
    {
        var w = s.Wavelengths;
        if (w.Length < 6) return false;
        double h = w[1] - w[0];
        for (int i = 2; i < w.Length; i++)
            if (Math.Abs(w[i] - w[i - 1] - h) > 1e-9) return false;
        return true;
    }

    /// <summary>
    /// Values at whole nanometres <paramref name="first"/> … <paramref name="last"/>: Sprague inside the table,
    /// the end values continued outside it (colour-science's constant extrapolation).
    /// </summary>
    public static double[] At1nm(TabulatedSpectrum s, int first, int last)
    {
        var w = s.Wavelengths; var v = s.Values;
        int n = w.Length;
        double h = w[1] - w[0];
        var y = new double[n + 4];
        for (int i = 0; i < n; i++) y[i + 2] = v[i];
        for (int k = 0; k < 6; k++)
        {
            y[0] += Boundary[0, k] * v[k] / 209; y[1] += Boundary[1, k] * v[k] / 209;
            y[n + 2] += Boundary[2, k] * v[n - 6 + k] / 209; y[n + 3] += Boundary[3, k] * v[n - 6 + k] / 209;
        }
        var r = new double[last - first + 1];
        for (int j = 0; j < r.Length; j++)
        {
            double x = first + j;
            if (x <= w[0]) { r[j] = v[0]; continue; }
            if (x >= w[n - 1]) { r[j] = v[n - 1]; continue; }
            int i = Math.Min(n - 2, (int)Math.Floor((x - w[0]) / h));
            double t = (x - w[i]) / h;
            if (t == 0) { r[j] = v[i]; continue; }
            // y_{i−2} … y_{i+3} are y[i] … y[i+5] in the padded array.
            double m2 = y[i], m1 = y[i + 1], p0 = y[i + 2], p1 = y[i + 3], p2 = y[i + 4], p3 = y[i + 5];
            double a1 = (2 * m2 - 16 * m1 + 16 * p1 - 2 * p2) / 24;
            double a2 = (-m2 + 16 * m1 - 30 * p0 + 16 * p1 - p2) / 24;
            double a3 = (-9 * m2 + 39 * m1 - 70 * p0 + 66 * p1 - 33 * p2 + 7 * p3) / 24;
            double a4 = (13 * m2 - 64 * m1 + 126 * p0 - 124 * p1 + 61 * p2 - 12 * p3) / 24;
            double a5 = (-5 * m2 + 25 * m1 - 50 * p0 + 50 * p1 - 25 * p2 + 5 * p3) / 24;
            r[j] = p0 + t * (a1 + t * (a2 + t * (a3 + t * (a4 + t * a5))));
        }
        return r;
    }
}
