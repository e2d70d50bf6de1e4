using System.Buffers.Binary;
using System.Text;
using System.Text.Json.Nodes;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// Writes small glTF 2.0 assets for the tests, by the specification (§3.6, §4.4), independently of our reader: the JSON
/// given, and accessors for float and index arrays appended to one binary buffer, written as a .gltf with a data: URI or an
/// external .bin, or as a .glb.
/// </summary>
sealed class GltfBuilder
{
    readonly MemoryStream _bin = new();
    public JsonObject Root { get; } = new()
    {
        ["asset"] = new JsonObject { ["version"] = "2.0", ["generator"] = "SpectralRenderer tests" },
        ["scene"] = 0,
        ["scenes"] = new JsonArray(new JsonObject { ["nodes"] = new JsonArray() }),
        ["nodes"] = new JsonArray(),
        ["meshes"] = new JsonArray(),
        ["accessors"] = new JsonArray(),
        ["bufferViews"] = new JsonArray(),
    };

    JsonArray Array(string key) => (JsonArray)Root[key]!;

    /// <summary>A buffer view of the bytes (4-aligned) and an accessor over it; returns the accessor's index.</summary>
    int Accessor(byte[] bytes, int componentType, string type, int count, JsonObject? extra = null)
    {
        while (_bin.Length % 4 != 0) _bin.WriteByte(0);
        long offset = _bin.Length;
        _bin.Write(bytes);
        Array("bufferViews").Add((JsonNode)new JsonObject { ["buffer"] = 0, ["byteOffset"] = offset, ["byteLength"] = bytes.Length });
        var a = new JsonObject
        {
            ["bufferView"] = Array("bufferViews").Count - 1,
            ["componentType"] = componentType,
            ["count"] = count,
            ["type"] = type,
        };
        if (extra is not null) foreach (var (k, v) in extra) a[k] = v?.DeepClone();
        Array("accessors").Add((JsonNode)a);
        return Array("accessors").Count - 1;
    }

    public int Floats(float[] v, string type)
    {
        var b = new byte[v.Length * 4];
        for (int i = 0; i < v.Length; i++) BinaryPrimitives.WriteSingleLittleEndian(b.AsSpan(4 * i), v[i]);
        int n = type switch { "VEC2" => 2, "VEC3" => 3, _ => 1 };
        return Accessor(b, 5126, type, v.Length / n);
    }

    public int Indices16(int[] v)
    {
        var b = new byte[v.Length * 2];
        for (int i = 0; i < v.Length; i++) BinaryPrimitives.WriteUInt16LittleEndian(b.AsSpan(2 * i), (ushort)v[i]);
        return Accessor(b, 5123, "SCALAR", v.Length);
    }

    /// <summary>A mesh of one triangle primitive; returns the mesh's index.</summary>
    public int Mesh(float[] positions, int[] indices, float[]? normals = null, float[]? uvs = null, int? material = null)
    {
        var attributes = new JsonObject { ["POSITION"] = Floats(positions, "VEC3") };
        if (normals is not null) attributes["NORMAL"] = Floats(normals, "VEC3");
        if (uvs is not null) attributes["TEXCOORD_0"] = Floats(uvs, "VEC2");
        var prim = new JsonObject { ["attributes"] = attributes, ["indices"] = Indices16(indices) };
        if (material is not null) prim["material"] = material;
        Array("meshes").Add((JsonNode)new JsonObject { ["primitives"] = new JsonArray(prim) });
        return Array("meshes").Count - 1;
    }

    /// <summary>A square of side <paramref name="size"/> in the node's xy plane, facing +z, uv (0, 0) at its top-left corner.</summary>
    public int Square(float size, int? material = null)
    {
        float h = size / 2;
        return Mesh([-h, h, 0, h, h, 0, h, -h, 0, -h, -h, 0], [0, 2, 1, 0, 3, 2], [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1],
            [0, 0, 1, 0, 1, 1, 0, 1], material);
    }

    /// <summary>Adds a node (a root of the scene unless <paramref name="parent"/> is given); returns its index.</summary>
    public int Node(JsonObject node, int? parent = null)
    {
        Array("nodes").Add((JsonNode)node);
        int i = Array("nodes").Count - 1;
        if (parent is null) ((JsonArray)Root["scenes"]![0]!["nodes"]!).Add((JsonNode)i);
        else
        {
            var p = (JsonObject)Array("nodes")[parent.Value]!;
            if (p["children"] is not JsonArray children) p["children"] = children = [];
            children.Add((JsonNode)i);
        }
        return i;
    }

    public void Add(string key, JsonNode item)
    {
        if (Root[key] is not JsonArray a) Root[key] = a = [];
        a.Add(item);
    }

    public void Light(JsonObject light)
    {
        if (Root["extensions"] is not JsonObject ext) Root["extensions"] = ext = [];
        if (ext["KHR_lights_punctual"] is not JsonObject lp)
            ext["KHR_lights_punctual"] = lp = new JsonObject { ["lights"] = new JsonArray() };
        ((JsonArray)lp["lights"]!).Add((JsonNode)light);
    }

    JsonObject WithBuffer(string? uri)
    {
        var root = (JsonObject)Root.DeepClone();
        var buffer = new JsonObject { ["byteLength"] = _bin.Length };
        if (uri is not null) buffer["uri"] = uri;
        root["buffers"] = new JsonArray(buffer);
        return root;
    }

    /// <summary>FILE.gltf with the buffer as a base64 data: URI (or, with <paramref name="binFile"/>, a .bin beside it).</summary>
    public string WriteGltf(string path, bool binFile = false)
    {
        string uri;
        if (binFile)
        {
            var bin = Path.ChangeExtension(path, ".bin");
            File.WriteAllBytes(bin, _bin.ToArray());
            uri = Path.GetFileName(bin);
        }
        else uri = "data:application/octet-stream;base64," + Convert.ToBase64String(_bin.ToArray());
        File.WriteAllText(path, WithBuffer(uri).ToJsonString());
        return path;
    }

    /// <summary>FILE.glb: the 12-byte header, the JSON chunk (space-padded) and the BIN chunk (zero-padded), §4.4.</summary>
    public string WriteGlb(string path)
    {
        var json = Encoding.UTF8.GetBytes(WithBuffer(null).ToJsonString());
        var jsonPadded = json.Concat(Enumerable.Repeat((byte)' ', (4 - json.Length % 4) % 4)).ToArray();
        var bin = _bin.ToArray();
        var binPadded = bin.Concat(new byte[(4 - bin.Length % 4) % 4]).ToArray();
        var file = new MemoryStream();
        void U32(uint v) { Span<byte> b = stackalloc byte[4]; BinaryPrimitives.WriteUInt32LittleEndian(b, v); file.Write(b); }
        U32(0x46546C67);
        U32(2);
        U32((uint)(12 + 8 + jsonPadded.Length + 8 + binPadded.Length));
        U32((uint)jsonPadded.Length);
        U32(0x4E4F534A);
        file.Write(jsonPadded);
        U32((uint)binPadded.Length);
        U32(0x004E4942);
        file.Write(binPadded);
        File.WriteAllBytes(path, file.ToArray());
        return path;
    }
}
