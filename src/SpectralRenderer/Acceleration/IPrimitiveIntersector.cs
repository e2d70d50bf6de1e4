using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// What a <see cref="Bvh"/> leaf asks of the primitives it holds. k is the primitive's position in BVH order
/// (<see cref="Bvh.PrimitiveOrder"/>[k] is its original index). Implemented by structs so traversal is
/// specialised per primitive type without virtual calls.
/// </summary>
public interface IPrimitiveIntersector
{
    /// <summary>Called once per query before any primitive test, to precompute what depends on the ray only.</summary>
    void Prepare(in Ray ray);

    /// <summary>Closest hit: if primitive k is hit at t in (0, ray.TMax), sets ray.TMax = t, fills hit (Primitive = k, U, V) and returns
    /// true.</summary>
    bool Intersect(int k, ref Ray ray, ref Hit hit);

    /// <summary>Any hit of primitive k at t in (0, ray.TMax).</summary>
    bool Occluded(int k, in Ray ray);
}
