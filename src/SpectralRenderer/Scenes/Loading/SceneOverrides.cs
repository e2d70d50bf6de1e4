namespace SpectralRenderer.Scenes.Loading;

/// <summary>Command-line overrides applied while a scene is loaded (before spectra become band values).</summary>
public sealed record SceneOverrides
{
    /// <summary>Image size in pixels; one of the two alone keeps the aspect ratio of the scene's camera.</summary>
    public int? Width { get; init; }
    public int? Height { get; init; }
    /// <summary>A band grid "start:end:count" (band edges).</summary>
    public string? Bands { get; init; }
    /// <summary>Band centres "start:step:end" (MATLAB/ISETCam colon notation, width = step); excludes <see cref="Bands"/>.</summary>
    public string? Wave { get; init; }
    public int? SamplesPerPixel { get; init; }
    /// <summary>Adaptive sampling's target relative standard error of a pixel's luminance (--target-error).</summary>
    public double? TargetError { get; init; }
    /// <summary>Multiplies the scene's own width and height (after the overrides above), at least 8 pixels.</summary>
    public double ResolutionScale { get; init; } = 1;
    public string? Rgb { get; init; }
    public string? Integration { get; init; }
    public string? Formats { get; init; }
    public string? ExrCompression { get; init; }
    /// <summary>The preview's exposure (--exposure): a number (XYZ multiplier) or "auto", over the scene's output.exposure.</summary>
    public string? Exposure { get; init; }
    public IReadOnlyList<string> ModelDirectories { get; init; } = [];
    /// <summary>
    /// False: mesh objects keep their name and material but no triangles (their files are not read). For work on a
    /// render that is already traced (relighting from the per-light outputs), where no ray meets the geometry.
    /// </summary>
    public bool LoadMeshes { get; init; } = true;
}
