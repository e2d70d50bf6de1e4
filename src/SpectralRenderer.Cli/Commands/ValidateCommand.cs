using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;
using SpectralRenderer.Validation;

namespace SpectralRenderer.Cli.Commands;

/// <summary>
/// `spectral validate`: the documented validation cases (<see cref="ValidationCases"/>) measured and judged against their
/// closed-form references, written as report.html, results.json and results.csv (one folder transaction); exit 1 when a
/// case is outside its stated tolerance.
/// </summary>
public static class ValidateCommand
{
    const string Help = """
        usage: spectral validate [-o DIR] [--quick] [--case NAME]... [--list] [--threads N] [--quiet]
                                 [--mitsuba PYTHON [--mitsuba-script FILE]]

        The tool's own accuracy, in its users' terms (docs/validation.md): CIE 171:2006-style lighting cases (a point
        source over a plane out to grazing angles, Lambertian rectangles by their form factors, a closed box and an
        integrating sphere by flux balance, a uniform and a CIE overcast sky on horizontal and vertical planes and
        through a roof opening and a window, luminous flux over closed surfaces, IES and EULUMDAT candela read back),
        radiometry and transport (furnaces, inverse square, a conductor from n and k, Sellmeier dispersion), colour (the
        ColorChecker against the CIE 1 nm summation) and the camera (cos⁴ fall-off, the Airy kernel, the EMVA 1288
        photon transfer). Each case builds a small scene in memory, measures it with the engine and compares each point
        with a reference computed independently in closed form; a sampled case must also be within 3σ. Writes
        DIR/report.html (self-contained: tables and a plot of the error per case), DIR/results.json and DIR/results.csv;
        progress on stderr. Exit 0 when every case is within its tolerance, 1 when one is not (the report says which), 2
        for bad input.

          -o DIR        output folder (default: out/validation); only these three files in it are replaced
          --quick       fewer points and samples per case (under a minute on two cores)
          --case NAME   only this case (repeat for more); --list names them
          --list        print the cases (name, group, title) and exit
          --threads N   worker threads (default: all cores)
          --quiet       no progress lines
          --mitsuba PYTHON  also the converged comparisons with Mitsuba 3 (the Cornell room's and the material
                        preview's region means; a few minutes): PYTHON imports mitsuba and numpy (the anchors' venv) and
                        runs scripts/compare-mitsuba.py of the source checkout the tool is in (or the working directory)
          --mitsuba-script FILE  that script, when the tool is not in a checkout
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("validate", argv, ["--out", "--case", "--threads", "--mitsuba", "--mitsuba-script"],
            ["--quick", "--list", "--quiet"],
            new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count > 0)
            throw new InputException("command line", $"unexpected argument {MessageText.Quote(a.Positionals[0])}",
                "see 'spectral validate --help'");
        if (a.Flag("--list"))
        {
            foreach (var c in ValidationCases.All) stdout.WriteLine($"{c.Name,-26} {c.Group,-11} {c.Title}");
            foreach (var c in MitsubaCases.For(new MitsubaAnchor("", "", "")))   // (their titles: nothing is run)
                stdout.WriteLine($"{c.Name,-26} {c.Group,-11} (with --mitsuba PYTHON) {c.Title}");
            return CommandLine.Success;
        }
        if (a.Value("--mitsuba-script") is not null && a.Value("--mitsuba") is null)
            throw new InputException("--mitsuba-script", "is given without --mitsuba PYTHON", "add --mitsuba PYTHON");
        var anchor = a.Value("--mitsuba") is { } python
            ? MitsubaAnchor.Resolve(python, a.Value("--mitsuba-script"), SpectralCommand(),
                [AppContext.BaseDirectory, Directory.GetCurrentDirectory()])
            : null;
        var cases = ValidationCases.Select([.. a.Values("--case").SelectMany(v => v.Split(',', StringSplitOptions.RemoveEmptyEntries))],
            anchor);
        int threads = a.Int("--threads", 1, 1024) ?? Environment.ProcessorCount;
        bool quick = a.Flag("--quick"), quiet = a.Flag("--quiet");
        var outDir = a.Value("--out") ?? Path.Combine("out", "validation");
        using var folder = OutputFolder.BeginFiles(outDir, ValidationReport.Files, "validation report");
        var results = ValidationRun.Run(cases, new CaseContext(quick, threads, Signals.Token), quiet ? null : stderr.WriteLine);
        ValidationReport.Write(folder.Staging, results, quick, CommandLine.Version, mitsuba: anchor is not null);
        folder.Commit(ValidationReport.Files);
        var failed = results.Where(r => !r.Passed).ToList();
        double seconds = results.Sum(r => r.Seconds);
        stdout.WriteLine($"{results.Count - failed.Count} of {results.Count} cases within tolerance in {seconds:F1} s; "
            + $"wrote {Path.Combine(folder.Final, ValidationReport.Html)}, {ValidationReport.JsonFile}, {ValidationReport.Csv}");
        if (failed.Count == 0) return CommandLine.Success;
        stderr.WriteLine($"spectral validate: {failed.Count} case{(failed.Count == 1 ? " is" : "s are")} outside the stated tolerance: "
            + string.Join(", ", failed.Select(r => r.Case.Name)) + " (see report.html)");
        return CommandLine.Failure;
    }

    /// <summary>
    /// This tool as compare-mitsuba.py runs it: the executable when the process is spectral itself (the apphost, a published
    /// or single-file binary), else the spectral.dll beside this code (run by dotnet: `dotnet spectral.dll`, a test host).
    /// </summary>
    static string SpectralCommand()
    {
        var process = Environment.ProcessPath;
        if (process is not null && Path.GetFileNameWithoutExtension(process).Equals("spectral", StringComparison.OrdinalIgnoreCase))
            return process;
        var dll = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        return File.Exists(dll) ? dll : process ?? "spectral";
    }
}
