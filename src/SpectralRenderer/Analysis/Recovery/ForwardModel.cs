using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// The recovery's forward model s = A·x + n for a surface lit like the render's white diffuser: A (C × M) the expected
/// rate (e⁻/s) per unit of each coordinate x_i of the reflectance, P (N × M) the output bands' means of the
/// coordinates, and the training set in the same coordinates (issue 24). It follows the capture's signal route:
/// <list type="bullet">
/// <item><b>bands</b> (<c>camera --signals bands</c>, a cube that is not a render): x are the band means themselves,
/// A_c,b = w_c,b·E_b (× the render's white scale) and P = I. The band route makes its signals the same way (the cube's
/// band values × the weights), so the model is its captures' own.</item>
/// <item><b>exact</b> (the exact route): x are the reflectance's values at the training spectra's knots (5 nm for the
/// named sets), r(λ) = Σ_i x_i φ_i(λ) with φ_i the piecewise-linear hat of knot i, and
/// A_c,i = (white scale)·k·∫ η_c(λ)·λ/(hc)·E(λ)·φ_i(λ) dλ over the grid's range, k = s·A·ff·πT/(1+4N²)·10⁻⁹ — the
/// exact route's own integral (<see cref="ChannelWeights.ExactIntegral"/>) of that reflectance, so the training spectra's
/// signals are what the exact route makes of them, their variation inside each band included; P_b,i = ∫_b φ_i dλ / Δλ_b
/// returns band means. (Taking the reflectance constant in each band instead, A_c,b = w_c,b·E_b, gives mosaic-16 a
/// noise-free Wiener ColorChecker RMSE of 0.0055 over 400–700 nm at 20 bands on exact signals, this model 0.0011:
/// docs/camera.md.)</item>
/// </list>
/// </summary>
public sealed class ForwardModel
{
    ForwardModel(string route, double[,] a, double[,]? bandMeans, TrainingSet training, double[]? knots)
    { Route = route; A = a; BandMeans = bandMeans; Training = training; Knots = knots; }

    /// <summary>"bands" or "exact": the signal route the model is for.</summary>
    public string Route { get; }
    /// <summary>C × M: e⁻/s per unit of each coordinate.</summary>
    public double[,] A { get; }
    /// <summary>N × M: the output bands' means of the coordinates; null on the band route (the coordinates are the bands).</summary>
    public double[,]? BandMeans { get; }
    /// <summary>The training set with its samples in the model's coordinates (T × M).</summary>
    public TrainingSet Training { get; }
    /// <summary>The wavelengths (nm) of the exact model's coordinates; null on the band route.</summary>
    public double[]? Knots { get; }

    /// <summary>What the model is, in words (recover's output and manifest).</summary>
    public string Description => BandMeans is null
        ? "bands: A_c,b = w_c,b * E_b, reflectance taken constant within each band (the band route's own signals)"
        : $"exact: A_c,i = k * integral(eta_c * lambda/(h c) * E * hat_i) at full spectral resolution over the {Knots!.Length} knots " +
          $"{Knots[0]:0.###}-{Knots[^1]:0.###} nm of the training spectra, recovered as band means";

    /// <summary>The band route's model: <paramref name="a"/> (C × N) on the band means of <paramref name="training"/>.</summary>
    public static ForwardModel Bands(double[,] a, TrainingSet training) => new("bands", a, null, training, null);

    /// <summary>
    /// The exact route's model for <paramref name="sensor"/> under <paramref name="light"/> on <paramref name="grid"/>'s range,
    /// with <paramref name="factor"/> the channel weights' k (<see cref="ChannelWeights.Factor"/>) and the render's white scale.
    /// </summary>
    public static ForwardModel Exact(SensorModel sensor, double factor, double whiteScale, TabulatedSpectrum light, BandGrid grid,
        TrainingSet training)
    {
        double lo = grid.Start, hi = grid.End;
        var all = new SortedSet<double>();
        foreach (var s in training.Spectra) foreach (var x in s.Wavelengths) all.Add(x);
        var k = all.ToArray();
        // The hats whose support meets the range; the end hats run on as 1 beyond the outermost knots (Σ φ_i = 1 everywhere).
        var kept = new List<(double Knot, double Lo, double Hi, TabulatedSpectrum Hat)>();
        for (int i = 0; i < k.Length; i++)
        {
            double left = i > 0 ? k[i - 1] : double.NegativeInfinity, right = i + 1 < k.Length ? k[i + 1] : double.PositiveInfinity;
            double a = Math.Max(lo, left), b = Math.Min(hi, right);
            if (!(b > a)) continue;
            var hat = k.Length == 1 ? TabulatedSpectrum.Constant(1, "hat")
                : i == 0 ? new TabulatedSpectrum("hat", [k[0], k[1]], [1, 0], Extrapolation.Clamp)
                : i + 1 == k.Length ? new TabulatedSpectrum("hat", [k[i - 1], k[i]], [0, 1], Extrapolation.Clamp)
                : new TabulatedSpectrum("hat", [k[i - 1], k[i], k[i + 1]], [0, 1, 0], Extrapolation.Clamp);
            kept.Add((k[i], a, b, hat));
        }
        int c = sensor.ChannelCount, m = kept.Count, n = grid.Count;
        var am = new double[c, m];
        Parallel.For(0, c, ch =>
        {
            for (int i = 0; i < m; i++)
                am[ch, i] = whiteScale * factor
                    * ChannelWeights.ExactIntegral(sensor.Channels[ch], light, kept[i].Hat, kept[i].Lo, kept[i].Hi);
        });
        var p = new double[n, m];
        for (int b = 0; b < n; b++)
            for (int i = 0; i < m; i++)
            {
                double a = Math.Max(grid.Lower(b), kept[i].Lo), e = Math.Min(grid.Upper(b), kept[i].Hi);
                if (e > a) p[b, i] = kept[i].Hat.Integrate(a, e) / (grid.Upper(b) - grid.Lower(b));
            }
        // The samples at the knots (tiny negatives count as 0, as in the band means).
        var samples = training.Spectra.Select(s => kept
            .Select(h => Math.Max(0, s.Evaluate(s.Covers(h.Knot, h.Knot) ? h.Knot : Math.Clamp(h.Knot, s.First, s.Last))))
            .ToArray()).ToArray();
        return new ForwardModel("exact", am, p, training.WithSamples(samples), kept.Select(h => h.Knot).ToArray());
    }

    /// <summary>The same model with channel c's row of A scaled by <paramref name="scales"/>[c] (a white calibration, §3.4).</summary>
    public ForwardModel WithChannelScales(double[] scales)
    {
        var a = (double[,])A.Clone();
        for (int i = 0; i < a.GetLength(0); i++) for (int j = 0; j < a.GetLength(1); j++) a[i, j] *= scales[i];
        return new ForwardModel(Route, a, BandMeans, Training, Knots);
    }

    /// <summary>Per channel, the expected rate of a white of reflectance 1, A·1 (the same on both routes).</summary>
    public double[] White()
    {
        var w = new double[A.GetLength(0)];
        for (int i = 0; i < w.Length; i++) for (int j = 0; j < A.GetLength(1); j++) w[i] += A[i, j];
        return w;
    }

    /// <summary>P·X (N × ·) for coordinates X (M × ·); X itself on the band route.</summary>
    public double[,] ToBands(double[,] x) => BandMeans is null ? x : Dense.Multiply(BandMeans, x);

    /// <summary>P·x; x itself on the band route.</summary>
    public double[] ToBands(double[] x) => BandMeans is null ? x : Dense.Multiply(BandMeans, x);
}
