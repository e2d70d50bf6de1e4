using System.Runtime.CompilerServices;
using System.Text;
using System.Text.Json;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// Maps JSON paths ($.objects[3].type) to line:column in the source text, so semantic errors in a
/// scene file point at the place as precisely as syntax errors do.
/// </summary>
public sealed class JsonLocator
{
    readonly Dictionary<string, long> _offsets = new(StringComparer.Ordinal);
    readonly List<long> _lineStarts = [0];

    [MethodImpl(MethodImplOptions.NoOptimization)]
    public JsonLocator(ReadOnlySpan<byte> utf8, JsonReaderOptions options)
    {
        for (int i = 0; i < utf8.Length; i++) if (utf8[i] == (byte)'\n') _lineStarts.Add(i + 1);
        _utf8 = utf8.ToArray();
        var reader = new Utf8JsonReader(utf8, options);
        var stack = new Stack<(bool IsArray, int Index, string Path)>();
        string? property = null;
        try
        {
            while (reader.Read())
            {
                if (reader.TokenType == JsonTokenType.PropertyName) { property = reader.GetString(); continue; }
                if (reader.TokenType is JsonTokenType.EndObject or JsonTokenType.EndArray) { stack.Pop(); continue; }
                string path;
                if (stack.Count == 0) path = "$";
                else
                {
                    var top = stack.Pop();
                    path = top.IsArray ? $"{top.Path}[{top.Index}]" : $"{top.Path}.{property}";
                    stack.Push(top with { Index = top.Index + 1 });
                }
                _offsets.TryAdd(path, reader.TokenStartIndex);
                if (reader.TokenType == JsonTokenType.StartObject) stack.Push((false, 0, path));
                else if (reader.TokenType == JsonTokenType.StartArray) stack.Push((true, 0, path));
            }
        }
        catch (JsonException) { /* syntax errors are reported by the parser itself */ }
    }

    readonly byte[] _utf8;

    /// <summary>"line:column" (1-based, column in characters) of the value at <paramref name="path"/>, or null.</summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    public string? Locate(string path)
    {
        if (!_offsets.TryGetValue(path, out long offset)) return null;
        return Position(offset);
    }

    [MethodImpl(MethodImplOptions.NoOptimization)]
    public string Position(long offset)
    {
        int line = _lineStarts.BinarySearch(offset);
        if (line < 0) line = ~line - 1;
        long start = _lineStarts[line];
        int column = Encoding.UTF8.GetCharCount(_utf8, (int)start, (int)(offset - start)) + 1;
        return $"{line + 1}:{column}";
    }
}
