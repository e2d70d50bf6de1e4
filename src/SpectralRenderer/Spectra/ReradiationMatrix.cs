namespace SpectralRenderer.Spectra;

/// <summary>
/// A bispectral re-radiation (Donaldson) matrix D[o, i] on one evenly spaced wavelength list λ_j (spacing Δ): what a
/// fluorescent surface returns at emission wavelength λ_o per unit incident spectral irradiance at excitation λ_i.
/// The diagonal is the ordinary reflectance R(λ) (taken, like every table here, as its piecewise-linear interpolant); an
/// off-diagonal entry is the re-radiated part integrated over one excitation cell, D[o, i] = f(λ_i, λ_o)·Δ, with f constant
/// on the cells [λ_j − Δ/2, λ_j + Δ/2] (Donaldson 1954; the layout of Fichet et al., "An OpenEXR layout for spectral
/// images", JCGT 10(3) 2021, T.&lt;in&gt;nm.&lt;out&gt;nm). The reflected radiance factor under an irradiance E is then
///   β(λ_o)·E(λ_o) = R(λ_o)·E(λ_o) + Σ_i D[o, i]·Ē_i,   Ē_i the mean of E over cell i,
/// the matrix applied to the incident spectrum: its reflective diagonal plus the shifted part. Projected onto bands it stays
/// exact: a band's value is the band mean of this piecewise-constant emission (<see cref="CellsToBands"/>), and the shift
/// on a band grid is the double integral over band × band (<see cref="ShiftOnBands(BandGrid)"/>), which conserves the emitted energy.
/// </summary>
public sealed class ReradiationMatrix
{
    readonly double[] _wavelengths;
    readonly double[] _d;   // row-major [o * n + i]

    /// <param name="d">D[o, i], row-major by emission o.</param>
    public ReradiationMatrix(string name, double[] wavelengths, double[] d)
    {
        int n = wavelengths.Length;
        if (n < 2 || d.Length != n * n) throw new ArgumentException("a re-radiation matrix needs n ≥ 2 wavelengths and n × n values");
        Spacing = (wavelengths[^1] - wavelengths[0]) / (n - 1);
        for (int j = 1; j < n; j++)
            if (Math.Abs(wavelengths[j] - wavelengths[j - 1] - Spacing) > 1e-6 * Spacing)
                throw new ArgumentException($"{name}: the wavelengths must be evenly spaced");
        Name = name;
        _wavelengths = wavelengths;
        _d = d;
        var knots = new double[n + 2];
        var r = new double[n + 2];
        knots[0] = wavelengths[0] - Spacing / 2; knots[^1] = wavelengths[^1] + Spacing / 2;
        for (int j = 0; j < n; j++) { knots[j + 1] = wavelengths[j]; r[j + 1] = d[j * n + j]; }
        r[0] = r[1]; r[^1] = r[^2];   // the end cells' half outside the first and last sample: the end value continues
        Reflectance = new TabulatedSpectrum($"{name} (diagonal)", knots, r);
        for (int o = 0; o < n && !HasShift; o++)
            for (int i = 0; i < n; i++)
                if (i != o && d[o * n + i] != 0) { HasShift = true; break; }
    }

    public string Name { get; }
    public int Count => _wavelengths.Length;
    public double Spacing { get; }
    public ReadOnlySpan<double> Wavelengths => _wavelengths;
    /// <summary>D[o, i]: emission o, excitation i.</summary>
    public double this[int o, int i] => _d[o * Count + i];
    /// <summary>The reflective diagonal R(λ), over the cells' whole range [λ_0 − Δ/2, λ_n + Δ/2].</summary>
    public TabulatedSpectrum Reflectance { get; }
    /// <summary>Any off-diagonal entry non-zero: without one the matrix is the plain reflectance.</summary>
    public bool HasShift { get; }
    public double CellLower(int j) => _wavelengths[j] - Spacing / 2;
    public double CellUpper(int j) => _wavelengths[j] + Spacing / 2;

