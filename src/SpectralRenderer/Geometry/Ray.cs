using System.Numerics;

namespace SpectralRenderer.Geometry;

/// <summary>A ray o + t·d, t in (0, TMax). Geometry is in float: one ray serves all bands.</summary>
public struct Ray
{
    public Vector3 Origin;
    public Vector3 Direction;
    public float TMax;

    public Ray(Vector3 origin, Vector3 direction, float tMax = float.PositiveInfinity)
    {
        Origin = origin;
        Direction = direction;
        TMax = tMax;
    }

    public readonly Vector3 At(float t) => Origin + t * Direction;
}
