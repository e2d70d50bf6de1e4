using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// RGB to reflectance spectrum by Jakob &amp; Hanika's sigmoid polynomial ("A Low-Dimensional Function Space for Efficient
/// Spectral Upsampling", Computer Graphics Forum 38(2), 2019): r(λ) = S(c₀x² + c₁x + c₂) with S(y) = ½ + y / (2√(1 + y²))
/// and x = (λ − 380 nm) / 400 nm — smooth, and within [0, 1] for every coefficient. The three coefficients of a colour
/// are solved here for each colour (no precomputed table): Levenberg–Marquardt on the CIELAB difference between the
/// target and the spectrum's colour under D65 (CIE 1931 2°, white Y = 1), the spectrum tabulated every 5 nm over
/// 380–780 nm (held beyond) and its colour integrated exactly as the renderer integrates a reflectance table, walked
/// from mid grey to the target in steps so that saturated colours converge. sRGB codes are decoded by IEC 61966-2-1
/// (the transfer curve and its 4-decimal RGB → XYZ matrix). Solutions are cached per colour.
/// </summary>
public sealed class SigmoidUplift
{
    /// <summary>The wavelengths the uplifted spectra are tabulated at: 380, 385, …, 780 nm.</summary>
    public static double[] Wavelengths { get; } = Enumerable.Range(0, 81).Select(i => 380 + 5.0 * i).ToArray();

    readonly double[][] _tent;   // XYZ of each sample's tent function (white Y = 1)
    readonly Xyz _white;
    readonly Dictionary<long, double[]> _cache = [];
    readonly Lock _lock = new();

    public SigmoidUplift()
    {
        var d65 = SpectrumLibrary.Resolve("D65");
        var cm = new Colorimeter(BandGrid.Default, Observer.Cie1931, d65, BandIntegration.Exact, false, 1);
        int n = Wavelengths.Length;
        _tent = new double[n][];
        for (int j = 0; j < n; j++)
        {
            var v = new double[n];
            v[j] = 1;
            var xyz = cm.OfReflectance(new TabulatedSpectrum("tent", Wavelengths, v, Extrapolation.Clamp));
            _tent[j] = [xyz.X, xyz.Y, xyz.Z];
        }
        _white = Colour(Enumerable.Repeat(1.0, n).ToArray());
    }

    /// <summary>The white the CIELAB differences are taken against: a perfect reflector under D65.</summary>
    public Xyz White => _white;

    /// <summary>sRGB (IEC 61966-2-1) non-linear values in [0, 1] to XYZ (white Y = 1).</summary>
    public static Xyz FromSrgb(double r, double g, double b)
    {
        static double Linear(double c) => c <= 0.04045 ? c / 12.92 : Math.Pow((c + 0.055) / 1.055, 2.4);
        double lr = Linear(r), lg = Linear(g), lb = Linear(b);
        return new Xyz(
            0.4124 * lr + 0.3576 * lg + 0.1805 * lb,
            0.2126 * lr + 0.7152 * lg + 0.0722 * lb,
            0.0193 * lr + 0.1192 * lg + 0.9505 * lb);
    }

    /// <summary>XYZ under D65 of a reflectance tabulated at <see cref="Wavelengths"/>.</summary>
    public Xyz Colour(ReadOnlySpan<double> r)
    {
        double x = 0, y = 0, z = 0;
        for (int j = 0; j < r.Length; j++) { x += _tent[j][0] * r[j]; y += _tent[j][1] * r[j]; z += _tent[j][2] * r[j]; }
        return new Xyz(x, y, z);
    }

    /// <summary>The reflectance (at <see cref="Wavelengths"/>) of an sRGB colour given as codes out of <paramref name="max"/> (255 or
    /// 65535).</summary>
    public double[] FromSrgbCodes(int r, int g, int b, int max)
    {
        long key = ((long)max << 48) | ((long)r << 32) | ((long)g << 16) | (long)b;
        lock (_lock) if (_cache.TryGetValue(key, out var hit)) return hit;
        var spectrum = Spectrum(FromSrgb((double)r / max, (double)g / max, (double)b / max), out _);
        lock (_lock) _cache[key] = spectrum;
        return spectrum;
    }

