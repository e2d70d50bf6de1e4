using System.Globalization;
using System.Net;
using System.Text;
using System.Text.Json;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Validation;

/// <summary>
/// What `spectral validate` writes: report.html (self-contained — inline CSS and SVG plots, no script, no external
/// resource: a summary table, then per case its reference and source, tolerance and why, a plot of the error against the
/// position, band or angle, and its points), results.json (every case and point, for machines; <see cref="Json"/>) and
/// results.csv (one row per point).
/// </summary>
public static class ValidationReport
{
    public const string Html = "report.html", JsonFile = "results.json", Csv = "results.csv";

    /// <summary>The files' names, in the order they are written.</summary>
    public static readonly string[] Files = [Html, JsonFile, Csv];

    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    static string N(double v) => double.IsFinite(v) ? v.ToString("R", Inv) : "";

    static string G(double v, int digits = 6) => double.IsFinite(v) ? v.ToString("G" + digits, Inv) : "n/a";

    /// <summary>Writes the three files into <paramref name="folder"/> (each atomically).</summary>
    public static void Write(string folder, IReadOnlyList<CaseResult> results, bool quick, string version, bool mitsuba = false)
    {
        AtomicFile.WriteAllText(Path.Combine(folder, Html), ToHtml(results, quick, version, mitsuba));
        AtomicFile.WriteAllText(Path.Combine(folder, JsonFile), Json(results, quick, version, mitsuba));
        AtomicFile.WriteAllText(Path.Combine(folder, Csv), ToCsv(results));
    }

    /// <summary>results.json: the version, quick or full, and per case its statement (reference, source, tolerance and
    /// why, statistical), its outcome (max and RMS error, pass, seconds, failure) and its points.</summary>
    public static string Json(IReadOnlyList<CaseResult> results, bool quick, string version, bool mitsuba = false)
    {
        using var stream = new MemoryStream();
        using (var w = new Utf8JsonWriter(stream, new JsonWriterOptions { Indented = true }))
        {
            w.WriteStartObject();
            w.WriteString("tool", "spectral validate");
            w.WriteString("version", version);
            w.WriteBoolean("quick", quick);
            w.WriteBoolean("passed", results.All(r => r.Passed));
            // The optional comparisons with Mitsuba 3, when they were not asked for: named, and why not.
            w.WriteStartArray("not_run");
            if (!mitsuba)
                foreach (var n in MitsubaCases.Names)
                {
                    w.WriteStartObject();
                    w.WriteString("name", n);
                    w.WriteString("why", NotRun);
                    w.WriteEndObject();
                }
            w.WriteEndArray();
            w.WriteStartArray("cases");
            foreach (var r in results)
            {
                var c = r.Case;
                w.WriteStartObject();
                w.WriteString("name", c.Name);
                w.WriteString("group", c.Group);
                w.WriteString("title", c.Title);
                w.WriteString("reference", c.Reference);
                w.WriteString("source", c.Source);
                w.WriteString("quantity", c.Quantity);
                w.WriteString("x", c.XLabel);
                w.WriteString("error_unit", c.ErrorUnit);
                w.WriteNumber("tolerance", c.Tolerance);
                w.WriteString("tolerance_why", c.ToleranceWhy);
                w.WriteBoolean("statistical", c.Statistical);
                w.WriteBoolean("passed", r.Passed);
                Number(w, "max_error", r.MaxError);
                Number(w, "rms_error", r.RmsError);
                w.WriteNumber("seconds", Math.Round(r.Seconds, 3));
                if (r.Failure is not null) w.WriteString("failure", r.Failure);
                w.WriteStartArray("points");
                foreach (var p in r.Points)
                {
                    w.WriteStartObject();
                    Number(w, "x", p.X);
                    w.WriteString("label", p.Label);
                    Number(w, "expected", p.Expected);
                    Number(w, "measured", p.Measured);
                    Number(w, "error", p.Error);
                    if (p.Sigma is { } s) Number(w, "sigma", s);
                    w.WriteBoolean("passed", c.Passes(p));
                    w.WriteEndObject();
                }
                w.WriteEndArray();
                w.WriteEndObject();
            }
            w.WriteEndArray();
            w.WriteEndObject();
        }
        return Encoding.UTF8.GetString(stream.ToArray()) + "\n";
    }

