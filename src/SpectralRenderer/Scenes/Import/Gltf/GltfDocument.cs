using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using System.Text.Json;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Gltf;

/// <summary>
/// A glTF 2.0 asset as read (Khronos glTF 2.0 specification §3.6, §4.4): the JSON of a .gltf file or of a .glb's JSON chunk,
/// its buffers (the .glb's BIN chunk, data: URIs, files beside it) and typed access to its accessors. Every error is one line
/// naming the file and the JSON path, e.g. <c>scene.gltf: $.accessors[2].count: …</c>.
/// </summary>
sealed class GltfDocument
{
    const uint GlbMagic = 0x46546C67, JsonChunk = 0x4E4F534A, BinChunk = 0x004E4942;

    readonly string _file;
    readonly byte[]?[] _buffers;
    readonly byte[]? _glbBin;

    GltfDocument(string path, JsonElement root, byte[]? glbBin)
    {
        Path = path;
        _file = path;
        Directory = System.IO.Path.GetDirectoryName(System.IO.Path.GetFullPath(path))!;
        Root = root;
        _glbBin = glbBin;
        _buffers = new byte[]?[Count("buffers")];
    }

    /// <summary>The file as given.</summary>
    public string Path { get; }
    /// <summary>The folder relative URIs resolve from.</summary>
    public string Directory { get; }
    public JsonElement Root { get; }

    public static GltfDocument Load(string path)
    {
        var bytes = InputFile.ReadAllBytes(path, "glTF file");
        byte[]? bin = null;
        ReadOnlyMemory<byte> json = bytes;
        if (bytes.Length >= 4 && BinaryPrimitives.ReadUInt32LittleEndian(bytes) == GlbMagic)
            (json, bin) = Glb(bytes, path);
        // glTF's JSON is UTF-8 (§3.5): an invalid byte inside a string would surface later, when that string is read.
        // Found by the gltf fuzz target in CI.
        if (!System.Text.Unicode.Utf8.IsValid(json.Span))
            throw new InputException($"{path}: byte {FirstInvalidUtf8(json.Span)}", "the glTF JSON is not valid UTF-8",
                "glTF 2.0 §3.5: save the JSON as UTF-8");
        try
        {
            var doc = JsonDocument.Parse(json, new JsonDocumentOptions { MaxDepth = 128 });
            if (doc.RootElement.ValueKind != JsonValueKind.Object)
                throw new InputException($"{path}: $", $"the glTF JSON is {Kind(doc.RootElement)}, not an object",
                    "is this a glTF 2.0 file? it is a JSON object with an \"asset\"");
            return new GltfDocument(path, doc.RootElement, bin);
        }
        catch (JsonException e)
        {
            throw new InputException($"{path}: line {(e.LineNumber ?? 0) + 1}:{(e.BytePositionInLine ?? 0) + 1}",
                "JSON syntax error in the glTF", "check the file is complete JSON (glTF 2.0 §3.5)");
        }
    }

    /// <summary>The offset of the first byte that does not start a valid UTF-8 sequence (within the JSON).</summary>
    static int FirstInvalidUtf8(ReadOnlySpan<byte> text)
    {
        int at = 0;
        while (at < text.Length)
        {
            if (System.Text.Rune.DecodeFromUtf8(text[at..], out _, out int used) != System.Buffers.OperationStatus.Done) return at;
            at += used;
        }
        return at;
    }

