using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Acceleration;

/// <summary>
/// The flat faces of a scene made of few quads and boxes (a room, a light booth), tested all at once: each face is a
/// parallelogram c + a·e₁ + b·e₂, |a|, |b| ≤ ½, in world space, stored a SIMD register of faces at a time, so a ray meets
/// every face in a handful of vector operations and no hierarchy is walked. For one ray from anywhere in any direction
/// (a path tracer's bounces and shadow rays) this beats a BVH over so few shapes. A box is its six sides, each with the
/// box's outward normal, as <see cref="AnalyticShape.Intersect"/> gives it. The distances are computed in world space,
/// so they agree with the object-space test of <see cref="AnalyticShape"/> to float rounding, not bit for bit.
/// </summary>
public sealed class FlatFaces
{
    /// <summary>Most faces worth testing all at once (beyond it the BVH is faster).</summary>
    public const int MaxFaces = 64;

    // Per register of W faces, 12 vectors: the unit normal n (3) and n·c; the dual vectors g₁ (3) and g₁·c; g₂ (3) and g₂·c
    // (gᵢ·eⱼ = δᵢⱼ, gᵢ·n = 0), so a = g₁·p − g₁·c and b = g₂·p − g₂·c are the hit's coordinates on the face's edges.
    const int Fields = 12;
    readonly float[] _lanes;
    readonly int _registers;
    readonly int[] _shape;
    readonly Vector3[] _normal;

    FlatFaces(List<(Vector3 C, Vector3 E1, Vector3 E2, Vector3 N, int Shape)> faces)
    {
        int w = Vector<float>.Count;
        _registers = (faces.Count + w - 1) / w;
        _lanes = new float[_registers * Fields * w];   // padding lanes stay 0: n·d = 0 and n·c − n·o = 0 give t = NaN, never a hit
        _shape = new int[faces.Count];
        _normal = new Vector3[faces.Count];
        for (int f = 0; f < faces.Count; f++)
        {
            var (c, e1, e2, n, shape) = faces[f];
            var m = Vector3.Cross(e1, e2);
            var g1 = Vector3.Cross(e2, m) / Vector3.Dot(e1, Vector3.Cross(e2, m));
            var g2 = Vector3.Cross(m, e1) / Vector3.Dot(e2, Vector3.Cross(m, e1));
            ReadOnlySpan<float> values =
                [n.X, n.Y, n.Z, Vector3.Dot(n, c), g1.X, g1.Y, g1.Z, Vector3.Dot(g1, c), g2.X, g2.Y, g2.Z, Vector3.Dot(g2, c)];
            int baseIndex = f / w * Fields * w + f % w;
            for (int i = 0; i < Fields; i++) _lanes[baseIndex + i * w] = values[i];
            _shape[f] = shape;
            _normal[f] = n;
        }
    }

    /// <summary>The faces of <paramref name="shapes"/> (indexed as given), or null when one is not a quad or box or there are too
    /// many.</summary>
    public static FlatFaces? TryBuild(IReadOnlyList<AnalyticShape> shapes)
    {
        var faces = new List<(Vector3, Vector3, Vector3, Vector3, int)>();
        for (int s = 0; s < shapes.Count; s++)
        {
            var shape = shapes[s];
            var m = shape.ObjectToWorld;
            if (shape.Kind == ShapeKind.Quad)
                faces.Add((Vector3.Transform(Vector3.Zero, m), Vector3.TransformNormal(Vector3.UnitX, m),
                    Vector3.TransformNormal(Vector3.UnitY, m), shape.FlatNormal!.Value, s));
            else if (shape.Kind == ShapeKind.Box)
                for (int axis = 0; axis < 3; axis++)
                    for (int sign = -1; sign <= 1; sign += 2)
                    {
                        var outward = sign * Axis(axis);
                        faces.Add((Vector3.Transform(0.5f * outward, m), Vector3.TransformNormal(Axis((axis + 1) % 3), m),
                            Vector3.TransformNormal(Axis((axis + 2) % 3), m),
                            Vector3.Normalize(Vector3.TransformNormal(outward, shape.NormalToWorld)), s));
                    }
            else return null;
            if (faces.Count > MaxFaces) return null;
        }
        return faces.Count == 0 ? null : new FlatFaces(faces);
    }

    static Vector3 Axis(int i) => i == 0 ? Vector3.UnitX : i == 1 ? Vector3.UnitY : Vector3.UnitZ;

    /// <summary>The shape (index as given to <see cref="TryBuild"/>) a face belongs to.</summary>
    public int ShapeOf(int face) => _shape[face];

