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
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Relighting;

/// <summary>
/// The camera's exact route (issue 24): a render's pixel is L = Σ_c F_c · E_k·m·Π k_chain over its eq. 2 components
/// (<see cref="ITermRoute"/>: a geometric factor F per pixel × a light spectrum × a material spectrum), so a channel's
/// signal is Σ_c F_c · s_c · Π k · Σ η(λ)·λ·E_k(λ)·m(λ) — the same per-term scalar × precomputed table that gives
/// the render its exact colour (<see cref="TermTables"/>), with the channel's η·λ/(hc) in place of x̄, summed by the same
/// rule (CIE 015's 1 nm sum, <see cref="ChannelWeights.ExactIntegral"/>). The factors come from the render's lights/
/// when it wrote them, else the transfer is traced again from the resolved scene (the same rays the render traced).
/// A component whose chain passes a coloured mirror or glass, a dispersive split, or a spectrum known only by its band
/// values takes the band route for itself (its band values × the channel weights), and the manifest counts them.
/// A path render has no eq. 2 terms; its channels are integrated from its sub-band grid (ExactChannelSignals.Path.cs).
/// Which route a render takes is its integrator's capability (<see cref="TransferFormat.Route"/>), not its name.
/// </summary>
public static partial class ExactChannelSignals
{
    /// <summary>
    /// The integrals (H × W × C), the white's radiance per unit of the reference white's band values (light scale × 1/π
    /// physical × the chart's geometric factor), and the route in words.
    /// </summary>
    public sealed record Result(float[] Integrals, double WhiteScale, string Route, string WhiteScaleSource, bool OpticsApplied);

    /// <summary>The camera's input on the exact route, or null (the band cube) when the folder cannot give it (the report's camera
    /// comparison).</summary>
    public static (RadianceCube Cube, double WhiteScale)? Input(CameraScene cs, SensorModel sensor) =>
        Compute(cs, sensor, -1, out _) is { } r
            ? (cs.Cube(1) with { ChannelIntegrals = r.Integrals, Route = r.Route, OpticsApplied = r.OpticsApplied }, r.WhiteScale)
            : null;

    /// <summary>The exact route for <paramref name="cs"/>'s render, or null (with the reason) when the folder cannot give it.</summary>
    public static Result? Compute(CameraScene cs, SensorModel sensor, int threads, out string reason)
    {
        Relighter.Source src;
        try { src = Relighter.Open(cs.Folder.Path); }
        catch (InputException e) { reason = $"the render folder cannot be rebuilt ({e.Message})"; return null; }
        // A path render's light is every bounce of the rendering equation, not eq. 2's terms: its sub-band grid is integrated instead.
        if (RouteOf(src) == CameraRoute.SubBandFilm) return PathRoute(cs, sensor, src, threads, out reason);
        return Transfer(src, threads, out var scene, out var transfer, out var from, out reason)
            ? Compute(cs, sensor, scene, transfer, from, threads, out reason) : null;
    }

    /// <summary>
    /// The white scale of a capture on the band route (<c>--signals bands</c>, or when the exact route cannot be had) of a
    /// render folder: the one the exact route uses — the lights' direct diffuse factor over the chart × their intensity
    /// (/π physical) for a Whitted render, the chart read off the picture for a path render — so white balance, colour
    /// correction and recovery see the render's radiometry on either route. Null when the folder is not a render (a cube
    /// from elsewhere: the light's band values, 1).
    /// </summary>
    public static (double Scale, string Source)? BandRouteWhite(CameraScene cs, int threads)
    {
        Relighter.Source src;
        try { src = Relighter.Open(cs.Folder.Path); }
        catch (InputException) { return LightsRoute(cs.Folder.Path) == CameraRoute.SubBandFilm ? PathWhite(cs) : null; }
        if (RouteOf(src) == CameraRoute.SubBandFilm) return PathWhite(cs);
        if (!Transfer(src, threads, out var scene, out var transfer, out _, out _)
            || transfer.Width != cs.Width || transfer.Height != cs.Height) return null;
        return WhiteScale(cs, scene, transfer, scene.Radiometry == Radiometry.Physical);
    }

