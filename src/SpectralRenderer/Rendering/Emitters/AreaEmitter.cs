using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// An object whose material emits (<see cref="Emission"/>), as a light the path tracer samples: a point x on its surface
/// with its outward normal n_x, drawn by solid angle where that is exact (a round sphere seen from outside: the cone it
/// subtends, uniform) and else uniformly by area (parallelograms of a quad or box, triangles of a mesh by area, a sphere
/// from inside), with the solid-angle density p_ω = p_A·d²/|n_x·ω| of an area draw (Veach 1997, eq. 8.10). A registered
/// shape kind (disk, cylinder, one added by a registration) is drawn by its own area sampling
/// (<see cref="AnalyticShape.SampleArea"/>, uniform in object space, p_A from the placement's area scale).
/// </summary>
[CompiledAtFirstCall]
internal sealed class AreaEmitter
{
    readonly Kind _kind;
    // sphere
    readonly Vector3 _centre;
    readonly float _radius;
    // parallelograms (quad, box faces) and triangles: corner, two edges, unit outward normal, cumulative area
    readonly Vector3[] _corner = [], _edge1 = [], _edge2 = [], _normal = [];
    readonly float[] _cumulative = [];
    readonly float _area;
    // texture coordinates of a point (a textured emission): the analytic shape, or the mesh's per-corner uvs
    readonly AnalyticShape? _shape;
    readonly Vector2[]? _meshUvs;

    enum Kind { Sphere, Parallelograms, Triangles, Shape }

    public AreaEmitter(SceneObject o, float[] radiance, bool twoSided, string where, SubBandTexture? texture = null)
    {
        Radiance = radiance;
        TwoSided = twoSided;
        Texture = texture;
        _shape = o.Shape;
        if (o.Mesh is { } mesh)
        {
            _meshUvs = mesh.TexCoords;
            _kind = Kind.Triangles;
            int n = mesh.TriangleCount;
            _corner = new Vector3[n]; _edge1 = new Vector3[n]; _edge2 = new Vector3[n]; _normal = new Vector3[n];
            _cumulative = new float[n];
            double total = 0;
            for (int t = 0; t < n; t++)
            {
                var (p0, p1, p2) = mesh.Triangle(t);
                _corner[t] = p0; _edge1[t] = p1 - p0; _edge2[t] = p2 - p0;
                var c = Vector3.Cross(_edge1[t], _edge2[t]);
                float a = c.Length();
                _normal[t] = a > 0 ? c / a : Vector3.UnitY;
                total += 0.5 * a;
                _cumulative[t] = (float)total;
            }
            _area = (float)total;
            return;
        }
        var shape = o.Shape ?? throw new ArgumentException($"object '{o.Name}' has no shape");
        var m = shape.ObjectToWorld;
        switch (shape.Kind)
        {
            case ShapeKind.Sphere:
                {
                    _kind = Kind.Sphere;
                    _centre = Vector3.Transform(Vector3.Zero, m);
                    float rx = Vector3.TransformNormal(Vector3.UnitX, m).Length(), ry = Vector3.TransformNormal(Vector3.UnitY, m).Length(),
                        rz = Vector3.TransformNormal(Vector3.UnitZ, m).Length();
                    if (Math.Abs(rx - ry) > 1e-4f * rx || Math.Abs(rx - rz) > 1e-4f * rx)
                        throw new InputException(where, $"object '{o.Name}' emits but is not round (scaled unevenly)",
                            "an emitting sphere needs one radius; use a mesh for an emitting ellipsoid");
                    _radius = rx;
                    _area = 4 * MathF.PI * _radius * _radius;
                    return;
                }
            case ShapeKind.Quad:
                _kind = Kind.Parallelograms;
                (_corner, _edge1, _edge2, _normal) = Faces(shape, [(new(-0.5f, -0.5f, 0), Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ)]);
                break;
            case ShapeKind.Box:
                {
                    _kind = Kind.Parallelograms;
                    var faces = new List<(Vector3, Vector3, Vector3, Vector3)>();
                    for (int axis = 0; axis < 3; axis++)
                        for (int sign = -1; sign <= 1; sign += 2)
                        {
                            var n = axis == 0 ? Vector3.UnitX : axis == 1 ? Vector3.UnitY : Vector3.UnitZ;
                            var u = axis == 0 ? Vector3.UnitY : axis == 1 ? Vector3.UnitZ : Vector3.UnitX;
                            var v = Vector3.Cross(n, u);
                            faces.Add((sign * 0.5f * n - 0.5f * u - 0.5f * v, u, v, sign * n));
                        }
                    (_corner, _edge1, _edge2, _normal) = Faces(shape, faces);
                    break;
                }
            case ShapeKind.Registered:
                _kind = Kind.Shape;
                _area = shape.Area;
                return;
            default:
                throw new InputException(where, $"object '{o.Name}' is an infinite plane and cannot emit (no finite area to sample)",
                    "use a quad or a box as the area light, or the scene's \"background\" as a uniform sky");
        }
        _cumulative = new float[_corner.Length];
        double sum = 0;
        for (int i = 0; i < _corner.Length; i++) { sum += Vector3.Cross(_edge1[i], _edge2[i]).Length(); _cumulative[i] = (float)sum; }
        _area = (float)sum;
    }

