using System.Numerics;

namespace SpectralRenderer.Rendering;

/// <summary>A ray's closest surface: distance, point, unit shading normal (outward, not yet facing the ray) and object index.</summary>
public struct SurfaceHit
{
    public float T;
    public Vector3 Position;
    public Vector3 Normal;
    public int Object;
}
