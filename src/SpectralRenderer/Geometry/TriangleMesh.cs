using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Geometry;

/// <summary>
/// An indexed triangle mesh: shared vertex positions (and optional per-vertex normals) and three indices per
/// triangle. Degenerate triangles (a repeated index or zero area) are dropped on construction and counted.
/// </summary>
public sealed class TriangleMesh
{
    public Vector3[] Positions { get; }
    public Vector3[]? Normals { get; private set; }
    public int[] Indices { get; private set; }
    /// <summary>Texture coordinates per triangle corner (three per triangle, parallel to <see cref="Indices"/>: OBJ's vt may
    /// differ per corner at a seam), or null when the file gave none.</summary>
    public Vector2[]? TexCoords { get; private set; }
    public int TriangleCount => Indices.Length / 3;
    /// <summary>How many triangles of the input were dropped as degenerate.</summary>
    public int DegenerateCount { get; }
    /// <summary>Where the mesh came from (a file path), for messages.</summary>
    public string Source { get; }

    /// <param name="indices">Three per triangle, each in [0, positions.Length).</param>
    public TriangleMesh(Vector3[] positions, int[] indices, Vector3[]? normals = null, string source = "")
        : this(positions, indices, indices.Length, normals, source) { }

    /// <summary>A mesh from the first <paramref name="indexCount"/> entries of <paramref name="indices"/> (a reader's
    /// buffer, which the mesh takes over).</summary>
    internal TriangleMesh(Vector3[] positions, int[] indices, int indexCount, Vector3[]? normals, string source,
        Vector2[]? cornerTexCoords = null)
    {
        if (indexCount % 3 != 0) throw new ArgumentException("indices must come in threes", nameof(indices));
        if (normals is not null && normals.Length != positions.Length)
            throw new ArgumentException("one normal per position", nameof(normals));
        Positions = positions;
        Normals = normals;
        Source = source;
        (Indices, DegenerateCount) = DropDegenerate(positions, indices, indexCount, cornerTexCoords);
        if (cornerTexCoords is not null)
            TexCoords = cornerTexCoords.Length == Indices.Length ? cornerTexCoords : cornerTexCoords[..Indices.Length];
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static (int[] kept, int dropped) DropDegenerate(Vector3[] p, int[] indices, int count, Vector2[]? uvs)
    {
        int write = 0;
        for (int read = 0; read < count; read += 3)
        {
            int a = indices[read], b = indices[read + 1], c = indices[read + 2];
            if ((uint)a >= (uint)p.Length || (uint)b >= (uint)p.Length || (uint)c >= (uint)p.Length)
                throw new ArgumentOutOfRangeException(nameof(indices), $"triangle {read / 3} has an index outside [0, {p.Length})");
            if (a == b || b == c || a == c || Vector3.Cross(p[b] - p[a], p[c] - p[a]) == Vector3.Zero) continue;
            if (uvs is not null) { uvs[write] = uvs[read]; uvs[write + 1] = uvs[read + 1]; uvs[write + 2] = uvs[read + 2]; }
            indices[write++] = a; indices[write++] = b; indices[write++] = c;
        }
        int dropped = (count - write) / 3;
        return (write == indices.Length ? indices : indices[..write], dropped);
    }

    public Bounds3 Bounds
    {
        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        get
        {
            var b = Bounds3.Empty;
            foreach (int i in Indices) b.Include(Positions[i]);
            return b;
        }
    }

    /// <summary>The corners of triangle <paramref name="t"/>.</summary>
    public (Vector3 P0, Vector3 P1, Vector3 P2) Triangle(int t)
        => (Positions[Indices[3 * t]], Positions[Indices[3 * t + 1]], Positions[Indices[3 * t + 2]]);

    /// <summary>
    /// Angle-weighted vertex normals (Thürmer &amp; Wüthrich 1998): each triangle adds its unit normal weighted by
    /// its interior angle at the vertex. Vertices used by no triangle get +Z. Parallel over ranges of vertices,
    /// each summing its vertices' corners in triangle order, so the result is the same bits for any thread count.
    /// </summary>
    public void ComputeVertexNormals() => ComputeVertexNormals(Math.Min(Environment.ProcessorCount, 1 + TriangleCount / 20_000));

    /// <summary>The normals computed in <paramref name="parts"/> vertex ranges, in parallel.</summary>
    internal void ComputeVertexNormals(int parts)
    {
        var n = new Vector3[Positions.Length];
        var (positions, indices) = (Positions, Indices);
        if (parts <= 1) AccumulateNormals(positions, indices, n, 0, n.Length);
        else
            Parallel.For(0, parts,
                part => AccumulateNormals(positions, indices, n, (int)((long)n.Length * part / parts),
                    (int)((long)n.Length * (part + 1) / parts)));
        Normals = n;
    }

    /// <summary>The normals of vertices [<paramref name="first"/>, <paramref name="end"/>): every triangle is
    /// visited, and only the corners at those vertices are added.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void AccumulateNormals(Vector3[] positions, int[] indices, Vector3[] n, int first, int end)
    {
        uint range = (uint)(end - first);
        for (int i = 0; i + 2 < indices.Length; i += 3)
        {
            int a = indices[i], b = indices[i + 1], c = indices[i + 2];
            bool hasA = (uint)(a - first) < range, hasB = (uint)(b - first) < range, hasC = (uint)(c - first) < range;
            if (!(hasA | hasB | hasC)) continue;
            Vector3 pa = positions[a], pb = positions[b], pc = positions[c];
            var face = Vector3.Normalize(Vector3.Cross(pb - pa, pc - pa));
            if (hasA) n[a] += Angle(pb - pa, pc - pa) * face;
            if (hasB) n[b] += Angle(pc - pb, pa - pb) * face;
            if (hasC) n[c] += Angle(pa - pc, pb - pc) * face;
        }
        for (int v = first; v < end; v++)
        {
            float len = n[v].Length();
            n[v] = len > 0 && float.IsFinite(len) ? n[v] / len : Vector3.UnitZ;
        }
    }

    /// <summary>The angle between two edge vectors, by atan2 (accurate for small and near-π angles).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static float Angle(Vector3 u, Vector3 v) => MathF.Atan2(Vector3.Cross(u, v).Length(), Vector3.Dot(u, v));

    /// <summary>
    /// Applies an affine transform (row-vector convention of System.Numerics: p' = p·M). Normals use the inverse
    /// transpose; a mirroring transform (negative determinant) also reverses the winding so the geometric normal
    /// keeps its side.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public TriangleMesh Transform(Matrix4x4 m)
    {
        if (!Matrix4x4.Invert(m, out var inverse)) throw new ArgumentException("the transform is singular", nameof(m));
        for (int i = 0; i < Positions.Length; i++) Positions[i] = Vector3.Transform(Positions[i], m);
        if (Normals is { } normals)
        {
            var normalMatrix = Matrix4x4.Transpose(inverse);
            for (int i = 0; i < normals.Length; i++) normals[i] = Vector3.Normalize(Vector3.TransformNormal(normals[i], normalMatrix));
        }
        if (m.GetDeterminant() < 0)
            for (int i = 0; i < Indices.Length; i += 3)
            {
                (Indices[i + 1], Indices[i + 2]) = (Indices[i + 2], Indices[i + 1]);
                if (TexCoords is { } uv) (uv[i + 1], uv[i + 2]) = (uv[i + 2], uv[i + 1]);
            }
        return this;
    }

    /// <summary>Scales uniformly and translates so the mesh's bounds are as large as fit, centred, in [min, max].</summary>
    public TriangleMesh Fit(Vector3 min, Vector3 max)
    {
        var from = Bounds;
        var e = from.Extent;
        var target = max - min;
        float scale = float.PositiveInfinity;
        if (e.X > 0) scale = MathF.Min(scale, target.X / e.X);
        if (e.Y > 0) scale = MathF.Min(scale, target.Y / e.Y);
        if (e.Z > 0) scale = MathF.Min(scale, target.Z / e.Z);
        if (!float.IsFinite(scale)) scale = 1;
        var centre = 0.5f * (min + max);
        return Transform(Matrix4x4.CreateTranslation(-from.Centre) * Matrix4x4.CreateScale(scale) * Matrix4x4.CreateTranslation(centre));
    }
}
