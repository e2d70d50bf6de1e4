using System.ComponentModel;
using System.Diagnostics;
using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Validation;

/// <summary>
/// What <c>spectral validate --mitsuba PYTHON</c> runs the comparisons with: a Python that imports Mitsuba 3 and NumPy (the
/// anchors' venv; the engine never depends on it, it is run as a subprocess), the repository's scripts/compare-mitsuba.py,
/// and our CLI as that script runs it (<see cref="Spectral"/>: a spectral.dll, run by dotnet, or an executable).
/// </summary>
public sealed record MitsubaAnchor(string Python, string Script, string Spectral)
{
    /// <summary>The script's path in a source checkout.</summary>
    public static readonly string ScriptPath = Path.Combine("scripts", "compare-mitsuba.py");

    /// <summary>
    /// The anchor of <paramref name="python"/>, checked: it runs and imports mitsuba and numpy (else bad input of
    /// <c>--mitsuba</c>); the script <paramref name="script"/> if given, else the first scripts/compare-mitsuba.py in or above
    /// one of <paramref name="searchFrom"/> (the tool's folder, the working directory).
    /// </summary>
    public static MitsubaAnchor Resolve(string python, string? script, string spectral, IEnumerable<string> searchFrom)
    {
        const string hint = "give a Python with Mitsuba 3 and NumPy: the anchors' venv (../shared/anchors/setup.sh), VENV/bin/python";
        var (exit, stdout, stderr) = RunProcess(python, ["-c", "import mitsuba, numpy; print('mitsuba', mitsuba.__version__)"],
            TimeSpan.FromMinutes(2), default, out string? startFailure);
        if (startFailure is not null)
            throw new InputException("--mitsuba", $"cannot run {MessageText.Quote(python)} (not found, or not executable)", hint);
        if (exit != 0 || !stdout.StartsWith("mitsuba ", StringComparison.Ordinal))
        {
            var last = stderr.Split('\n', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries).LastOrDefault();
            throw new InputException("--mitsuba", $"{MessageText.Quote(python)} is not a Python that imports mitsuba and numpy"
                + (last is null ? $" (exit {exit})" : $": {MessageText.Quote(last, 120)}"), hint);
        }
        if (script is not null)
        {
            if (!File.Exists(script))
                throw new InputException("--mitsuba-script", $"{MessageText.Quote(script)} is not a file",
                    $"give the path of {ScriptPath} in a source checkout of SpectralRenderer");
            return new MitsubaAnchor(python, Path.GetFullPath(script), spectral);
        }
        foreach (var start in searchFrom)
            for (var dir = new DirectoryInfo(start); dir is not null; dir = dir.Parent)
                if (File.Exists(Path.Combine(dir.FullName, ScriptPath)))
                    return new MitsubaAnchor(python, Path.Combine(dir.FullName, ScriptPath), spectral);
        throw new InputException("--mitsuba", $"{ScriptPath} is not in or above the tool's folder or the working directory",
            $"run spectral validate --mitsuba from a source checkout, or give the script: --mitsuba-script PATH/{ScriptPath}");
    }

    /// <summary>Runs <paramref name="file"/> with <paramref name="args"/>: exit code, stdout, stderr (killed on timeout or
    /// cancellation); <paramref name="startFailure"/> says why it could not start (then the exit is −1).</summary>
    internal static (int Exit, string Out, string Err) RunProcess(string file, IEnumerable<string> args, TimeSpan timeout,
        CancellationToken cancel, out string? startFailure)
    {
        var info = new ProcessStartInfo(file) { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var a in args) info.ArgumentList.Add(a);
        startFailure = null;
        Process? p;
        try { p = Process.Start(info); }
        catch (Exception e) when (e is Win32Exception or InvalidOperationException)
        {
            startFailure = e.Message;
            return (-1, "", "");
        }
        if (p is null) { startFailure = "the process did not start"; return (-1, "", ""); }
        using (p)
        {
            var stdout = p.StandardOutput.ReadToEndAsync(CancellationToken.None);
            var stderr = p.StandardError.ReadToEndAsync(CancellationToken.None);
            using var limit = CancellationTokenSource.CreateLinkedTokenSource(cancel);
            limit.CancelAfter(timeout);
            try { p.WaitForExitAsync(limit.Token).GetAwaiter().GetResult(); }
            catch (OperationCanceledException)
            {
                p.Kill(entireProcessTree: true);
                p.WaitForExit();
                cancel.ThrowIfCancellationRequested();
                throw new WorkFailedException(
                    $"{Path.GetFileName(file)} {string.Join(' ', args.Take(2))}: no result in {timeout.TotalMinutes:F0} min");
            }
            return (p.ExitCode, stdout.GetAwaiter().GetResult(), stderr.GetAwaiter().GetResult());
        }
    }
}

