using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Relighting;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral relight OUTDIR --light NAME=SPECTRUM …`: the render under other lights, exactly, without tracing a ray.</summary>
public static class RelightCommand
{
    const string Help = """
        usage: spectral relight OUTDIR --light NAME=SPECTRUM [--light …] [--intensity NAME=F] [--white SPECTRUM]
                                [-o NEWDIR] [--metrics] [--quiet]
               spectral relight OUTDIR --sweep FILE.csv [-o DIR] [--quiet]

        Relights a render that has the per-light outputs (rendered with --formats …,lights or
        "output": { "light_groups": true }): every file a render writes, equal to a fresh render of the same
        scene with those lights, computed from lights/ without tracing a ray. render.json says it was relit
        and from what.

          --light NAME=SPECTRUM   light NAME's new spectrum: a built-in (D65, A, FL11, led-blue, …),
                                  blackbody:T, daylight:T (K), file.csv:column, or a scene's named spectrum
          --intensity NAME=F      light NAME's new intensity (the scene's "intensity")
          --white SPECTRUM        a new reference white (κ and the colour weights follow it, as in a render)
          -o NEWDIR               where to write (default: OUTDIR-relit)
          --sweep FILE.csv        one relit render per row into DIR/0001, DIR/0002, … with DIR/index.csv;
                                  columns: a light's name (its spectrum), NAME.intensity, white; empty = keep
          --metrics               also write relight-metrics.csv (and render.json's relit.metrics): each relit
                                  light's CIE 13.3 Ra, CIE 224 Rf and CCT, and per object the mean and maximum
                                  ΔE00 between its pixels' colours in OUTDIR and in the relit render
          --quiet                 no summary on stderr
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("relight", argv, ["--light", "--intensity", "--white", "--out", "--sweep"], ["--quiet", "--metrics"],
            new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        JitWarmup.Start(JitWarmup.Relight);   // the writers compile while the transfer is read
        if (a.Positionals.Count != 1)
            throw new InputException("", a.Positionals.Count == 0 ? "no render folder given" : $"unexpected argument '{a.Positionals[1]}'",
                "usage: spectral relight OUTDIR --light NAME=SPECTRUM");
        var dir = a.Positionals[0];
        var src = Relighter.Open(dir);
        bool quiet = a.Flag("--quiet");
        var commandLine = "spectral relight " + string.Join(' ', argv);
        var clock = System.Diagnostics.Stopwatch.StartNew();

        if (a.Value("--sweep") is { } sweep)
        {
            if (a.Values("--light").Count + a.Values("--intensity").Count > 0 || a.Value("--white") is not null)
                throw new InputException("--sweep",
                    "give the lights either in the sweep file or with --light/--intensity/--white, not both",
                    "see 'spectral relight --help'");
            var rows = Relighter.ReadSweep(sweep, src.LightNames);
            Signals.ExpectCommits(int.MaxValue);   // finished only by its index.csv, written last
            // Every row checked (its spectra resolved, its scene loaded) before the first is written: a bad cell is named
            // by the sweep file's row and column, and no earlier row's folder is left behind for it.
            foreach (var row in rows)
            {
                Signals.Token.ThrowIfCancellationRequested();
                Relighter.ChangedScene(src, row.Changes, row.White, row.WhiteWhere);
            }
            var outRoot = a.Value("--out") ?? dir.TrimEnd('/', '\\') + "-sweep";
            RenderCommand.PrepareOutputFolder(outRoot);
            var index = new StringBuilder("row,folder,white,changes\n");
            for (int r = 0; r < rows.Count; r++)
            {
                var folder = (r + 1).ToString("0000", CultureInfo.InvariantCulture);
                var (changes, white) = (rows[r].Changes, rows[r].White);
                Relighter.Write(src, changes, white, Path.Combine(outRoot, folder), commandLine, Signals.Token,
                    metrics: a.Flag("--metrics"));
                index.Append(CultureInfo.InvariantCulture, $"{r + 1},{folder},{white},\"{string.Join("; ", changes.Select(Describe))}\"\n");
            }
            AtomicFile.WriteAllText(Path.Combine(outRoot, "index.csv"), index.ToString());
            if (!quiet)
                stderr.WriteLine(
                    $"relit {rows.Count} variants of {dir} into {outRoot} in {clock.Elapsed.TotalSeconds:0.###} s (index.csv)");
            return CommandLine.Success;
        }

        var byName = new Dictionary<string, LightChange>(StringComparer.Ordinal);
        foreach (var v in a.Values("--light"))
        {
            var (name, spectrum) = Split(v, "--light", "NAME=SPECTRUM, e.g. --light D65=blackbody:3000");
            byName[name] = (byName.GetValueOrDefault(name) ?? new LightChange(name, null, null)) with { Spectrum = spectrum };
        }
        foreach (var v in a.Values("--intensity"))
        {
            var (name, text) = Split(v, "--intensity", "NAME=F, e.g. --intensity D65=0.5");
            if (!double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out double f) || !double.IsFinite(f) || f < 0
                || f > 1e30)
                throw new InputException("--intensity", $"'{text}' is not a non-negative number ≤ 1e30 (a scene's intensity range)",
                    "e.g. --intensity D65=0.5");
            byName[name] = (byName.GetValueOrDefault(name) ?? new LightChange(name, null, null)) with { Intensity = f };
        }
        var whiteArg = a.Value("--white");
        if (byName.Count == 0 && whiteArg is null)
            throw new InputException("", "nothing to change",
                $"give --light NAME=SPECTRUM, --intensity NAME=F or --white; lights: {string.Join(", ", src.LightNames)}");
        var outDir = a.Value("--out") ?? dir.TrimEnd('/', '\\') + "-relit";
        // The folder is checked, locked and staged by the write itself (OutputFolder): nothing is made under its name before
        // the relit render is swapped in whole.
        var (scene, files, compute) =
            Relighter.Write(src, byName.Values.ToList(), whiteArg, outDir, commandLine, Signals.Token, metrics: a.Flag("--metrics"));
        if (a.Flag("--metrics")) stdout.Write(File.ReadAllText(Path.Combine(outDir, "relight-metrics.csv")));
        if (!quiet)
            stderr.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"relit {scene.Camera.Width}×{scene.Camera.Height}, {scene.Bands} bands "
                    + $"({string.Join(", ", byName.Values.Select(Describe))}{(whiteArg is null ? "" : $", white {whiteArg}")}) in "
                    + $"{compute.TotalSeconds:0.###} s; wrote {files.Count} files to {outDir}; "
                    + $"{clock.Elapsed.TotalSeconds:0.##} s in all"));
        return CommandLine.Success;
    }

    static string Describe(LightChange c) =>
        c.Light + (c.Spectrum is null ? "" : "=" + c.Spectrum)
            + (c.Intensity is null ? "" : string.Create(CultureInfo.InvariantCulture, $" ×{c.Intensity}"));

    static (string, string) Split(string v, string option, string hint)
    {
        int eq = v.IndexOf('=');
        if (eq <= 0 || eq == v.Length - 1) throw new InputException(option, $"'{v}' is not NAME=VALUE", hint);
        return (v[..eq].Trim(), v[(eq + 1)..].Trim());
    }
}
