using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;

namespace SpectralRenderer.Diagnostics;

/// <summary>
/// Checked reads of a JSON file this tool wrote (render.json, lights/lights.json, camera.json, a sweep's job.json):
/// nothing derived is trusted. Each read names its JSON path; a missing field, a wrong type, a number outside its
/// range, an array of the wrong length or a file name that leaves its folder is bad input in one line naming the file
/// and the path — "FILE: $.colour.weights_x[3]: is a string, expected a number (hint: …)". A JSON null reads as absent.
/// </summary>
public sealed class JsonFields(string file, string hint)
{
    /// <summary>Duplicate keys are refused (a writer never repeats one), nesting beyond 64 levels too.</summary>
    static readonly JsonDocumentOptions Strict = new() { AllowDuplicateProperties = false, MaxDepth = 64 };

    public string File { get; } = file;
    public string Hint { get; } = hint;

    /// <summary>
    /// The file's top-level object: a missing file, one that is not a regular file or too large, broken JSON (with its
    /// line:column) or a root that is not an object is bad input; <paramref name="what"/> names the kind of file.
    /// </summary>
    public static JsonObject ParseFile(string path, string what, string hint)
    {
        return Parse(InputFile.ReadAllText(path, what), path, hint);
    }

    /// <summary>JSON text as a top-level object, as <see cref="ParseFile"/> reads a file's.</summary>
    public static JsonObject Parse(string text, string path, string hint)
    {
        try
        {
            return JsonNode.Parse(text, documentOptions: Strict) as JsonObject
                ?? throw new InputException($"{path}: $", "is not a JSON object", hint);
        }
        catch (JsonException e)
        {
            string msg = e.Message;
            int cut = msg.IndexOf(" LineNumber:", StringComparison.Ordinal);
            if (cut > 0) msg = msg[..cut].TrimEnd('.', ' ');
            throw new InputException($"{path}:{Place(e, text, default)}", $"broken JSON: {msg}", hint);
        }
    }

    /// <summary>
    /// "line:column" of a JSON error: the parser's own for a syntax error; for a duplicate key (which the parser reports
    /// without a place) the second occurrence of the key, found by one pass of a reader over the text.
    /// </summary>
    public static string Place(JsonException e, string text, JsonReaderOptions options)
    {
        if (e.LineNumber is { } line) return $"{line + 1}:{(e.BytePositionInLine ?? 0) + 1}";
        return DuplicateKey(text, options) ?? "1:1";
    }

    /// <summary>"line:column" (1-based, column in bytes of the line) of the first key that repeats a key of its object, or null.</summary>
    public static string? DuplicateKey(string text, JsonReaderOptions options)
    {
        var utf8 = System.Text.Encoding.UTF8.GetBytes(text);
        var reader = new Utf8JsonReader(utf8, options);
        var keys = new Stack<HashSet<string>?>();
        try
        {
            while (reader.Read())
            {
                switch (reader.TokenType)
                {
                    case JsonTokenType.StartObject: keys.Push(new HashSet<string>(StringComparer.Ordinal)); break;
                    case JsonTokenType.StartArray: keys.Push(null); break;
                    case JsonTokenType.EndObject or JsonTokenType.EndArray: keys.Pop(); break;
                    case JsonTokenType.PropertyName when keys.TryPeek(out var set) && set is not null && !set.Add(reader.GetString()!):
                        long at = reader.TokenStartIndex;
                        int lineStart = System.Array.LastIndexOf(utf8, (byte)'\n', (int)Math.Max(0, at - 1)) + 1;
                        if (at == 0) lineStart = 0;
                        int lineNo = 1;
                        for (int i = 0; i < lineStart; i++) if (utf8[i] == (byte)'\n') lineNo++;
                        return $"{lineNo}:{at - lineStart + 1}";
                }
            }
        }
        catch (Exception x) when (x is JsonException or InvalidOperationException) { }
        return null;
    }

    public InputException Bad(string at, string what) => new($"{File}: {at}", what, Hint);

    InputException Wrong(JsonNode? found, string at, string expected) =>
        Bad(at, found is null ? $"is missing, expected {expected}" : $"is {Kind(found)}, expected {expected}");

    /// <summary>What a JSON value is, for a message: "a string", "the number 1e+300", "an array of 4".</summary>
    public static string Kind(JsonNode? node) => node switch
    {
        null => "null",
        JsonObject => "an object",
        JsonArray a => $"an array of {a.Count}",
        JsonValue v => v.GetValueKind() switch
        {
            JsonValueKind.String => $"the string {MessageText.Quote(v.GetValue<string>(), 24)}",
            JsonValueKind.Number => $"the number {MessageText.Escape(v.ToJsonString())}",
            JsonValueKind.True or JsonValueKind.False => v.ToJsonString(),
            _ => "a value",
        },
        _ => "a value",
    };

