namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>A directive with a type and parameters (Camera "perspective" …, Material "diffuse" …) and where it stands.</summary>
public sealed record PbrtEntity(string Type, PbrtParameters Parameters, PbrtToken Token)
{
    public string Where => Token.Where;
}

/// <summary>The material a shape has: an anonymous `Material` (its index) or a `NamedMaterial`.</summary>
public readonly record struct PbrtMaterialRef(int Anonymous, string? Named, PbrtToken? Token)
{
    public static PbrtMaterialRef Default => new(-1, null, null);
}

/// <summary>A light source with the transformation in force where it was declared (light to world).</summary>
public sealed record PbrtLight(PbrtEntity Entity, PbrtTransform WorldFromLight);

/// <summary>
/// A shape with everything the graphics state gave it: object to world (for an instance's copy, the instance's
/// transformation times the shape's own), its material, its area light, ReverseOrientation, and the instance it came from.
/// </summary>
public sealed record PbrtShape(
    PbrtEntity Entity,
    PbrtTransform WorldFromObject,
    PbrtMaterialRef Material,
    PbrtEntity? AreaLight,
    bool ReverseOrientation,
    string? Instance,
    int InstanceCopy);

/// <summary>A named texture: `Texture "name" "spectrum"|"float" "class" …`.</summary>
public sealed record PbrtTexture(string Name, string ValueType, PbrtEntity Entity);

/// <summary>What a pbrt-v4 file (with its includes) declares, in document order, instances expanded.</summary>
public sealed class PbrtDocument
{
    public PbrtEntity? Camera { get; set; }
    public PbrtTransform CameraFromWorld { get; set; } = PbrtTransform.Identity;
    public PbrtEntity? Film { get; set; }
    public PbrtEntity? Sampler { get; set; }
    public PbrtEntity? Integrator { get; set; }
    public List<PbrtEntity> Materials { get; } = [];
    public Dictionary<string, PbrtEntity> NamedMaterials { get; } = new(StringComparer.Ordinal);
    public Dictionary<string, PbrtTexture> Textures { get; } = new(StringComparer.Ordinal);
    public List<PbrtLight> Lights { get; } = [];
    public List<PbrtShape> Shapes { get; } = [];
    public HashSet<string> InstancedObjects { get; } = new(StringComparer.Ordinal);
}
