using System.Text;
using System.Text.Json;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// Maps JSON paths ($.objects[3].type) to line:column in the source text, so semantic errors in a
/// scene file point at the place as precisely as syntax errors do. It also finds the first duplicate key
/// of an object (reported at its second occurrence). Elements of long arrays (index ≥ <see cref="EagerIndex"/>)
/// are not indexed up front — a 200 000-pair inline spectrum would cost hundreds of MB of paths — but
/// found by a second pass over the text when an error names one.
/// </summary>
public sealed class JsonLocator
{
    const int EagerIndex = 256;
    readonly Dictionary<string, long> _offsets = new(StringComparer.Ordinal);
    readonly List<long> _lineStarts = [0];
    readonly byte[] _utf8;
    readonly JsonReaderOptions _options;
    bool _skipped;

    /// <summary>The JSON path and offset of the first key that repeats an earlier key of its object, or null.</summary>
    public (string Path, long Offset)? Duplicate { get; private set; }

    public JsonLocator(ReadOnlySpan<byte> utf8, JsonReaderOptions options)
    {
        for (int i = 0; i < utf8.Length; i++) if (utf8[i] == (byte)'\n') _lineStarts.Add(i + 1);
        _utf8 = utf8.ToArray();
        _options = options;
        Walk(null, out _);
    }

    /// <summary>
    /// One pass over the tokens, recording each value's offset under its path (all of them when
    /// <paramref name="find"/> is given, then stopping at that path), and every object's keys to catch duplicates.
    /// </summary>
    void Walk(string? find, out long found)
    {
        found = -1;
        var reader = new Utf8JsonReader(_utf8, _options);
        var stack = new Stack<(bool IsArray, int Index, string Path, HashSet<string>? Keys, bool Bulk)>();
        string? property = null;
        try
        {
            while (reader.Read())
            {
                if (reader.TokenType == JsonTokenType.PropertyName)
                {
                    property = reader.GetString();
                    if (find is null && stack.TryPeek(out var obj) && obj.Keys is not null && !obj.Keys.Add(property!) && Duplicate is null)
                        Duplicate = ($"{(obj.Bulk ? "(an element of a long array)" : obj.Path)}.{property}", reader.TokenStartIndex);
                    continue;
                }
                if (reader.TokenType is JsonTokenType.EndObject or JsonTokenType.EndArray) { stack.Pop(); continue; }
                string path;
                bool bulk = false;
                if (stack.Count == 0) path = "$";
                else
                {
                    var top = stack.Pop();
                    bulk = top.Bulk || (top.IsArray && top.Index >= EagerIndex);
                    path = bulk && find is null ? "" : top.IsArray ? $"{top.Path}[{top.Index}]" : $"{top.Path}.{property}";
                    stack.Push(top with { Index = top.Index + 1 });
                }
                if (find is null)
                {
                    if (bulk) _skipped = true;
                    else _offsets.TryAdd(path, reader.TokenStartIndex);
                }
                else if (path == find) { found = reader.TokenStartIndex; return; }
                if (reader.TokenType == JsonTokenType.StartObject)
                    stack.Push((false, 0, path, find is null ? new HashSet<string>(StringComparer.Ordinal) : null, bulk));
                else if (reader.TokenType == JsonTokenType.StartArray) stack.Push((true, 0, path, null, bulk));
            }
        }
        catch (JsonException) { /* syntax errors are reported by the parser itself */ }
        catch (InvalidOperationException) { /* invalid UTF-8 in a key: reported before the locator runs */ }
    }

    /// <summary>"line:column" (1-based, column in characters) of the value at <paramref name="path"/>, or null.</summary>
    public string? Locate(string path)
    {
        if (_offsets.TryGetValue(path, out long offset)) return Position(offset);
        if (!_skipped) return null;
        Walk(path, out offset);
        if (offset < 0) return null;
        _offsets[path] = offset;
        return Position(offset);
    }

    public string Position(long offset)
    {
        int line = _lineStarts.BinarySearch(offset);
        if (line < 0) line = ~line - 1;
        long start = _lineStarts[line];
        int column = Encoding.UTF8.GetCharCount(_utf8, (int)start, (int)(offset - start)) + 1;
        return $"{line + 1}:{column}";
    }
}
