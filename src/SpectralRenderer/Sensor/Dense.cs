namespace SpectralRenderer.Sensor;

/// <summary>Small dense matrices (double[rows, columns]): products, solves and the symmetric eigenproblem, for fits of a few dozen
/// unknowns.</summary>
public static class Dense
{
    public static double[,] Multiply(double[,] a, double[,] b)
    {
        int n = a.GetLength(0), m = a.GetLength(1), p = b.GetLength(1);
        if (b.GetLength(0) != m) throw new ArgumentException($"{n}×{m} times {b.GetLength(0)}×{p}");
        var c = new double[n, p];
        for (int i = 0; i < n; i++)
            for (int k = 0; k < m; k++)
            {
                double v = a[i, k];
                if (v == 0) continue;
                for (int j = 0; j < p; j++) c[i, j] += v * b[k, j];
            }
        return c;
    }

    public static double[] Multiply(double[,] a, ReadOnlySpan<double> x)
    {
        int n = a.GetLength(0), m = a.GetLength(1);
        var y = new double[n];
        for (int i = 0; i < n; i++) { double s = 0; for (int k = 0; k < m; k++) s += a[i, k] * x[k]; y[i] = s; }
        return y;
    }

    public static double[,] Transpose(double[,] a)
    {
        int n = a.GetLength(0), m = a.GetLength(1);
        var t = new double[m, n];
        for (int i = 0; i < n; i++) for (int j = 0; j < m; j++) t[j, i] = a[i, j];
        return t;
    }

    public static double[,] Identity(int n, double s = 1)
    {
        var m = new double[n, n];
        for (int i = 0; i < n; i++) m[i, i] = s;
        return m;
    }

    public static double[,] Add(double[,] a, double[,] b)
    {
        var c = (double[,])a.Clone();
        for (int i = 0; i < a.GetLength(0); i++) for (int j = 0; j < a.GetLength(1); j++) c[i, j] += b[i, j];
        return c;
    }

    public static double Trace(double[,] a)
    {
        double t = 0;
        for (int i = 0; i < Math.Min(a.GetLength(0), a.GetLength(1)); i++) t += a[i, i];
        return t;
    }

    /// <summary>X with A·X = B (A square), Gaussian elimination with partial pivoting; throws when A is singular.</summary>
    public static double[,] Solve(double[,] a, double[,] b)
    {
        int n = a.GetLength(0), m = b.GetLength(1);
        if (a.GetLength(1) != n || b.GetLength(0) != n) throw new ArgumentException("Solve needs a square A and as many rows in B");
        var lu = (double[,])a.Clone();
        var x = (double[,])b.Clone();
        double scale = 0;
        foreach (var v in a) scale = Math.Max(scale, Math.Abs(v));
        for (int col = 0; col < n; col++)
        {
            int piv = col;
            for (int r = col + 1; r < n; r++) if (Math.Abs(lu[r, col]) > Math.Abs(lu[piv, col])) piv = r;
            if (!(Math.Abs(lu[piv, col]) > 1e-300 + 1e-15 * scale)) throw new InvalidOperationException("singular matrix");
            if (piv != col)
            {
                for (int j = 0; j < n; j++) (lu[col, j], lu[piv, j]) = (lu[piv, j], lu[col, j]);
                for (int j = 0; j < m; j++) (x[col, j], x[piv, j]) = (x[piv, j], x[col, j]);
            }
            for (int r = col + 1; r < n; r++)
            {
                double f = lu[r, col] / lu[col, col];
                if (f == 0) continue;
                for (int j = col; j < n; j++) lu[r, j] -= f * lu[col, j];
                for (int j = 0; j < m; j++) x[r, j] -= f * x[col, j];
            }
        }
        for (int col = n - 1; col >= 0; col--)
            for (int j = 0; j < m; j++)
            {
                double s = x[col, j];
                for (int k = col + 1; k < n; k++) s -= lu[col, k] * x[k, j];
                x[col, j] = s / lu[col, col];
            }
        return x;
    }

    public static double[,] Inverse(double[,] a) => Solve(a, Identity(a.GetLength(0)));

    /// <summary>B·A⁻¹ (A square): the solution of X·A = B.</summary>
    public static double[,] SolveRight(double[,] b, double[,] a) => Transpose(Solve(Transpose(a), Transpose(b)));

    /// <summary>Eigenvalues (descending) and eigenvectors (columns) of a symmetric matrix, cyclic Jacobi rotations.</summary>
    public static (double[] Values, double[,] Vectors) SymmetricEigen(double[,] s)
    {
        int n = s.GetLength(0);
        var a = (double[,])s.Clone();
        var v = Identity(n);
        for (int sweep = 0; sweep < 100; sweep++)
        {
            double off = 0, diag = 0;
            for (int i = 0; i < n; i++) { diag += a[i, i] * a[i, i]; for (int j = i + 1; j < n; j++) off += a[i, j] * a[i, j]; }
            if (off <= 1e-30 * diag || off == 0) break;
            for (int p = 0; p < n; p++)
                for (int q = p + 1; q < n; q++)
                {
                    if (a[p, q] == 0) continue;
                    double theta = (a[q, q] - a[p, p]) / (2 * a[p, q]);
                    double t = Math.Sign(theta == 0 ? 1 : theta) / (Math.Abs(theta) + Math.Sqrt(theta * theta + 1));
                    double c = 1 / Math.Sqrt(t * t + 1), sn = t * c;
                    for (int k = 0; k < n; k++)
                    {
                        double akp = a[k, p], akq = a[k, q];
                        a[k, p] = c * akp - sn * akq; a[k, q] = sn * akp + c * akq;
                    }
                    for (int k = 0; k < n; k++)
                    {
                        double apk = a[p, k], aqk = a[q, k];
                        a[p, k] = c * apk - sn * aqk; a[q, k] = sn * apk + c * aqk;
                    }
                    for (int k = 0; k < n; k++)
                    {
                        double vkp = v[k, p], vkq = v[k, q];
                        v[k, p] = c * vkp - sn * vkq; v[k, q] = sn * vkp + c * vkq;
                    }
                }
        }
        var order = Enumerable.Range(0, n).OrderByDescending(i => a[i, i]).ToArray();
        var values = order.Select(i => a[i, i]).ToArray();
        var vectors = new double[n, n];
        for (int j = 0; j < n; j++) for (int k = 0; k < n; k++) vectors[k, j] = v[k, order[j]];
        return (values, vectors);
    }
}
