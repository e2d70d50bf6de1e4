namespace SpectralRenderer.Validation;

/// <summary>How a case's error is expressed: relative to the expected value, or in the quantity's own unit (ΔE00).</summary>
public enum ErrorKind { Relative, Absolute }

/// <summary>
/// One compared point of a case: where it is (<paramref name="X"/> on the plot's axis and a label: a position, a band,
/// an angle), the closed-form value, the engine's, their error (relative or absolute, as the case states) and, for a
/// sampled measurement, the standard error of that error (null: deterministic).
/// </summary>
public sealed record ValidationPoint(double X, string Label, double Expected, double Measured, double Error, double? Sigma)
{
    /// <summary>A point whose error is (measured − expected)/expected, its standard error σ/expected.</summary>
    public static ValidationPoint Relative(double x, string label, double expected, double measured, double? sigma = null) =>
        new(x, label, expected, measured, (measured - expected) / expected, sigma / Math.Abs(expected));

    /// <summary>A point whose error is given in the quantity's unit (ΔE00 of a colour).</summary>
    public static ValidationPoint Absolute(double x, string label, double expected, double measured, double error) =>
        new(x, label, expected, measured, error, null);
}

/// <summary>What a case's <see cref="ValidationCase.Measure"/> is given: the reduced set or the full one, threads, cancellation.</summary>
public sealed record CaseContext(bool Quick, int Threads, CancellationToken Cancel);

/// <summary>
/// A validation case: a small scene built in memory through the engine's public API, rendered or gathered, and compared
/// point by point with a reference computed independently in closed form (or from a published table) — never the
/// engine against itself. It states the reference (formula and source), its tolerance and why, and for sampled cases
/// that each point must also be within 3σ of the reference (<see cref="Statistical"/>).
/// </summary>
public sealed class ValidationCase
{
    /// <summary>The case's name (lower-case words and '-'), what `--case` selects.</summary>
    public required string Name { get; init; }
    /// <summary>lighting, radiometry, colour, camera, or interop (the comparisons with Mitsuba 3).</summary>
    public required string Group { get; init; }
    /// <summary>One line: what is set up and measured.</summary>
    public required string Title { get; init; }
    /// <summary>The reference's formula, as the report prints it.</summary>
    public required string Reference { get; init; }
    /// <summary>Where the formula comes from (a standard's section, a paper, a textbook).</summary>
    public required string Source { get; init; }
    /// <summary>The largest |error| a point may have (relative, or in the unit of <see cref="ErrorUnit"/>).</summary>
    public required double Tolerance { get; init; }
    /// <summary>Why the tolerance is what it is.</summary>
    public required string ToleranceWhy { get; init; }
    /// <summary>The plot's horizontal axis: what <see cref="ValidationPoint.X"/> is.</summary>
    public required string XLabel { get; init; }
    /// <summary>The compared quantity and its unit ("illuminance (lx)").</summary>
    public required string Quantity { get; init; }
    public ErrorKind ErrorKind { get; init; } = ErrorKind.Relative;
    /// <summary>The error's unit in the report ("relative" or "ΔE00").</summary>
    public string ErrorUnit => ErrorKind == ErrorKind.Relative ? "relative" : AbsoluteUnit;
    /// <summary>The unit of an absolute error.</summary>
    public string AbsoluteUnit { get; init; } = "";
    /// <summary>A sampled (Monte Carlo) measurement: each point is also within 3σ (+ <see cref="Floor"/>) of its reference.</summary>
    public bool Statistical { get; init; }
    /// <summary>The measurement: the compared points.</summary>
    public required Func<CaseContext, IReadOnlyList<ValidationPoint>> Measure { get; init; }

    /// <summary>
    /// An error this small is never a 3σ failure: the float32 arithmetic of the engine's geometry and radiance, and the
    /// luminance of a sampled emitter from its band means (Σ_b S̄_b·K_m∫_b V dλ for K_m∫V·S dλ: 8e-5 for D65 on 10 nm
    /// bands), which are below any sampled case's tolerance and not noise.
    /// </summary>
    public const double Floor = 2e-4;

    /// <summary>Whether one point is within the case's tolerance (and, sampled, within 3σ + <see cref="Floor"/>).</summary>
    public bool Passes(ValidationPoint p) =>
        double.IsFinite(p.Error) && Math.Abs(p.Error) <= Tolerance
            && (!Statistical || p.Sigma is not { } s || Math.Abs(p.Error) <= 3 * s + Floor);
}

/// <summary>A case's outcome: its points, the largest and RMS |error|, pass/fail, the seconds it took, or what went wrong.</summary>
public sealed record CaseResult(ValidationCase Case, IReadOnlyList<ValidationPoint> Points, double MaxError, double RmsError,
    bool Passed, double Seconds, string? Failure)
{
    /// <summary>The largest σ of the points (sampled cases), else null.</summary>
    public double? MaxSigma => Points.Where(p => p.Sigma is not null).Select(p => p.Sigma!.Value).DefaultIfEmpty(double.NaN).Max()
        is var s && double.IsNaN(s) ? null : s;
}
