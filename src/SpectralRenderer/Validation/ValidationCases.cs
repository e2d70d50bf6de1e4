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

    /// <summary>The cases named (each once, in the registry's order); an unknown name is bad input naming the closest and
    /// pointing to the list.</summary>
    public static IReadOnlyList<ValidationCase> Select(IReadOnlyCollection<string> names)
    {
        if (names.Count == 0) return All;
        foreach (var n in names)
            if (!All.Any(c => c.Name == n))
                throw new InputException("--case", $"no validation case is called {MessageText.Quote(n, 60)}",
                    (InputException.DidYouMean(n, All.Select(c => c.Name)) is { } guess ? guess + " " : "")
                        + $"('spectral validate --list' names all {All.Count}: {string.Join(", ", All.Select(c => c.Group).Distinct())})");
        return [.. All.Where(c => names.Contains(c.Name))];
    }
}