    static (Vector3[], Vector3[], Vector3[], Vector3[]) Faces(AnalyticShape shape,
        IReadOnlyList<(Vector3 Corner, Vector3 U, Vector3 V, Vector3 N)> faces)
    {
        var m = shape.ObjectToWorld;
        int n = faces.Count;
        var corner = new Vector3[n]; var e1 = new Vector3[n]; var e2 = new Vector3[n]; var normal = new Vector3[n];
        for (int i = 0; i < n; i++)
        {
            var (c, u, v, nn) = faces[i];
            corner[i] = Vector3.Transform(c, m);
            e1[i] = Vector3.Transform(c + u, m) - corner[i];
            e2[i] = Vector3.Transform(c + v, m) - corner[i];
            normal[i] = Vector3.Normalize(Vector3.TransformNormal(nn, shape.NormalToWorld));
        }
        return (corner, e1, e2, normal);
    }

    /// <summary>L_e on the path tracer's grid (a textured emitter's: the texture's mean).</summary>
    public float[] Radiance { get; }
    /// <summary>L_e as a texture on the sub-band grid (<see cref="TexCoord"/> places a point on it), or null.</summary>
    public SubBandTexture? Texture { get; }
    public bool TwoSided { get; }
    /// <summary>The emitting surface's area in m² (scene units²).</summary>
    public float Area => _area;

    /// <summary>
    /// Its bounds for a light tree: the box of its surface, the cone of its outward normals (about their area-weighted mean;
    /// every direction for a sphere, a box, a registered kind or normals that cancel) and θ_e = π/2 (a Lambertian surface).
    /// </summary>
    public EmitterBounds Bounds()
    {
        var box = Bounds3.Empty;
        Vector3 axis = Vector3.UnitY;
        float cosSpread = -1;
        switch (_kind)
        {
            case Kind.Sphere:
                box.Include(_centre - new Vector3(_radius));
                box.Include(_centre + new Vector3(_radius));
                break;
            case Kind.Shape:
                box = _shape!.Bounds;   // its normals: every direction (a registered kind's sidedness is its own)
                break;
            default:
                {
                    var mean = Vector3.Zero;
                    for (int i = 0; i < _corner.Length; i++)
                    {
                        box.Include(_corner[i]);
                        box.Include(_corner[i] + _edge1[i]);
                        box.Include(_corner[i] + _edge2[i]);
                        if (_kind == Kind.Parallelograms) box.Include(_corner[i] + _edge1[i] + _edge2[i]);
                        mean += Vector3.Cross(_edge1[i], _edge2[i]).Length() * _normal[i];
                    }
                    if (mean.LengthSquared() > 0 && float.IsFinite(mean.LengthSquared()))
                    {
                        axis = Vector3.Normalize(mean);
                        cosSpread = 1;
                        for (int i = 0; i < _normal.Length; i++) cosSpread = MathF.Min(cosSpread, Vector3.Dot(axis, _normal[i]));
                        // a little wider than the normals, so rounding never leaves one outside; all but a hemisphere: all
                        cosSpread = cosSpread > 1e-3f ? MathF.Cos(MathF.Acos(MathF.Min(cosSpread, 1)) + 1e-4f) : -1;
                    }
                    break;
                }
        }
        return new EmitterBounds(box, axis, cosSpread, 0, TwoSided);
    }

