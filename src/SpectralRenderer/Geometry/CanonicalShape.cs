using System.Numerics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// A kind of analytic shape in its own object space, as a registered shape type gives it (Scenes/Loading/ShapeTypes.cs):
/// what <see cref="AnalyticShape"/> needs to place it with a transform, trace it, texture it and sample it as an emitter.
/// A new kind is one such class and one registration. It must be finite; its normal is outward (or a flat shape's one
/// side, like the quad's +z), and <see cref="SampleArea"/> must be uniform in object-space area: an affine placement
/// then gives the world density p_A = 1/(A_obj·J), J = |det L|·|L⁻ᵀn| the area scale of the linear part L at normal n.
/// The built-in sphere, plane, quad and box keep their own code paths (SIMD faces, packets) and are not of this class.
/// </summary>
public abstract class CanonicalShape
{
    /// <summary>The closest hit of o + t·d (object space, d not normalised) with t in (tMin, tMax): t and the
    /// outward normal there (any length).</summary>
    public abstract bool Intersect(Vector3 o, Vector3 d, float tMin, float tMax, out float t, out Vector3 normal);

    /// <summary>An object-space box holding the shape.</summary>
    public abstract Bounds3 Bounds { get; }

    /// <summary>The one object-space normal of a flat shape (every hit returns it), else null.</summary>
    public virtual Vector3? FlatNormal => null;

    /// <summary>The surface area in object space.</summary>
    public abstract float Area { get; }

    /// <summary>A point for <paramref name="u"/> ∈ [0, 1)², uniform in object-space area, and its unit outward normal.</summary>
    public abstract Vector3 SampleArea(Vector2 u, out Vector3 normal);

    /// <summary>The texture coordinates (u, v) at object-space point <paramref name="p"/> on the surface (v up).</summary>
    public abstract Vector2 TexCoord(Vector3 p);

    /// <summary>The area the surface covers in (u, v), for the texel density √(uv area / world area) of a lookup.</summary>
    public abstract float TexCoordArea { get; }
}