    /// <summary>A binary glTF (§4.4): 12-byte header, the JSON chunk, an optional BIN chunk.</summary>
    static (ReadOnlyMemory<byte> Json, byte[]? Bin) Glb(byte[] bytes, string path)
    {
        InputException Bad(string where, string what) => new($"{path}: {where}", what, "the .glb is damaged or truncated: export it again");
        if (bytes.Length < 20) throw Bad("byte 0", "the file is shorter than a GLB header and its JSON chunk");
        uint version = BinaryPrimitives.ReadUInt32LittleEndian(bytes.AsSpan(4));
        if (version != 2)
            throw new InputException($"{path}: byte 4", $"GLB version {version} is not supported", "export the file as glTF 2.0");
        long length = BinaryPrimitives.ReadUInt32LittleEndian(bytes.AsSpan(8));
        if (length > bytes.Length) throw Bad("byte 8", $"the header says {length} bytes, the file has {bytes.Length}");
        ReadOnlyMemory<byte> json = default;
        byte[]? bin = null;
        long pos = 12;
        for (int chunk = 0; pos < length; chunk++)
        {
            if (pos + 8 > length) throw Bad($"byte {pos}", $"chunk {chunk}'s header runs past the end of the file");
            long size = BinaryPrimitives.ReadUInt32LittleEndian(bytes.AsSpan((int)pos));
            uint type = BinaryPrimitives.ReadUInt32LittleEndian(bytes.AsSpan((int)pos + 4));
            if (pos + 8 + size > length) throw Bad($"byte {pos}", $"chunk {chunk} ({size} bytes) runs past the end of the file");
            if (chunk == 0 && type != JsonChunk) throw Bad($"byte {pos + 4}", "the first chunk is not the JSON chunk");
            if (chunk == 0) json = bytes.AsMemory((int)pos + 8, (int)size);
            else if (chunk == 1 && type == BinChunk) bin = bytes.AsSpan((int)pos + 8, (int)size).ToArray();
            pos += 8 + size;
        }
        if (json.IsEmpty) throw Bad("byte 12", "the GLB has no JSON chunk");
        return (json, bin);
    }

    public InputException Error(string path, string what, string hint) => new($"{_file}: {path}", what, hint);

    public string Where(string path) => $"{System.IO.Path.GetFileName(_file)}: {path}";

    public static string Kind(JsonElement e) => e.ValueKind switch
    {
        JsonValueKind.Object => "an object",
        JsonValueKind.Array => "an array",
        JsonValueKind.String => "a string",
        JsonValueKind.Number => "a number",
        JsonValueKind.True or JsonValueKind.False => "a boolean",
        _ => "null",
    };

    // ---- typed reads with the JSON path in every error ----

    /// <summary>The length of the top-level array <paramref name="key"/> (0 when absent).</summary>
    public int Count(string key) => Root.TryGetProperty(key, out var a) && a.ValueKind == JsonValueKind.Array ? a.GetArrayLength() : 0;

    /// <summary>Element <paramref name="i"/> of the top-level array <paramref name="key"/>, an object.</summary>
    public JsonElement Item(string key, int i) => Object(Array(Root, key, "$")[i], $"$.{key}[{i}]");

    public JsonElement Object(JsonElement e, string path) => e.ValueKind == JsonValueKind.Object
        ? e
        : throw Error(path, $"expected an object, found {Kind(e)}", "see the glTF 2.0 schema for this property");

    public JsonElement Array(JsonElement parent, string key, string path)
    {
        if (!parent.TryGetProperty(key, out var a)) return default;
        if (a.ValueKind != JsonValueKind.Array)
            throw Error($"{path}.{key}", $"expected an array, found {Kind(a)}", "see the glTF 2.0 schema for this property");
        return a;
    }

    public static bool Has(JsonElement parent, string key, out JsonElement value)
    {
        value = default;
        return parent.ValueKind == JsonValueKind.Object && parent.TryGetProperty(key, out value);
    }

    public double Number(JsonElement parent, string key, string path, double fallback, double min = double.MinValue,
        double max = double.MaxValue)
    {
        if (!Has(parent, key, out var v)) return fallback;
        if (v.ValueKind != JsonValueKind.Number || !v.TryGetDouble(out double x) || !double.IsFinite(x))
            throw Error($"{path}.{key}", $"expected a number, found {Kind(v)}", "see the glTF 2.0 schema for this property");
        if (x < min || x > max)
            throw Error($"{path}.{key}", $"{x.ToString("R", CultureInfo.InvariantCulture)} is out of range "
                + $"[{min.ToString(CultureInfo.InvariantCulture)}, {max.ToString(CultureInfo.InvariantCulture)}]",
                "see the glTF 2.0 schema for this property");
        return x;
    }

