using System.Numerics;

namespace SpectralRenderer.Rendering;

/// <summary>A ray's closest surface: distance, point, unit shading normal (outward, not yet facing the ray) and object index.</summary>
public struct SurfaceHit
{
    public float T;
    public Vector3 Position;
    /// <summary>Unit shading normal (interpolated for smooth meshes).</summary>
    public Vector3 Normal;
    /// <summary>Unit geometric (face) normal: decides the side and offsets secondary rays.</summary>
    public Vector3 GeometricNormal;
    public int Object;
}
