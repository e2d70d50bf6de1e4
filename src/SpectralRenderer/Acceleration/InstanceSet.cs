using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// Instanced meshes as a two-level hierarchy (pbrt-v4's and Embree's instancing): each distinct mesh (a prototype) has its
/// own <see cref="TriangleSet"/> in object space, and a top-level <see cref="Bvh"/> holds the instances by the world bounds
/// of their prototype's box under their transform. An instance is tested by taking the ray into its object space —
/// o' = o·M⁻¹, d' = d·M⁻¹ (System.Numerics' row vectors, p_world = p·M), d' not normalised — so the ray's parameter t is
/// the same in both spaces: o' + t·d' = (o + t·d)·M⁻¹. The prototype's hit distance is thus the world distance, whatever
/// the scale, and TMax carries over unchanged. Hit.Primitive is the instance in top-level order, Hit.Element the triangle in
/// its prototype's order. No allocation per ray.
/// </summary>
public struct InstanceSet : IPrimitiveIntersector
{
    readonly TriangleSet[] _prototypes;
    readonly int[] _prototypeOf;          // k → its prototype
    readonly Matrix4x4[] _worldToObject;  // k → M⁻¹

    public Bvh Bvh { get; }
    /// <summary>k → the instance's index as given to <see cref="Build"/>.</summary>
    public int[] InstanceOf => Bvh.PrimitiveOrder;
    public int Count => _prototypeOf.Length;
    public ReadOnlySpan<TriangleSet> Prototypes => _prototypes;

    InstanceSet(TriangleSet[] prototypes, int[] prototypeOf, Matrix4x4[] worldToObject, Bvh bvh)
    {
        _prototypes = prototypes; _prototypeOf = prototypeOf; _worldToObject = worldToObject; Bvh = bvh;
    }

    /// <summary>The prototype (index into <see cref="Prototypes"/>) of instance k (top-level order).</summary>
    public int PrototypeOf(int k) => _prototypeOf[k];

    /// <summary>Instance i of the input is <paramref name="prototypes"/>[<paramref name="prototypeOf"/>[i]] placed by
    /// <paramref name="objectToWorld"/>[i] (affine, invertible).</summary>
    public static InstanceSet Build(IReadOnlyList<TriangleSet> prototypes, IReadOnlyList<int> prototypeOf,
        IReadOnlyList<Matrix4x4> objectToWorld)
    {
        int n = prototypeOf.Count;
        var bounds = new Bounds3[n];
        var inverse = new Matrix4x4[n];
        for (int i = 0; i < n; i++)
        {
            if (!Matrix4x4.Invert(objectToWorld[i], out inverse[i]))
                throw new ArgumentException($"instance {i} has a singular transform", nameof(objectToWorld));
            bounds[i] = WorldBounds(prototypes[prototypeOf[i]].Bvh.Bounds, objectToWorld[i]);
        }
        var bvh = Bvh.Build(bounds, 1);
        var order = bvh.PrimitiveOrder;
        return new InstanceSet([.. prototypes], [.. order.Select(i => prototypeOf[i])], [.. order.Select(i => inverse[i])], bvh);
    }

    /// <summary>The world box of an object-space box under <paramref name="m"/> (<see cref="Bounds3.Transformed"/>), widened by a
    /// few float ulps of its size so a ray that meets the geometry in object space (rounded there) is never culled by a box
    /// rounded in world space.</summary>
    public static Bounds3 WorldBounds(Bounds3 box, Matrix4x4 m)
    {
        var b = box.Transformed(m);
        var pad = new Vector3(4e-7f * (b.Extent.Length() + Vector3.Max(Vector3.Abs(b.Min), Vector3.Abs(b.Max)).Length()));
        return new Bounds3(b.Min - pad, b.Max + pad);
    }

    /// <summary>The ray in instance k's object space, with the same t (see the type's summary).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly Ray ToObject(int k, in Ray ray)
    {
        ref readonly var m = ref _worldToObject[k];
        return new Ray(Vector3.Transform(ray.Origin, m), Vector3.TransformNormal(ray.Direction, m), ray.TMax);
    }

    public void Prepare(in Ray ray) { }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Intersect(int k, ref Ray ray, ref Hit hit)
    {
        var local = ToObject(k, ray);
        var prototype = _prototypes[_prototypeOf[k]];
        var h = new Hit { Primitive = -1 };
        if (!prototype.Wide.Intersect(ref prototype, ref local, ref h)) return false;
        ray.TMax = local.TMax;
        hit.Primitive = k; hit.U = h.U; hit.V = h.V; hit.Element = h.Primitive;
        return true;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Occluded(int k, in Ray ray)
    {
        var local = ToObject(k, ray);
        var prototype = _prototypes[_prototypeOf[k]];
        return prototype.Wide.Occluded(ref prototype, in local);
    }

    /// <summary>The closest instanced triangle hit in (0, ray.TMax).</summary>
    public bool Intersect(ref Ray ray, ref Hit hit)
    {
        var self = this;
        return Bvh.Intersect(ref self, ref ray, ref hit);
    }

    /// <summary>Whether any instanced triangle is hit in (0, ray.TMax).</summary>
    public bool Occluded(in Ray ray)
    {
        var self = this;
        return Bvh.Occluded(ref self, in ray);
    }
}
