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
    /// <summary>What was hit, for texture coordinates (<see cref="SceneGeometry.TexCoord"/>): 1 triangle, 2 analytic shape, 3
    /// plane, 4 a triangle of an instanced mesh.</summary>
    public int Kind;
    /// <summary>The triangle (BVH order), analytic shape, plane or instance (top-level order) index within its kind.</summary>
    public int Primitive;
    /// <summary>An instance's triangle, in its prototype's BVH order.</summary>
    public int Element;
    /// <summary>A triangle's barycentric coordinates of corners 1 and 2.</summary>
    public float B1, B2;
}
