using System.Globalization;
using System.Text.RegularExpressions;
using System.Xml;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

/// <summary>An element of a Mitsuba 3 scene file with its place (file, line, column) and its attributes in document order.</summary>
public sealed class MitsubaElement
{
    public MitsubaElement(string tag, string file, int line, int column)
    {
        Tag = tag;
        File = file;
        Line = line;
        Column = column;
    }

    public string Tag { get; }
    public string File { get; }
    public int Line { get; }
    public int Column { get; }
    public List<KeyValuePair<string, string>> Attributes { get; } = [];
    public List<MitsubaElement> Children { get; } = [];

    /// <summary>"file.xml:12:5", for messages.</summary>
    public string Where => $"{System.IO.Path.GetFileName(File)}:{Line}:{Column}";
    /// <summary>"file.xml:12", for the report.</summary>
    public string Place => $"{System.IO.Path.GetFileName(File)}:{Line}";

    public string? Attr(string name)
    {
        foreach (var (k, v) in Attributes)
            if (k == name) return v;
        return null;
    }

    /// <summary>"shape rectangle", "bsdf diffuse 'red'": the element as the report names it.</summary>
    public string Label => Attr("type") is { } t ? $"{Tag} {t}" + (Attr("id") is { } id ? $" '{id}'" : "") : Tag;
}

/// <summary>
/// Reads a Mitsuba 3 scene file into <see cref="MitsubaElement"/>s: XML with line numbers, &lt;include&gt; spliced in place
/// (relative to the including file), &lt;default&gt; parameters collected and every "$name" in an attribute value replaced.
/// Bad XML is one line, file:line:column, what is wrong and a hint.
/// </summary>
public static partial class MitsubaXml
{
    const int MaxIncludeDepth = 16;

    /// <summary>The scene element of <paramref name="path"/> with its includes spliced and parameters substituted.</summary>
    public static MitsubaElement Read(string path)
    {
        var root = Parse(path, []);
        if (root.Tag != "scene")
            throw new InputException(root.Where, $"the root element is <{root.Tag}>, not <scene>",
                "a Mitsuba 3 scene file starts with <scene version=\"3.0.0\">");
        var parameters = new Dictionary<string, string>(StringComparer.Ordinal);
        foreach (var c in root.Children)
            if (c.Tag == "default")
            {
                var name = c.Attr("name")
                    ?? throw new InputException(c.Where, "<default> without a name", "e.g. <default name=\"spp\" value=\"64\"/>");
                var value = c.Attr("value") ?? throw new InputException(c.Where, $"<default name=\"{name}\"> without a value",
                    "e.g. <default name=\"spp\" value=\"64\"/>");
                parameters.TryAdd(name, value);   // the first definition counts, as in Mitsuba
            }
        Substitute(root, parameters);
        return root;
    }

    static MitsubaElement Parse(string path, List<string> including)
    {
        var full = System.IO.Path.GetFullPath(path);
        if (including.Contains(full))
            throw new InputException(path, "includes itself (a cycle of <include>)", "remove the include that leads back to this file");
        if (including.Count > MaxIncludeDepth)
            throw new InputException(path, $"<include> nested deeper than {MaxIncludeDepth}", "flatten the includes");
        var bytes = InputFile.ReadAllBytes(path, "Mitsuba scene file");
        var settings = new XmlReaderSettings
        {
            DtdProcessing = DtdProcessing.Prohibit,
            XmlResolver = null,
            IgnoreComments = true,
            IgnoreWhitespace = true,
            IgnoreProcessingInstructions = true,
            MaxCharactersFromEntities = 0,
        };
        var name = System.IO.Path.GetFileName(path);
        var stack = new Stack<MitsubaElement>();
        MitsubaElement? root = null;
        try
        {
            using var reader = XmlReader.Create(new MemoryStream(bytes), settings);
            var info = (IXmlLineInfo)reader;
            while (reader.Read())
            {
                switch (reader.NodeType)
                {
                    case XmlNodeType.Element:
                        {
                            var e = new MitsubaElement(reader.LocalName, path, info.LineNumber, info.LinePosition);
                            bool empty = reader.IsEmptyElement;
                            if (reader.MoveToFirstAttribute())
                                do e.Attributes.Add(new(reader.LocalName, reader.Value)); while (reader.MoveToNextAttribute());
                            if (stack.Count == 0)
                            {
                                if (root is not null)
                                    throw new InputException(e.Where, "a second root element", "a scene file has one <scene> element");
                                root = e;
                            }
                            else stack.Peek().Children.Add(e);
                            if (!empty) stack.Push(e);
                            break;
                        }
                    case XmlNodeType.EndElement:
                        stack.Pop();
                        break;
                    case XmlNodeType.Text or XmlNodeType.CDATA:
                        throw new InputException($"{name}:{info.LineNumber}:{info.LinePosition}",
                            $"unexpected text {MessageText.Quote(reader.Value.Trim(), 40)}",
                            "Mitsuba elements carry their values in attributes, e.g. <float name=\"fov\" value=\"45\"/>");
                }
            }
        }
        catch (XmlException ex)
        {
            var what = ex.Message;
            int cut = what.IndexOf(" Line ", StringComparison.Ordinal);
            if (cut > 0) what = what[..cut];
            throw new InputException($"{name}:{ex.LineNumber}:{ex.LinePosition}", $"malformed XML: {what.TrimEnd('.', ' ')}",
                "check the tags are closed and the attributes quoted");
        }
        if (root is null)
            throw new InputException($"{name}:1:1", "no XML element", "a Mitsuba 3 scene file starts with <scene version=\"3.0.0\">");
        including.Add(full);
        try { Splice(root, path, including); }
        finally { including.RemoveAt(including.Count - 1); }
        return root;
    }

