using System.Globalization;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Relighting;

public static partial class ExactChannelSignals
{
    /// <summary>
    /// The exact route of a path render (issue 24): its radiance is carried on the sub-band grid (<see cref="SubBandFilm"/>:
    /// exact sub-band means, 5 nm by default), which the film reduces to output bands and integrates into XYZ as
    /// X = Σ_f L_f·κ∫_f x̄ dλ. A channel is integrated the same way, rate_c = Σ_f L_f · ∫_f η_c(λ)·λ dλ (× the sensor's
    /// étendue/(hc)), each ∫_f at the sensitivity's full resolution (<see cref="ChannelWeights.BoxIntegral"/>), so the
    /// signals depend on the sub-band grid and the samples but not on the output band count. The sub-band film comes from the
    /// render's lights/ when it wrote a path transfer (no rays), else its camera samples are traced again (the same paths:
    /// the render's time once more, and 4 bytes per pixel and sub-band).
    /// </summary>
    static Result? PathRoute(CameraScene cs, SensorModel sensor, Relighter.Source src, int threads, out string reason)
    {
        Scene scene;
        SubBandFilm film;
        string from;
        try
        {
            if (LightsRoute(src.Dir) == CameraRoute.SubBandFilm)
            {
                scene = Relighter.ChangedScene(src, [], null);
                var transfer = (ISubBandFilmRoute)TransferFiles.Read(src.Dir, scene);   // its format's route is SubBandFilm
                film = transfer.Film(scene);
                from = $"the render's lights/ ({transfer.FilmMethod})";
            }
            else
            {
                scene = SceneLoader.Parse(src.Scene.WithLights([], null), src.ScenePath, src.Overrides with { LoadMeshes = true });
                if (scene.TargetError > 0)
                {   // Adaptive sampling stopped each pixel at its own sample count, which a trace with spp samples does not repeat.
                    reason = "the path render sampled adaptively (target_error): its pixels' samples cannot be traced again; render with "
                        + "the lights output for the exact route";
                    return null;
                }
                if (scene.Camera.Width != cs.Width || scene.Camera.Height != cs.Height)
                {
                    reason = $"the rebuilt scene is {scene.Camera.Width}×{scene.Camera.Height}, the cube "
                        + $"{cs.Width}×{cs.Height} (a crop or shard)";
                    return null;
                }
                if (Integrators.Create(scene, new SceneGeometry(scene), IntegratorOf(src)) is not ISubBandFilmIntegrator integrator)
                {
                    reason = $"the render's {IntegratorOf(src)} integrator cannot trace its film on a fine grid";
                    return null;
                }
                if (FilmTooLarge(scene, integrator.FilmSubBands, sensor) is { } why) { reason = why; return null; }
                var clock = System.Diagnostics.Stopwatch.StartNew();
                film = integrator.TraceSubBandFilm(scene, threads < 0 ? 0 : threads);
                from = string.Create(CultureInfo.InvariantCulture,
                    $"the render's camera samples traced again from render.json's resolved scene (the same paths, "
                        + $"{clock.Elapsed.TotalSeconds:F1} s)");
            }
        }
        catch (InputException e) { reason = $"the path render's scene cannot be rebuilt for its fine grid ({e.Message})"; return null; }
        return Compute(cs, sensor, scene, film, from, threads, out reason);
    }

