using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import;

/// <summary>One thing an importer did with an element of the source file that our scene does not hold as written.</summary>
/// <param name="Kind">One of <see cref="ImportReport.Kinds"/>.</param>
/// <param name="Where">"file:line" (XML line, pbrt token line) or "file: $.json.path" (glTF).</param>
/// <param name="Element">The element, e.g. "bsdf roughplastic".</param>
/// <param name="Action">What was done, one sentence.</param>
public sealed record ImportEntry(string Kind, string Where, string Element, string Action);

/// <summary>
/// What a conversion approximated, ignored, uplifted or converted, in document order (import-report.json). An "error" entry is
/// an element that would change the picture materially and has no counterpart: the importer throws unless
/// <see cref="ImportOptions.Lenient"/>, when it is recorded here and skipped.
/// </summary>
public sealed class ImportReport
{
    /// <summary>The kinds of entry, in the order the summary counts them.</summary>
    public static readonly string[] Kinds = ["error", "approximated", "ignored", "uplifted", "converted"];

    readonly List<ImportEntry> _entries = [];

    public ImportReport(string source, string format) { Source = source; Format = format; }

    /// <summary>The source file as given.</summary>
    public string Source { get; }
    /// <summary>The format's name ("mitsuba", "pbrt", "gltf").</summary>
    public string Format { get; }
    public IReadOnlyList<ImportEntry> Entries => _entries;

    public void Add(string kind, string where, string element, string action)
    {
        if (Array.IndexOf(Kinds, kind) < 0) throw new ArgumentException($"unknown report kind '{kind}'", nameof(kind));
        _entries.Add(new ImportEntry(kind, where, element, action));
    }

    /// <summary>How many entries of <paramref name="kind"/>.</summary>
    public int Count(string kind) => _entries.Count(e => e.Kind == kind);

    /// <summary>{ "source", "format", "entries": [{ "kind", "where", "element", "action" }, …] }.</summary>
    public JsonObject ToJson()
    {
        var entries = new JsonArray();
        foreach (var e in _entries)
            entries.Add(
                (JsonNode)new JsonObject { ["kind"] = e.Kind, ["where"] = e.Where, ["element"] = e.Element, ["action"] = e.Action });
        return new JsonObject { ["source"] = Source, ["format"] = Format, ["entries"] = entries };
    }

    /// <summary>One line: the counts per kind ("mitsuba: 2 approximated, 1 uplifted; first: file:12 bsdf plastic: …").</summary>
    public string Summary()
    {
        var counts = Kinds.Select(k => (Kind: k, N: Count(k))).Where(c => c.N > 0).Select(c => $"{c.N} {c.Kind}").ToList();
        var line = $"{Path.GetFileName(Source)} ({Format}): " + (counts.Count == 0 ? "converted as written" : string.Join(", ", counts));
        var first = _entries.FirstOrDefault(e => e.Kind != "converted") ?? _entries.FirstOrDefault();
        if (first is not null) line += $"; first: {first.Where} {first.Element}: {first.Action}";
        return line;
    }
}
