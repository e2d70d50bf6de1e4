using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral recover CAMERADIR`: spectral reflectance from a simulated camera's signals, scored against the render's
/// truth.</summary>
public static class RecoverCommand
{
    const string Help = """
        usage: spectral recover CAMERADIR [--method pinv|wiener|linear|tikhonov|wiener-local|all] [--training NAME|CSV]
                                          [--white-object NAME | --white-region X0,Y0,X1,Y1] [--range LO:HI] [--csv]

        Recovers each pixel's reflectance from the camera signals of a 'spectral camera' folder, with the
        sensor's channel weights and the scene light (the forward model of a surface lit like the white):
          pinv       minimum-norm least squares (pseudo-inverse)
          wiener     Wiener estimate: the training set's mean and covariance, the sensor's noise covariance
          linear     linear model on the training set's first C principal components (C = channels)
          tikhonov   regularised regression learned on the training set, λ by generalised cross-validation
          wiener-local  Wiener estimate with a local prior: the training samples weighted by how near their
                     signals are to the pixel's (chromaticity and intensity), widths by leave-one-out
        --method takes a comma list; default all. --training: rawtoaces-190 (default), cie224-ces99,
        colorchecker, or a CSV of reflectances (first column wavelength_nm). --white-object / --white-region
        calibrate each channel on a white reference of reflectance 1 (§3.4); its pixels are then excluded.
        --white-region X0,Y0,X1,Y1 is columns X0…X1−1 and rows Y0…Y1−1 (X1 and Y1 exclusive, as --crop).
        --range LO:HI scores RMSE and GFC on the bands inside LO–HI nm only (e.g. 400:700, where the sensors
        respond; default every band); ΔE00 always uses the whole spectrum.

        The forward model follows the capture's signal route (camera.json): on the band route the band
        weights (reflectance constant within each band, as the band route's signals are made), on the exact
        route the training spectra's signals at full spectral resolution, recovered as band means.

        Scores against the render's ground truth (reflectance.exr): RMSE, GFC, CIEDE2000 under D65 and A, per
        region (lit, shadow, partial, highlight, all) and over the ColorChecker patches when the render shows
        them. Writes CAMERADIR/recovered-<method>.npy (H×W×N float32), recovery-metrics.csv (one row per
        method and region), recovery-<method>.svg (recovered vs true spectra) and recovery.json (the forward
        model, training set, methods and scoring range).

          --csv   print recovery-metrics.csv instead of the table
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("recover", argv, ["--method", "--training", "--white-object", "--white-region", "--range"], ["--csv"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one camera folder", "usage: spectral recover CAMERADIR --method wiener");
        var methodText = a.Value("--method") ?? "all";
        var methods = methodText == "all" ? Enum.GetValues<RecoveryMethod>().ToList()
            : methodText.Split(',').Select(m => SpectralEstimator.Parse(m.Trim())).Distinct().ToList();
        string? obj = a.Value("--white-object"), region = a.Value("--white-region");
        if (obj is not null && region is not null)
            throw new InputException("command line", "give at most one of --white-object and --white-region",
                "see 'spectral recover --help'");

        var dir = a.Positionals[0];
        var capture = CameraCapture.Open(dir);
        var scene = capture.Scene;
        var training = TrainingSet.Load(a.Value("--training") ?? "rawtoaces-190", scene.Grid);
        WhiteReference? white = obj is not null ? Reconstruction.WhiteObject(scene.Folder, obj, scene.Aovs)
            : region is not null ? ParseRegion(scene, region) : null;

        (double, double)? range = null;
        if (a.Value("--range") is { } rt)
        {
            var parts = rt.Split(':');
            if (parts.Length != 2 || !double.TryParse(parts[0], NumberStyles.Float, CultureInfo.InvariantCulture, out double lo)
                || !double.TryParse(parts[1], NumberStyles.Float, CultureInfo.InvariantCulture, out double hi) || !(hi > lo))
                throw new InputException("--range", $"'{rt}' is not LO:HI in nm", "e.g. --range 400:700");
            range = (lo, hi);
        }
        var (firstBand, bandCount) = RecoveryEvaluation.BandsInside(scene.Grid, range);
        string rangeText = string.Create(CultureInfo.InvariantCulture,
            $"{scene.Grid.Lower(firstBand):0.##}-{scene.Grid.Upper(firstBand + bandCount - 1):0.##}");
        var results = methods.Select(m => RecoveryEvaluation.Run(capture, m, training, white?.Mask, white?.Description, range)).ToList();
        var inv = CultureInfo.InvariantCulture;
        var csv = new StringBuilder("method,region,count,rmse,gfc,dE00_D65,dE00_A,metric_range_nm\n");
        foreach (var r in results.SelectMany(r => r.Rows))
            csv.Append(inv, $"{r.Method},{r.Region},{r.Count},{r.Rmse:R},{r.Gfc:R},{r.DeltaE00D65:R},{r.DeltaE00A:R},{rangeText}\n");
        var written = new List<string>();
        var g = scene.Grid;
        var centres = Enumerable.Range(0, g.Count).Select(g.Centre).ToArray();
        // One folder transaction (OutputFolder): staged beside CAMERADIR and swapped in together; nothing else there is touched.
        var names = results.SelectMany(r =>
            new[] { $"recovered-{SpectralEstimator.Name(r.Method)}.npy", $"recovery-{SpectralEstimator.Name(r.Method)}.svg" })
            .Append("recovery-metrics.csv").Append("recovery.json").ToList();
        using var folder = OutputFolder.BeginFiles(dir, names, "recovery");
        foreach (var r in results)
        {
            Signals.Token.ThrowIfCancellationRequested();
            var name = SpectralEstimator.Name(r.Method);
            AtomicFile.Write(Path.Combine(folder.Staging, $"recovered-{name}.npy"),
                s => NpyWriter.Write(s, [scene.Height, scene.Width, g.Count], r.Reflectance));
            var plot = new SvgPlot
            {
                Title = $"Reflectance recovered by {name} from {capture.Sensor.Name} ({training.Name} "
                    + $"prior{(white is null ? "" : ", white-calibrated")})",
                XLabel = "wavelength (nm)",
                YLabel = "reflectance factor",
            };
            // Each recovered curve (solid) in the colour of its truth (dashed).
            for (int k = 0; k < r.Examples.Count; k++) plot.Add(r.Examples[k].Label, centres, r.Examples[k].Recovered, colour: k);
            for (int k = 0; k < r.Examples.Count; k++)
                plot.Add($"truth: {r.Examples[k].Label}", centres, r.Examples[k].Truth, dashed: true, colour: k);
            plot.Write(Path.Combine(folder.Staging, $"recovery-{name}.svg"));
            written.Add($"recovered-{name}.npy");
            written.Add($"recovery-{name}.svg");
        }
        AtomicFile.WriteAllText(Path.Combine(folder.Staging, "recovery-metrics.csv"), csv.ToString());
        written.Add("recovery-metrics.csv");
        var model = results[0].Estimator.Model;
        AtomicFile.WriteAllText(Path.Combine(folder.Staging, "recovery.json"), new JsonObject
        {
            ["forward_model"] = model.Route,
            ["forward_model_description"] = model.Description,
            ["training"] = training.Name,
            ["methods"] = new JsonArray(results.Select(r => (JsonNode)SpectralEstimator.Name(r.Method)).ToArray()),
            ["metric_range_nm"] = rangeText,
            ["white"] = white?.Description,
        }.ToJsonString(new JsonSerializerOptions { WriteIndented = true }) + "\n");
        written.Add("recovery.json");
        folder.Commit(written, Signals.Token);

        if (a.Flag("--csv")) { stdout.Write(csv.ToString()); return CommandLine.Success; }
        stdout.WriteLine($"recovery from {capture.Sensor.Name} ({capture.Sensor.ChannelCount} channels, noise "
            + $"{(capture.Raw.Options.Noise ? "on" : "off")}) of {scene.Folder.Path}; training {training.Name} ({training.Count} "
            + $"reflectances); {g} bands{(white is null ? "" : $"; white: {white.Description}")}; RMSE and GFC over {rangeText} nm");
        stdout.WriteLine($"forward model: {model.Description}");
        if (!scene.Aovs.HasMasks)
            stdout.WriteLine("no mask-lit-<k>.png / mask-highlight.png: regions are not classified (render with --formats including aov)");
        stdout.WriteLine($"{"method",-12} {"region",-13} {"count",7} {"RMSE",9} {"GFC",9} {"ΔE00 D65",9} {"ΔE00 A",9}");
        foreach (var r in results.SelectMany(r => r.Rows))
            stdout.WriteLine(string.Create(inv,
                $"{r.Method,-12} {r.Region,-13} {r.Count,7} {r.Rmse,9:F5} {r.Gfc,9:F5} {r.DeltaE00D65,9:F3} {r.DeltaE00A,9:F3}"));
        foreach (var r in results.Where(r => r.Estimator.Lambda is not null))
            stdout.WriteLine(string.Create(inv, $"tikhonov: λ = {r.Estimator.Lambda:G3} × the mean eigenvalue of SSᵀ (by GCV)"));
        foreach (var r in results.Where(r => r.Estimator.Components is not null))
            stdout.WriteLine($"linear: {r.Estimator.Components} principal components (the most with cond(AB) ≤ 100)");
        foreach (var r in results.Where(r => r.Estimator.Local is not null))
        {
            var l = r.Estimator.Local!;
            stdout.WriteLine(string.Create(inv,
                $"wiener-local: h_c = {l.ChromaticityWidth:G3}, h_I = "
                    + $"{(double.IsPositiveInfinity(l.IntensityWidth) ? "∞" : l.IntensityWidth.ToString("G3", inv))}, β = {l.Shrinkage:G3} "
                    + $"(by leave-one-out on the training set: mean RMSE {l.LeaveOneOutRmse:F4})"));
        }
        stdout.WriteLine($"wrote {string.Join(", ", written)} in {dir}");
        return CommandLine.Success;
    }

    static WhiteReference ParseRegion(CameraScene scene, string text)
    {
        var v = text.Split(',')
            .Select(t => int.TryParse(t.Trim(), NumberStyles.Integer, CultureInfo.InvariantCulture, out int n) ? n : (int?)null).ToArray();
        if (v.Length != 4 || v.Any(n => n is null))
            throw new InputException("--white-region", $"'{text}' is not X0,Y0,X1,Y1",
                "four whole pixel numbers, X1 and Y1 exclusive (as for --crop), e.g. 0,0,16,10: columns 0–15, rows 0–9");
        return Reconstruction.WhiteRegion(scene.Folder, v[0]!.Value, v[1]!.Value, v[2]!.Value, v[3]!.Value);
    }
}
