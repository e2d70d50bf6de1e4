using System.Text.RegularExpressions;

namespace SpectralRenderer.Tests.Architecture;

/// <summary>
/// The namespace dependencies written in C# source, for the layers of a rule table (<see cref="LayeringTests.Allowed"/>):
/// every dotted name (in using directives — plain, static, alias — and in code) that C# would resolve into one of the
/// table's namespaces: fully qualified (SpectralRenderer.X.Y, global::SpectralRenderer.X.Y) or qualified from any
/// enclosing namespace (Sensor.SensorPresets inside SpectralRenderer.Imaging, Loading.SceneLoader inside
/// SpectralRenderer.Scenes). The names it looks for are built from the table itself, so a new layer is seen as soon as it
/// has a rule. It complements <see cref="NamespaceDependencies"/>, which cannot see what the compiler folds away
/// (constants, enum values, nameof). Line comments are skipped, XML doc comments (whose crefs the compiler resolves) are
/// not. A file may have one file-scoped namespace or block-scoped ones one after another.
/// </summary>
public static partial class SourceDependencies
{
    public static Dictionary<string, SortedSet<string>> Read(IEnumerable<string> files, IReadOnlyDictionary<string, string[]>? rules = null)
    {
        var graph = new Dictionary<string, SortedSet<string>>(StringComparer.Ordinal);
        foreach (var f in files)
            foreach (var (from, to) in Scan(File.ReadAllText(f), rules))
            {
                if (!graph.TryGetValue(from, out var set)) graph[from] = set = new SortedSet<string>(StringComparer.Ordinal);
                if (to != from) set.Add(to);
            }
        return graph;
    }

    /// <summary>
    /// The (namespace, referenced name) pairs of one source file; a referenced name is the fully qualified dotted name,
    /// e.g. SpectralRenderer.Rendering.Renderer.TileSize. Only names inside the namespaces of <paramref name="rules"/>
    /// (by default <see cref="LayeringTests.Allowed"/>) are returned.
    /// </summary>
    public static IEnumerable<(string From, string To)> Scan(string source, IReadOnlyDictionary<string, string[]>? rules = null)
    {
        var known = Namespaces(rules ?? LayeringTests.Allowed);
        var code = LineComment().Replace(source, "");
        var declarations = Namespace().Matches(code);
        for (int i = 0; i < declarations.Count; i++)
        {
            string from = declarations[i].Groups[1].Value;
            int start = declarations[i].Index + declarations[i].Length;
            int end = i + 1 < declarations.Count ? declarations[i + 1].Index : code.Length;
            // Using directives before the first namespace resolve from the global namespace only.
            var parts = new List<(string Text, string Scope)> { (code[start..end], from) };
            if (i == 0) parts.Add((code[..declarations[0].Index], ""));
            foreach (var (text, scope) in parts)
                foreach (Match m in DottedName().Matches(text))
                {
                    var to = Resolve(m.Groups[2].Value, m.Groups[1].Success ? "" : scope, known);
                    if (to is not null) yield return (from, to);
                }
        }
    }

    /// <summary>
    /// What C# binds the dotted <paramref name="name"/> to inside namespace <paramref name="from"/>: its first identifier is
    /// looked up in <paramref name="from"/>, then in each enclosing namespace out to the global one; the first that has a
    /// namespace of that name wins. Null when no namespace of the table (or one enclosing a table's namespace) is named.
    /// </summary>
    public static string? Resolve(string name, string from, ISet<string> known)
    {
        int dot = name.IndexOf('.');
        string first = dot < 0 ? name : name[..dot];
        for (string scope = from; ; scope = scope.Contains('.') ? scope[..scope.LastIndexOf('.')] : "")
        {
            string candidate = scope.Length == 0 ? first : scope + "." + first;
            if (known.Contains(candidate)) return scope.Length == 0 ? name : scope + "." + name;
            if (scope.Length == 0) return null;
        }
    }

    /// <summary>The table's namespaces and every namespace enclosing one of them (SpectralRenderer.Scenes.Loading →
    /// SpectralRenderer.Scenes, SpectralRenderer).</summary>
    public static HashSet<string> Namespaces(IReadOnlyDictionary<string, string[]> rules)
    {
        var set = new HashSet<string>(StringComparer.Ordinal);
        foreach (var key in rules.Keys)
            for (string ns = key; ns.Length > 0; ns = ns.Contains('.') ? ns[..ns.LastIndexOf('.')] : "")
                set.Add(ns);
        return set;
    }

    [GeneratedRegex(@"^\s*namespace\s+([\w.]+)\s*[;{]", RegexOptions.Multiline)]
    private static partial Regex Namespace();

    // A // comment that is not a /// doc comment, to the end of the line.
    [GeneratedRegex(@"(?<!/)//(?!/)[^\n]*")]
    private static partial Regex LineComment();

    // A dotted name of at least two identifiers, each starting with a capital (a namespace or type name), not itself
    // a member of something before it (x.Sensor.Gain); global:: marks a name resolved from the global namespace.
    [GeneratedRegex(@"(?<![\w.:])(global::)?([A-Z]\w*(?:\.[A-Z]\w*)+)")]
    private static partial Regex DottedName();
}
