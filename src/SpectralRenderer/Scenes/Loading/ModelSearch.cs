namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// The model search path for mesh files: the scene's folder, then each --models folder, then the
/// folders in $SPECTRAL_MODELS (separated by ':' on Unix, ';' on Windows). The meshes are third-party
/// scans kept outside the repository.
/// </summary>
public static class ModelSearch
{
    public const string Variable = "SPECTRAL_MODELS";

    public static IEnumerable<string> Folders(string sceneDir, IEnumerable<string> extra)
    {
        yield return sceneDir;
        foreach (var d in extra) yield return d;
        var env = Environment.GetEnvironmentVariable(Variable);
        if (!string.IsNullOrEmpty(env))
            foreach (var d in env.Split(Path.PathSeparator, StringSplitOptions.RemoveEmptyEntries)) yield return d;
    }

    public static string? Find(string file, string sceneDir, IEnumerable<string> extra)
    {
        if (Path.IsPathRooted(file)) return File.Exists(file) ? file : null;
        foreach (var d in Folders(sceneDir, extra))
        {
            var p = Path.Combine(d, file);
            if (File.Exists(p)) return p;
        }
        return null;
    }

    /// <summary>The longest folder a search-path description shows, in characters; longer ones are cut in the middle.</summary>
    public const int MaxFolder = 32;

    /// <summary>
    /// The search path for a message whose place already names the scene file: "the scene's folder", then each
    /// --models folder and $SPECTRAL_MODELS cut to <see cref="MaxFolder"/> characters, so the labels survive the
    /// cut to <see cref="Diagnostics.MessageText.MaxLine"/> characters however long the folders are.
    /// </summary>
    public static string Describe(string sceneDir, IEnumerable<string> extra)
    {
        static string Cut(string folder) => Diagnostics.MessageText.Shorten(folder, MaxFolder);
        var env = Environment.GetEnvironmentVariable(Variable);
        var list = new List<string> { "the scene's folder" };
        list.AddRange(extra.Where(d => Path.GetFullPath(d) != Path.GetFullPath(sceneDir)).Select(d => $"--models {Cut(d)}"));
        list.Add(string.IsNullOrEmpty(env) ? "$SPECTRAL_MODELS (unset)" : $"$SPECTRAL_MODELS={Cut(env)}");
        return string.Join(", ", list);
    }
}
