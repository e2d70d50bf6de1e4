namespace SpectralRenderer.Scenes.Import;

/// <summary>How an import treats what it cannot convert, and where it finds meshes.</summary>
/// <param name="Lenient">Elements without a counterpart (report kind "error") are reported and skipped instead of failing.</param>
/// <param name="ModelDirectories">Folders searched for referenced meshes after the source file's own (as --models).</param>
public sealed record ImportOptions(bool Lenient = false, IReadOnlyList<string>? ModelDirectories = null)
{
    public IReadOnlyList<string> ModelDirectories { get; init; } = ModelDirectories ?? [];
}
