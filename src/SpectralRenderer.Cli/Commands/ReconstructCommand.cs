using System.Globalization;
using System.Text;
using SpectralRenderer.Analysis;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral reconstruct OUTDIR`: the paper's §3.4 white-board reflectance reconstruction (Fig. 7) against the truth.</summary>
public static class ReconstructCommand
{
    const string Help = """
        usage: spectral reconstruct OUTDIR (--white-object NAME | --white-region X0,Y0,X1,Y1)
                                    [--pixel X,Y[:LABEL] …] [--csv]

        The paper's §3.4 white-board calibration: reflectance = pixel radiance ÷ white radiance, band by
        band, the white being the mean over the pixels of object NAME or of the rectangle X0,Y0,X1,Y1: columns
        X0…X1−1 and rows Y0…Y1−1 (X1 and Y1 exclusive, as --crop). Compares it with the ground-truth
        reflectance the render wrote (reflectance.exr) by RMSE, GFC (goodness-of-fit coefficient), CIEDE2000
        under D65, and the least-squares scale c with the RMSE left after scaling (c·truth ≈ reconstruction:
        a shadow is a scale error).

        Regions (from the render's mask-lit-<k>.png and mask-highlight.png):
          highlight  specular > highlight_fraction × diffuse
          lit        lit by every light, not highlight
          shadow     lit by no light (ambient only)
          partial    lit by some lights but not all
        The background and the white reference's own pixels are excluded.

        Prints each --pixel's metrics (without --pixel: the median-RMSE pixel of each region) and each
        region's count and means. Writes OUTDIR/reconstructed.exr (T.<λ>nm channels) and .npy, the curves
        to reconstruction.csv, the metrics to reconstruction-metrics.csv and the plot (Fig. 7) to
        reconstruction.svg.

          --csv   print the metrics as CSV: kind,label,x,y,object,region,count,rmse,gfc,dE00,c,residual
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("reconstruct", argv, ["--white-object", "--white-region", "--pixel"], ["--csv"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one render folder", "usage: spectral reconstruct OUTDIR --white-object NAME");
        string? obj = a.Value("--white-object"), region = a.Value("--white-region");
        if ((obj is null) == (region is null))
            throw new InputException("command line", "give exactly one of --white-object NAME and --white-region X0,Y0,X1,Y1",
                "e.g. --white-object board");
        var dir = a.Positionals[0];
        var folder = RenderFolder.Open(dir);
        var img = folder.Image;
        var chosen = PixelOption.ParseAll(a.Values("--pixel"), "reconstruct", img.Width, img.Height);
        var aovs = RenderAovs.Open(folder);
        var white = obj is not null ? Reconstruction.WhiteObject(folder, obj, aovs) : ParseRegion(folder, region!);
        var rec = Reconstruction.Compute(folder, aovs, white);

        var surface = rec.SurfacePixels();
        var summaries = Reconstruction.Summarise(surface);
        var pixels = chosen.Count > 0 ? chosen.Select(p => rec.At(p.X, p.Y, p.Label)).ToList() : Reconstruction.Representatives(surface);

        // One folder transaction (OutputFolder): the five files staged beside OUTDIR and swapped in together.
        string[] names =
            ["reconstructed.npy", "reconstructed.exr", "reconstruction.csv", "reconstruction-metrics.csv", "reconstruction.svg"];
        using var target = OutputFolder.BeginFiles(dir, names, "reconstruction");
        var staging = target.Staging;
        NpyWriter.Write(Path.Combine(staging, "reconstructed.npy"), rec.Reflectance);
        ExrWriter.Write(Path.Combine(staging, "reconstructed.exr"), rec.Reflectance, new ExrOptions
        {
            Reflective = true,
            Rgb = false,
            Attributes = new Dictionary<string, string>
            {
                ["comments"] = $"reflectance reconstructed by white-board calibration against "
                + $"{white.Description} (Li et al. 2010 §3.4)"
            },
        });
        AtomicFile.WriteAllText(Path.Combine(staging, "reconstruction.csv"), CurvesCsv(rec, pixels));
        var metrics = MetricsCsv(pixels, summaries);
        AtomicFile.WriteAllText(Path.Combine(staging, "reconstruction-metrics.csv"), metrics);
        Plot(rec, pixels).Write(Path.Combine(staging, "reconstruction.svg"));
        target.Commit(names, Signals.Token);

        if (a.Flag("--csv")) { stdout.Write(metrics); return CommandLine.Success; }
        var inv = CultureInfo.InvariantCulture;
        stdout.WriteLine($"white reference: {white.Description}, {white.Pixels} pixels; {img.Grid} bands; ΔE00 under D65");
        if (!aovs.HasMasks)
            stdout.WriteLine("no mask-lit-<k>.png / mask-highlight.png: regions are not classified (render with --formats including aov)");
        stdout.WriteLine(
            $"{"pixel",-16} {"x",5} {"y",5} {"object",-14} {"region",-12} {"RMSE",10} {"GFC",10} {"ΔE00",8} {"c",9} {"residual",10}");
        foreach (var p in pixels)
            stdout.WriteLine(string.Create(inv,
                $"{Fit(p.Label, 16),-16} {p.X,5} {p.Y,5} {Fit(p.Object, 14),-14} {Reconstruction.Name(p.Region),-12} {p.Rmse,10:G4} "
                    + $"{p.Gfc,10:F6} {p.DeltaE00,8:F3} {p.Scale,9:F5} {p.Residual,10:G4}"));
        stdout.WriteLine();
        stdout.WriteLine($"{"region",-12} {"pixels",8} {"mean RMSE",10} {"mean GFC",10} {"mean ΔE00",10} {"mean c",9} {"mean resid.",11}");
        foreach (var s in summaries)
            stdout.WriteLine(string.Create(inv,
                $"{s.Region,-12} {s.Count,8} {s.MeanRmse,10:G4} {s.MeanGfc,10:F6} {s.MeanDeltaE00,10:F3} "
                    + $"{s.MeanScale,9:F5} {s.MeanResidual,11:G4}"));
        stdout.WriteLine(
            $"wrote reconstructed.exr, reconstructed.npy, reconstruction.csv, reconstruction-metrics.csv, reconstruction.svg in {dir}");
        return CommandLine.Success;
    }

    static string Fit(string s, int n) => s.Length <= n ? s : s[..(n - 1)] + "…";

    static WhiteReference ParseRegion(RenderFolder folder, string text)
    {
        var v = text.Split(',')
            .Select(t => int.TryParse(t.Trim(), NumberStyles.Integer, CultureInfo.InvariantCulture, out int n) ? n : (int?)null).ToArray();
        if (v.Length != 4 || v.Any(n => n is null))
            throw new InputException("--white-region", $"'{text}' is not X0,Y0,X1,Y1",
                "four whole pixel numbers, X1 and Y1 exclusive (as for --crop), e.g. 0,0,16,10: columns 0–15, rows 0–9");
        return Reconstruction.WhiteRegion(folder, v[0]!.Value, v[1]!.Value, v[2]!.Value, v[3]!.Value);
    }

    /// <summary>The Fig. 7 data: per band, each pixel's reconstructed reflectance and its truth.</summary>
    static string CurvesCsv(Reconstruction rec, IReadOnlyList<PixelReconstruction> pixels)
    {
        var inv = CultureInfo.InvariantCulture;
        var g = rec.Folder.Image.Grid;
        var sb = new StringBuilder(WavelengthsCsv.Header).Append(",white");
        foreach (var p in pixels) sb.Append(',').Append(PixelOption.Csv(p.Label)).Append(',').Append(PixelOption.Csv(p.Label + " truth"));
        sb.Append('\n');
        for (int b = 0; b < g.Count; b++)
        {
            WavelengthsCsv.AppendRow(sb, g, b).Append(',').Append(rec.White.Spectrum[b].ToString("R", inv));
            foreach (var p in pixels) sb.Append(inv, $",{p.Reflectance[b].ToString("R", inv)},{p.Truth[b].ToString("R", inv)}");
            sb.Append('\n');
        }
        return sb.ToString();
    }

    static string MetricsCsv(IReadOnlyList<PixelReconstruction> pixels, IReadOnlyList<RegionSummary> summaries)
    {
        var inv = CultureInfo.InvariantCulture;
        var sb = new StringBuilder("kind,label,x,y,object,region,count,rmse,gfc,dE00,c,residual\n");
        foreach (var p in pixels)
            sb.Append(inv,
                $"pixel,{PixelOption.Csv(p.Label)},{p.X},{p.Y},{PixelOption.Csv(p.Object)},{Reconstruction.Name(p.Region)},1,{p.Rmse:R},"
                    + $"{p.Gfc:R},{p.DeltaE00:R},{p.Scale:R},{p.Residual:R}\n");
        foreach (var s in summaries)
            sb.Append(inv,
                $"region,{s.Region},,,,{s.Region},{s.Count},{s.MeanRmse:R},{s.MeanGfc:R},{s.MeanDeltaE00:R},"
                    + $"{s.MeanScale:R},{s.MeanResidual:R}\n");
        return sb.ToString();
    }

    /// <summary>Fig. 7: each pixel's reconstructed reflectance (solid) and the truth of each object among them (dashed).</summary>
    static SvgPlot Plot(Reconstruction rec, IReadOnlyList<PixelReconstruction> pixels)
    {
        var g = rec.Folder.Image.Grid;
        var centres = Enumerable.Range(0, g.Count).Select(g.Centre).ToArray();
        var plot = new SvgPlot
        {
            Title = $"Reflectance reconstructed against {rec.White.Description}",
            XLabel = "wavelength (nm)",
            YLabel = "reflectance (1 = white board)"
        };
        // Each object's truth (dashed) in the colour of its first pixel's curve (solid).
        for (int k = 0; k < pixels.Count; k++) plot.Add(pixels[k].Label, centres, pixels[k].Reflectance, colour: k);
        foreach (var t in pixels.Select((p, k) => (p, k)).Where(e => e.p.Object != "background").GroupBy(e => e.p.Object))
            plot.Add($"truth: {t.Key}", centres, t.First().p.Truth, dashed: true, colour: t.First().k);
        return plot;
    }
}
