namespace SpectralRenderer.Geometry;

/// <summary>What a closest-hit query found: the primitive and its barycentric (u, v); the distance is the ray's TMax.</summary>
public struct Hit
{
    public int Primitive;
    public float U;
    public float V;
    /// <summary>When <see cref="Primitive"/> is an instance (<c>InstanceSet</c>): the triangle hit in its prototype's order.</summary>
    public int Element;
}