/// <summary>
/// The optional converged comparisons with Mitsuba 3, an independent spectral renderer (<c>--mitsuba PYTHON</c>): the
/// Cornell-like room (scenes/path-cornell-room.json, the same tabulated spectra, geometry, pinhole camera and box filter given
/// to Mitsuba) and the material preview (scenes/mitsuba-material-preview.xml: conductors, glass and a diffuse ball under an
/// environment map, Mitsuba loading the file and we importing it). scripts/compare-mitsuba.py renders each with both, in
/// independent parts (seeds), and prints per region (the objects seen, the image's quadrants) the radiance over the band range
/// of each and the standard error of their ratio from the parts; each region is a point, Mitsuba's value the reference.
/// </summary>
public static class MitsubaCases
{
    /// <summary>The cases' names (what <c>--case</c> selects once <c>--mitsuba</c> is given).</summary>
    public static IReadOnlyList<string> Names { get; } = ["mitsuba-cornell-room", "mitsuba-material-preview"];

    /// <summary>The cases run through <paramref name="anchor"/>.</summary>
    public static IReadOnlyList<ValidationCase> For(MitsubaAnchor anchor) => [CornellRoom(anchor), MaterialPreview(anchor)];

    static ValidationCase CornellRoom(MitsubaAnchor anchor) => Comparison("mitsuba-cornell-room",
        "the Cornell-like room (scenes/path-cornell-room.json) rendered by our path tracer and by Mitsuba 3 "
            + "(scalar_spectral) from the same spectra and geometry: each region's radiance over 380–780 nm",
        "Mitsuba 3 (Jakob, Speierer, Roussel et al. 2022), scripts/compare-mitsuba.py --regions-only",
        "(the converged comparison agrees within 1 %: BENCHMARKS.md)",
        context => Compare(anchor, context, ["--scene", Path.Combine(Root(anchor), "scenes", "path-cornell-room.json"),
            "--width", "32", "--height", "24", "--ref-spp", context.Quick ? "1024" : "4096", "--parts", "8"]));

    static ValidationCase MaterialPreview(MitsubaAnchor anchor) => Comparison("mitsuba-material-preview",
        "the material preview (scenes/mitsuba-material-preview.xml: smooth and rough conductors, glass, a diffuse ball "
            + "under an environment map) rendered by Mitsuba 3 (scalar_spectral) from the file and by us through the importer",
        "Mitsuba 3 (Jakob, Speierer, Roussel et al. 2022), scripts/compare-mitsuba.py --xml; docs/import.md",
        "(Mitsuba renders 0.2–0.6 % lower in most regions, a cause not found yet: docs/import.md)",
        context => Compare(anchor, context, ["--xml", Path.Combine(Root(anchor), "scenes", "mitsuba-material-preview.xml"),
            "--xml-bands", "380:780:10", "--width", "32", "--height", "24", "--ref-spp", context.Quick ? "2048" : "8192",
            "--parts", "8"]));

    /// <summary>A comparison with Mitsuba 3: each region's radiance over the band range, within 2 % and 3σ.</summary>
    static ValidationCase Comparison(string name, string title, string source, string converged,
        Func<CaseContext, IReadOnlyList<ValidationPoint>> measure) => new()
        {
            Name = name,
            Group = "interop",
            Title = title,
            Reference = "Mitsuba 3's path tracer on the same scene (its spectral film's bands integrated as our band means)",
            Source = source,
            Tolerance = 0.02,
            ToleranceWhy = "two sampled renderers: within 3σ of the two estimates' standard error (σ from the spread of the "
                + "independent parts), and no region off by more than 2 % " + converged,
            XLabel = "region (objects seen, then the image's quadrants)",
            Quantity = "radiance over the band range (W·m⁻²·sr⁻¹)",
            Statistical = true,
            Measure = measure,
        };

    /// <summary>The checkout the script lies in (scripts/…).</summary>
    static string Root(MitsubaAnchor anchor) => Path.GetDirectoryName(Path.GetDirectoryName(anchor.Script))!;

    /// <summary>The script's region comparison (scalar_spectral), its TOTAL lines as points: Mitsuba's the reference, ours
    /// the measurement, σ the standard error of the ratio.</summary>
    static IReadOnlyList<ValidationPoint> Compare(MitsubaAnchor anchor, CaseContext context, string[] args)
    {
        var (exit, stdout, stderr) = MitsubaAnchor.RunProcess(anchor.Python,
            [anchor.Script, "--regions-only", "--variant", "scalar_spectral", "--spectral", anchor.Spectral, .. args],
            TimeSpan.FromMinutes(30), context.Cancel, out var startFailure);
        if (startFailure is not null || exit != 0)
        {
            var last = stderr.Split('\n', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries).LastOrDefault();
            throw new WorkFailedException($"compare-mitsuba.py failed ({startFailure ?? $"exit {exit}"}): {last}");
        }
        var points = new List<ValidationPoint>();
        foreach (var line in stdout.Split('\n'))
        {
            if (!line.StartsWith("TOTAL ", StringComparison.Ordinal)) continue;
            var f = line[6..].Split(' ', StringSplitOptions.RemoveEmptyEntries).Select(kv => kv.Split('=', 2))
                .ToDictionary(kv => kv[0], kv => kv[1]);
            double D(string k) => double.Parse(f[k], CultureInfo.InvariantCulture);
            double ours = D("ours"), mitsuba = D("mitsuba");
            points.Add(ValidationPoint.Relative(points.Count, f["region"].Replace('_', ' '), mitsuba, ours, D("se") * ours));
        }
        return points;
    }
}
