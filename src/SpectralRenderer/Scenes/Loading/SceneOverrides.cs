namespace SpectralRenderer.Scenes.Loading;

/// <summary>Command-line overrides applied while a scene is loaded (before spectra become band values).</summary>
public sealed record SceneOverrides
{
    public int? Width { get; init; }
    public int? Height { get; init; }
    public string? Bands { get; init; }
    public int? SamplesPerPixel { get; init; }
    /// <summary>Multiplies the scene's own width and height (after the overrides above), at least 8 pixels.</summary>
    public double ResolutionScale { get; init; } = 1;
    public string? Rgb { get; init; }
    public string? Integration { get; init; }
    public string? Formats { get; init; }
    public string? ExrCompression { get; init; }
    public IReadOnlyList<string> ModelDirectories { get; init; } = [];
}
