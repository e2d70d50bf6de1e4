using System.Buffers.Binary;
using System.Text;
using System.Text.Encodings.Web;
using System.Text.Json;
using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// An imported scene as bytes: the scene JSON with its meshes inline (what `spectral render FILE.xml` parses), or written as
/// a folder (`spectral import -o scene.json`): the JSON, each inline mesh as binary PLY in SCENE-meshes/, import-report.json.
/// Indented and in a fixed key order, so the same input gives the same bytes.
/// </summary>
public static class ImportWriter
{
    /// <summary>The scene JSON (UTF-8, indented, meshes inline), as the loader reads it from the source file's folder.</summary>
    public static byte[] InlineJson(ImportedScene scene) => Serialize(scene.Scene);

    /// <summary>
    /// Any JSON node, indented with two spaces and a final newline; an array of numbers or strings (or of such arrays: λ, v
    /// pairs) on one line, so a matrix or a spectrum reads as one.
    /// </summary>
    public static byte[] Serialize(JsonNode node)
    {
        var text = new StringBuilder();
        Write(node, text, 0);
        text.Append('\n');
        return Encoding.UTF8.GetBytes(text.ToString());
    }

    static readonly JsonSerializerOptions Compact = new() { Encoder = JavaScriptEncoder.UnsafeRelaxedJsonEscaping };

    static void Write(JsonNode? node, StringBuilder text, int depth)
    {
        switch (node)
        {
            case JsonObject o when o.Count > 0:
                {
                    text.Append("{\n");
                    int i = 0;
                    foreach (var (k, v) in o)
                    {
                        text.Append(' ', 2 * (depth + 1)).Append(JsonValue.Create(k).ToJsonString(Compact)).Append(": ");
                        Write(v, text, depth + 1);
                        text.Append(++i < o.Count ? ",\n" : "\n");
                    }
                    text.Append(' ', 2 * depth).Append('}');
                    break;
                }
            case JsonArray a when a.Count > 0 && !Flat(a):
                {
                    text.Append("[\n");
                    for (int i = 0; i < a.Count; i++)
                    {
                        text.Append(' ', 2 * (depth + 1));
                        Write(a[i], text, depth + 1);
                        text.Append(i + 1 < a.Count ? ",\n" : "\n");
                    }
                    text.Append(' ', 2 * depth).Append(']');
                    break;
                }
            case JsonArray a:
                text.Append('[');
                for (int i = 0; i < a.Count; i++)
                {
                    if (i > 0) text.Append(", ");
                    Write(a[i], text, depth);
                }
                text.Append(']');
                break;
            case null:
                text.Append("null");
                break;
            default:
                text.Append(node.ToJsonString(Compact));
                break;
        }
    }

    /// <summary>Numbers, strings, booleans, or arrays of them: written on one line.</summary>
    static bool Flat(JsonArray a) => a.All(v => v is JsonValue || (v is JsonArray inner && inner.All(x => x is JsonValue)));

    /// <summary>
    /// Writes <paramref name="output"/> (the scene), its inline meshes as PLY files in STEM-meshes/ beside it (objects and
    /// prototypes then name them by "file"), and import-report.json beside it. Relative paths of the source's folder (mesh and texture
    /// files, CSV spectra) are rewritten relative to the output's folder. Returns the files written.
    /// </summary>
    public static IReadOnlyList<string> WriteFolder(ImportedScene scene, string sourcePath, string output)
    {
        var outDir = Path.GetDirectoryName(Path.GetFullPath(output))!;
        var sourceDir = Path.GetDirectoryName(Path.GetFullPath(sourcePath))!;
        var json = (JsonObject)scene.Scene.DeepClone();
        var written = new List<string>();
        Rebase(json, sourceDir, outDir);
        if (scene.Meshes.Count > 0)
        {
            var stem = Path.GetFileNameWithoutExtension(output);
            var meshDir = Path.Combine(outDir, $"{stem}-meshes");
            Directory.CreateDirectory(meshDir);
            var byName = scene.Meshes.ToDictionary(m => m.Name, StringComparer.Ordinal);
            // An inline mesh of an object (named by its "name") or of a prototype (named by its key) is written as a PLY file,
            // and "file" takes the place of "inline"; the other keys keep their order.
            JsonObject? Externalize(JsonNode? node, string? name)
            {
                if (node is not JsonObject obj || obj["inline"] is null || name is null || !byName.TryGetValue(name, out var mesh))
                    return null;
                var file = Path.Combine(meshDir, $"{mesh.Name}.ply");
                File.WriteAllBytes(file, Ply(mesh));
                written.Add(file);
                var copy = new JsonObject();
                foreach (var (k, v) in obj)
                    copy[k == "inline" ? "file" : k] = k == "inline" ? JsonValue.Create($"{stem}-meshes/{mesh.Name}.ply") : v?.DeepClone();
                return copy;
            }
            if (json["objects"] is JsonArray objects)
                for (int i = 0; i < objects.Count; i++)
                    if (Externalize(objects[i], (objects[i] as JsonObject)?["name"]?.GetValue<string>()) is { } copy) objects[i] = copy;
            if (json["prototypes"] is JsonObject prototypes)
                foreach (var (name, node) in prototypes.ToList())
                    if (Externalize(node, name) is { } copy) prototypes[name] = copy;
        }
        File.WriteAllBytes(output, Serialize(json));
        written.Add(output);
        var report = Path.Combine(outDir, "import-report.json");
        File.WriteAllBytes(report, Serialize(scene.Report.ToJson()));
        written.Add(report);
        return written;
    }

