using SpectralRenderer.Sensor;

namespace SpectralRenderer.Analysis.Recovery;

public enum RecoveryMethod { Pinv, Wiener, Linear, Tikhonov, WienerLocal }

/// <summary>
/// Reflectance from camera signals, r̂ = G·s + h (N bands from C channels), for the forward model s = A·r + n:
/// A (C × N) the expected photo-electron rate per unit reflectance in each band (channel weights × the light's band
/// values: a surface lit like the white diffuser), n the sensor noise of covariance K_n. On the exact route r is the
/// reflectance at full resolution (its values at the training spectra's knots, <see cref="ForwardModel"/>) and the
/// estimate is of its band means: G and h below, computed there, are then taken through the band means P.
/// <list type="bullet">
/// <item><b>pinv</b>: the minimum-norm least-squares solution, G = A⁺ = Aᵀ(AAᵀ)⁻¹.</item>
/// <item><b>wiener</b>: the linear minimum-mean-square-error estimate with the training set's mean μ and covariance K_r
/// as prior: G = K_r Aᵀ (A K_r Aᵀ + K_n)⁻¹, h = μ − G A μ (Pratt &amp; Mancill 1976; Shimano 2006).</item>
/// <item><b>linear</b>: a finite-dimensional linear model, r = μ + B a with B the training set's first k principal
/// components (Maloney 1986), a = (A B)⁺ (s − A μ); k the most, up to min(C, 8), with cond(A B) ≤ 100.</item>
/// <item><b>tikhonov</b>: regularised least-squares regression from signals to reflectances learned on the training set
/// (the simulated, noisy signals S of its reflectances R, both centred): G = R Sᵀ (S Sᵀ + λ I)⁻¹, with λ minimising the
/// generalised cross-validation score GCV(λ) = T‖R − G S‖² / (T − tr H)², H = Sᵀ(SSᵀ + λI)⁻¹S (Golub, Heath &amp;
/// Wahba 1979).</item>
/// <item><b>wiener-local</b>: the Wiener estimate with a prior local to the signal, the training samples weighted by the
/// distance of their signals to the measured one (<see cref="LocalWiener"/>): nonlinear in s; G, h are then the global
/// Wiener estimate's, the limit of an infinitely wide weighting.</item>
/// </list>
/// </summary>
public sealed class SpectralEstimator
{
    SpectralEstimator(RecoveryMethod method, double[,] g, double[] h, double? lambda, int? components, LocalWiener? local,
        ForwardModel model)
    { Method = method; G = g; H = h; Lambda = lambda; Components = components; Local = local; Model = model; }

    public RecoveryMethod Method { get; }
    /// <summary>The forward model the estimator inverts (its route: bands or exact).</summary>
    public ForwardModel Model { get; }
    /// <summary>N × C.</summary>
    public double[,] G { get; }
    public double[] H { get; }
    /// <summary>The regularisation chosen by GCV (tikhonov only), in units of the mean eigenvalue of S Sᵀ.</summary>
    public double? Lambda { get; }
    /// <summary>The number of principal components kept (linear only).</summary>
    public int? Components { get; }
    /// <summary>The locally weighted estimate (wiener-local only), which <see cref="Apply"/> then uses instead of G, h.</summary>
    public LocalWiener? Local { get; }

    public const int MaxLinearComponents = 8;
    public const double MaxLinearCondition = 100;

    public static RecoveryMethod Parse(string name) => name.ToLowerInvariant() switch
    {
        "pinv" => RecoveryMethod.Pinv,
        "wiener" => RecoveryMethod.Wiener,
        "linear" => RecoveryMethod.Linear,
        "tikhonov" => RecoveryMethod.Tikhonov,
        "wiener-local" => RecoveryMethod.WienerLocal,
        _ => throw new Diagnostics.InputException("--method", $"unknown method '{name}'",
            Diagnostics.InputException.DidYouMean(name, ["pinv", "wiener", "linear", "tikhonov", "wiener-local", "all"])
                ?? "pinv, wiener, linear, tikhonov, wiener-local or all"),
    };

    public static string Name(RecoveryMethod m) => m == RecoveryMethod.WienerLocal ? "wiener-local" : m.ToString().ToLowerInvariant();

    /// <param name="a">C × N forward matrix.</param>
    /// <param name="noiseVariance">per channel, the variance of s (same units squared); zeros without noise.</param>
    public static SpectralEstimator Build(RecoveryMethod method, double[,] a, TrainingSet training, double[] noiseVariance,
        ulong seed = 1) =>
        Build(method, ForwardModel.Bands(a, training), noiseVariance, seed);