    // ---- a node ------------------------------------------------------------------------------------------------

    public JsonObject Object(JsonNode? node, string at) => node as JsonObject ?? throw Wrong(node, at, "an object");

    public JsonArray Array(JsonNode? node, string at, int? count = null, int max = int.MaxValue)
    {
        var a = node as JsonArray ?? throw Wrong(node, at, count is { } n ? $"an array of {n}" : "an array");
        if (count is { } c && a.Count != c) throw Bad(at, $"has {a.Count} entries, expected {c}");
        if (a.Count > max) throw Bad(at, $"has {a.Count} entries, more than {max}");
        return a;
    }

    public string String(JsonNode? node, string at) =>
        node is JsonValue v && v.GetValueKind() == JsonValueKind.String ? v.GetValue<string>() : throw Wrong(node, at, "a string");

    public bool Bool(JsonNode? node, string at) => node is JsonValue v && v.GetValueKind() is JsonValueKind.True or JsonValueKind.False
        ? v.GetValue<bool>() : throw Wrong(node, at, "true or false");

    /// <summary>A finite number in [<paramref name="min"/>, <paramref name="max"/>].</summary>
    public double Number(JsonNode? node, string at, double min = double.MinValue, double max = double.MaxValue)
    {
        string range = Range(min, max);
        if (node is not JsonValue v || v.GetValueKind() != JsonValueKind.Number || !v.TryGetValue(out double d) || !double.IsFinite(d))
            throw Wrong(node, at, $"a finite number{range}");
        if (d < min || d > max) throw Bad(at, $"is {Num(d)}, {Expected(range)}{range}");
        return d;
    }

    /// <summary>A whole number in [<paramref name="min"/>, <paramref name="max"/>].</summary>
    public long Long(JsonNode? node, string at, long min = long.MinValue, long max = long.MaxValue)
    {
        string range = Range(min, max);
        if (node is not JsonValue v || v.GetValueKind() != JsonValueKind.Number) throw Wrong(node, at, $"a whole number{range}");
        if (!v.TryGetValue(out long n))
        {
            // 3.0 is whole; 2.5, 1e300 are not (or not representable).
            if (v.TryGetValue(out double d) && double.IsFinite(d) && d == Math.Floor(d) && Math.Abs(d) < 9e15) n = (long)d;
            else throw Wrong(node, at, $"a whole number{range}");
        }
        if (n < min || n > max)
            throw Bad(at, $"is {n.ToString(CultureInfo.InvariantCulture)}, {Expected(range)}{range}");
        return n;
    }

    public int Int(JsonNode? node, string at, int min = int.MinValue, int max = int.MaxValue) => (int)Long(node, at, min, max);

    /// <summary>An array of <paramref name="count"/> (any, when null) finite numbers in range.</summary>
    public double[] Numbers(JsonNode? node, string at, int? count = null, double min = double.MinValue, double max = double.MaxValue,
        int maxCount = 1 << 20)
    {
        var a = Array(node, at, count, maxCount);
        var r = new double[a.Count];
        for (int i = 0; i < r.Length; i++) r[i] = Number(a[i], $"{at}[{i}]", min, max);
        return r;
    }

    /// <summary>
    /// A file name relative to its folder as a writer records it: not empty, not rooted, '/'-separated parts that are
    /// not "", "." or "..", no backslash or control character — so no name in a manifest can lead out of the folder.
    /// </summary>
    public string RelativeName(JsonNode? node, string at)
    {
        string s = String(node, at);
        if (!IsRelativeName(s, out string why)) throw Bad(at, $"{MessageText.Quote(s, 60)} {why}");
        return s;
    }

    /// <summary>Whether <paramref name="s"/> is a safe relative name (see <see cref="RelativeName"/>); else why not.</summary>
    public static bool IsRelativeName(string s, out string why)
    {
        why = s.Length == 0 ? "is empty"
            : s.Length > 1024 ? "is longer than 1024 characters"
            : Path.IsPathRooted(s) || s[0] == '/' ? "is an absolute path, not a name inside the folder"
            : s.Any(c => c == '\\' || char.IsControl(c)) ? "holds a backslash or a control character"
            : s.Split('/').Any(p => p is "" or "." or "..") ? "has an empty, '.' or '..' part, so it could lead out of the folder"
            : "";
        return why.Length == 0;
    }