    /// <summary>Does the emitter send light from surface normal <paramref name="n"/> along <paramref name="towards"/>?</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool Emits(Vector3 n, Vector3 towards) => TwoSided || Vector3.Dot(n, towards) > 0;

    /// <summary>A point x (normal n_x) on the emitter seen from <paramref name="p"/> for <paramref name="u"/> ∈ [0, 1)², and the
    /// solid-angle density of its direction; false when it has none (p on the surface, a grazing draw).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Sample(Vector3 p, Vector2 u, out Vector3 x, out Vector3 nx, out float pdf) => Sample(p, u, out x, out nx, out pdf, out _);

    /// <summary>As <see cref="Sample(Vector3, Vector2, out Vector3, out Vector3, out float)"/>, and the face (parallelogram or
    /// triangle; 0 on a sphere) the point lies on, for <see cref="TexCoord"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public bool Sample(Vector3 p, Vector2 u, out Vector3 x, out Vector3 nx, out float pdf, out int face)
    {
        x = default; nx = default; pdf = 0; face = 0;
        if (_kind == Kind.Sphere)
        {
            var toCentre = _centre - p;
            float d2 = toCentre.LengthSquared(), r2 = _radius * _radius;
            if (d2 > r2 * 1.0001f)
            {
                // Uniform in the cone the sphere subtends: cos θ from 1 to cos θ_max, 1 − cos θ_max = sin²/(1 + cos) for precision.
                float d = MathF.Sqrt(d2), sin2Max = r2 / d2, cosMax = MathF.Sqrt(MathF.Max(0, 1 - sin2Max));
                float oneMinusCosMax = sin2Max / (1 + cosMax);
                float oneMinusCos = u.X * oneMinusCosMax, cos = 1 - oneMinusCos;
                float sin2 = oneMinusCos * (2 - oneMinusCos), sin = MathF.Sqrt(MathF.Max(0, sin2)), phi = 2 * MathF.PI * u.Y;
                var axis = toCentre / d;
                var (t, b) = Bsdf.Frame(axis);
                var w = sin * MathF.Cos(phi) * t + sin * MathF.Sin(phi) * b + cos * axis;
                // The near intersection of p + s·w with the sphere (clamped at grazing).
                float s = d * cos - MathF.Sqrt(MathF.Max(0, r2 - d2 * sin2));
                x = p + s * w;
                nx = Vector3.Normalize(x - _centre);
                x = _centre + _radius * nx;
                pdf = 1 / (2 * MathF.PI * oneMinusCosMax);
                return true;
            }
            float z = 1 - 2 * u.X, rr = MathF.Sqrt(MathF.Max(0, 1 - z * z)), ph = 2 * MathF.PI * u.Y;
            nx = new Vector3(rr * MathF.Cos(ph), rr * MathF.Sin(ph), z);
            x = _centre + _radius * nx;
            return AreaToSolidAngle(p, x, nx, 1 / _area, out pdf);
        }
        if (_kind == Kind.Shape)
        {
            x = _shape!.SampleArea(u, out nx, out float pdfArea);
            return AreaToSolidAngle(p, x, nx, pdfArea, out pdf);
        }
        // Pick a parallelogram or triangle by area with u.X, reuse its rescaled remainder.
        float target = u.X * _area;
        int i = Array.BinarySearch(_cumulative, target);
        if (i < 0) i = ~i;
        if (i >= _cumulative.Length) i = _cumulative.Length - 1;
        face = i;
        float lo = i == 0 ? 0 : _cumulative[i - 1], width = _cumulative[i] - lo;
        float a = width > 0 ? Math.Clamp((target - lo) / width, 0, 0.99999994f) : 0.5f;
        if (_kind == Kind.Parallelograms) x = _corner[i] + a * _edge1[i] + u.Y * _edge2[i];
        else
        {   // uniform on the triangle: (1 − √a, √a·(1 − v)), √a·v (Osada et al. 2002)
            float sa = MathF.Sqrt(a);
            x = _corner[i] + sa * (1 - u.Y) * _edge1[i] + sa * u.Y * _edge2[i];
        }
        nx = _normal[i];
        return AreaToSolidAngle(p, x, nx, 1 / _area, out pdf);
    }

