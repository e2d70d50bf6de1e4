using System.Numerics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Geometry;

public class NormalsTests
{
    /// <summary>A bumpy grid of n × n vertices, its triangles shuffled so vertex ranges share many triangles.</summary>
    static TriangleMesh Grid(int n, int seed)
    {
        var rng = new Random(seed);
        var p = new Vector3[n * n];
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                p[y * n + x] = new Vector3(x + 0.3f * rng.NextSingle(), y + 0.3f * rng.NextSingle(), rng.NextSingle());
        var tris = new List<int[]>();
        for (int y = 0; y + 1 < n; y++)
            for (int x = 0; x + 1 < n; x++)
            {
                int a = y * n + x;
                tris.Add([a, a + 1, a + n + 1]);
                tris.Add([a, a + n + 1, a + n]);
            }
        rng.Shuffle(System.Runtime.InteropServices.CollectionsMarshal.AsSpan(tris));
        return new TriangleMesh(p, [.. tris.SelectMany(t => t)]);
    }

    /// <summary>The angle-weighted normals the straightforward way: one pass over the triangles in order.</summary>
    static Vector3[] Sequential(TriangleMesh m)
    {
        var n = new Vector3[m.Positions.Length];
        static float Angle(Vector3 u, Vector3 v) => MathF.Atan2(Vector3.Cross(u, v).Length(), Vector3.Dot(u, v));
        for (int t = 0; t < m.TriangleCount; t++)
        {
            int a = m.Indices[3 * t], b = m.Indices[3 * t + 1], c = m.Indices[3 * t + 2];
            Vector3 pa = m.Positions[a], pb = m.Positions[b], pc = m.Positions[c];
            var face = Vector3.Normalize(Vector3.Cross(pb - pa, pc - pa));
            n[a] += Angle(pb - pa, pc - pa) * face;
            n[b] += Angle(pc - pb, pa - pb) * face;
            n[c] += Angle(pa - pc, pb - pc) * face;
        }
        for (int i = 0; i < n.Length; i++)
        {
            float len = n[i].Length();
            n[i] = len > 0 && float.IsFinite(len) ? n[i] / len : Vector3.UnitZ;
        }
        return n;
    }

    [Theory]
    [InlineData(1), InlineData(2), InlineData(3), InlineData(7), InlineData(64)]
    public void Normals_are_the_same_bits_for_any_number_of_vertex_ranges(int parts)
    {
        var m = Grid(60, 5);
        var expected = Sequential(m);
        m.ComputeVertexNormals(parts);
        Assert.Equal(expected.Length, m.Normals!.Length);
        for (int i = 0; i < expected.Length; i++)
            Assert.True(expected[i].Equals(m.Normals[i]), $"vertex {i}: {m.Normals[i]} != {expected[i]}");
        // And they are normals: unit length, pointing up out of the bumpy z ≈ 0.5 sheet.
        Assert.All(m.Normals, v => { Assert.Equal(1, v.Length(), 5); Assert.True(v.Z > 0.3f); });
    }

    [Fact]
    public void An_unused_vertex_gets_plus_z()
    {
        var m = new TriangleMesh([new(0, 0, 0), new(1, 0, 0), new(0, 0, 1), new(5, 5, 5)], [0, 1, 2]);
        m.ComputeVertexNormals(2);
        Assert.Equal(new Vector3(0, -1, 0), m.Normals![0]);
        Assert.Equal(Vector3.UnitZ, m.Normals[3]);
    }
}