    /// <summary>A face's world-space unit normal (a box side's outward one).</summary>
    public Vector3 Normal(int face) => _normal[face];

    /// <summary>The closest face hit in (0, ray.TMax), which shortens ray.TMax to it; −1 if none.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Intersect(ref Ray ray)
    {
        int w = Vector<float>.Count;
        var v = MemoryMarshal.Cast<float, Vector<float>>(_lanes.AsSpan());
        Vector<float> ox = new(ray.Origin.X), oy = new(ray.Origin.Y), oz = new(ray.Origin.Z);
        Vector<float> dx = new(ray.Direction.X), dy = new(ray.Direction.Y), dz = new(ray.Direction.Z);
        var tMax = new Vector<float>(ray.TMax);
        var half = new Vector<float>(0.5f);
        int best = -1;
        for (int r = 0, i = 0; r < _registers; r++, i += Fields)
        {
            var t = Distance(v, i, ox, oy, oz, dx, dy, dz);
            var hit = Inside(v, i, t, ox, oy, oz, dx, dy, dz, tMax, half);
            if (hit == Vector<int>.Zero) continue;
            for (uint bits = Bits(hit); bits != 0; bits &= bits - 1)
            {   // the lanes hit, lowest first (so of two faces at the same distance the first wins)
                int l = BitOperations.TrailingZeroCount(bits);
                if (t[l] < ray.TMax) { ray.TMax = t[l]; best = r * w + l; }
            }
            tMax = new Vector<float>(ray.TMax);
        }
        return best;
    }

    /// <summary>Whether any face is hit in (0, ray.TMax).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Occluded(in Ray ray)
    {
        var v = MemoryMarshal.Cast<float, Vector<float>>(_lanes.AsSpan());
        Vector<float> ox = new(ray.Origin.X), oy = new(ray.Origin.Y), oz = new(ray.Origin.Z);
        Vector<float> dx = new(ray.Direction.X), dy = new(ray.Direction.Y), dz = new(ray.Direction.Z);
        var tMax = new Vector<float>(ray.TMax);
        var half = new Vector<float>(0.5f);
        for (int r = 0, i = 0; r < _registers; r++, i += Fields)
        {
            var t = Distance(v, i, ox, oy, oz, dx, dy, dz);
            if (Inside(v, i, t, ox, oy, oz, dx, dy, dz, tMax, half) != Vector<int>.Zero) return true;
        }
        return false;
    }

    /// <summary>Bit l set where lane l of <paramref name="mask"/> is set (its sign bit).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static uint Bits(Vector<int> mask)
    {
        if (Vector<int>.Count == 8) return Vector256.ExtractMostSignificantBits(mask.AsVector256());
        if (Vector<int>.Count == 4) return Vector128.ExtractMostSignificantBits(mask.AsVector128());
        uint bits = 0;
        for (int l = 0; l < Vector<int>.Count; l++) if (mask[l] != 0) bits |= 1u << l;
        return bits;
    }

    /// <summary>t where the ray meets each face's plane: (n·c − n·o)/(n·d).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector<float> Distance(Span<Vector<float>> v, int i, Vector<float> ox, Vector<float> oy, Vector<float> oz, Vector<float> dx,
        Vector<float> dy, Vector<float> dz)
    {
        var nd = v[i] * dx + v[i + 1] * dy + v[i + 2] * dz;
        var no = v[i] * ox + v[i + 1] * oy + v[i + 2] * oz;
        return (v[i + 3] - no) / nd;
    }

    /// <summary>Lanes whose plane hit is in (0, TMax) and inside the parallelogram (|a|, |b| ≤ ½).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector<int> Inside(Span<Vector<float>> v, int i, Vector<float> t, Vector<float> ox, Vector<float> oy, Vector<float> oz,
        Vector<float> dx, Vector<float> dy, Vector<float> dz,
        Vector<float> tMax, Vector<float> half)
    {
        var px = ox + t * dx;
        var py = oy + t * dy;
        var pz = oz + t * dz;
        var a = v[i + 4] * px + v[i + 5] * py + v[i + 6] * pz - v[i + 7];
        var b = v[i + 8] * px + v[i + 9] * py + v[i + 10] * pz - v[i + 11];
        return Vector.GreaterThan(t, Vector<float>.Zero) & Vector.LessThan(t, tMax)
            & Vector.LessThanOrEqual(Vector.Abs(a), half) & Vector.LessThanOrEqual(Vector.Abs(b), half);
    }
}
