using System.Diagnostics;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Validation;

/// <summary>Runs cases one after the other and judges each against its tolerance (<see cref="ValidationCase.Passes"/>).</summary>
public static class ValidationRun
{
    /// <summary>
    /// Each case measured and judged, in order; <paramref name="progress"/> hears a line as each starts and ends. A case
    /// that throws fails with the exception's message (the others still run); cancellation stops the run.
    /// </summary>
    public static IReadOnlyList<CaseResult> Run(IEnumerable<ValidationCase> cases, CaseContext context, Action<string>? progress = null)
    {
        var list = cases.ToList();
        var results = new List<CaseResult>();
        for (int i = 0; i < list.Count; i++)
        {
            context.Cancel.ThrowIfCancellationRequested();
            var c = list[i];
            progress?.Invoke($"[{i + 1}/{list.Count}] {c.Name}: {c.Title}");
            var r = One(c, context);
            results.Add(r);
            progress?.Invoke($"[{i + 1}/{list.Count}] {c.Name}: {(r.Passed ? "pass" : "FAIL")}, max |error| "
                + $"{Format.Error(c, r.MaxError)} (tolerance {Format.Error(c, c.Tolerance)}), {r.Seconds:F1} s"
                + (r.Failure is null ? "" : $": {r.Failure}"));
        }
        return results;
    }

    /// <summary>One case measured and judged.</summary>
    public static CaseResult One(ValidationCase c, CaseContext context)
    {
        var clock = Stopwatch.StartNew();
        try
        {
            var points = c.Measure(context);
            double seconds = clock.Elapsed.TotalSeconds;
            if (points.Count == 0) return new(c, points, double.NaN, double.NaN, false, seconds, "no points were measured");
            double max = points.Max(p => Math.Abs(p.Error));
            if (points.Any(p => !double.IsFinite(p.Error))) max = double.NaN;
            double rms = Math.Sqrt(points.Average(p => p.Error * p.Error));
            return new(c, points, max, rms, points.All(c.Passes), seconds, null);
        }
        catch (Exception e) when (e is not OperationCanceledException)
        {
            return new(c, [], double.NaN, double.NaN, false, clock.Elapsed.TotalSeconds,
                e is InputException or WorkFailedException ? e.Message : $"{e.GetType().Name}: {e.Message}");
        }
    }
}

/// <summary>How errors and numbers read in the progress lines and the report.</summary>
public static class Format
{
    /// <summary>An error in the case's unit: relative as a percentage with its exponent, absolute with its unit.</summary>
    public static string Error(ValidationCase c, double e) =>
        !double.IsFinite(e) ? "n/a"
        : c.ErrorKind == ErrorKind.Relative ? e.ToString("0.00E+0", System.Globalization.CultureInfo.InvariantCulture)
        : $"{e.ToString("0.0000", System.Globalization.CultureInfo.InvariantCulture)} {c.AbsoluteUnit}";
}