    public bool Bool(JsonElement parent, string key, string path, bool fallback)
    {
        if (!Has(parent, key, out var v)) return fallback;
        return v.ValueKind switch
        {
            JsonValueKind.True => true,
            JsonValueKind.False => false,
            _ => throw Error($"{path}.{key}", $"expected true or false, found {Kind(v)}", "see the glTF 2.0 schema"),
        };
    }

    public string? String(JsonElement parent, string key, string path)
    {
        if (!Has(parent, key, out var v)) return null;
        return v.ValueKind == JsonValueKind.String
            ? v.GetString()!
            : throw Error($"{path}.{key}", $"expected a string, found {Kind(v)}", "see the glTF 2.0 schema for this property");
    }

    /// <summary>An index into the top-level array <paramref name="of"/>; −1 when absent and not required.</summary>
    public int Index(JsonElement parent, string key, string path, string of, bool required = false)
    {
        if (!Has(parent, key, out var v))
            return required ? throw Error(path, $"missing \"{key}\"", $"each element here names one of \"{of}\" by index") : -1;
        int n = Count(of);
        if (v.ValueKind != JsonValueKind.Number || !v.TryGetInt32(out int i) || i < 0 || i >= n)
            throw Error($"{path}.{key}", $"{v.GetRawText()} is not an index into \"{of}\" ({n} elements)",
                n == 0 ? $"the file has no \"{of}\"" : $"give 0 to {n - 1}");
        return i;
    }

    /// <summary>A fixed-length array of numbers (a factor, a vector), or the fallback when absent.</summary>
    public double[] Numbers(JsonElement parent, string key, string path, double[] fallback, double min = double.MinValue,
        double max = double.MaxValue)
    {
        if (!Has(parent, key, out var a)) return fallback;
        if (a.ValueKind != JsonValueKind.Array || a.GetArrayLength() != fallback.Length)
            throw Error($"{path}.{key}", $"expected {fallback.Length} numbers, found {Kind(a)}"
                + (a.ValueKind == JsonValueKind.Array ? $" of {a.GetArrayLength()}" : ""), "see the glTF 2.0 schema for this property");
        var v = new double[fallback.Length];
        for (int i = 0; i < v.Length; i++)
        {
            var x = a[i];
            if (x.ValueKind != JsonValueKind.Number || !x.TryGetDouble(out v[i]) || !double.IsFinite(v[i]) || v[i] < min || v[i] > max)
                throw Error($"{path}.{key}[{i}]", $"expected a number in [{min.ToString(CultureInfo.InvariantCulture)}, "
                    + $"{max.ToString(CultureInfo.InvariantCulture)}], found {x.GetRawText()}",
                        "see the glTF 2.0 schema for this property");
        }
        return v;
    }

    // ---- buffers, buffer views and accessors (§3.6) ----

    /// <summary>Buffer <paramref name="i"/>'s bytes: the GLB's BIN chunk (no uri), a data: URI or a file beside the asset.</summary>
    public byte[] Buffer(int i)
    {
        if (_buffers[i] is { } cached) return cached;
        var path = $"$.buffers[{i}]";
        var b = Item("buffers", i);
        long byteLength = (long)Number(b, "byteLength", path, -1, 1, int.MaxValue);
        if (byteLength < 0) throw Error(path, "missing \"byteLength\"", "a buffer states its length in bytes");
        var uri = String(b, "uri", path);
        byte[] data;
        if (uri is null)
        {
            if (i != 0 || _glbBin is null)
                throw Error(path, "a buffer without \"uri\" but no GLB BIN chunk", "only the first buffer of a .glb may omit its uri");
            data = _glbBin;
        }
        else data = UriBytes(uri, $"{path}.uri", "buffer");
        if (data.Length < byteLength)
            throw Error($"{path}.byteLength", $"the buffer holds {data.Length} bytes, fewer than its byteLength {byteLength}",
                "the buffer file is truncated or the wrong one");
        _buffers[i] = data;
        return data;
    }

