using System.Globalization;
using System.Text;
using SpectralRenderer.Analysis;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral probe OUTDIR --pixel X,Y[:LABEL] …`: the spectra of chosen pixels, as the paper's Fig. 6b.</summary>
public static class ProbeCommand
{
    const string Help = """
        usage: spectral probe OUTDIR --pixel X,Y[:LABEL] [--pixel …] [-o PREFIX] [--csv]

        Prints each chosen pixel's band values (the framebuffer's float32 values, exactly) with the bands'
        start, centre and end wavelengths, and writes them to PREFIX.csv with a plot of spectral radiance
        against wavelength, one line per pixel, to PREFIX.svg (the paper's Fig. 6b). PREFIX defaults to
        OUTDIR/probe. Pixels are 0-based, x to the right, y down; LABEL names the column (default xXyY).
        Bands are numbered from 1, as in wavelengths.csv and the band PNGs' names.

          --pixel X,Y[:LABEL]   a pixel to probe (repeatable)
          -o PREFIX             where to write PREFIX.csv and PREFIX.svg
          --csv                 print only the CSV
        """;

    /// <summary>A plot's radiance axis in the render's radiometry (issue 24): W·m⁻²·sr⁻¹·nm⁻¹ physical, relative in the paper's.</summary>
    /// <summary>The plot's axis: physical units for a physical render; a paper render's band values (eq. 2 without units)
    /// are relative, and the axis names no physical unit for them.</summary>
    internal static string RadianceAxis(bool physical) =>
        physical ? "spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry)" : "band value (relative units, the paper's eq. 2)";

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("probe", argv, ["--pixel", "--output"], ["--csv"], new Dictionary<string, string> { ["-o"] = "--output" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one render folder", "usage: spectral probe OUTDIR --pixel X,Y[:LABEL]");
        if (a.Values("--pixel").Count == 0)
            throw new InputException("command line", "give at least one --pixel X,Y[:LABEL]", "e.g. --pixel 120,80:lit");
        var dir = a.Positionals[0];
        var (manifest, image) = RenderFolder.OpenCube(dir);
        // The unit of the band values is the render's radiometry's (issue 24): W·m⁻²·sr⁻¹·nm⁻¹ physical, relative in the paper's.
        bool physical = manifest.ResolvedScene?.Radiometry == "physical";
        var pixels = PixelOption.ParseAll(a.Values("--pixel"), "probe", image.Width, image.Height);
        var prefix = a.Value("--output") ?? Path.Combine(dir, "probe");

        var csv = Csv(image, pixels);
        // One folder transaction (OutputFolder): PREFIX.csv and PREFIX.svg staged and swapped in together.
        var stem = Path.GetFileName(prefix);
        using var folder =
            OutputFolder.BeginFiles(Path.GetDirectoryName(Path.GetFullPath(prefix))!, [stem + ".csv", stem + ".svg"], "probe", "-o");
        AtomicFile.WriteAllText(Path.Combine(folder.Staging, stem + ".csv"), csv);
        var plot = new SvgPlot
        {
            Title = $"Spectra of {pixels.Count} pixel{(pixels.Count == 1 ? "" : "s")} — "
                + $"{Path.GetFileName(Path.GetFullPath(dir).TrimEnd(Path.DirectorySeparatorChar))}",
            XLabel = "wavelength (nm)",
            YLabel = RadianceAxis(physical),
        };
        var centres = Enumerable.Range(0, image.Bands).Select(image.Grid.Centre).ToArray();
        foreach (var p in pixels) plot.Add(p.Label, centres, Values(image, p).Select(v => (double)v).ToArray());
        plot.Write(Path.Combine(folder.Staging, stem + ".svg"));
        folder.Commit([stem + ".csv", stem + ".svg"], Signals.Token);

        if (a.Flag("--csv")) { stdout.Write(csv); return CommandLine.Success; }
        var inv = CultureInfo.InvariantCulture;
        stdout.WriteLine($"{image.Width}×{image.Height}, {image.Grid} bands; radiance per band "
            + $"({(physical ? "W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry" : "relative units")})");
        stdout.WriteLine($"{"band",4} {"nm",15}" + string.Concat(pixels.Select(p => $" {Fit(p.Label),14}")));
        for (int b = 0; b < image.Bands; b++)
            stdout.WriteLine(
                string.Create(inv, $"{Spectra.BandGrid.Number(b),4} {image.Grid.Lower(b),7:0.##}–{image.Grid.Upper(b),-7:0.##}")
                + string.Concat(pixels.Select(p => $" {image[p.X, p.Y, b].ToString("G7", inv),14}")));
        stdout.WriteLine($"wrote {prefix}.csv, {prefix}.svg");
        return CommandLine.Success;
    }

    static string Fit(string s) => s.Length <= 14 ? s : s[..13] + "…";

    static float[] Values(SpectralImage image, PixelOption p) => image.Pixel(p.X, p.Y).ToArray();

    /// <summary>band,start_nm,centre_nm,end_nm, then one column per pixel; floats printed round-trip exact.</summary>
    public static string Csv(SpectralImage image, IReadOnlyList<PixelOption> pixels)
    {
        var inv = CultureInfo.InvariantCulture;
        var sb = new StringBuilder(WavelengthsCsv.Header);
        foreach (var p in pixels) sb.Append(',').Append(PixelOption.Csv(p.Label));
        sb.Append('\n');
        var g = image.Grid;
        for (int b = 0; b < image.Bands; b++)
        {
            WavelengthsCsv.AppendRow(sb, g, b);
            foreach (var p in pixels) sb.Append(',').Append(image[p.X, p.Y, b].ToString("R", inv));
            sb.Append('\n');
        }
        return sb.ToString();
    }

    /// <summary>A render folder's cube, through its manifest (present, consistent, every listed file there).</summary>
    public static SpectralImage OpenCube(string dir) => RenderFolder.OpenCube(dir).Image;
}