    /// <summary>A render's scene and its eq. 2 terms: its lights/ when written, else traced again (the render's rays).</summary>
    static bool Transfer(Relighter.Source src, int threads, out Scene scene, out ITermRoute transfer, out string from, out string reason)
    {
        string dir = src.Dir;
        scene = null!; transfer = null!; from = "";
        try
        {
            bool written = File.Exists(Path.Combine(dir, TransferFormat.Folder, TransferFormat.Description));
            scene = written ? Relighter.ChangedScene(src, [], null)
                : SceneLoader.Parse(src.Scene.WithLights([], null), src.ScenePath, src.Overrides with { LoadMeshes = true });
            if (!HasTermTransfer(src, out reason)) return false;
            if (written)
            {
                transfer = (ITermRoute)TransferFiles.Read(dir, scene);   // its format's route is Terms
                from = "the render's lights/ (per-pixel factors of each eq. 2 term)";
            }
            else
            {
                if (Integrators.Create(scene, new SceneGeometry(scene), IntegratorOf(src)) is not ITransferIntegrator integrator
                    || integrator.TraceTransfer(scene, threads < 0 ? 0 : threads, default, null) is not ITermRoute terms)
                {
                    reason = $"the render's {IntegratorOf(src)} integrator records no eq. 2 terms";
                    return false;
                }
                transfer = terms;
                from = "the per-light transfer traced again from render.json's resolved scene (the render's rays)";
            }
        }
        catch (InputException e) { reason = $"the render's scene cannot be rebuilt for its eq. 2 terms ({e.Message})"; return false; }
        return true;
    }

    /// <summary>
    /// The exact route a render folder gives: its lights/' format's when it wrote them, else its integrator's (the command
    /// line's run.integrator, else the resolved scene's, else the default) transfer format's.
    /// </summary>
    static CameraRoute RouteOf(Relighter.Source src) => LightsRoute(src.Dir) is var written && written != CameraRoute.None
        ? written
        : Integrators.Entry(IntegratorOf(src))?.Transfer?.Route ?? CameraRoute.None;

    /// <summary>The route of the transfer in <paramref name="dir"/>/lights/, None without one (or one no integrator writes).</summary>
    static CameraRoute LightsRoute(string dir)
    {
        try { return TransferFiles.FormatOf(dir)?.Route ?? CameraRoute.None; }
        catch (InputException) { return CameraRoute.None; }
    }

    /// <summary>
    /// The integrator a render ran: render.json's run.integrator, else its resolved scene's (lower case, as the loader reads
    /// it), else the default.
    /// </summary>
    static string IntegratorOf(Relighter.Source src) => src.Manifest.Run?.Integrator ?? (src.Scene.ToJson()["integrator"] is { } i
        ? ((i as System.Text.Json.Nodes.JsonValue)?.ToString() ?? (string?)i["type"])?.ToLowerInvariant() : null) ?? Integrators.Default;

    /// <summary>
    /// Whether the render is a sum of eq. 2 terms whose per-light transfer the exact route can use (its integrator's
    /// transfer gives <see cref="CameraRoute.Terms"/>: the Whitted model's). A path-traced render is not (its light bounces
    /// between surfaces): its sub-band grid is integrated instead (<see cref="PathRoute"/>).
    /// </summary>
    static bool HasTermTransfer(Relighter.Source src, out string reason)
    {
        string name = IntegratorOf(src);
        bool terms = RouteOf(src) == CameraRoute.Terms;
        reason = terms ? "" : $"the render's {name} integrator has no per-term light transfer (that is the {Integrators.Default} model's)";
        return terms;
    }