    /// <summary>The bytes a URI names: a base64 data: URI, or a file relative to the asset (percent-decoded).</summary>
    public byte[] UriBytes(string uri, string path, string what)
    {
        if (uri.StartsWith("data:", StringComparison.OrdinalIgnoreCase))
        {
            int comma = uri.IndexOf(',', StringComparison.Ordinal);
            if (comma < 0 || !uri[..comma].EndsWith(";base64", StringComparison.OrdinalIgnoreCase))
                throw Error(path, $"the {what}'s data URI is not base64", "use data:<type>;base64,<data> or a file");
            try { return Convert.FromBase64String(uri[(comma + 1)..]); }
            catch (FormatException) { throw Error(path, $"the {what}'s data URI is not valid base64", "export the file again"); }
        }
        return InputFile.ReadAllBytes(FilePath(uri, path, what), $"glTF {what}");
    }

    /// <summary>The full path of a relative file URI, which must exist.</summary>
    public string FilePath(string uri, string path, string what)
    {
        if (uri.Contains("://", StringComparison.Ordinal))
            throw Error(path, $"the {what} is a URL ({MessageText.Quote(uri)}): only files beside the asset are read",
                "download it and refer to it by a relative path");
        var full = System.IO.Path.GetFullPath(System.IO.Path.Combine(Directory, Uri.UnescapeDataString(uri)));
        if (!File.Exists(full))
            throw new InputException($"{_file}: {path}", $"the {what} file {MessageText.Quote(uri)} was not found (looked in {Directory})",
                "keep the asset's files beside it")
            { Problem = InputProblem.MissingFile };
        return full;
    }

    /// <summary>A buffer view's bytes and its byteStride (0 when tightly packed).</summary>
    public (ArraySegment<byte> Bytes, int Stride) BufferView(int i, string path)
    {
        var v = Item("bufferViews", i);
        var where = $"$.bufferViews[{i}]";
        int buffer = Index(v, "buffer", where, "buffers", required: true);
        long offset = (long)Number(v, "byteOffset", where, 0, 0, int.MaxValue);
        long length = (long)Number(v, "byteLength", where, -1, 1, int.MaxValue);
        if (length < 0) throw Error(where, "missing \"byteLength\"", "a buffer view states its length in bytes");
        int stride = (int)Number(v, "byteStride", where, 0, 4, 252);
        if (stride % 4 != 0) throw Error($"{where}.byteStride", $"byteStride {stride} is not a multiple of 4", "glTF 2.0 §3.6.2.4");
        var data = Buffer(buffer);
        if (offset + length > data.Length)
            throw Error(where, $"bytes {offset}–{offset + length} run past buffer {buffer}'s {data.Length} bytes",
                $"the view (named at {path}) does not fit its buffer: export the file again");
        return (new ArraySegment<byte>(data, (int)offset, (int)length), stride);
    }

    static int ComponentSize(int type) => type switch { 5120 or 5121 => 1, 5122 or 5123 => 2, 5125 or 5126 => 4, _ => 0 };

    static int Components(string type) => type switch
    {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        "VEC4" => 4,
        "MAT2" => 4,
        "MAT3" => 9,
        "MAT4" => 16,
        _ => 0,
    };

    /// <summary>
    /// Accessor <paramref name="i"/> as floats, its type's components per element: float components as they are, integer ones
    /// (which must then be "normalized") mapped to [0, 1] (unsigned) or [−1, 1] (signed) as §3.11 says; sparse substitutions
    /// applied. <paramref name="types"/> lists the component types the attribute at <paramref name="usedAt"/> allows.
    /// </summary>
    public float[] Floats(int i, string usedAt, string type, int[] types)
    {
        var a = Layout(i, usedAt, type, types, floats: true);
        var values = new float[a.Count * a.Components];
        for (int e = 0; e < (a.Bytes.Array is null ? 0 : a.Count); e++)
            for (int c = 0; c < a.Components; c++)
                values[e * a.Components + c] = Component(a.Bytes.AsSpan((int)(a.Offset + (long)e * a.Stride + c * a.Size)),
                    a.ComponentType, a.Normalized);
        if (Has(Item("accessors", i), "sparse", out var sparse))
            Sparse(sparse, $"$.accessors[{i}].sparse", values, a.Count, a.Components, a.ComponentType, a.Normalized);
        foreach (var v in values)
            if (!float.IsFinite(v))
                throw Error($"$.accessors[{i}]", "the accessor holds a value that is not a finite number", "export the file again");
        return values;
    }

