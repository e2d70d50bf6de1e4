namespace SpectralRenderer.Scenes;

/// <summary>How a photometric file's horizontal (C) planes cover the full circle (IES LM-63 §5.1, EULUMDAT Isym).</summary>
public enum CandelaSymmetry
{
    /// <summary>One plane: the same in every C-plane (LM-63: one horizontal angle 0; EULUMDAT Isym 1).</summary>
    Axial,
    /// <summary>C 0–90: mirrored about the C0–C180 and C90–C270 planes (LM-63: last angle 90; Isym 4).</summary>
    Quadrant,
    /// <summary>C 0–180: mirrored about the C0–C180 plane (LM-63: last angle 180; Isym 2).</summary>
    BilateralC0,
    /// <summary>C 90–270 (LM-63: first 90, last 270) or C 270–90 (Isym 3): mirrored about the C90–C270 plane.</summary>
    BilateralC90,
    /// <summary>C 0–360 (LM-63: last angle above 180; Isym 0).</summary>
    Full,
}

/// <summary>
/// A luminaire's luminous intensity distribution in type C photometry (IES LM-63, EULUMDAT): I(C, γ) in cd over
/// horizontal angles C (0–360°, the file's symmetry expanded) and vertical angles γ (0° = nadir, 180° = zenith), the
/// bilinear interpolant of the table; zero at vertical angles outside the table (e.g. above 90° for a 0–90° table).
/// </summary>
public sealed class CandelaTable
{
    readonly double[] _c;       // ascending, 0 … 360
    readonly double[] _gamma;   // ascending
    readonly double[] _cd;      // [c · nγ + g]

    /// <param name="horizontal">The file's horizontal angles (ascending; for <see cref="CandelaSymmetry.BilateralC90"/> from
    /// EULUMDAT, 270 … 450 unwrapped), <paramref name="rows"/>[h][v] its candela values at <paramref name="vertical"/>.</param>
    public CandelaTable(double[] vertical, double[] horizontal, double[][] rows, CandelaSymmetry symmetry, string source)
    {
        Symmetry = symmetry;
        Source = source;
        _gamma = vertical;
        var knots = new SortedSet<double>();
        void Add(double c)
        {
            c = ((c % 360) + 360) % 360;
            knots.Add(Math.Round(c, 9));
            if (Math.Round(c, 9) == 0) knots.Add(360);
        }
        foreach (var h in horizontal)
            switch (symmetry)
            {
                case CandelaSymmetry.Axial: Add(0); break;
                case CandelaSymmetry.Quadrant: Add(h); Add(180 - h); Add(180 + h); Add(360 - h); break;
                case CandelaSymmetry.BilateralC0: Add(h); Add(360 - h); break;
                case CandelaSymmetry.BilateralC90: Add(h); Add(180 - h); break;
                default: Add(h); break;
            }
        if (symmetry == CandelaSymmetry.Full) { Add(0); }   // a full table 0 … 350 closes at 360 = its first plane
        _c = [.. knots];
        _cd = new double[_c.Length * _gamma.Length];
        for (int i = 0; i < _c.Length; i++)
        {
            double s = ToSource(_c[i], horizontal);
            for (int g = 0; g < _gamma.Length; g++) _cd[i * _gamma.Length + g] = Row(horizontal, rows, s, g);
        }
    }

    public CandelaSymmetry Symmetry { get; }
    /// <summary>The file the table came from (render.json).</summary>
    public string Source { get; }
    public ReadOnlySpan<double> VerticalAngles => _gamma;
    /// <summary>The horizontal angles of the expanded table, 0 … 360.</summary>
    public ReadOnlySpan<double> HorizontalAngles => _c;

