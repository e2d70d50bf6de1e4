using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>The finite analytic shapes of a scene in BVH order, intersected in their object spaces.</summary>
public readonly struct AnalyticSet : IPrimitiveIntersector
{
    readonly AnalyticShape[] _shapes;

    public AnalyticSet(AnalyticShape[] shapesInBvhOrder) { _shapes = shapesInBvhOrder; }

    public AnalyticShape this[int k] => _shapes[k];

    public void Prepare(in Ray ray) { }

    public bool Intersect(int k, ref Ray ray, ref Hit hit)
    {
        if (!_shapes[k].Intersect(ray, 0, out float t, out _)) return false;
        ray.TMax = t;
        hit.Primitive = k;
        return true;
    }

    public bool Occluded(int k, in Ray ray) => _shapes[k].Intersect(ray, 0, out _, out _);
}