    /// <summary>
    /// The exact route from a scene and its per-light transfer (<paramref name="from"/> says where it came from: a folder's
    /// lights/, traced again, or a render held in memory), or null (with the reason) when they do not match the cube.
    /// </summary>
    public static Result? Compute(CameraScene cs, SensorModel sensor, Scene scene, ITermRoute transfer, string from, int threads,
        out string reason)
    {
        if (transfer.Width != cs.Width || transfer.Height != cs.Height || transfer.Bands != cs.Grid.Count)
        {
            reason = $"the rebuilt scene is {transfer.Width}×{transfer.Height}×{transfer.Bands}, the cube "
                + $"{cs.Width}×{cs.Height}×{cs.Grid.Count} (a crop or shard)";
            return null;
        }

        int cc = sensor.ChannelCount, n = cs.Width * cs.Height;
        var tables = new TermTables(scene, TexelContent.None);
        var bandWeights = ChannelWeights.Compute(sensor, scene.Grid, cs.Light, 1);
        bool physical = scene.Radiometry == Radiometry.Physical;
        // With the lens's optics (cos⁴, the Airy blur per band) each band's share of the integrals goes through them on
        // its own — the integral over a band is exact there too, and the bands' shares sum to the whole range's.
        var optics = Optics.For(sensor, cs.Width, cs.Height, cs.FovDegrees, scene.Grid);
        int parts = optics.Any ? scene.Bands : 1;
        var padded = new float[scene.PaddedBands];
        var perComponent = new double[transfer.Components.Length][];
        // A textured term (issue 26): per part, channel and texture sample i the integral with the sample's tent function as m,
        // summed at each entry with its recorded texel samples V_i (Σ F × the filtered texel); perComponent then holds the
        // part the same at every texel (a fluorescent shift), per unit F.
        var perSample = new double[transfer.Components.Length][];
        int bandRoute = 0;
        for (int k = 0; k < perComponent.Length; k++)
        {
            var comp = transfer.Components[k];
            var t = perComponent[k] = new double[parts * cc];
            if (transfer.Texels?[k] is not null && comp.Texture(scene) is { } texture)
            {
                if (!TexturedIntegrals(sensor, scene, tables, comp, texture, physical, parts, bandWeights, t, out perSample[k]))
                    bandRoute++;
                continue;
            }
            var (e, m, factor) = Term(scene, comp, physical);
            double chain = 1;
            bool exact = comp.Band < 0 && !comp.Coloured(tables) && e is not null && scene.Spectra.TryGetValue(e, out _)
                && (m is null || scene.Spectra.TryGetValue(m, out _));
            if (exact) foreach (var (cm, tr) in comp.Chain) chain *= (tr ? tables.Transmit[cm] : tables.Mirror[cm])[0];
            if (exact && SpectralMath.Any(e!) && (m is null || SpectralMath.Any(m)))
            {
                var se = scene.Spectra[e!];
                var sm = m is null ? null : scene.Spectra[m];
                // A fluorescent material's diffuse term is its re-radiation matrix applied to the light: the shifted part too.
                var shifted = comp.Lobe == TransferLobe.Diffuse && scene.Materials[comp.Material].Fluorescence is { HasShift: true } fl
                    ? (Matrix: fl, Cells: fl.ShiftedCells(se.Integrate, scene.Grid.Start, scene.Grid.End)) : default;
                for (int part = 0; part < parts; part++)
                {
                    double lo =
                        parts == 1 ? scene.Grid.Start : scene.Grid.Lower(part), hi = parts == 1 ? scene.Grid.End : scene.Grid.Upper(part);
                    for (int c = 0; c < cc; c++)
                    {
                        double v = ChannelWeights.ExactIntegral(sensor.Channels[c], se, sm, lo, hi);
                        if (shifted.Matrix is { } matrix) v += ShiftIntegral(sensor.Channels[c], matrix, shifted.Cells, lo, hi);
                        t[part * cc + c] = factor * chain * v;
                    }
                }
            }
            else if (!exact)
            {   // Band route for this component: Σ_b P_b · w_c,b / (the weights' constant), in the exact integrals' units.
                bandRoute++;
                comp.BandValues(tables, padded);
                for (int c = 0; c < cc; c++)
                    for (int b = 0; b < scene.Bands; b++)
                        t[(parts == 1 ? 0 : b) * cc + c] += padded[b] * bandWeights[c, b] / bandWeights.Factor;
            }
        }
        // Σ_c F_c · T_c per pixel, in doubles, one pixel range per task (components' pixels ascend); per band through the optics.
        var sum = new double[(long)n * cc];
        var share = optics.Any ? new double[(long)n * cc] : sum;
        var plane = optics.Any ? new float[n * cc] : null;
        // A mosaic reads one channel per pixel: only that one is blurred.
        int[]? planeOf = sensor.Arrangement == Arrangement.Mosaic
            ? Enumerable.Range(0, n).Select(i => sensor.ChannelAt(i % cs.Width, i / cs.Width)).ToArray()
            : null;
        var parallel = new ParallelOptions { MaxDegreeOfParallelism = threads };
        const int Chunk = 8192;
        for (int part = 0; part < parts; part++)
        {
            if (optics.Any) Array.Clear(share);
            Parallel.For(0, (n + Chunk - 1) / Chunk, parallel, chunk =>
            {
                int i0 = chunk * Chunk, i1 = Math.Min(n, i0 + Chunk);
                for (int k = 0; k < perComponent.Length; k++)
                {
                    var pix = transfer.Pixels[k];
                    var f = transfer.Factors[k];
                    var t = perComponent[k].AsSpan(part * cc, cc);
                    int j = Array.BinarySearch(pix, i0);
                    if (j < 0) j = ~j;
                    if (perSample[k] is { } ps)
                    {
                        var texels = transfer.Texels![k]!;
                        int samples = ps.Length / (parts * cc);
                        for (; j < pix.Length && pix[j] < i1; j++)
                        {
                            var v = texels.AsSpan(j * samples, samples);
                            for (int c = 0; c < cc; c++)
                            {
                                double sum = f[j] * t[c];
                                var row = ps.AsSpan((part * cc + c) * samples, samples);
                                for (int i = 0; i < samples; i++) sum += v[i] * row[i];
                                share[(long)pix[j] * cc + c] += sum;
                            }
                        }
                        continue;
                    }
                    for (; j < pix.Length && pix[j] < i1; j++)
                        for (int c = 0; c < cc; c++) share[(long)pix[j] * cc + c] += f[j] * t[c];
                }
            });
            if (plane is null) continue;
            for (int i = 0; i < plane.Length; i++) plane[i] = (float)share[i];
            Optics.Apply(plane, cs.Width, cs.Height, cc, optics.Illumination, optics.Kernels is { } ks ? [ks[part]] : null, threads,
                planeOf);
            for (int i = 0; i < plane.Length; i++) sum[i] += plane[i];
        }
        var integrals = GC.AllocateUninitializedArray<float>(sum.Length);
        for (long i = 0; i < sum.Length; i++) integrals[i] = (float)sum[i];

        var (whiteScale, whiteSource) = WhiteScale(cs, scene, transfer, physical);
        var inv = CultureInfo.InvariantCulture;
        reason = "";
        string route = $"exact: rate_c = sum over eq. 2 terms of F * s * integral(eta_c * lambda/(h c) * E_k * "
            + $"m) at full spectral resolution, " +
            $"{transfer.Components.Length} components from {from}" +
            (bandRoute > 0
                ? string.Create(inv,
                    $"; {bandRoute} components (coloured mirror/glass chain, dispersion or band-valued spectra) by their band values")
                : "") +
            (optics.Any
                ? "; each band's share through the lens (cos4th fall-off, Airy blur at the band centre) before the bands are summed"
                : "");
        return new Result(integrals, whiteScale, route, whiteSource, optics.Any);
    }