    /// <summary>An index accessor: unsigned byte, short or int scalars (§3.7.2.1), each below <paramref name="vertices"/>.</summary>
    public int[] Indices(int i, string usedAt, int vertices)
    {
        var a = Layout(i, usedAt, "SCALAR", [5121, 5123, 5125], floats: false);
        if (Has(Item("accessors", i), "sparse", out _) || a.Bytes.Array is null)
            throw Error($"$.accessors[{i}]", "indices must be stored in a buffer view, not sparse", "glTF 2.0 §3.7.2.1");
        var indices = new int[a.Count];
        for (int k = 0; k < indices.Length; k++)
        {
            var b = a.Bytes.AsSpan((int)(a.Offset + (long)k * a.Stride));
            uint v = a.ComponentType switch
            {
                5121 => b[0],
                5123 => BinaryPrimitives.ReadUInt16LittleEndian(b),
                _ => BinaryPrimitives.ReadUInt32LittleEndian(b),
            };
            if (v >= vertices)
                throw Error($"$.accessors[{i}]", $"index {v} (element {k}) is not below the {vertices} vertices of the primitive at "
                    + usedAt, "the indices and the attributes do not belong together");
            indices[k] = (int)v;
        }
        return indices;
    }

    readonly record struct AccessorLayout(ArraySegment<byte> Bytes, long Offset, int Stride, int Count, int Components, int Size,
        int ComponentType, bool Normalized);