    static void Number(Utf8JsonWriter w, string name, double v)
    {
        if (double.IsFinite(v)) w.WriteNumber(name, v);
        else w.WriteNull(name);
    }

    /// <summary>results.csv: one row per point.</summary>
    public static string ToCsv(IReadOnlyList<CaseResult> results)
    {
        var sb = new StringBuilder("case,group,x,label,expected,measured,error,error_unit,sigma,tolerance,passed\n");
        foreach (var r in results)
            foreach (var p in r.Points)
                sb.Append(Inv, $"{r.Case.Name},{r.Case.Group},{N(p.X)},{CsvText(p.Label)},{N(p.Expected)},{N(p.Measured)},{N(p.Error)},")
                    .Append(Inv, $"{CsvText(r.Case.ErrorUnit)},{(p.Sigma is { } s ? N(s) : "")},{N(r.Case.Tolerance)},")
                    .Append(r.Case.Passes(p) ? "true" : "false").Append('\n');
        return sb.ToString();
    }

    static string CsvText(string s) => s.IndexOfAny([',', '"', '\n']) >= 0 ? "\"" + s.Replace("\"", "\"\"") + "\"" : s;

    static string E(string s) => WebUtility.HtmlEncode(s);

    /// <summary>Why the comparisons with Mitsuba 3 are not in a report run without <c>--mitsuba</c>.</summary>
    const string NotRun = "not run: each needs --mitsuba PYTHON (a Python that imports mitsuba and numpy)";

    /// <summary>report.html.</summary>
    public static string ToHtml(IReadOnlyList<CaseResult> results, bool quick, string version, bool mitsuba = false)
    {
        int passed = results.Count(r => r.Passed);
        var sb = new StringBuilder();
        sb.Append("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n")
            .Append($"<title>spectral validate {E(version)}</title>\n")
            .Append("""
                <style>
                body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1100px; padding: 0 1em; color: #222; }
                table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
                th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: left; vertical-align: top; }
                td.n { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
                .pass { color: #1a7f37; font-weight: bold; } .fail { color: #c62828; font-weight: bold; }
                section.case { border-top: 2px solid #ddd; margin-top: 2em; }
                dl { display: grid; grid-template-columns: max-content auto; gap: 2px 12px; }
                dt { font-weight: bold; } dd { margin: 0; }
                svg { max-width: 100%; height: auto; }
                </style>

                """)
            .Append("</head>\n<body>\n")
            .Append($"<h1>spectral validate — {E(version)}</h1>\n")
            .Append($"<p id=\"summary\">{passed} of {results.Count} cases within their stated tolerance"
                + $"{(quick ? " (the quick set: fewer points and samples)" : "")}. Each case builds a small scene in memory, "
                + "measures it with the engine and compares it point by point with a reference computed independently in closed "
                + "form or from a published table. A sampled (Monte Carlo) case passes when every point is within its tolerance "
                + "and within 3σ of its reference (σ the standard error of the estimate).</p>\n")
            .Append(mitsuba ? "" : $"<p id=\"not-run\">The comparisons with Mitsuba 3 ({string.Join(", ", MitsubaCases.Names)}): "
                + $"{E(NotRun)}.</p>\n")
            .Append("<table id=\"cases\">\n<tr><th>case</th><th>group</th><th>reference</th><th>tolerance</th><th>max |error|</th>"
                + "<th>RMS error</th><th>max σ</th><th>time (s)</th><th>result</th></tr>\n");
        foreach (var r in results)
        {
            var c = r.Case;
            sb.Append($"<tr><td><a href=\"#{c.Name}\">{E(c.Name)}</a></td><td>{E(c.Group)}</td><td>{E(c.Reference)}</td>")
                .Append($"<td class=\"n\">{E(Format.Error(c, c.Tolerance))}</td><td class=\"n\">{E(Format.Error(c, r.MaxError))}</td>")
                .Append($"<td class=\"n\">{E(Format.Error(c, r.RmsError))}</td>")
                .Append($"<td class=\"n\">{(r.MaxSigma is { } s ? E(Format.Error(c, s)) : "—")}</td>")
                .Append($"<td class=\"n\">{r.Seconds.ToString("F2", Inv)}</td>")
                .Append($"<td class=\"{(r.Passed ? "pass" : "fail")}\">{(r.Passed ? "pass" : "FAIL")}</td></tr>\n");
        }
        sb.Append("</table>\n");
        foreach (var r in results) Section(sb, r);
        sb.Append("</body>\n</html>\n");
        return sb.ToString();
    }

