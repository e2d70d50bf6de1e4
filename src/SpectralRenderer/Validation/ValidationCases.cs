using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Validation;

/// <summary>
/// The validation cases, in the report's order: each family of cases is one file (lighting, interreflection,
/// luminaires, radiometry and transport, colour, camera) and one line here.
/// </summary>
public static class ValidationCases
{
    /// <summary>Every case.</summary>
    public static IReadOnlyList<ValidationCase> All { get; } =
    [
        .. LightingCases.All,
        .. InterreflectionCases.All,
        .. LuminaireCases.All,
        .. RadiometryCases.All,
        .. ColourCases.All,
        .. CameraCases.All,
    ];

    /// <summary>The cases named (each once, in the registry's order; none named: all), and with <paramref name="mitsuba"/> the
    /// comparisons with Mitsuba 3 (<see cref="MitsubaCases"/>) after them; an unknown name is bad input naming the closest
    /// and pointing to the list, a Mitsuba case without <paramref name="mitsuba"/> bad input asking for it.</summary>
    public static IReadOnlyList<ValidationCase> Select(IReadOnlyCollection<string> names, MitsubaAnchor? mitsuba = null)
    {
        IReadOnlyList<ValidationCase> optional = mitsuba is null ? [] : MitsubaCases.For(mitsuba);
        if (names.Count == 0) return [.. All, .. optional];
        foreach (var n in names)
            if (mitsuba is null && MitsubaCases.Names.Contains(n))
                throw new InputException("--case", $"{MessageText.Quote(n)} compares with Mitsuba 3 and needs --mitsuba PYTHON",
                    "add --mitsuba PYTHON (a Python that imports mitsuba and numpy: the anchors' venv)");
        foreach (var n in names)
            if (!All.Any(c => c.Name == n) && !optional.Any(c => c.Name == n))
                throw new InputException("--case", $"no validation case is called {MessageText.Quote(n, 60)}",
                    (InputException.DidYouMean(n, All.Select(c => c.Name).Concat(MitsubaCases.Names)) is { } guess ? guess + " " : "")
                        + $"('spectral validate --list' names all {All.Count}: {string.Join(", ", All.Select(c => c.Group).Distinct())})");
        return [.. All.Where(c => names.Contains(c.Name)), .. optional.Where(c => names.Contains(c.Name))];
    }
}
