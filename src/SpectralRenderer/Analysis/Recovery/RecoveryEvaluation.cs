using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>A region's (or the ColorChecker's) mean recovery metrics for one method.</summary>
public sealed record RecoveryRow(string Method, string Region, int Count, double Rmse, double Gfc, double DeltaE00D65, double DeltaE00A);

/// <summary>One method's recovered cube, its metrics and the spectra a figure shows.</summary>
public sealed record RecoveryResult(RecoveryMethod Method, SpectralEstimator Estimator, float[] Reflectance, List<RecoveryRow> Rows,
    List<(string Label, double[] Recovered, double[] Truth)> Examples, string? WhiteDescription);

/// <summary>
/// Reflectance recovered from a camera capture and scored against the render's ground truth (reflectance.exr):
/// RMSE, GFC, CIEDE2000 under D65 and under A (<see cref="SpectralMetrics"/>, <see cref="ReflectanceDifference"/>),
/// averaged per region (lit, shadow, partial, highlight from the render's masks; "all" surfaces) and, when the render
/// shows ColorChecker patches, over the patches (each patch's mean recovered spectrum against its truth).
/// Optionally calibrated on a white reference as in §3.4: each channel of A is scaled so A·1 matches the signal
/// measured on the white, which absorbs the light's level and the geometry.
/// </summary>
public static class RecoveryEvaluation
{
    /// <param name="regions">false: only the ColorChecker patches are scored, and only their pixels recovered (the cube is NaN
    /// elsewhere): much faster on large images, the same patch figures.</param>
    /// <param name="metricRange">RMSE and GFC over the bands inside [lo, hi] nm only (null: every band); ΔE00 always uses the whole
    /// spectrum.</param>
    public static RecoveryResult Run(CameraCapture capture, RecoveryMethod method, TrainingSet training, bool[]? whiteMask = null,
        string? whiteDescription = null,
        (double Lo, double Hi)? metricRange = null, bool regions = true)
    {
        var scene = capture.Scene;
        var truth = scene.Aovs.Reflectance
            ?? throw new InputException(scene.Folder.Path, "has no ground-truth reflectance (reflectance.exr)",
                "render with --formats including aov");
        int c = capture.Sensor.ChannelCount, n = scene.Grid.Count, pixels = scene.Width * scene.Height;
        var model = capture.ForwardModel(training);
        if (whiteMask is not null)
        {
            var measured = new double[c];
            int count = 0;
            for (int i = 0; i < pixels; i++)
            {
                if (!whiteMask[i]) continue;
                for (int k = 0; k < c; k++) measured[k] += capture.Image.Rates[i * c + k];
                count++;
            }
            var predicted = model.White();
            var scales = new double[c];
            for (int k = 0; k < c; k++) scales[k] = count > 0 && predicted[k] > 0 ? measured[k] / count / predicted[k] : 1;
            model = model.WithChannelScales(scales);
        }
        var estimator = SpectralEstimator.Build(method, model, capture.NoiseVariance());
        var cube = new float[pixels * n];
        // Without regions only the patches' pixels are scored, so only they are recovered.
        bool[]? recover = null;
        if (!regions && scene.Patches.Count > 0)
        {
            recover = new bool[pixels];
            foreach (var p in scene.Patches) foreach (int i in p.Pixels) recover[i] = true;
            Array.Fill(cube, float.NaN);
        }
        Parallel.For(0, scene.Height, y =>
        {
            Span<double> r = stackalloc double[n];
            for (int i = y * scene.Width; i < (y + 1) * scene.Width; i++)
            {
                if (recover is not null && !recover[i]) continue;
                var signal = capture.Image.Rates.AsSpan(i * c, c);
                // A pixel whose signal equals its left neighbour's (a flat patch without noise) gets the same estimate.
                if (i > y * scene.Width && (recover is null || recover[i - 1])
                    && signal.SequenceEqual(capture.Image.Rates.AsSpan((i - 1) * c, c)))
                {
                    cube.AsSpan((i - 1) * n, n).CopyTo(cube.AsSpan(i * n, n));
                    continue;
                }
                estimator.Apply(signal, r);
                for (int b = 0; b < n; b++) cube[i * n + b] = (float)r[b];
            }
        });

        var scheme = scene.Folder.Integration;
        var observer = scene.Observer;
        var d65 = new ReflectanceDifference(new Colorimeter(scene.Grid, observer, SpectrumLibrary.Resolve("D65"), scheme));
        var illA = new ReflectanceDifference(new Colorimeter(scene.Grid, observer, SpectrumLibrary.Resolve("A"), scheme));
        string name = SpectralEstimator.Name(method);

        var (first, bands) = BandsInside(scene.Grid, metricRange);
        (double Rmse, double Gfc, double D65, double A) Score(double[] est, double[] tru) =>
            (SpectralMetrics.Rmse(est.AsSpan(first, bands), tru.AsSpan(first, bands)),
                SpectralMetrics.Gfc(est.AsSpan(first, bands), tru.AsSpan(first, bands)),
             d65.DeltaE00(est, tru), illA.DeltaE00(est, tru));

        // Per pixel, by region.
        var sums = new Dictionary<string, (int N, double R, double G, double D, double A)>();
        void Add(string region, (double R, double G, double D, double A) s)
        {
            sums.TryGetValue(region, out var v);
            sums[region] = (v.N + 1, v.R + s.R, v.G + s.G, v.D + s.D, v.A + s.A);
        }
        var est = new double[n];
        var tru = new double[n];
        var medianCandidates = new Dictionary<string, List<(double Rmse, int Pixel)>>();
        for (int i = 0; i < (regions ? pixels : 0); i++)
        {
            var region = RegionOf(scene, i, whiteMask);
            if (region is PixelRegion.Background or PixelRegion.White) continue;
            for (int b = 0; b < n; b++) { est[b] = cube[i * n + b]; tru[b] = truth.Data[i * n + b]; }
            var s = Score(est, tru);
            var key = Reconstruction.Name(region);
            Add(key, s);
            Add("all", s);
            if (!medianCandidates.TryGetValue(key, out var list)) medianCandidates[key] = list = [];
            list.Add((s.Rmse, i));
        }
        var rows = sums.OrderBy(kv => kv.Key == "all" ? 1 : 0)
            .ThenBy(kv => Enum.TryParse<PixelRegion>(kv.Key, true, out var r) ? (int)r : 99)
            .Select(kv => new RecoveryRow(name, kv.Key, kv.Value.N, kv.Value.R / kv.Value.N, kv.Value.G / kv.Value.N,
                kv.Value.D / kv.Value.N, kv.Value.A / kv.Value.N))
            .ToList();

        var examples = new List<(string, double[], double[])>();
        if (scene.Patches.Count > 0)
        {
            double sr = 0, sg = 0, sd = 0, sa = 0;
            foreach (var p in scene.Patches)
            {
                var (me, mt) = PatchMeans(p, cube, truth.Data, n);
                var s = Score(me, mt);
                sr += s.Rmse; sg += s.Gfc; sd += s.D65; sa += s.A;
                if (p.Number is 2 or 13 or 14 or 15 or 16) examples.Add(($"patch {p.Number} {ColorChecker.Name(p.Number)}", me, mt));
            }
            int np = scene.Patches.Count;
            rows.Add(new RecoveryRow(name, "colorchecker", np, sr / np, sg / np, sd / np, sa / np));
        }
        else
        {
            foreach (var (key, list) in medianCandidates.OrderBy(kv => kv.Key))
            {
                list.Sort((x, y) => x.Rmse.CompareTo(y.Rmse));
                int i = list[list.Count / 2].Pixel;
                examples.Add(($"{key} ({i % scene.Width},{i / scene.Width})",
                    Enumerable.Range(0, n).Select(b => (double)cube[i * n + b]).ToArray(),
                        Enumerable.Range(0, n).Select(b => (double)truth.Data[i * n + b]).ToArray()));
            }
        }
        return new RecoveryResult(method, estimator, cube, rows, examples, whiteDescription);
    }