    /// <summary>The light spectrum, material spectrum (null: none) and constant factor of a component's term, as <see cref="TermTables"/>
    /// forms it.</summary>
    /// <summary>
    /// ∫_lo^hi η_c(λ)·λ·L_s(λ) dλ of a fluorescent term's shifted emission L_s, constant over each of the matrix's emission
    /// cells (<see cref="ReradiationMatrix.ShiftedCells"/>, as the render's exact colour takes it: <see cref="FluorescentTerms"/>;
    /// <see cref="ChannelWeights.BoxIntegral"/>).
    /// </summary>
    static double ShiftIntegral(SensorChannel channel, ReradiationMatrix matrix, double[] cells, double lo, double hi)
    {
        double sum = 0;
        for (int o = 0; o < cells.Length; o++)
        {
            double a = Math.Max(lo, matrix.CellLower(o)), b = Math.Min(hi, matrix.CellUpper(o));
            if (b > a && cells[o] != 0) sum += cells[o] * ChannelWeights.BoxIntegral(channel, a, b);
        }
        return sum;
    }

    /// <summary>
    /// A textured component's integrals: per part, channel and texture sample i, F-free, ∫ η_c·λ/(hc)·E·tent_i dλ × the lobe's
    /// constant × the chain's weight (<paramref name="perSample"/>, [part, channel, sample]), and into <paramref name="constant"/>
    /// a fluorescent diffuse term's shift per unit F. False when it takes the band route (a coloured chain, a dispersive
    /// split or a light known only by its band values): then the texel columns' band values × the channel weights.
    /// </summary>
    static bool TexturedIntegrals(SensorModel sensor, Scene scene, TermTables tables, TransferComponent comp,
        Scenes.Textures.SpectralTexture texture, bool physical, int parts, ChannelWeights bandWeights, double[] constant,
        out double[] perSample)
    {
        int cc = sensor.ChannelCount, samples = texture.Samples;
        perSample = new double[parts * cc * samples];
        var (e, _, factor) = Term(scene, comp, physical);
        bool exact = comp.Band < 0 && !comp.Coloured(tables) && e is not null && scene.Spectra.TryGetValue(e, out _);
        if (!exact)
        {
            var columns = comp.TexelColumns(scene, tables, out var shift)!;
            int padded = scene.PaddedBands;
            for (int c = 0; c < cc; c++)
                for (int b = 0; b < scene.Bands; b++)
                {
                    double w = bandWeights[c, b] / bandWeights.Factor;
                    int part = parts == 1 ? 0 : b;
                    constant[part * cc + c] += shift[b] * w;
                    for (int i = 0; i < samples; i++) perSample[(part * cc + c) * samples + i] += columns[i * padded + b] * w;
                }
            return false;
        }
        if (!SpectralMath.Any(e!)) return true;
        double chain = 1;
        foreach (var (cm, tr) in comp.Chain) chain *= (tr ? tables.Transmit[cm] : tables.Mirror[cm])[0];
        var se = scene.Spectra[e!];
        var hats = TexturedTerms.Hats(texture);
        var mat = scene.Materials[comp.Material];
        var shifted = comp.Lobe == TransferLobe.Diffuse && mat.Fluorescence is { HasShift: true } fl
            ? (Matrix: fl, Cells: fl.ShiftedCells(se.Integrate, scene.Grid.Start, scene.Grid.End)) : default;
        for (int part = 0; part < parts; part++)
        {
            double lo = parts == 1 ? scene.Grid.Start : scene.Grid.Lower(part), hi = parts == 1 ? scene.Grid.End : scene.Grid.Upper(part);
            for (int c = 0; c < cc; c++)
            {
                for (int i = 0; i < samples; i++)
                    perSample[(part * cc + c) * samples + i] =
                        factor * chain * ChannelWeights.ExactIntegral(sensor.Channels[c], se, hats[i], lo, hi);
                if (shifted.Matrix is { } matrix)
                    constant[part * cc + c] = factor * chain * ShiftIntegral(sensor.Channels[c], matrix, shifted.Cells, lo, hi);
            }
        }
        return true;
    }

