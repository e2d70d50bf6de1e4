namespace SpectralRenderer.Scenes.Import.Mitsuba;

/// <summary>Mitsuba 3 scene files (.xml whose first element is &lt;scene&gt;): <see cref="MitsubaConverter"/>.</summary>
public sealed class MitsubaFormat : ISceneFormat
{
    public string Name => "mitsuba";

    public bool Claims(string path, ReadOnlySpan<byte> head)
    {
        if (!path.EndsWith(".xml", StringComparison.OrdinalIgnoreCase)) return false;
        // Any XML file by its extension: a file that is not a Mitsuba scene is then told so with its line.
        return true;
    }

    public ImportedScene Convert(string path, ImportOptions options) => new MitsubaConverter(path, options).Convert();
}