    /// <summary>
    /// Checks that <paramref name="relative"/> (a safe name) stays inside <paramref name="dir"/> on disk: no part of it
    /// that exists is a symbolic link resolving outside the folder. A file that does not exist passes (the caller says).
    /// </summary>
    public void StaysInside(string dir, string relative, string at)
    {
        string root = Path.GetFullPath(dir).TrimEnd(Path.DirectorySeparatorChar) + Path.DirectorySeparatorChar;
        string p = root;
        foreach (var part in relative.Split('/'))
        {
            p = Path.Combine(p, part);
            FileSystemInfo info = Directory.Exists(p) ? new DirectoryInfo(p) : new FileInfo(p);
            if (info.LinkTarget is null) continue;
            FileSystemInfo? target;
            try { target = info.ResolveLinkTarget(returnFinalTarget: true); }
            catch (IOException) { target = null; }
            if (target is null || !Path.GetFullPath(target.FullName).StartsWith(root, StringComparison.Ordinal))
                throw Bad(at, $"names {MessageText.Quote(relative, 60)}, a symbolic link leading out of the folder " +
                    $"(to {MessageText.Quote(info.LinkTarget, 60)})");
        }
    }

    // ---- a member of an object: the node at o[key], its path at.key; Opt… read an absent or null member as null --------

    public JsonObject Object(JsonObject o, string key, string at) => Object(o[key], $"{at}.{key}");
    public JsonObject? OptObject(JsonObject o, string key, string at) => o[key] is null ? null : Object(o[key], $"{at}.{key}");
    public JsonArray Array(JsonObject o, string key, string at, int? count = null, int max = int.MaxValue) =>
        Array(o[key], $"{at}.{key}", count, max);
    public JsonArray? OptArray(JsonObject o, string key, string at) => o[key] is null ? null : Array(o[key], $"{at}.{key}");
    public string String(JsonObject o, string key, string at) => String(o[key], $"{at}.{key}");
    public string? OptString(JsonObject o, string key, string at) => o[key] is null ? null : String(o[key], $"{at}.{key}");
    public bool? OptBool(JsonObject o, string key, string at) => o[key] is null ? null : Bool(o[key], $"{at}.{key}");

    public double Number(JsonObject o, string key, string at, double min = double.MinValue, double max = double.MaxValue) =>
        Number(o[key], $"{at}.{key}", min, max);

    public double? OptNumber(JsonObject o, string key, string at, double min = double.MinValue, double max = double.MaxValue) =>
        o[key] is null ? null : Number(o[key], $"{at}.{key}", min, max);

    public int Int(JsonObject o, string key, string at, int min = int.MinValue, int max = int.MaxValue) =>
        Int(o[key], $"{at}.{key}", min, max);

    public int? OptInt(JsonObject o, string key, string at, int min = int.MinValue, int max = int.MaxValue) =>
        o[key] is null ? null : Int(o[key], $"{at}.{key}", min, max);

    public long? OptLong(JsonObject o, string key, string at, long min = long.MinValue, long max = long.MaxValue) =>
        o[key] is null ? null : Long(o[key], $"{at}.{key}", min, max);

    public double[] Numbers(JsonObject o, string key, string at, int? count = null, double min = double.MinValue,
        double max = double.MaxValue) =>
        Numbers(o[key], $"{at}.{key}", count, min, max);

    public double[]? OptNumbers(JsonObject o, string key, string at, int? count = null, double min = double.MinValue,
        double max = double.MaxValue) =>
        o[key] is null ? null : Numbers(o[key], $"{at}.{key}", count, min, max);

    static string Range(double min, double max) =>
        (min, max) switch
        {
            (double.MinValue, double.MaxValue) => "",
            (double.MinValue, _) => $" ≤ {Num(max)}",
            (_, double.MaxValue) => $" ≥ {Num(min)}",
            _ => $" {Num(min)}–{Num(max)}",
        };

    static string Range(long min, long max) =>
        (min, max) switch
        {
            (long.MinValue or int.MinValue, long.MaxValue or int.MaxValue) => "",
            (long.MinValue or int.MinValue, _) => $" ≤ {max.ToString(CultureInfo.InvariantCulture)}",
            (_, long.MaxValue or int.MaxValue) => $" ≥ {min.ToString(CultureInfo.InvariantCulture)}",
            _ => $" {min.ToString(CultureInfo.InvariantCulture)}–{max.ToString(CultureInfo.InvariantCulture)}",
        };

    /// <summary>How a value outside <paramref name="range"/> is told: "expected" for a one-sided bound, else "outside".</summary>
    static string Expected(string range) =>
        range.StartsWith(" ≥", StringComparison.Ordinal) || range.StartsWith(" ≤", StringComparison.Ordinal) ? "expected" : "outside";

    static string Num(double d) => d.ToString("G6", CultureInfo.InvariantCulture);
}