    /// <summary>The sigmoid-polynomial reflectance whose colour under D65 is nearest <paramref name="target"/>, and that ΔE00.</summary>
    public double[] Spectrum(Xyz target, out double deltaE)
    {
        var goal = Lab.FromXyz(target, _white);
        var c = new double[3];
        var start = Lab.FromXyz(Colour(Evaluate(c)), _white);
        // Continuation: the targets walk from the grey of c = 0 to the goal, each solve starting where the last ended.
        const int Steps = 8;
        for (int k = 1; k <= Steps; k++)
        {
            double f = (double)k / Steps;
            var t = new Lab(start.L + f * (goal.L - start.L), start.A + f * (goal.A - start.A), start.B + f * (goal.B - start.B));
            Solve(c, t, k == Steps ? 200 : 30);
        }
        var r = Evaluate(c);
        deltaE = DeltaE2000.Between(Lab.FromXyz(Colour(r), _white), goal);
        return r;
    }

    static double Sigmoid(double y) => 0.5 + y / (2 * Math.Sqrt(1 + y * y));

    /// <summary>r(λ_j) for coefficients c.</summary>
    static double[] Evaluate(ReadOnlySpan<double> c)
    {
        var r = new double[Wavelengths.Length];
        for (int j = 0; j < r.Length; j++)
        {
            double x = (Wavelengths[j] - 380) / 400;
            r[j] = Sigmoid((c[0] * x + c[1]) * x + c[2]);
        }
        return r;
    }

    double[] Residual(ReadOnlySpan<double> c, Lab target)
    {
        var lab = Lab.FromXyz(Colour(Evaluate(c)), _white);
        return [lab.L - target.L, lab.A - target.A, lab.B - target.B];
    }

    /// <summary>Levenberg–Marquardt on the three Lab residuals (a central-difference Jacobian), in place.</summary>
    void Solve(double[] c, Lab target, int iterations)
    {
        double lambda = 1e-3;
        var f = Residual(c, target);
        double cost = Dot(f, f);
        for (int it = 0; it < iterations && cost > 1e-14; it++)
        {
            var jac = new double[3, 3];
            for (int k = 0; k < 3; k++)
            {
                double h = 1e-6 * Math.Max(1, Math.Abs(c[k]));
                var cp = (double[])c.Clone(); cp[k] += h;
                var cm = (double[])c.Clone(); cm[k] -= h;
                var fp = Residual(cp, target);
                var fm = Residual(cm, target);
                for (int i = 0; i < 3; i++) jac[i, k] = (fp[i] - fm[i]) / (2 * h);
            }
            // (JᵀJ + λ diag(JᵀJ)) δ = −Jᵀf
            var a = new double[3, 3];
            var g = new double[3];
            for (int p = 0; p < 3; p++)
            {
                for (int q = 0; q < 3; q++) for (int i = 0; i < 3; i++) a[p, q] += jac[i, p] * jac[i, q];
                for (int i = 0; i < 3; i++) g[p] -= jac[i, p] * f[i];
            }
            bool improved = false;
            for (int tries = 0; tries < 12 && !improved; tries++)
            {
                var m = (double[,])a.Clone();
                for (int p = 0; p < 3; p++) m[p, p] += lambda * Math.Max(a[p, p], 1e-12);
                if (!Solve3(m, g, out var delta)) { lambda *= 10; continue; }
                var next = new[] { c[0] + delta[0], c[1] + delta[1], c[2] + delta[2] };
                var fn = Residual(next, target);
                double nc = Dot(fn, fn);
                if (nc < cost && double.IsFinite(nc))
                {
                    Array.Copy(next, c, 3); f = fn; cost = nc;
                    lambda = Math.Max(lambda / 10, 1e-12);
                    improved = true;
                }
                else lambda *= 10;
            }
            if (!improved) break;
        }
    }

    static double Dot(double[] a, double[] b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

    /// <summary>A 3 × 3 system by Cramer's rule; false when singular.</summary>
    static bool Solve3(double[,] m, double[] b, out double[] x)
    {
        double Det(double[,] a) =>
            a[0, 0] * (a[1, 1] * a[2, 2] - a[1, 2] * a[2, 1]) - a[0, 1] * (a[1, 0] * a[2, 2] - a[1, 2] * a[2, 0])
                + a[0, 2] * (a[1, 0] * a[2, 1] - a[1, 1] * a[2, 0]);
        double d = Det(m);
        x = new double[3];
        if (!(Math.Abs(d) > 1e-300) || !double.IsFinite(d)) return false;
        for (int k = 0; k < 3; k++)
        {
            var mk = (double[,])m.Clone();
            for (int i = 0; i < 3; i++) mk[i, k] = b[i];
            x[k] = Det(mk) / d;
        }
        return true;
    }
}