    /// <summary>The solid-angle density with which <see cref="Sample(Vector3, Vector2, out Vector3, out Vector3, out float)"/> from
    /// <paramref name="p"/> picks point
    /// <paramref name="x"/> (normal <paramref name="nx"/>) of this emitter.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Pdf(Vector3 p, Vector3 x, Vector3 nx)
    {
        if (_kind == Kind.Sphere)
        {
            float d2 = (_centre - p).LengthSquared(), r2 = _radius * _radius;
            if (d2 > r2 * 1.0001f)
            {
                float sin2Max = r2 / d2, cosMax = MathF.Sqrt(MathF.Max(0, 1 - sin2Max));
                return 1 / (2 * MathF.PI * (sin2Max / (1 + cosMax)));
            }
        }
        float pdfArea = _kind == Kind.Shape ? _shape!.AreaPdf(nx) : 1 / _area;
        return AreaToSolidAngle(p, x, nx, pdfArea, out float pdf) ? pdf : 0;
    }

    /// <summary>
    /// The (u, v) of point <paramref name="x"/> on <paramref name="face"/> and the mapping's density (uv units per length), as
    /// <see cref="SceneGeometry.TexCoord"/> gives them where a ray hits the same point: an analytic shape's generated
    /// coordinates, a mesh triangle's interpolated at x's barycentrics (the barycentrics themselves without uvs).
    /// </summary>
    public Vector2 TexCoord(int face, Vector3 x, out float uvPerLength)
    {
        if (_kind != Kind.Triangles) return TextureCoordinates.OfShape(_shape!, x, out uvPerLength);
        // x − p0 = b1·e1 + b2·e2, solved in the triangle's plane (normal equations of the 2 × 2 system).
        Vector3 e1 = _edge1[face], e2 = _edge2[face], d = x - _corner[face];
        float a11 = Vector3.Dot(e1, e1), a12 = Vector3.Dot(e1, e2), a22 = Vector3.Dot(e2, e2);
        float r1 = Vector3.Dot(d, e1), r2 = Vector3.Dot(d, e2), det = a11 * a22 - a12 * a12;
        float b1 = det != 0 ? (r1 * a22 - r2 * a12) / det : 0, b2 = det != 0 ? (r2 * a11 - r1 * a12) / det : 0;
        var p0 = _corner[face];
        return _meshUvs is { } uvs
            ? TextureCoordinates.OfTriangle(uvs[3 * face], uvs[3 * face + 1], uvs[3 * face + 2], b1, b2, p0, p0 + e1, p0 + e2,
                out uvPerLength)
            : TextureCoordinates.OfTriangle(Vector2.Zero, Vector2.UnitX, Vector2.UnitY, b1, b2, p0, p0 + e1, p0 + e2, out uvPerLength);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static bool AreaToSolidAngle(Vector3 p, Vector3 x, Vector3 nx, float pdfArea, out float pdf)
    {
        var d = x - p;
        float d2 = d.LengthSquared();
        float cos = MathF.Abs(Vector3.Dot(nx, d)) / MathF.Sqrt(d2);
        pdf = cos > 0 && d2 > 0 ? pdfArea * d2 / cos : 0;
        return pdf > 0 && float.IsFinite(pdf);
    }

}
