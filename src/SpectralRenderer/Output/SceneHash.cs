using System.Security.Cryptography;
using System.Text;
using System.Text.Json.Nodes;

using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output;

/// <summary>
/// The identity of what a render computes, written into every render.json as "scene_hash": SHA-256 of the
/// manifest's description of the image — tool version, film size, spp, band grid, colorimetry, objects, lights,
/// AOV settings and the scene file as resolved — plus the output formats and EXR compression. Not hashed: where and
/// when it ran, timings, ray counts, the crop. Shards of one render have equal hashes; <c>spectral merge</c> refuses
/// shards whose hashes differ.
/// </summary>
public static class SceneHash
{
    static readonly string[] Keys =
        ["tool", "version", "width", "height", "spp", "bands", "colour", "objects", "lights", "aov", "resolved_scene"];

    public static string Of(JsonObject manifest, OutputProducts products, ExrCompressionChoice exrCompression)
    {
        var identity = new JsonObject();
        foreach (var key in Keys)
        {
            var value = manifest[key]?.DeepClone();
            // The band images' scale is the brightest value of the pixels present: a property of the crop, not the scene.
            if (key == "bands" && value is JsonObject b) b.Remove("band_image_scale");
            // How many pixels fell back to products of band means is a count over the pixels present, too.
            if (key == "colour" && value is JsonObject c) c.Remove("fallback_pixels");
            identity[key] = value;
        }
        identity["formats"] = new JsonArray(OutputNames.Products.Where(p => (products & p.Product) != 0)
            .Select(p => (JsonNode)JsonValue.Create(p.Name)!).ToArray());
        identity["exr_compression"] = OutputNames.Name(exrCompression);
        return "sha256:" + Convert.ToHexStringLower(SHA256.HashData(Encoding.UTF8.GetBytes(identity.ToJsonString())));
    }
}
