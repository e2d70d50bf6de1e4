namespace SpectralRenderer.Geometry;

/// <summary>What a closest-hit query found: the primitive and its barycentric (u, v); the distance is the ray's TMax.</summary>
public struct Hit
{
    public int Primitive;
    public float U;
    public float V;
}