    /// <summary>
    /// The ColorChecker scored from each patch's mean signal, as a camera is characterised (average the patch, then
    /// estimate): per patch one estimate from the mean of its pixels' signals, against the mean of its true spectra;
    /// the mean over the patches of the RMSE over all bands and over the bands inside <paramref name="range"/>, and of
    /// ΔE00 under D65. For the affine methods (pinv, wiener, linear, tikhonov) the estimate of the mean signal is the mean
    /// of the pixels' estimates, so this is <see cref="Run"/>'s "colorchecker" row up to rounding, from 24 estimates
    /// instead of every patch pixel's; for wiener-local (nonlinear in the signal) it is the estimate of the patch's signal.
    /// </summary>
    public static (double RmseAllBands, double RmseInRange, double DeltaE00D65) PatchMeanSignals(CameraCapture capture,
        SpectralEstimator estimator, (double Lo, double Hi) range)
    {
        var scene = capture.Scene;
        var truth = scene.Aovs.Reflectance
            ?? throw new InputException(scene.Folder.Path, "has no ground-truth reflectance (reflectance.exr)",
                "render with --formats including aov");
        if (scene.Patches.Count == 0)
            throw new InputException(scene.Folder.Path, "shows no ColorChecker patches",
                "render the §3.1 chart (scenes/paper-3.1-colorchecker-d65.json)");
        int c = capture.Sensor.ChannelCount, n = scene.Grid.Count;
        var d65 = new ReflectanceDifference(
            new Colorimeter(scene.Grid, scene.Observer, SpectrumLibrary.Resolve("D65"), scene.Folder.Integration));
        var (first, bands) = BandsInside(scene.Grid, range);
        var mean = new double[c];
        var signal = new float[c];
        var est = new double[n];
        double all = 0, inRange = 0, de = 0;
        foreach (var p in scene.Patches)
        {
            Array.Clear(mean);
            foreach (int i in p.Pixels) for (int k = 0; k < c; k++) mean[k] += capture.Image.Rates[i * c + k];
            for (int k = 0; k < c; k++) signal[k] = (float)(mean[k] / p.Pixels.Length);
            estimator.Apply(signal, est);
            var tru = PatchMean(p, truth.Data, n);
            all += SpectralMetrics.Rmse(est, tru);
            inRange += SpectralMetrics.Rmse(est.AsSpan(first, bands), tru.AsSpan(first, bands));
            de += d65.DeltaE00(est, tru);
        }
        int np = scene.Patches.Count;
        return (all / np, inRange / np, de / np);
    }