    static (float[]? E, float[]? M, double Factor) Term(Scene scene, TransferComponent comp, bool physical)
    {
        var mat = comp.Material >= 0 ? scene.Materials[comp.Material] : null;
        return comp.Lobe switch
        {
            TransferLobe.Diffuse => (scene.Lights[comp.Light].Intensity, mat!.Diffuse, physical ? 1 / Math.PI : 1),
            TransferLobe.Specular =>
                (scene.Lights[comp.Light].Intensity, mat!.Specular, physical ? mat.Model.EnergyNormalisation(mat.Shininess) : 1),
            TransferLobe.Ambient => (scene.Lights[comp.Light].Ambient, mat!.Ambient, 1),
            TransferLobe.GlobalAmbient => (scene.GlobalAmbient, mat!.Ambient, 1),
            _ => (scene.Background, null, 1),
        };
    }

    /// <summary>
    /// The radiance of a perfect white diffuser where the render's chart is (else at the best-lit surface), per unit of the
    /// reference white's band values: Σ_k F̄_k · intensity_k (× 1/π physical), with F̄_k the mean direct diffuse factor of
    /// light k over the chart's patch pixels (the maximum over the image without a chart). A light whose spectrum is not
    /// the reference white counts by its band sum relative to the white's.
    /// </summary>
    static (double Scale, string Source) WhiteScale(CameraScene cs, Scene scene, ITermRoute transfer, bool physical)
    {
        int lights = scene.Lights.Count;
        var chart = new bool[cs.Width * cs.Height];
        int chartPixels = 0;
        foreach (var p in cs.Patches) foreach (int i in p.Pixels) { chart[i] = true; chartPixels++; }
        var mean = new double[lights];
        var max = new double[lights];
        for (int k = 0; k < transfer.Components.Length; k++)
        {
            var comp = transfer.Components[k];
            if (comp.Lobe != TransferLobe.Diffuse || comp.Chain.Length > 0 || comp.Band >= 0) continue;
            var pix = transfer.Pixels[k];
            var f = transfer.Factors[k];
            for (int j = 0; j < pix.Length; j++)
            {
                if (chart[pix[j]]) mean[comp.Light] += f[j];
                max[comp.Light] = Math.Max(max[comp.Light], f[j]);
            }
        }
        var white = BandProjection.Means(cs.Light, scene.Grid);
        double whiteSum = white.Sum(), scale = 0;
        for (int l = 0; l < lights; l++)
        {
            var light = scene.Lights[l];
            double level = light.Spectrum is { } s && s.Name == cs.Light.Name ? light.Scale
                : whiteSum > 0 ? light.Intensity.AsSpan(0, scene.Bands).ToArray().Sum(v => (double)v) / whiteSum : 0;
            scale += (chartPixels > 0 ? mean[l] / chartPixels : max[l]) * level;
        }
        if (physical) scale /= Math.PI;
        if (!(scale > 0)) return (1, "1: no light reaches a diffuse surface directly");
        return (scale,
            (chartPixels > 0
                ? "the lights' direct diffuse factor over the ColorChecker patches"
                : "the lights' largest direct diffuse factor in the image")
            + " × their intensity" + (physical ? " / π (physical radiometry)" : ""));
    }
}