    static void Section(StringBuilder sb, CaseResult r)
    {
        var c = r.Case;
        sb.Append($"<section class=\"case\" id=\"{c.Name}\">\n<h2>{E(c.Name)}: <span class=\"{(r.Passed ? "pass" : "fail")}\">")
            .Append($"{(r.Passed ? "pass" : "FAIL")}</span></h2>\n<p>{E(c.Title)}</p>\n<dl>\n")
            .Append($"<dt>reference</dt><dd>{E(c.Reference)}</dd>\n<dt>source</dt><dd>{E(c.Source)}</dd>\n")
            .Append($"<dt>tolerance</dt><dd>{E(Format.Error(c, c.Tolerance))} ({E(c.ErrorUnit)} error"
                + $"{(c.Statistical ? ", and within 3σ" : "")}): {E(c.ToleranceWhy)}</dd>\n")
            .Append($"<dt>measured</dt><dd>max |error| {E(Format.Error(c, r.MaxError))}, RMS {E(Format.Error(c, r.RmsError))}, "
                + $"{r.Points.Count} points, {r.Seconds.ToString("F2", Inv)} s</dd>\n");
        if (r.Failure is not null) sb.Append($"<dt>failure</dt><dd class=\"fail\">{E(r.Failure)}</dd>\n");
        sb.Append("</dl>\n");
        if (r.Points.Count > 1) sb.Append(Plot(r)).Append('\n');
        sb.Append($"<table class=\"points\">\n<tr><th>{E(c.XLabel)}</th><th>expected: {E(c.Quantity)}</th><th>measured</th>")
            .Append($"<th>error ({E(c.ErrorUnit)})</th>{(c.Statistical ? "<th>σ</th>" : "")}<th>result</th></tr>\n");
        foreach (var p in r.Points)
        {
            bool ok = c.Passes(p);
            sb.Append($"<tr><td>{E(p.Label)}</td><td class=\"n\">{G(p.Expected, 8)}</td><td class=\"n\">{G(p.Measured, 8)}</td>")
                .Append($"<td class=\"n\">{E(Format.Error(c, p.Error))}</td>")
                .Append(c.Statistical ? $"<td class=\"n\">{(p.Sigma is { } s ? E(Format.Error(c, s)) : "—")}</td>" : "")
                .Append($"<td class=\"{(ok ? "pass" : "fail")}\">{(ok ? "pass" : "FAIL")}</td></tr>\n");
        }
        sb.Append("</table>\n</section>\n");
    }

    /// <summary>The error against the case's axis, with ±3σ for a sampled case and the tolerance when it is in scale.</summary>
    static string Plot(CaseResult r)
    {
        var c = r.Case;
        var points = r.Points.OrderBy(p => p.X).ToList();
        var x = points.Select(p => p.X).ToArray();
        var plot = new SvgPlot
        {
            Title = $"{c.Name}: error against {c.XLabel}",
            XLabel = c.XLabel,
            YLabel = c.ErrorKind == ErrorKind.Relative ? "relative error" : $"error ({c.AbsoluteUnit})",
            YFromZero = true,
            Width = 760,
            Height = 360,
        };
        plot.Add("error", x, points.Select(p => p.Error).ToArray());
        double scale = points.Max(p => Math.Max(Math.Abs(p.Error), 3 * (p.Sigma ?? 0)));
        if (c.Statistical && points.Any(p => p.Sigma is not null))
        {
            plot.Add("+3σ", x, points.Select(p => 3 * (p.Sigma ?? 0)).ToArray(), dashed: true);
            plot.Add("−3σ", x, points.Select(p => -3 * (p.Sigma ?? 0)).ToArray(), dashed: true);
        }
        if (!(scale < c.Tolerance / 20))
        {
            plot.Add("+tolerance", x, x.Select(_ => c.Tolerance).ToArray(), dashed: true);
            if (c.ErrorKind == ErrorKind.Relative) plot.Add("−tolerance", x, x.Select(_ => -c.Tolerance).ToArray(), dashed: true);
        }
        var svg = plot.ToSvg();
        int start = svg.IndexOf("<svg", StringComparison.Ordinal);
        return start >= 0 ? svg[start..] : svg;
    }
}