    /// <summary>
    /// The estimator for <paramref name="model"/>: each method in the model's coordinates x (M of them: the bands, or the
    /// exact route's knots) with the training set's mean and covariance there, then the band means P·x: G = P·G_x, h = P·h_x.
    /// </summary>
    /// <param name="noiseVariance">per channel, the variance of s (same units squared); zeros without noise.</param>
    public static SpectralEstimator Build(RecoveryMethod method, ForwardModel model, double[] noiseVariance, ulong seed = 1)
    {
        var a = model.A;
        var training = model.Training;
        int c = a.GetLength(0), n = a.GetLength(1);
        var at = Dense.Transpose(a);
        var mu = training.Mean();
        var amu = Dense.Multiply(a, mu);
        var muBands = model.ToBands(mu);
        // A ridge of 1e-12 of the mean diagonal keeps noise-free systems solvable without changing them measurably.
        double[,] Ridge(double[,] m)
        {
            double eps = 1e-12 * Dense.Trace(m) / m.GetLength(0);
            return Dense.Add(m, Dense.Identity(m.GetLength(0), eps));
        }
        double[,] g;
        double[] h;
        double? lambda = null;
        int? components = null;
        LocalWiener? local = null;
        switch (method)
        {
            case RecoveryMethod.Pinv:
                g = model.ToBands(Dense.SolveRight(at, Ridge(Dense.Multiply(a, at))));
                h = new double[g.GetLength(0)];
                break;
            case RecoveryMethod.Wiener:
            case RecoveryMethod.WienerLocal:
                {
                    var kr = training.Covariance();
                    var krat = Dense.Multiply(kr, at);
                    var m = Dense.Multiply(a, krat);
                    for (int i = 0; i < c; i++) m[i, i] += noiseVariance[i];
                    g = model.ToBands(Dense.SolveRight(krat, Ridge(m)));
                    h = Affine(g, muBands, amu);
                    if (method == RecoveryMethod.WienerLocal) local = LocalWiener.Build(model, noiseVariance);
                    break;
                }
            case RecoveryMethod.Linear:
                {
                    // The most components k ≤ min(C, 8) the sensor resolves: cond(A B) ≤ 100, so the coefficients amplify
                    // signal errors at most a hundredfold (beyond that a component is nearly invisible to the channels).
                    var (_, vectors) = Dense.SymmetricEigen(training.Covariance());
                    g = new double[n, c];
                    for (int k = 1; k <= Math.Min(Math.Min(c, n), MaxLinearComponents); k++)
                    {
                        var b = new double[n, k];
                        for (int i = 0; i < n; i++) for (int j = 0; j < k; j++) b[i, j] = vectors[i, j];
                        var ab = Dense.Multiply(a, b);                                   // C × k
                        var abt = Dense.Transpose(ab);
                        var normal = Dense.Multiply(abt, ab);
                        var (ev, _) = Dense.SymmetricEigen(normal);
                        if (k > 1 && !(ev[^1] > 0 && Math.Sqrt(ev[0] / ev[^1]) <= MaxLinearCondition)) break;
                        g = Dense.Multiply(b, Dense.Solve(Ridge(normal), abt));         // B (AB)⁺
                        components = k;
                    }
                    g = model.ToBands(g);
                    h = Affine(g, muBands, amu);
                    break;
                }
            default:
                {
                    int t = training.Count;
                    // Simulated training signals with the sensor's noise (a fixed seed: the fit is reproducible).
                    var s = new double[c, t];
                    int nb = muBands.Length;
                    var r = new double[nb, t];   // the targets: band means
                    var sMean = new double[c];
                    for (int j = 0; j < t; j++)
                    {
                        var sig = Dense.Multiply(a, training.Samples[j]);
                        for (int i = 0; i < c; i++)
                        {
                            var rng = new NoiseStream(seed, 11, j, i);
                            s[i, j] = sig[i] + Math.Sqrt(noiseVariance[i]) * rng.Normal();
                            sMean[i] += s[i, j] / t;
                        }
                        var rj = model.ToBands(training.Samples[j]);
                        for (int b = 0; b < nb; b++) r[b, j] = rj[b] - muBands[b];
                    }
                    for (int i = 0; i < c; i++) for (int j = 0; j < t; j++) s[i, j] -= sMean[i];
                    var sst = Dense.Multiply(s, Dense.Transpose(s));
                    var (eig, _) = Dense.SymmetricEigen(sst);
                    double unit = Dense.Trace(sst) / c;
                    var rst = Dense.Multiply(r, Dense.Transpose(s));
                    double best = double.PositiveInfinity;
                    double[,]? bestG = null;
                    for (double e = -14; e <= 1.001; e += 0.25)
                    {
                        double lam = Math.Pow(10, e) * unit;
                        var gl = Dense.SolveRight(rst, Dense.Add(sst, Dense.Identity(c, lam)));
                        var fit = Dense.Multiply(gl, s);
                        double res = 0;
                        for (int b = 0; b < nb; b++) for (int j = 0; j < t; j++) { double d = r[b, j] - fit[b, j]; res += d * d; }
                        double trH = eig.Sum(v => Math.Max(0, v) / (Math.Max(0, v) + lam));
                        double gcv = t * res / ((t - trH) * (t - trH));
                        if (gcv < best) { best = gcv; bestG = gl; lambda = Math.Pow(10, e); }
                    }
                    g = bestG!;
                    h = Affine(g, muBands, sMean);
                    break;
                }
        }
        return new SpectralEstimator(method, g, h, lambda, components, local, model);
    }

    /// <summary>h = μ − G·s₀: the estimate is μ at the signal s₀ of the mean.</summary>
    static double[] Affine(double[,] g, double[] mu, double[] s0)
    {
        var gs = Dense.Multiply(g, s0);
        return mu.Select((m, i) => m - gs[i]).ToArray();
    }

    public void Apply(ReadOnlySpan<float> signal, Span<double> reflectance)
    {
        if (Local is not null) { Local.Apply(signal, reflectance); return; }
        int n = G.GetLength(0), c = G.GetLength(1);
        for (int b = 0; b < n; b++)
        {
            double v = H[b];
            for (int i = 0; i < c; i++) v += G[b, i] * signal[i];
            reflectance[b] = v;
        }
    }
}
