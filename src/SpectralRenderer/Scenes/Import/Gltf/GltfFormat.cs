namespace SpectralRenderer.Scenes.Import.Gltf;

/// <summary>glTF 2.0 (Khronos): a .gltf JSON file with its buffers and images, or a binary .glb.</summary>
public sealed class GltfFormat : ISceneFormat
{
    public string Name => "gltf";

    public bool Claims(string path, ReadOnlySpan<byte> head)
    {
        var ext = Path.GetExtension(path).ToLowerInvariant();
        return ext is ".gltf" or ".glb" || head.StartsWith("glTF"u8);
    }

    public ImportedScene Convert(string path, ImportOptions options) => new GltfConverter(GltfDocument.Load(path), options).Convert();
}