    static readonly string[] PathKeys = ["file", "texture", "csv", "matrix_file"];

    /// <summary>Every relative path under a key of <see cref="PathKeys"/> made relative to the output's folder.</summary>
    static void Rebase(JsonNode? node, string sourceDir, string outDir)
    {
        if (sourceDir == outDir) return;
        switch (node)
        {
            case JsonObject o:
                foreach (var (k, v) in o.ToList())
                {
                    if (Array.IndexOf(PathKeys, k) >= 0 && v is JsonValue s && s.TryGetValue<string>(out var p) && !Path.IsPathRooted(p)
                        && File.Exists(Path.Combine(sourceDir, p)))
                        o[k] = Path.GetRelativePath(outDir, Path.Combine(sourceDir, p)).Replace('\\', '/');
                    else Rebase(v, sourceDir, outDir);
                }
                break;
            case JsonArray a:
                foreach (var v in a) Rebase(v, sourceDir, outDir);
                break;
        }
    }

    /// <summary>A binary little-endian PLY: vertex x y z [nx ny nz] [u v] as float, faces as uchar count + int indices.</summary>
    public static byte[] Ply(ImportedMesh m)
    {
        int vertices = m.Positions.Length / 3, faces = m.Indices.Length / 3;
        var header = new StringBuilder();
        header.Append("ply\nformat binary_little_endian 1.0\ncomment written by spectral import\n");
        header.Append($"element vertex {vertices}\nproperty float x\nproperty float y\nproperty float z\n");
        if (m.Normals is not null) header.Append("property float nx\nproperty float ny\nproperty float nz\n");
        if (m.Uvs is not null) header.Append("property float u\nproperty float v\n");
        header.Append($"element face {faces}\nproperty list uchar int vertex_indices\nend_header\n");
        int stride = 3 + (m.Normals is null ? 0 : 3) + (m.Uvs is null ? 0 : 2);
        var head = Encoding.ASCII.GetBytes(header.ToString());
        var bytes = new byte[head.Length + 4 * stride * vertices + 13 * faces];
        head.CopyTo(bytes, 0);
        int at = head.Length;
        for (int v = 0; v < vertices; v++)
        {
            for (int c = 0; c < 3; c++, at += 4) BinaryPrimitives.WriteSingleLittleEndian(bytes.AsSpan(at), m.Positions[3 * v + c]);
            if (m.Normals is not null)
                for (int c = 0; c < 3; c++, at += 4) BinaryPrimitives.WriteSingleLittleEndian(bytes.AsSpan(at), m.Normals[3 * v + c]);
            if (m.Uvs is not null)
                for (int c = 0; c < 2; c++, at += 4) BinaryPrimitives.WriteSingleLittleEndian(bytes.AsSpan(at), m.Uvs[2 * v + c]);
        }
        for (int f = 0; f < faces; f++)
        {
            bytes[at++] = 3;
            for (int c = 0; c < 3; c++, at += 4) BinaryPrimitives.WriteInt32LittleEndian(bytes.AsSpan(at), m.Indices[3 * f + c]);
        }
        return bytes;
    }
}
