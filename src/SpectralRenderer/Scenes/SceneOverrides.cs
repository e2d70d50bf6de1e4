namespace SpectralRenderer.Scenes;

/// <summary>Command-line overrides applied while a scene is loaded (before spectra become band values).</summary>
public sealed record SceneOverrides
{
    public int? Width { get; init; }
    public int? Height { get; init; }
    public string? Bands { get; init; }
    public int? SamplesPerPixel { get; init; }
    public string? Rgb { get; init; }
    public string? Integration { get; init; }
    public string? Formats { get; init; }
    public IReadOnlyList<string> ModelDirectories { get; init; } = [];
}
