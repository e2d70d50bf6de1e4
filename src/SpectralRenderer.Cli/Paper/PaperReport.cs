using System.Globalization;
using System.Net;
using System.Text;
using SpectralRenderer.Analysis;
using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Relighting;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Cli.Paper;

/// <summary>
/// report.html: one self-contained page (images embedded, inline SVG plots, no network) reproducing the
/// paper's Figs. 2–7 from a <see cref="PaperExperiments"/> run, with the ColorChecker ΔE00 table, the
/// probed spectra and the reconstruction metrics, and notes where our numbers differ from the paper's.
/// A small script checks on load that every image decoded and every plot has content, and records any
/// script error in the page (data-selfcheck on &lt;body&gt;), so a headless browser can verify it.
/// </summary>
public static class PaperReport
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    /// <summary>
    /// Starts computing, on the thread pool, the report section of a scene just written whose section is slow (the
    /// §3.1 chart: the camera comparison; §3.4: the analysis), so it runs while the other scenes render; null for
    /// the other scenes. <see cref="Write"/> takes the started sections.
    /// </summary>
    public static Task<string>? Prepare(ExperimentRun run) => run.Name switch
    {
        ChartScene => Task.Run(() => CameraSection(run)),
        AnalysisScene => Task.Run(() => { var h = new StringBuilder(); Analysis(h, run); return h.ToString(); }),
        _ => null,
    };

    const string ChartScene = "paper-3.1-colorchecker-d65", AnalysisScene = "paper-3.4-bunny-analysis";

    static string CameraSection(ExperimentRun? chart) =>
        global::SpectralRenderer.Analysis.Recovery.RecoveryComparison.HtmlSection(chart is { Done: true } ? chart.OutDir : null,
            ExactChannelSignals.Input);

    /// <summary>Writes report.html; <paramref name="prepared"/>: the sections <see cref="Prepare"/> started, by scene name.</summary>
    /// <param name="gi">The direct-against-global-illumination comparison (<see cref="GlobalIlluminationComparison"/>), when it
    /// ran.</param>
    public static string Write(string outDir, IReadOnlyList<ExperimentRun> runs, double totalSeconds,
        IReadOnlyDictionary<string, Task<string>>? prepared = null,
        GlobalIlluminationComparison.Result? gi = null)
    {
        var h = new StringBuilder();
        h.Append("""
            <!DOCTYPE html>
            <html lang="en"><head><meta charset="utf-8">
            <title>SpectralRenderer — the paper's experiments (Li et al. 2010, §3)</title>
            <style>
            body { font: 15px/1.45 system-ui, sans-serif; max-width: 1180px; margin: 2em auto; padding: 0 1em; color: #222; }
            h1 { font-size: 1.6em; } h2 { margin-top: 2.2em; border-bottom: 1px solid #ccc; }
            figure { margin: 1.2em 0; } figcaption { color: #444; font-size: 0.93em; margin-top: .4em; }
            .row { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; } .row figure { margin: 0; }
            img { max-width: 100%; image-rendering: auto; border: 1px solid #ddd; }
            table { border-collapse: collapse; font-size: 0.88em; }
            td, th { padding: 2px 7px; border-bottom: 1px solid #eee; text-align: right; }
            th { background: #f4f4f4; } td.l, th.l { text-align: left; }
            .note { background: #fff8e0; padding: .6em .9em; border-left: 4px solid #e0b000; }
            .skip { background: #fbeaea; padding: .5em .8em; border-left: 4px solid #c33; }
            </style></head><body>
            """);
        h.Append("<h1>Spectral-based rendering: the paper's experiments, reproduced</h1>\n");
        h.Append(Inv,
            $"<p>Li, Feng, Yang &amp; Bai (2010), <i>Spectral-based rendering method and its application in multispectral colour "
                + $"reproduction</i>, §3, rendered by SpectralRenderer "
                + $"{Esc(typeof(PaperReport).Assembly.GetName().Version?.ToString(3) ?? "")} on {DateTime.UtcNow:yyyy-MM-dd HH:mm} UTC, "
                + $"{Environment.ProcessorCount} cores, in {totalSeconds:0.0} s. Every image carries light in bands; colours come from eq. "
                + $"3 (CIE 1931 2°) and sRGB unless noted.</p>\n");

        var byName = runs.ToDictionary(r => r.Name);
        // The camera comparison (Fig. 1's second half) and the §3.4 analysis each read and score on about one thread:
        // unless started while the scenes rendered (Prepare), they run beside each other and the sections before them.
        var cameras = prepared?.GetValueOrDefault(ChartScene) ?? Task.Run(() => CameraSection(byName.GetValueOrDefault(ChartScene)));
        var analysis = prepared?.GetValueOrDefault(AnalysisScene);
        Chart(h, byName.GetValueOrDefault(ChartScene));
        Gallery(h, "Fig. 4 — §3.2 materials on a complex object", runs.Where(r => r.Section == "3.2").ToList());
        Gallery(h, "Fig. 5 — §3.3 one material under different lights", runs.Where(r => r.Section == "3.3").ToList());
        if (analysis is not null) h.Append(analysis.GetAwaiter().GetResult());
        else Analysis(h, byName.GetValueOrDefault(AnalysisScene));
        h.Append(cameras.GetAwaiter().GetResult());
        if (gi is not null) GlobalIllumination(h, gi);
        Timings(h, runs, totalSeconds);

        h.Append("""
            <script>
            (function () {
              var errors = [];
              window.addEventListener('error', function (e) { errors.push(String(e.message || e)); });
              var origError = console.error;
              console.error = function () { errors.push(Array.prototype.join.call(arguments, ' ')); origError.apply(console, arguments); };
              window.addEventListener('load', function () {
                var imgs = document.querySelectorAll('img'), bad = [];
                imgs.forEach(function (i) { if (!(i.complete && i.naturalWidth > 0)) bad.push(i.alt || i.src.slice(0, 40)); });
                var svgs = document.querySelectorAll('svg.plot, svg.marked');
                svgs.forEach(function (s, k) { if (s.querySelectorAll('polyline, image').length === 0) bad.push('plot ' + k); });
                var r = { images: imgs.length, plots: svgs.length, empty: bad, errors: errors };
                document.body.setAttribute('data-selfcheck', JSON.stringify(r));
                var p = document.getElementById('selfcheck');
                if (p) p.textContent = 'self-check: ' + imgs.length + ' images, ' + svgs.length + ' plots, '
                  + bad.length + ' empty, ' + errors.length + ' script errors';
              });
            })();
            </script>
            <p id="selfcheck" style="color:#888">self-check: not run</p>
            </body></html>
            """);
        var path = Path.Combine(outDir, "report.html");
        AtomicFile.WriteAllText(path, h.ToString());
        return path;
    }

    static string Esc(string s) => WebUtility.HtmlEncode(s);

    // ---- direct light against global illumination ---------------------------------------------------

    static void GlobalIllumination(StringBuilder h, GlobalIlluminationComparison.Result gi)
    {
        h.Append("<h2>Direct light (the paper's model) against global illumination</h2>\n");
        h.Append(Inv,
            $"<p>One scene of each section rendered twice in physical radiometry: <i>direct</i> is the paper's model (Whitted: eq. 2's "
                + $"light terms, mirror and glass chains), <i>path</i> the path integrator (every bounce); the scenes' constant ambient "
                + $"term, the paper's stand-in for the light between surfaces, is left out of both. Regions are the direct render's: "
                + $"<i>lit</i> where every light reaches the pixel's point, <i>shadow</i> where none does. Luminance Y from each band "
                + $"cube; all numbers in gi/comparison.csv ({gi.Seconds:0.0} s).</p>\n");
        foreach (var (scene, why) in gi.Skipped) h.Append($"<p class=\"skip\">{Esc(scene)} was not rendered: {Esc(why)}.</p>\n");
        if (gi.Rows.Count == 0) return;
        h.Append("<table><tr><th>§</th><th class=l>scene</th><th class=l>quantity</th><th class=l>region</th><th>pixels</th><th>direct</th>"
            + "<th>path</th><th>path ÷ direct</th></tr>\n");
        foreach (var r in gi.Rows)
            h.Append(Inv,
                $"<tr><td>{r.Section}</td><td class=l>{Esc(r.Scene)}</td><td class=l>{r.Quantity}</td><td class=l>{r.Region}</td>"
                    + $"<td>{r.Pixels}</td><td>{r.Direct:G5}</td><td>{r.Path:G5}</td>"
                    + $"<td>{(double.IsFinite(r.Ratio) ? r.Ratio.ToString("0.000", Inv) : "—")}</td></tr>\n");
        h.Append("</table>\n<ul>\n");
        foreach (var g in gi.Rows.GroupBy(r => r.Scene))
        {
            var y = g.Where(r => r.Quantity == "Y").ToDictionary(r => r.Region);
            var sb = new StringBuilder();
            if (y.TryGetValue("lit", out var lit)) sb.Append(Inv, $"lit ×{lit.Ratio:0.000}");
            if (y.TryGetValue("shadow", out var sh) && y.TryGetValue("lit", out lit) && lit.Direct > 0 && lit.Path > 0)
                sb.Append(Inv,
                    $"; shadow at {100 * sh.Direct / lit.Direct:0.0} % of the lit level in direct light and "
                        + $"{100 * sh.Path / lit.Path:0.0} % with every bounce");
            else sb.Append("; no pixel in shadow");
            foreach (var r in g.Where(r => r.Quantity == "rmse" && r.Region is "lit" or "shadow"))
                sb.Append(Inv, $"; white-board reconstruction RMSE ({r.Region}) {r.Direct:0.0000} → {r.Path:0.0000}");
            h.Append($"<li>{Esc(g.Key)}: {sb}</li>\n");
        }
        h.Append("</ul>\n");
    }

    static string Img(string file, string alt, int? width = null)
    {
        var data = Convert.ToBase64String(File.ReadAllBytes(file));
        return $"<img alt=\"{Esc(alt)}\" src=\"data:image/png;base64,{data}\"{(width is { } w ? $" width=\"{w}\"" : "")}>";
    }

    static void Skipped(StringBuilder h, ExperimentRun? r, string what)
    {
        h.Append($"<p class=\"skip\">{Esc(what)} was not rendered: {Esc(r?.Skipped ?? "the scene did not run")}. The meshes are "
            + $"third-party scans outside the repository; see the README, “Meshes”.</p>\n");
    }

    // ---- §3.1 -------------------------------------------------------------------------------------

    static void Chart(StringBuilder h, ExperimentRun? r)
    {
        h.Append("<h2>Fig. 2 — §3.1 the band images</h2>\n");
        if (r is not { Done: true }) { Skipped(h, r, "The ColorChecker"); return; }
        var folder = RenderFolder.Open(r.OutDir);
        var grid = folder.Manifest.Grid;
        h.Append(Inv,
            $"<figure>{Img(Path.Combine(r.OutDir, "bands.png"), "band mosaic")}<figcaption>{Esc(r.Title)}: {grid.Count} bands of "
                + $"{grid.Width.ToString("0.###", Inv)} nm from {grid.Start:0.###} nm (top left) to {grid.End:0.###} nm, all on one scale. "
                + $"{Esc(Brightest(folder))}</figcaption></figure>\n");

        h.Append("<h2>Fig. 3 — §3.1 the synthesised colours</h2>\n<div class=\"row\">");
        h.Append($"<figure>{Img(Path.Combine(r.OutDir, "preview.png"), "chart sRGB", 540)}<figcaption>sRGB (IEC "
            + $"61966-2-1).</figcaption></figure>");
        var eq4 = Path.Combine(r.OutDir, "preview-eq4.png");
        if (File.Exists(eq4))
            h.Append($"<figure>{Img(eq4, "chart eq. 4", 540)}<figcaption>The paper's eq. 4 (NTSC 1953 matrix, illuminant C white), linear "
                + $"and clipped.</figcaption></figure>");
        h.Append("</div>\n");

        var rows = ColorCheckerReport.Compute(folder);
        h.Append("<table><tr><th>#</th><th class=l>patch</th><th>X</th><th>Y</th><th>Z</th><th>L*</th><th>a*</th><th>b*</th><th>L* 1 "
            + "nm</th><th>a* 1 nm</th><th>b* 1 nm</th><th>sRGB</th><th>eq. 4 RGB (linear)</th><th>ΔE00</th></tr>\n");
        foreach (var p in rows)
        {
            var (er, eg, eb) = RgbSpace.Paper.Linear(p.Rendered);
            h.Append(Inv,
                $"<tr><td>{p.Patch}</td><td class=l>{Esc(ColorChecker.Name(p.Patch))}</td><td>{p.Rendered.X:0.0000}</td>"
                    + $"<td>{p.Rendered.Y:0.0000}</td><td>{p.Rendered.Z:0.0000}</td><td>{p.RenderedLab.L:0.00}</td>"
                    + $"<td>{p.RenderedLab.A:0.00}</td><td>{p.RenderedLab.B:0.00}</td><td>{p.ReferenceLab.L:0.00}</td>"
                    + $"<td>{p.ReferenceLab.A:0.00}</td><td>{p.ReferenceLab.B:0.00}</td><td>"
                    + $"<span style=\"display:inline-block;width:1.4em;height:.9em;background:rgb({p.Srgb8.R},{p.Srgb8.G},{p.Srgb8.B})\">"
                    + $"</span> {p.Srgb8.R} {p.Srgb8.G} {p.Srgb8.B}</td><td>{er:0.000} {eg:0.000} {eb:0.000}</td>"
                    + $"<td>{p.DeltaE00:0.000}</td></tr>\n");
        }
        h.Append(Inv,
            $"</table><p>CIEDE2000 of the rendered patches against the same reflectances under D65 integrated at 1 nm: mean "
                + $"<b>{rows.Average(x => x.DeltaE00):0.000}</b>, max <b>{rows.Max(x => x.DeltaE00):0.000}</b> "
                + $"({BandIntegrations.Name(folder.Integration)} band integration). The paper compared with a photograph instead; "
                + $"its Fig. 3 has no numbers.</p>\n");

        var greys = rows.Where(x => x.Patch is 19 or 20 or 21).ToList();
        if (greys.Count == 3)
        {
            var sb = new StringBuilder();
            foreach (var g in greys)
            {
                var (er, eg, eb) = RgbSpace.Paper.Linear(g.Rendered);
                sb.Append(Inv, $"#{g.Patch}: ({er:0.000}, {eg:0.000}, {eb:0.000}), B/G = {eb / eg:0.000}; ");
            }
            // The paper: with eq. 4 patch #21 came out slightly bluish and #19, #20 saturated to white. Measured here:
            var bright = greys.Where(g => g.Patch is 19 or 20).Select(g => RgbSpace.Paper.Linear(g.Rendered)).ToList();
            bool clipped = bright.Any(c => c.Item1 >= 1 || c.Item2 >= 1 || c.Item3 >= 1);
            var g21 = RgbSpace.Paper.Linear(greys.First(g => g.Patch == 21).Rendered);
            bool bluish = g21.Item3 > g21.Item2 && g21.Item3 > g21.Item1;
            var verdict = new StringBuilder();
            verdict.Append(clipped
                ? "#19 or #20 reaches 1 in some channel, as the paper reports; "
                : "no channel of #19 or #20 reaches 1, unlike the paper; ");
            verdict.Append(bluish
                ? "#21 has more blue than red and green, as the paper reports."
                : "#21 has no more blue than red or green, unlike the paper's bluish #21.");
            double chroma = greys.Max(g => Math.Max(Math.Abs(g.RenderedLab.A), Math.Abs(g.RenderedLab.B)));
            h.Append($"<p class=\"note\"><b>Against the paper.</b> The paper reports that with eq. 4 patch #21 came out slightly bluish "
                + $"and #19 and #20 saturated to white. Eq. 4 applied to the rendered XYZ gives {Esc(sb.ToString().TrimEnd(' ', ';'))}: "
                + $"{Esc(verdict.ToString())} In CIELAB (D65 white) the greys' largest |a*| or |b*| is "
                + $"{chroma.ToString("0.00", Inv)}{(chroma < 1 ? ": neutral within 1" : "")}.</p>\n");
        }
    }

    /// <summary>
    /// From the objects' mean spectra divided by the reference white's (the light's shape taken out): which object is
    /// brightest in the first quarter of the bands and which in the last, relative to its own mean (the most violet- and
    /// the most red-weighted), and which is brightest in its own darkest band (the whitest).
    /// </summary>
    static string Brightest(RenderFolder folder)
    {
        var names = folder.ObjectNames;
        var reflectances = folder.ObjectReflectances;
        var grid = folder.Image.Grid;
        int bands = grid.Count, first = -1, last = -1, flat = -1;
        double bf = double.NegativeInfinity, bl = double.NegativeInfinity, bm = double.NegativeInfinity;
        var white = Enumerable.Range(0, bands).Select(b => folder.ReferenceWhite.Integrate(grid.Lower(b), grid.Upper(b))).ToArray();
        int quarter = Math.Max(1, bands / 4);
        for (int o = 0; o < names.Length; o++)
        {
            var (mean, pixels) = folder.MeanSpectrum(o);
            if (pixels == 0) continue;
            var relative = mean.Select((v, b) => white[b] > 0 ? v / white[b] : 0).ToArray();
            double average = relative.Average();
            if (!(average > 0)) continue;
            double low = relative[..quarter].Average() / average, high = relative[^quarter..].Average() / average;
            if (low > bf) { bf = low; first = o; }
            if (high > bl) { bl = high; last = o; }
            if (relative.Min() > bm) { bm = relative.Min(); flat = o; }
        }
        if (first < 0) return "";
        string Name(int o) => reflectances[o] is { } r && r.StartsWith("colorchecker:", StringComparison.Ordinal)
            && int.TryParse(r["colorchecker:".Length..], out int p)
            ? $"#{p} ({ColorChecker.Name(p)})" : names[o];
        return string.Create(Inv,
            $"Relative to its own mean, {Name(first)} is the brightest in the first quarter of the bands ({bf:0.00}× its mean) and "
                + $"{Name(last)} in the last quarter ({bl:0.00}×); {Name(flat)} is the brightest in its own darkest band.");
    }

    // ---- §3.2, §3.3 -------------------------------------------------------------------------------

    static void Gallery(StringBuilder h, string heading, List<ExperimentRun> runs)
    {
        h.Append($"<h2>{Esc(heading)}</h2>\n<div class=\"row\">");
        foreach (var r in runs)
        {
            if (!r.Done) { h.Append($"<div class=\"skip\">{Esc(r.Title)}: skipped</div>"); continue; }
            h.Append($"<figure>{Img(Path.Combine(r.OutDir, "preview.png"), r.Title, r.Section == "3.3" ? 270 : 280)}"
                + $"<figcaption>{Esc(r.Title)}</figcaption></figure>");
        }
        h.Append("</div>");
        var done = runs.Where(r => r.Done).ToList();
        if (done.Count > 0)
        {
            var triangles = done.Select(r => r.Triangles).Distinct().ToList();
            var adapted = done.Select(r => RenderManifest.Read(r.OutDir).Adapt).Distinct().ToList();
            string meshes = triangles.Count == 1
                ? $"The same mesh size in every image: {triangles[0]:N0} triangles."
                : $"Triangles: {string.Join(", ", triangles.Select(t => t.ToString("N0", Inv)))}.";
            h.Append(Inv, $"<p>{meshes} ");
            h.Append(adapted.Count == 1 && !adapted[0]
                ? "κ is set by each scene's reference white and no image is chromatically adapted, so a "
                    + "coloured light shows as colour.</p>\n"
                : "Some images are chromatically adapted to the display white (Bradford).</p>\n");
        }
        var missing = runs.FirstOrDefault(r => !r.Done);
        if (missing is not null) Skipped(h, missing, heading);
    }

    // ---- §3.4 -------------------------------------------------------------------------------------

    static void Analysis(StringBuilder h, ExperimentRun? r)
    {
        h.Append("<h2>Fig. 6 — §3.4 pixel spectra</h2>\n");
        if (r is not { Done: true }) { Skipped(h, r, "The §3.4 analysis scene"); return; }
        var folder = RenderFolder.Open(r.OutDir);
        var aovs = RenderAovs.Open(folder);
        var (whiteIndex, subjectIndex, whiteLevel) = Cast(folder, aovs);
        if (whiteIndex < 0 || subjectIndex < 0)
        {
            Skipped(h, r, "The §3.4 analysis (no ground-truth reflectance or fewer than two objects)");
            return;
        }
        string whiteName = folder.ObjectNames[whiteIndex], subjectName = folder.ObjectNames[subjectIndex];
        string subjectTruth = folder.ObjectReflectances[subjectIndex] ?? "its diffuse reflectance";
        var white = Reconstruction.WhiteObject(folder, whiteName, aovs);
        var rec = Reconstruction.Compute(folder, aovs, white);
        var surface = rec.SurfacePixels();
        var picks = LabelledPixels(rec, surface, folder, subjectName, whiteIndex);
        var img = folder.Image;
        var centres = Enumerable.Range(0, img.Bands).Select(img.Grid.Centre).ToArray();

        // The render with the labelled pixels marked.
        var png = Convert.ToBase64String(File.ReadAllBytes(Path.Combine(r.OutDir, "preview.png")));
        h.Append(Inv,
            $"<div class=\"row\"><figure>"
                + $"<svg class=\"marked\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{img.Width}\" height=\"{img.Height}\" viewBox=\"0 0 "
                + $"{img.Width} {img.Height}\">"
                + $"<image width=\"{img.Width}\" height=\"{img.Height}\" href=\"data:image/png;base64,{png}\"/>");
        for (int k = 0; k < picks.Count; k++)
        {
            var p = picks[k];
            var colour = SvgPlot.Palette[k % SvgPlot.Palette.Length];
            h.Append(Inv,
                $"<circle cx=\"{p.X + 0.5}\" cy=\"{p.Y + 0.5}\" r=\"6\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2.5\"/>"
                    + $"<text x=\"{p.X + 9}\" y=\"{p.Y - 6}\" fill=\"{colour}\" font-size=\"15\" font-weight=\"bold\" stroke=\"white\" "
                    + $"stroke-width=\"0.6\">{k + 1}</text>");
        }
        h.Append(Inv,
            $"</svg><figcaption>(a) {Esc(subjectName)} ({Esc(subjectTruth)}) with {Esc(whiteName)} (ground-truth reflectance ≥ "
                + $"{whiteLevel:0.000} in every band) under {Esc(LightsOf(folder))}; the labelled pixels.</figcaption></figure>");

        var probe = new SvgPlot
        {
            Title = "(b) spectra of the labelled pixels",
            XLabel = "wavelength (nm)",
            YLabel = Commands.ProbeCommand.RadianceAxis(folder.Manifest.Radiometry == "physical"),
            Width = 560,
            Height = 380,
        };
        for (int k = 0; k < picks.Count; k++) probe.Add($"{k + 1}: {picks[k].Label}", centres, picks[k].Radiance);
        h.Append($"<figure>{PlotSvg(probe)}</figure></div>\n");

        h.Append($"<h2>Fig. 7 — §3.4 reflectance reconstructed from the white reference ({Esc(whiteName)})</h2>\n");
        var plot = new SvgPlot
        {
            Title = $"reconstructed reflectance = pixel ÷ {whiteName}",
            XLabel = "wavelength (nm)",
            YLabel = "reflectance",
            Width = 720,
            Height = 420
        };
        // The truth (dashed) in the colour of the subject's first pixel (solid).
        int first = picks.FindIndex(p => p.Object == subjectName);
        for (int k = 0; k < picks.Count; k++)
            if (picks[k].Object == subjectName) plot.Add($"{k + 1}: {picks[k].Label}", centres, picks[k].Reflectance);
        if (first >= 0) plot.Add($"truth: {subjectTruth}", centres, picks[first].Truth, dashed: true, colour: 0);
        h.Append($"<figure>{PlotSvg(plot)}<figcaption>White reference: {Esc(white.Description)} ({white.Pixels} pixels). The dashed curve "
            + $"is the reflectance {Esc(subjectName)} was given.</figcaption></figure>\n");

        h.Append("<table><tr><th class=l>pixel</th><th>x</th><th>y</th><th class=l>object</th><th class=l>region</th><th>RMSE</th>"
            + "<th>GFC</th><th>ΔE00 (D65)</th><th>scale c</th><th>residual after c</th></tr>\n");
        for (int k = 0; k < picks.Count; k++)
        {
            var p = picks[k];
            h.Append(Inv,
                $"<tr><td class=l>{k + 1}: {Esc(p.Label)}</td><td>{p.X}</td><td>{p.Y}</td><td class=l>{Esc(p.Object)}</td>"
                    + $"<td class=l>{Reconstruction.Name(p.Region)}</td><td>{p.Rmse:0.00000}</td><td>{p.Gfc:0.000000}</td>"
                    + $"<td>{p.DeltaE00:0.00}</td><td>{p.Scale:0.0000}</td><td>{p.Residual:0.00000}</td></tr>\n");
        }
        h.Append("</table>\n<p>Per region, over every surface pixel but the white reference:</p>\n<table><tr><th class=l>region</th>"
            + "<th>pixels</th><th>mean RMSE</th><th>mean GFC</th><th>mean ΔE00</th><th>mean c</th><th>mean residual</th></tr>\n");
        foreach (var s in Reconstruction.Summarise(surface))
            h.Append(Inv,
                $"<tr><td class=l>{Esc(s.Region)}</td><td>{s.Count}</td><td>{s.MeanRmse:0.00000}</td><td>{s.MeanGfc:0.000000}</td>"
                    + $"<td>{s.MeanDeltaE00:0.00}</td><td>{s.MeanScale:0.0000}</td><td>{s.MeanResidual:0.00000}</td></tr>\n");
        h.Append("</table>\n");

        var summaries = Reconstruction.Summarise(surface).ToList();
        var shadow = picks.FirstOrDefault(p => p.Region == PixelRegion.Shadow && p.Object == subjectName);
        var high = picks.FirstOrDefault(p => p.Region == PixelRegion.Highlight);
        var lit = summaries.FirstOrDefault(x => x.Region == Reconstruction.Name(PixelRegion.Lit));
        var best = picks.FirstOrDefault(p => p.Region == PixelRegion.Lit && p.Object == subjectName);
        var sb = new StringBuilder("<p class=\"note\"><b>The paper's two findings, measured.</b> ");
        // The words follow the numbers: a scale is "a factor" only when the residual after scaling is small,
        // a shape is "right" only when GFC is at least 0.999 (Romero et al.'s "good" colorimetric match).
        const double SmallResidual = 1e-3, GoodGfc = 0.999;
        if (shadow is not null)
        {
            if (shadow.Residual <= SmallResidual)
                sb.Append(Inv,
                    $"In shadow the reconstruction is the truth times a factor: c = {shadow.Scale:0.0000} with a residual of "
                        + $"{shadow.Residual:0.0e0} after scaling (GFC {shadow.Gfc:0.000000}); eq. 2 predicts c = ambient ÷ "
                        + $"lit irradiance of the reference. ");
            else
                sb.Append(Inv,
                    $"In shadow the reconstruction is not a scaled truth: c = {shadow.Scale:0.0000} leaves a residual of "
                        + $"{shadow.Residual:0.0e0} (GFC {shadow.Gfc:0.000000}). ");
        }
        if (high is not null)
        {
            if (high.Scale > 1 && high.Gfc < GoodGfc)
                sb.Append(Inv,
                    $"In a highlight light is added to the truth: the highlight pixel's reconstruction has GFC {high.Gfc:0.0000} with the "
                        + $"truth and c = {high.Scale:0.000} > 1. ");
            else
                sb.Append(Inv,
                    $"The highlight pixel's reconstruction has GFC {high.Gfc:0.0000} with the truth and c = {high.Scale:0.000}. ");
        }
        if (best is not null)
            sb.Append(Inv,
                $"The lit pixel whose irradiance is closest to the reference's (c = {best.Scale:0.0000}) reconstructs the "
                    + $"truth with RMSE {best.Rmse:0.0e0}. ");
        if (lit is not null)
        {
            if (lit.MeanGfc >= GoodGfc)
                sb.Append(Inv,
                    $"Over all {lit.Count} lit pixels the shape is right (mean GFC {lit.MeanGfc:0.000000}) and the scale varies (mean c = "
                        + $"{lit.MeanScale:0.000}) with the angle to the light.");
            else
                sb.Append(Inv,
                    $"Over all {lit.Count} lit pixels the mean GFC is {lit.MeanGfc:0.000000} (mean c = {lit.MeanScale:0.000}): the "
                        + $"shape is not preserved everywhere.");
        }
        sb.Append("</p>\n");
        h.Append(sb);
    }

    /// <summary>
    /// The §3.4 cast, chosen from the numbers rather than by name: the white reference is the object whose ground-truth
    /// reflectance, averaged over its pixels, is highest in its darkest band; the subject is the other object seen in
    /// most pixels. Returns −1 for either when there is no ground truth or no such object.
    /// </summary>
    static (int White, int Subject, double WhiteLevel) Cast(RenderFolder folder, RenderAovs aovs)
    {
        var truth = aovs.Reflectance;
        int objects = folder.ObjectNames.Length, bands = folder.Image.Bands;
        if (truth is null || objects < 2) return (-1, -1, 0);
        var count = new int[objects];
        var sum = new double[objects * bands];
        for (int i = 0; i < folder.ObjectIds.Length; i++)
        {
            int o = folder.ObjectIds[i];
            if (o < 0) continue;
            count[o]++;
            var px = truth.Data.AsSpan(i * bands, bands);
            for (int b = 0; b < bands; b++) sum[o * bands + b] += px[b];
        }
        int white = -1;
        double level = double.NegativeInfinity;
        for (int o = 0; o < objects; o++)
        {
            if (count[o] == 0) continue;
            double min = double.PositiveInfinity;
            for (int b = 0; b < bands; b++) min = Math.Min(min, sum[o * bands + b] / count[o]);
            if (min > level) { level = min; white = o; }
        }
        int subject = -1;
        for (int o = 0; o < objects; o++)
            if (o != white && count[o] > 0 && (subject < 0 || count[o] > count[subject])) subject = o;
        return (white, subject, level);
    }

    static string LightsOf(RenderFolder folder)
    {
        var lights = folder.Manifest.Lights;
        if (lights.Count == 0) return "no light";
        return string.Join(" and ", lights.Select(l => $"{l.Kind} light {l.Name}" + (l.Spectrum is { } s && s != l.Name ? $" ({s})" : "")));
    }

    /// <summary>Fig. 6's labelled pixels: a lit subject pixel whose irradiance matches the white reference's, a typical lit one, the
    /// strongest highlight, a shadowed subject pixel and the white reference.</summary>
    static List<PixelReconstruction> LabelledPixels(Reconstruction rec, List<PixelReconstruction> surface, RenderFolder folder,
        string subject, int whiteIndex)
    {
        var picks = new List<PixelReconstruction>();
        var subjectLit = surface.Where(p => p.Object == subject && p.Region == PixelRegion.Lit).ToList();
        if (subjectLit.Count > 0)
        {
            picks.Add(subjectLit.MinBy(p => Math.Abs(p.Scale - 1))! with { Label = "lit, c ≈ 1" });
            var sorted = subjectLit.OrderBy(p => p.Scale).ToList();
            picks.Add(sorted[sorted.Count / 2] with { Label = "lit, typical" });
        }
        var high = surface.Where(p => p.Region == PixelRegion.Highlight && p.Object == subject).ToList();
        if (high.Count > 0) picks.Add(high.MaxBy(p => p.Radiance.Sum())! with { Label = "highlight" });
        var shadow = surface.Where(p => p.Object == subject && p.Region == PixelRegion.Shadow).ToList();
        if (shadow.Count > 0) picks.Add(shadow.OrderBy(p => p.Rmse).ElementAt(shadow.Count / 2) with { Label = "shadow" });
        if (whiteIndex >= 0)
        {
            // The lit reference pixel nearest the lower left of the picture.
            int w = folder.Image.Width, h = folder.Image.Height, best = -1;
            double bestD = double.MaxValue;
            for (int i = 0; i < rec.White.Mask.Length; i++)
            {
                if (!rec.White.Mask[i]) continue;
                double dx = i % w - 0.2 * w, dy = i / w - 0.85 * h, d = dx * dx + dy * dy;
                if (d < bestD) { bestD = d; best = i; }
            }
            if (best >= 0) picks.Add(rec.At(best % w, best / w, "white reference"));
        }
        return picks;
    }

    static string PlotSvg(SvgPlot plot)
    {
        var svg = plot.ToSvg();
        int start = svg.IndexOf("<svg", StringComparison.Ordinal);
        svg = svg[start..];
        return svg.Replace("<svg ", "<svg class=\"plot\" ", StringComparison.Ordinal);
    }

    // ---- timings ----------------------------------------------------------------------------------

    static void Timings(StringBuilder h, IReadOnlyList<ExperimentRun> runs, double total)
    {
        h.Append("<h2>The run</h2>\n<table><tr><th class=l>scene</th><th>size</th><th>bands</th><th>triangles</th><th>load s</th>"
            + "<th>render s</th><th>Mrays/s</th><th>write s</th></tr>\n");
        foreach (var r in runs)
        {
            if (!r.Done)
            {
                h.Append($"<tr><td class=l>{Esc(r.Name)}</td><td colspan=7 class=l>skipped: {Esc(r.Skipped!)}</td></tr>\n");
                continue;
            }
            h.Append(Inv,
                $"<tr><td class=l>{Esc(r.Name)}</td><td>{r.Width}×{r.Height}</td><td>{r.Bands}</td><td>{r.Triangles:N0}</td>"
                    + $"<td>{r.LoadSeconds:0.000}</td><td>{r.RenderSeconds:0.000}</td>"
                    + $"<td>{r.Rays / Math.Max(1e-9, r.RenderSeconds) / 1e6:0.0}</td><td>{r.WriteSeconds:0.000}</td></tr>\n");
        }
        h.Append(Inv,
            $"</table><p>Total {total:0.0} s including writing every output. Each scene's folder beside this page holds its band PNGs, "
                + $"spectral.npy, masks and render.json.</p>\n");
    }
}