    /// <summary>An accessor's layout, checked (§3.6.2): its bytes (none without a bufferView: zeros), offset, stride, count.</summary>
    AccessorLayout Layout(int i, string usedAt, string type, int[] types, bool floats)
    {
        var a = Item("accessors", i);
        var path = $"$.accessors[{i}]";
        int componentType = (int)Number(a, "componentType", path, -1);
        int size = ComponentSize(componentType);
        if (size == 0) throw Error($"{path}.componentType", $"unknown componentType {componentType}", "5120–5123, 5125 or 5126");
        if (System.Array.IndexOf(types, componentType) < 0)
            throw Error($"{path}.componentType", $"componentType {componentType} is not allowed for the attribute at {usedAt}",
                $"allowed: {string.Join(", ", types)} (glTF 2.0 §3.7.2.1)");
        var t = String(a, "type", path) ?? throw Error(path, "missing \"type\"", "SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
        int components = Components(t);
        if (components == 0) throw Error($"{path}.type", $"unknown accessor type {MessageText.Quote(t)}", "SCALAR, VEC2, VEC3, VEC4");
        if (t != type)
            throw Error($"{path}.type", $"the attribute at {usedAt} needs type {type}, the accessor is {t}", "glTF 2.0 §3.7.2.1");
        int count = (int)Number(a, "count", path, -1, 1, int.MaxValue);
        if (count < 1) throw Error(path, "missing \"count\"", "an accessor states how many elements it holds");
        bool normalized = Bool(a, "normalized", path, false);
        if (normalized && (componentType is 5125 or 5126))
            throw Error($"{path}.normalized", "only byte and short components can be normalized", "glTF 2.0 §3.6.2.2");
        if (floats && componentType != 5126 && !normalized)
            throw Error($"{path}.normalized", $"integer components for the attribute at {usedAt} must be normalized",
                "set \"normalized\": true, or store floats");
        if ((long)count * components > 1L << 28)
            throw Error($"{path}.count", $"{count} elements are more than we read", "split the mesh");
        int elementSize = size * components;
        int view = Index(a, "bufferView", path, "bufferViews");
        if (view < 0) return new AccessorLayout(default, 0, elementSize, count, components, size, componentType, normalized);
        var (bytes, stride) = BufferView(view, path);
        long offset = (long)Number(a, "byteOffset", path, 0, 0, int.MaxValue);
        if (offset % size != 0)
            throw Error($"{path}.byteOffset", $"byteOffset {offset} is not a multiple of the component size {size}", "glTF 2.0 §3.6.2.4");
        if (stride == 0) stride = elementSize;
        else if (stride < elementSize)
            throw Error($"$.bufferViews[{view}].byteStride", $"byteStride {stride} is shorter than the element ({elementSize} bytes) "
                + $"of {path}", "glTF 2.0 §3.6.2.4");
        if (offset + (long)stride * (count - 1) + elementSize > bytes.Count)
            throw Error(path, $"{count} elements of {elementSize} bytes every {stride} from byte {offset} run past "
                + $"buffer view {view}'s {bytes.Count} bytes", "the accessor's count or offset is wrong: export the file again");
        return new AccessorLayout(bytes, offset, stride, count, components, size, componentType, normalized);
    }

    /// <summary>A sparse accessor's substitutions (§3.6.2.3): element indices (strictly increasing) and their values.</summary>
    void Sparse(JsonElement sparse, string path, float[] values, int count, int components, int componentType, bool normalized)
    {
        Object(sparse, path);
        int n = (int)Number(sparse, "count", path, -1, 1, count);
        if (n < 1) throw Error(path, "missing \"count\"", "the number of substituted elements");
        if (!Has(sparse, "indices", out var idx) || !Has(sparse, "values", out var val))
            throw Error(path, "a sparse accessor needs \"indices\" and \"values\"", "glTF 2.0 §3.6.2.3");
        int indexType = (int)Number(Object(idx, $"{path}.indices"), "componentType", $"{path}.indices", -1);
        if (indexType is not (5121 or 5123 or 5125))
            throw Error($"{path}.indices.componentType", $"componentType {indexType} for sparse indices", "5121, 5123 or 5125");
        var (ib, _) = BufferView(Index(idx, "bufferView", $"{path}.indices", "bufferViews", required: true), $"{path}.indices");
        long io = (long)Number(idx, "byteOffset", $"{path}.indices", 0, 0, int.MaxValue);
        var (vb, _) = BufferView(Index(Object(val, $"{path}.values"), "bufferView", $"{path}.values", "bufferViews", required: true),
            $"{path}.values");
        long vo = (long)Number(val, "byteOffset", $"{path}.values", 0, 0, int.MaxValue);
        int isize = ComponentSize(indexType), vsize = ComponentSize(componentType);
        if (io + (long)n * isize > ib.Count || vo + (long)n * vsize * components > vb.Count)
            throw Error(path, $"{n} sparse elements run past their buffer views", "export the file again");
        long previous = -1;
        for (int k = 0; k < n; k++)
        {
            long e = (long)Component(ib.AsSpan((int)(io + k * isize)), indexType, false);
            if (e <= previous || e >= count)
                throw Error($"{path}.indices", $"sparse index {e} (entry {k}) is not increasing or not below count {count}",
                    "glTF 2.0 §3.6.2.3");
            previous = e;
            for (int c = 0; c < components; c++)
                values[e * components + c] =
                    Component(vb.AsSpan((int)(vo + ((long)k * components + c) * vsize)), componentType, normalized);
        }
    }

    static float Component(ReadOnlySpan<byte> b, int type, bool normalized) => type switch
    {
        5126 => BinaryPrimitives.ReadSingleLittleEndian(b),
        5121 => normalized ? b[0] / 255f : b[0],
        5120 => normalized ? MathF.Max((sbyte)b[0] / 127f, -1) : (sbyte)b[0],
        5123 => normalized ? BinaryPrimitives.ReadUInt16LittleEndian(b) / 65535f : BinaryPrimitives.ReadUInt16LittleEndian(b),
        5122 => normalized ? MathF.Max(BinaryPrimitives.ReadInt16LittleEndian(b) / 32767f, -1) : BinaryPrimitives.ReadInt16LittleEndian(b),
        _ => BinaryPrimitives.ReadUInt32LittleEndian(b),
    };

    /// <summary>Raw JSON text of a small value, for messages.</summary>
    public static string Text(JsonElement e) => MessageText.Quote(e.GetRawText());

    public static string Utf8(ReadOnlySpan<byte> b) => Encoding.UTF8.GetString(b);
}
