using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import;

/// <summary>
/// Instancing in an imported scene (docs/scene-format.md, "Instancing"): a shape converted on its own as a mesh object
/// becomes an entry of the scene's "prototypes" — its mesh keys, without the object's type, name and material, which
/// each instance gives — keyed by the object's name.
/// </summary>
static class Prototypes
{
    /// <summary>
    /// Moves the last of <paramref name="objects"/> (a mesh object just converted) into <paramref name="prototypes"/> and
    /// returns the prototype's name.
    /// </summary>
    public static string TakeLast(JsonArray objects, JsonObject prototypes)
    {
        var converted = (JsonObject)objects[^1]!;
        objects.RemoveAt(objects.Count - 1);
        string name = converted["name"]!.GetValue<string>();
        var entry = new JsonObject();
        foreach (var (k, v) in converted)
            if (k is not ("type" or "name" or "material")) entry[k] = v?.DeepClone();
        prototypes[name] = entry;
        return name;
    }
}