    /// <summary>Each &lt;include filename="…"/&gt; replaced by the children of that file's &lt;scene&gt;.</summary>
    static void Splice(MitsubaElement e, string path, List<string> including)
    {
        for (int i = 0; i < e.Children.Count; i++)
        {
            var c = e.Children[i];
            if (c.Tag != "include") { Splice(c, path, including); continue; }
            var file = c.Attr("filename")
                ?? throw new InputException(c.Where, "<include> without a filename", "e.g. <include filename=\"materials.xml\"/>");
            var full = System.IO.Path.Combine(System.IO.Path.GetDirectoryName(System.IO.Path.GetFullPath(path))!, file);
            if (!System.IO.File.Exists(full))
                throw new InputException(c.Where, $"included file {MessageText.Quote(file)} not found",
                    "the path is relative to the including file")
                { Problem = InputProblem.MissingFile };
            var inner = Parse(full, including);
            if (inner.Tag != "scene")
                throw new InputException(inner.Where, $"an included file's root is <{inner.Tag}>, not <scene>",
                    "wrap its elements in <scene version=\"3.0.0\">");
            e.Children.RemoveAt(i);
            e.Children.InsertRange(i, inner.Children);
            i += inner.Children.Count - 1;
        }
    }

    [GeneratedRegex(@"\$([A-Za-z_][A-Za-z0-9_]*)")]
    private static partial Regex Parameter();

    static void Substitute(MitsubaElement e, Dictionary<string, string> parameters)
    {
        for (int i = 0; i < e.Attributes.Count; i++)
        {
            var (k, v) = e.Attributes[i];
            if (!v.Contains('$')) continue;
            var replaced = Parameter().Replace(v, m => parameters.TryGetValue(m.Groups[1].Value, out var p) ? p
                : throw new InputException(e.Where, $"parameter ${m.Groups[1].Value} has no value",
                    $"add <default name=\"{m.Groups[1].Value}\" value=\"…\"/> to the scene"));
            e.Attributes[i] = new(k, replaced);
        }
        foreach (var c in e.Children) Substitute(c, parameters);
    }

    /// <summary>Numbers separated by commas and/or spaces ("1, 2, 3" or "1 2 3").</summary>
    public static double[] Numbers(string text, string where, string what)
    {
        var parts = text.Split([',', ' ', '\t', '\n', '\r'], StringSplitOptions.RemoveEmptyEntries);
        var v = new double[parts.Length];
        for (int i = 0; i < parts.Length; i++)
            if (!double.TryParse(parts[i], NumberStyles.Float, CultureInfo.InvariantCulture, out v[i]) || !double.IsFinite(v[i]))
                throw new InputException(where, $"{what}: {MessageText.Quote(parts[i], 30)} is not a number",
                    "write numbers like 0.5 or 1e-3");
        return v;
    }
}