    /// <summary>A cube's mean spectrum over a patch's pixels.</summary>
    static double[] PatchMean(ChartPatch p, float[] cube, int n)
    {
        var m = new double[n];
        foreach (int i in p.Pixels) for (int b = 0; b < n; b++) m[b] += cube[i * n + b];
        for (int b = 0; b < n; b++) m[b] /= p.Pixels.Length;
        return m;
    }

    /// <summary>A patch's mean recovered and mean true spectrum over its pixels.</summary>
    static (double[] Recovered, double[] Truth) PatchMeans(ChartPatch p, float[] cube, float[] truth, int n)
    {
        var (me, mt) = (new double[n], new double[n]);
        foreach (int i in p.Pixels) for (int b = 0; b < n; b++) { me[b] += cube[i * n + b]; mt[b] += truth[i * n + b]; }
        for (int b = 0; b < n; b++) { me[b] /= p.Pixels.Length; mt[b] /= p.Pixels.Length; }
        return (me, mt);
    }

    /// <summary>
    /// The mean ColorChecker RMSE of a recovered cube (<see cref="RecoveryResult.Reflectance"/>) over the bands inside
    /// <paramref name="range"/>: each patch's mean recovered spectrum against its mean truth, as the "colorchecker" row of
    /// <see cref="Run"/> with that metric range scores it — another range from the same recovery.
    /// </summary>
    public static double PatchRmse(CameraScene scene, float[] cube, (double Lo, double Hi)? range)
    {
        var truth = scene.Aovs.Reflectance
            ?? throw new InputException(scene.Folder.Path, "has no ground-truth reflectance (reflectance.exr)",
                "render with --formats including aov");
        int n = scene.Grid.Count;
        var (first, bands) = BandsInside(scene.Grid, range);
        double sr = 0;
        foreach (var p in scene.Patches)
        {
            var (me, mt) = PatchMeans(p, cube, truth.Data, n);
            sr += SpectralMetrics.Rmse(me.AsSpan(first, bands), mt.AsSpan(first, bands));
        }
        return sr / scene.Patches.Count;
    }

    /// <summary>The first band and the number of bands lying wholly inside [lo, hi] (all bands without a range).</summary>
    public static (int First, int Count) BandsInside(BandGrid grid, (double Lo, double Hi)? range)
    {
        if (range is null) return (0, grid.Count);
        var (lo, hi) = range.Value;
        var inside = Enumerable.Range(0, grid.Count).Where(b => grid.Lower(b) >= lo - 1e-9 && grid.Upper(b) <= hi + 1e-9).ToList();
        if (inside.Count == 0) throw new InputException("--range", $"no band of {grid} lies inside {lo}–{hi} nm", "e.g. --range 400:700");
        return (inside[0], inside.Count);
    }

    /// <summary>The §3.4 regions (<see cref="PixelRegion"/>) from the render's masks.</summary>
    public static PixelRegion RegionOf(CameraScene scene, int i, bool[]? whiteMask)
    {
        if (scene.Folder.ObjectIds[i] < 0) return PixelRegion.Background;
        if (whiteMask is not null && whiteMask[i]) return PixelRegion.White;
        var aovs = scene.Aovs;
        if (!aovs.HasMasks) return PixelRegion.Unclassified;
        if (aovs.Highlight![i]) return PixelRegion.Highlight;
        int lit = aovs.Lit!.Count(m => m[i]);
        return lit == aovs.Lit!.Length ? PixelRegion.Lit : lit == 0 ? PixelRegion.Shadow : PixelRegion.Partial;
    }
}
