using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// A converted scene: our scene JSON (docs/scene-format.md), loadable by SceneLoader.Parse with the source file's folder as
/// base (relative paths resolve from there), its report, and the meshes it holds inline (objects of type "mesh" with an
/// "inline" block, named by <see cref="ImportedMesh.Name"/>, and "prototypes" entries with one, keyed by it).
/// </summary>
public sealed record ImportedScene(JsonObject Scene, ImportReport Report, IReadOnlyList<ImportedMesh> Meshes);

/// <summary>An indexed triangle mesh an importer made (not a file it referenced).</summary>
/// <param name="Name">File-safe and unique in the scene (the PLY's stem when written beside).</param>
/// <param name="Positions">x, y, z per vertex.</param>
/// <param name="Indices">Three per triangle.</param>
/// <param name="Normals">x, y, z per vertex, or null.</param>
/// <param name="Uvs">u, v per vertex, or null.</param>
public sealed record ImportedMesh(string Name, float[] Positions, int[] Indices, float[]? Normals = null, float[]? Uvs = null)
{
    /// <summary>The scene JSON's "inline" block of this mesh: { "positions", "indices", "normals"?, "uvs"? }.</summary>
    public JsonObject InlineJson()
    {
        var o = new JsonObject { ["positions"] = Numbers(Positions), ["indices"] = Ints(Indices) };
        if (Normals is not null) o["normals"] = Numbers(Normals);
        if (Uvs is not null) o["uvs"] = Numbers(Uvs);
        return o;
    }

    static JsonArray Numbers(float[] v)
    {
        var a = new JsonArray();
        foreach (var x in v) a.Add((JsonNode)JsonValue.Create(x));
        return a;
    }

    static JsonArray Ints(int[] v)
    {
        var a = new JsonArray();
        foreach (var x in v) a.Add((JsonNode)JsonValue.Create(x));
        return a;
    }
}

/// <summary>A scene format we import: one class in its own folder (Import/Mitsuba/, …), one line in <see cref="SceneFormats"/>.</summary>
public interface ISceneFormat
{
    /// <summary>"mitsuba", "pbrt", "gltf": the report's format.</summary>
    string Name { get; }

    /// <summary>Whether the file is this format, by its extension and its first bytes.</summary>
    bool Claims(string path, ReadOnlySpan<byte> head);

    /// <summary>The file converted; bad input is an InputException (one line, file:line:column, exit 2).</summary>
    ImportedScene Convert(string path, ImportOptions options);
}
