using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// The scene formats we import, one registration line each. <see cref="Find"/> says which one claims a file (by extension and
/// first bytes); a file no format claims is our own JSON.
/// </summary>
public static class SceneFormats
{
    static readonly List<ISceneFormat> Formats =
    [
        new Mitsuba.MitsubaFormat(),
        new Pbrt.PbrtFormat(),
        new Gltf.GltfFormat(),
    ];

    /// <summary>Adds a format (after the built-in ones); a second format under a taken name is refused.</summary>
    public static void Register(ISceneFormat format)
    {
        lock (Formats)
        {
            if (Formats.Any(f => f.Name == format.Name))
                throw new ArgumentException($"a scene format '{format.Name}' is already registered");
            Formats.Add(format);
        }
    }

    /// <summary>The registered formats' names.</summary>
    public static IReadOnlyList<string> Names { get { lock (Formats) return [.. Formats.Select(f => f.Name)]; } }

    /// <summary>The format that claims <paramref name="path"/> (its extension and first 512 bytes), or null: our JSON.</summary>
    public static ISceneFormat? Find(string path)
    {
        Span<byte> head = stackalloc byte[512];
        int n = 0;
        // Only a regular file with content is opened to sniff (opening a FIFO blocks, a device never ends): what is not
        // one is left to the reader that loads it, which says why in one line.
        if (IsRegularFile(path))
        {
            try
            {
                using var f = File.OpenRead(path);
                n = f.ReadAtLeast(head, head.Length, throwOnEndOfStream: false);
            }
            catch (IOException) { n = 0; }
            catch (UnauthorizedAccessException) { n = 0; }
        }
        ISceneFormat[] formats;
        lock (Formats) formats = [.. Formats];
        foreach (var f in formats)
            if (f.Claims(path, head[..n])) return f;
        return null;
    }

    static bool IsRegularFile(string path)
    {
        try { return InputFile.CheckedLength(path) > 0; }
        catch (InputException) { return false; }
    }

    /// <summary>The file converted by the format that claims it; a file none claims is bad input here.</summary>
    public static ImportedScene Convert(string path, ImportOptions options) =>
        (Find(path) ?? throw new InputException(path, "not a scene format we import",
            $"import reads {string.Join(", ", Names)} files (.xml, .pbrt, .gltf, .glb); our own JSON scenes render as they are"))
        .Convert(path, options);
}
