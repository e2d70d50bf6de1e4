namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>pbrt-v4 scene files (.pbrt): <see cref="PbrtConverter"/> (docs/import.md "pbrt-v4").</summary>
public sealed class PbrtFormat : ISceneFormat
{
    public string Name => "pbrt";

    public bool Claims(string path, ReadOnlySpan<byte> head) => path.EndsWith(".pbrt", StringComparison.OrdinalIgnoreCase);

    public ImportedScene Convert(string path, ImportOptions options) => new PbrtConverter(path, options).Convert();
}
