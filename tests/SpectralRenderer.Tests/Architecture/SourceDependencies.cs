using System.Text.RegularExpressions;

namespace SpectralRenderer.Tests.Architecture;

/// <summary>
/// The namespace dependencies written in C# source: using directives (plain, static and alias), fully qualified names
/// (SpectralRenderer.X.Y, global::SpectralRenderer.X.Y) and names qualified from the root namespace (Rendering.Renderer
/// inside SpectralRenderer.*). It complements <see cref="NamespaceDependencies"/>, which cannot see what the compiler
/// folds away (constants, enum values, nameof). Line comments are skipped, XML doc comments (whose crefs the compiler
/// resolves) are not.
/// </summary>
public static partial class SourceDependencies
{
    /// <summary>The layers' first names, the only names a partially qualified reference can start with.</summary>
    public static readonly string[] Roots = ["Diagnostics", "Spectra", "Color", "Geometry", "Acceleration", "Scenes", "Rendering", "Imaging", "Output", "Analysis", "Cli"];

    public static Dictionary<string, SortedSet<string>> Read(IEnumerable<string> files)
    {
        var graph = new Dictionary<string, SortedSet<string>>(StringComparer.Ordinal);
        foreach (var f in files)
            foreach (var (from, to) in Scan(File.ReadAllText(f)))
            {
                if (!graph.TryGetValue(from, out var set)) graph[from] = set = new SortedSet<string>(StringComparer.Ordinal);
                if (to != from) set.Add(to);
            }
        return graph;
    }

    /// <summary>The (namespace, referenced name) pairs of one file with a file-scoped namespace; a referenced name is dotted, e.g. SpectralRenderer.Rendering.Renderer.</summary>
    public static IEnumerable<(string From, string To)> Scan(string source)
    {
        var ns = FileNamespace().Match(source);
        if (!ns.Success) yield break;
        string from = ns.Groups[1].Value;
        var code = LineComment().Replace(source, "");
        code = FileNamespace().Replace(code, "");
        foreach (Match m in UsingDirective().Matches(code)) yield return (from, m.Groups[1].Value);
        code = UsingDirective().Replace(code, "");
        foreach (Match m in FullyQualified().Matches(code)) yield return (from, m.Groups[1].Value);
        if (from.StartsWith("SpectralRenderer", StringComparison.Ordinal))
            foreach (Match m in RootQualified().Matches(code)) yield return (from, "SpectralRenderer." + m.Groups[1].Value);
    }

    [GeneratedRegex(@"^\s*namespace\s+([\w.]+)\s*;", RegexOptions.Multiline)]
    private static partial Regex FileNamespace();

    // A // comment that is not a /// doc comment, to the end of the line.
    [GeneratedRegex(@"(?<!/)//(?!/)[^\n]*")]
    private static partial Regex LineComment();

    [GeneratedRegex(@"^\s*(?:global\s+)?using\s+(?:static\s+)?(?:\w+\s*=\s*)?(?:global::)?(SpectralRenderer(?:\.\w+)+)\s*;", RegexOptions.Multiline)]
    private static partial Regex UsingDirective();

    [GeneratedRegex(@"(?<![\w.])(?:global::)?(SpectralRenderer(?:\.[A-Z]\w*)+)")]
    private static partial Regex FullyQualified();

    [GeneratedRegex(@"(?<![\w.:])((?:Diagnostics|Spectra|Color|Geometry|Acceleration|Scenes|Rendering|Imaging|Output|Analysis|Cli)(?:\.[A-Z]\w*)+)")]
    private static partial Regex RootQualified();
}