    /// <summary>The file's plane that horizontal angle <paramref name="c"/> (0–360) mirrors to.</summary>
    double ToSource(double c, double[] horizontal)
    {
        c = ((c % 360) + 360) % 360;
        switch (Symmetry)
        {
            case CandelaSymmetry.Axial: return horizontal[0];
            case CandelaSymmetry.Quadrant:
                if (c > 180) c = 360 - c;
                return c > 90 ? 180 - c : c;
            case CandelaSymmetry.BilateralC0: return c > 180 ? 360 - c : c;
            case CandelaSymmetry.BilateralC90:
                if (horizontal[0] >= 180)
                {   // EULUMDAT 270 … 450: C in (90, 270) mirrors to 180 − C, unwrapped above 270.
                    double m = c > 90 && c < 270 ? 180 - c : c;
                    m = ((m % 360) + 360) % 360;
                    return m < 270 ? m + 360 : m;
                }
                return c < 90 ? 180 - c : c > 270 ? 540 - c : c;   // LM-63 90 … 270
            default:
                return c;   // a full table that ends below 360 closes towards its first plane (Row)
        }
    }

    /// <summary>The file's candela at vertical index <paramref name="g"/>, linearly between its planes at angle s.</summary>
    static double Row(double[] h, double[][] rows, double s, int g)
    {
        if (h.Length == 1 || s <= h[0]) return rows[0][g];
        if (s >= h[^1])
        {
            // A full table that ends below 360 closes towards its first plane (at 360).
            if (s > h[^1] && h[0] == 0 && s < 360) return rows[^1][g] + (s - h[^1]) / (360 - h[^1]) * (rows[0][g] - rows[^1][g]);
            return rows[^1][g];
        }
        int i = Array.BinarySearch(h, s);
        if (i >= 0) return rows[i][g];
        i = ~i - 1;
        double t = (s - h[i]) / (h[i + 1] - h[i]);
        return rows[i][g] + t * (rows[i + 1][g] - rows[i][g]);
    }

    /// <summary>I(C, γ) in cd: bilinear in (C, γ) on the expanded table; 0 outside its vertical range.</summary>
    public double Evaluate(double c, double gamma)
    {
        var v = _gamma;
        // Within 1e-4° of the table's edge (a float direction's rounding) is on it; beyond, the file says nothing: 0.
        if (gamma < v[0] - 1e-4 || gamma > v[^1] + 1e-4) return 0;
        gamma = Math.Clamp(gamma, v[0], v[^1]);
        c = ((c % 360) + 360) % 360;
        int j = Interval(v, gamma, out double tg);
        int i = Interval(_c, c, out double tc);
        int n = v.Length;
        double At(int ci, int gi) => _cd[ci * n + gi];
        int j1 = Math.Min(j + 1, n - 1), i1 = Math.Min(i + 1, _c.Length - 1);
        double a = At(i, j) + tg * (At(i, j1) - At(i, j));
        double b = At(i1, j) + tg * (At(i1, j1) - At(i1, j));
        return a + tc * (b - a);
    }

    static int Interval(double[] x, double value, out double t)
    {
        if (x.Length == 1) { t = 0; return 0; }
        int i = Array.BinarySearch(x, value);
        if (i >= 0) { t = 0; return i; }
        i = Math.Clamp(~i - 1, 0, x.Length - 2);
        t = (value - x[i]) / (x[i + 1] - x[i]);
        return i;
    }

    /// <summary>
    /// The luminous flux Φ = ∫ I dΩ = ∫∫ I(C, γ) sin γ dγ dC (lm) of the interpolated table, by the midpoint rule on a
    /// 0.5° × 0.1° grid.
    /// </summary>
    public double Flux()
    {
        const double dc = 0.5, dg = 0.1;
        double sum = 0;
        for (double g = dg / 2; g < 180; g += dg)
        {
            double s = Math.Sin(g * Math.PI / 180), row = 0;
            for (double c = dc / 2; c < 360; c += dc) row += Evaluate(c, g);
            sum += row * s;
        }
        return sum * (dc * Math.PI / 180) * (dg * Math.PI / 180);
    }
}
