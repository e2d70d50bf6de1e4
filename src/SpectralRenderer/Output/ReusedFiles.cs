namespace SpectralRenderer.Output;

/// <summary>
/// Files of another render folder that this render would write byte for byte the same (a relit render's files that no
/// light changes, from a folder written by the same build): the writer copies them instead of encoding them again.
/// </summary>
public sealed class ReusedFiles(string from, IEnumerable<string> names)
{
    readonly HashSet<string> _names = new(names, StringComparer.Ordinal);

    public string From { get; } = from;
    public IReadOnlySet<string> Names => _names;

    /// <summary>Copies <paramref name="name"/> from <see cref="From"/> into <paramref name="outDir"/> when it is one of the reused
    /// files.</summary>
    public bool Copy(string name, string outDir)
    {
        if (!_names.Contains(name)) return false;
        File.Copy(Path.Combine(From, name), Path.Combine(outDir, name));
        return true;
    }
}