    /// <summary>
    /// Photon balance per excitation wavelength: the photons re-emitted, Σ_{o≠i} D[o, i]·λ_o, may not exceed those absorbed,
    /// (1 − D[i, i])·λ_i (both per unit irradiance at λ_i, in units of hc). Returns the first column that emits more (beyond
    /// a relative <paramref name="tolerance"/>), or −1.
    /// </summary>
    public int PhotonExcess(double tolerance, out double emitted, out double absorbed)
    {
        int n = Count;
        emitted = absorbed = 0;
        for (int i = 0; i < n; i++)
        {
            double e = 0;
            for (int o = 0; o < n; o++) if (o != i) e += _d[o * n + i] * _wavelengths[o];
            double a = (1 - _d[i * n + i]) * _wavelengths[i];
            if (e > a + tolerance * _wavelengths[i]) { emitted = e; absorbed = a; return i; }
        }
        return -1;
    }

    /// <summary>Length of [a0, a1] ∩ [b0, b1].</summary>
    public static double Overlap(double a0, double a1, double b0, double b1) => Math.Max(0, Math.Min(a1, b1) - Math.Max(a0, b0));

    /// <summary>
    /// The shifted emission per cell, L_o = Σ_{i≠o} D[o, i]·Ē_i, for an incident spectrum given by its integral over an interval
    /// (<paramref name="integral"/>(lo, hi) = ∫ E dλ); light outside [<paramref name="lo"/>, <paramref name="hi"/>] (the render's
    /// bands) is not carried, so it excites nothing.
    /// </summary>
    public double[] ShiftedCells(Func<double, double, double> integral, double lo, double hi)
    {
        int n = Count;
        var mean = new double[n];
        for (int i = 0; i < n; i++)
        {
            double a = Math.Max(lo, CellLower(i)), b = Math.Min(hi, CellUpper(i));
            mean[i] = b > a ? integral(a, b) / Spacing : 0;
        }
        var l = new double[n];
        for (int o = 0; o < n; o++)
        {
            double s = 0;
            for (int i = 0; i < n; i++) if (i != o) s += _d[o * n + i] * mean[i];
            l[o] = s;
        }
        return l;
    }

    /// <summary>Band means of a spectrum constant on the cells (zero outside them).</summary>
    public double[] CellsToBands(ReadOnlySpan<double> cells, BandGrid grid)
    {
        var bands = new double[grid.Count];
        for (int b = 0; b < grid.Count; b++)
        {
            double lo = grid.Lower(b), hi = grid.Upper(b), s = 0;
            for (int o = 0; o < Count; o++) s += cells[o] * Overlap(lo, hi, CellLower(o), CellUpper(o));
            bands[b] = s / (hi - lo);
        }
        return bands;
    }

    /// <summary>
    /// The shift as a matrix on a band grid, S[b, a] (row-major, emission band b), for an incident spectrum constant within each
    /// band: S[b, a] = (1/w_b) Σ_o |cell_o ∩ b| Σ_{i≠o} D[o, i]·|cell_i ∩ a|/Δ — the exact band mean of the emission, so the
    /// energy re-emitted from band a, Σ_b S[b, a]·w_b, is the matrix's own.
    /// </summary>
    public double[] ShiftOnBands(BandGrid grid) => ShiftOnBands(grid.Count, grid.Lower, grid.Upper);

    /// <summary><see cref="ShiftOnBands(BandGrid)"/> on bands given by their edges.</summary>
    public double[] ShiftOnBands(int bands, Func<int, double> lower, Func<int, double> upper)
    {
        int n = Count;
        var inCell = new double[bands * n];    // |cell_i ∩ a| / Δ
        var outCell = new double[bands * n];   // |cell_o ∩ b| / w_b
        for (int a = 0; a < bands; a++)
            for (int j = 0; j < n; j++)
            {
                double lo = lower(a), hi = upper(a), w = Overlap(lo, hi, CellLower(j), CellUpper(j));
                inCell[a * n + j] = w / Spacing;
                outCell[a * n + j] = w / (hi - lo);
            }
        var s = new double[bands * bands];
        var row = new double[n];
        for (int b = 0; b < bands; b++)
        {
            for (int i = 0; i < n; i++)
            {   // row[i] = Σ_{o≠i} |cell_o ∩ b|/w_b · D[o, i]
                double r = 0;
                for (int o = 0; o < n; o++) if (o != i && outCell[b * n + o] != 0) r += outCell[b * n + o] * _d[o * n + i];
                row[i] = r;
            }
            for (int a = 0; a < bands; a++)
            {
                double v = 0;
                for (int i = 0; i < n; i++) v += row[i] * inCell[a * n + i];
                s[b * bands + a] = v;
            }
        }
        return s;
    }
}