    /// <summary>
    /// The exact route of a path render from its sub-band film (<paramref name="from"/> says where the film came from: a folder's
    /// lights/, traced again, or a render held in memory), or null (with the reason) when it does not match the cube.
    /// </summary>
    public static Result? Compute(CameraScene cs, SensorModel sensor, Scene scene, SubBandFilm film, string from, int threads,
        out string reason)
    {
        if (film.Width != cs.Width || film.Height != cs.Height || film.BandStart.Length != cs.Grid.Count + 1
            || film.BandStart[^1] != film.SubBands)
        {
            reason = $"the fine film is {film.Width}×{film.Height}×{film.SubBands} sub-bands, the cube "
                + $"{cs.Width}×{cs.Height}×{cs.Grid.Count} bands (a crop or shard)";
            return null;
        }

        int cc = sensor.ChannelCount, n = cs.Width * cs.Height, sub = film.SubBands, per = film.PerBand;
        // ∫_f η_c(λ)·λ dλ per channel and sub-band, at the sensitivity's full resolution.
        var g = new double[cc * sub];
        for (int c = 0; c < cc; c++)
            for (int f = 0; f < sub; f++)
                g[c * sub + f] = ChannelWeights.BoxIntegral(sensor.Channels[c], film.Lower[f], film.Upper[f]);
        // With the lens's optics each output band's share (its sub-bands) goes through them on its own, as on the Whitted route.
        var optics = Optics.For(sensor, cs.Width, cs.Height, cs.FovDegrees, scene.Grid);
        int parts = optics.Any ? scene.Bands : 1;
        int[]? planeOf = sensor.Arrangement == Arrangement.Mosaic
            ? Enumerable.Range(0, n).Select(i => sensor.ChannelAt(i % cs.Width, i / cs.Width)).ToArray()
            : null;
        var sum = optics.Any ? new double[(long)n * cc] : null;
        var plane = new float[n * cc];
        var data = film.Data;
        var parallel = new ParallelOptions { MaxDegreeOfParallelism = threads };
        for (int part = 0; part < parts; part++)
        {
            int f0 = parts == 1 ? 0 : film.BandStart[part], f1 = parts == 1 ? sub : film.BandStart[part + 1];
            Parallel.For(0, cs.Height, parallel, y =>
            {
                for (int i = y * cs.Width; i < (y + 1) * cs.Width; i++)
                {
                    var l = data.AsSpan(i * sub, sub);
                    for (int c = 0; c < cc; c++)
                    {
                        var gc = g.AsSpan(c * sub, sub);
                        double v = 0;
                        for (int f = f0; f < f1; f++) v += l[f] * gc[f];
                        plane[i * cc + c] = (float)v;
                    }
                }
            });
            if (sum is null) continue;
            Optics.Apply(plane, cs.Width, cs.Height, cc, optics.Illumination, optics.Kernels is { } ks ? [ks[part]] : null, threads,
                planeOf);
            for (int i = 0; i < plane.Length; i++) sum[i] += plane[i];
        }
        if (sum is not null) for (int i = 0; i < plane.Length; i++) plane[i] = (float)sum[i];

        var (whiteScale, whiteSource) = PathWhite(cs);
        reason = "";
        string width = (film.Upper[0] - film.Lower[0]).ToString("0.###", CultureInfo.InvariantCulture);
        string route = "exact (path): rate_c = sum over the fine grid's sub-bands f of L_f * integral_f(eta_c * lambda/(h c)) at the "
            + "sensitivity's full resolution, " +
            (per > 0 ? $"{sub} sub-bands of {width} nm ({per} per band)" : $"{sub} sub-bands, adaptive ({Widths(film)})")
            + $" from {from}" +
            (optics.Any
                ? "; each band's share through the lens (cos4th fall-off, Airy blur at the band centre) before the bands are summed"
                : "");
        return new Result(plane, whiteScale, route, whiteSource, optics.Any);
    }

    /// <summary>An adaptive grid's sub-band widths, run by run: "1 nm × 40, 10 nm × 8, …".</summary>
    static string Widths(SubBandFilm film)
    {
        var runs = new List<(double Width, int Count)>();
        for (int f = 0; f < film.SubBands; f++)
        {
            double w = Math.Round(film.Upper[f] - film.Lower[f], 3);
            if (runs.Count > 0 && runs[^1].Width == w) runs[^1] = (w, runs[^1].Count + 1);
            else runs.Add((w, 1));
        }
        return string.Join(", ", runs.Select(r => string.Create(CultureInfo.InvariantCulture, $"{r.Width:0.###} nm × {r.Count}")));
    }

    /// <summary>
    /// Why the sub-band film (4 bytes per pixel and sub-band) and the channel sums (12 bytes per pixel and channel) do not fit
    /// in what this process may still use (the GC's available memory less what is in use, a tenth kept back), else null.
    /// </summary>
    static string? FilmTooLarge(Scene scene, int subBands, SensorModel sensor)
    {
        long need = SubBandFilm.Bytes(scene.Camera.Width, scene.Camera.Height, subBands)
            + 12L * scene.Camera.Width * scene.Camera.Height * sensor.ChannelCount;
        long usable = (long)(0.9 * GC.GetGCMemoryInfo().TotalAvailableMemoryBytes) - GC.GetTotalMemory(false);
        return need <= usable ? null
            : $"the path render's fine film needs about {InputFile.Size(need)}, more than the {InputFile.Size(Math.Max(0, usable))} this "
                + $"process has left; a coarser \"spectral_grid\" or fewer pixels, or --signals bands";
    }

    /// <summary>
    /// The band route's white of a render held in memory (libspectral): a path render's read off its chart, a Whitted
    /// render's from its per-light transfer, as <see cref="BandRouteWhite(CameraScene, int)"/> takes a folder's.
    /// </summary>
    public static (double Scale, string Source)? BandRouteWhite(CameraScene cs, Scene scene, ITermRoute? transfer, bool path) =>
        path ? PathWhite(cs)
        : transfer is not null && transfer.Width == cs.Width && transfer.Height == cs.Height
            ? WhiteScale(cs, scene, transfer, scene.Radiometry == Radiometry.Physical)
        : null;

    /// <summary>A path render's white: read off its ColorChecker (<see cref="ChartWhite"/>), its light at the chart being every
    /// bounce.</summary>
    static (double Scale, string Source) PathWhite(CameraScene cs) => ChartWhite.Scale(cs) is { } s
        ? (s,
            "the ColorChecker in the render: its patches' band values against the light's × their reflectances "
                + "(least squares; a path render)")
        : (1, "1: the light's band values (a path render without a ColorChecker to read its white off)");
}
