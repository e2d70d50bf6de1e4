using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Ray queries against every object of a scene: closest hit for camera and secondary rays, any hit
/// for shadow rays.
/// </summary>
public sealed class SceneGeometry
{
    readonly AnalyticShape[] _shapes;
    readonly int[] _shapeObject;

    public SceneGeometry(Scene scene)
    {
        var shapes = new List<AnalyticShape>();
        var owner = new List<int>();
        for (int i = 0; i < scene.Objects.Count; i++)
            if (scene.Objects[i].Shape is { } s) { shapes.Add(s); owner.Add(i); }
        _shapes = shapes.ToArray();
        _shapeObject = owner.ToArray();
        var b = Bounds3.Empty;
        foreach (var s in _shapes) if (!s.IsInfinite) b.Include(s.Bounds);
        SceneBounds = b;
        float extent = b.IsEmpty ? 1 : Math.Max(b.Extent.Length(), Vector3.Max(Vector3.Abs(b.Min), Vector3.Abs(b.Max)).Length());
        Epsilon = 1e-5f * Math.Max(1f, extent);
    }

    public Bounds3 SceneBounds { get; }
    /// <summary>Offset for secondary-ray origins, scaled to the scene's size.</summary>
    public float Epsilon { get; }

    public bool Intersect(ref Ray ray, out SurfaceHit hit)
    {
        hit = default;
        int found = -1;
        Vector3 normal = default;
        for (int i = 0; i < _shapes.Length; i++)
        {
            if (_shapes[i].Intersect(ray, 0, out float t, out var n))
            {
                ray.TMax = t;
                found = i;
                normal = n;
            }
        }
        if (found < 0) return false;
        hit.T = ray.TMax;
        hit.Position = ray.At(ray.TMax);
        hit.Normal = normal;
        hit.Object = _shapeObject[found];
        return true;
    }

    public bool Occluded(in Ray ray)
    {
        for (int i = 0; i < _shapes.Length; i++)
            if (_shapes[i].Intersect(ray, 0, out _, out _)) return true;
        return false;
    }
}
