using System.Buffers.Binary;
using System.Numerics;
using System.Text;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Geometry;

/// <summary>The box [0,1]×[0,2]×[0,3] written as OBJ and as four kinds of PLY loads to the same 12 triangles, and rays hit it where the
/// slab method says.</summary>
public class CubeFormatsTests
{
    static readonly Vector3 BoxMax = new(1, 2, 3);
    static readonly Vector3[] Corners = [.. Enumerable.Range(0, 8).Select(i => new Vector3(i & 1, 2 * ((i >> 1) & 1), 3 * ((i >> 2) & 1)))];

    /// <summary>Outward-wound quads (counter-clockwise seen from outside) and their normals.</summary>
    static readonly (int[] quad, Vector3 normal)[] Faces =
    [
        ([0, 4, 6, 2], -Vector3.UnitX), ([1, 3, 7, 5], Vector3.UnitX),
        ([0, 1, 5, 4], -Vector3.UnitY), ([2, 6, 7, 3], Vector3.UnitY),
        ([0, 2, 3, 1], -Vector3.UnitZ), ([4, 5, 7, 6], Vector3.UnitZ),
    ];

    static string Obj()
    {
        var s = new StringBuilder("# cube\no cube\n");
        foreach (var c in Corners) s.Append($"v {c.X} {c.Y} {c.Z}\n");
        foreach (var (_, n) in Faces) s.Append($"vn {n.X} {n.Y} {n.Z}\n");
        s.Append("vt 0 0\n");
        for (int f = 0; f < Faces.Length; f++)
        {
            var q = Faces[f].quad;
            // Alternate the corner forms: v, v//vn, v/vt/vn with negative indices, v/vt.
            s.Append("f");
            foreach (int i in q)
                s.Append((f % 4) switch
                {
                    0 => $" {i + 1}",
                    1 => $" {i + 1}//{f + 1}",
                    2 => $" {i - 8}/-1/{f - 6}",
                    _ => $" {i + 1}/1",
                });
            s.Append('\n');
        }
        return s.ToString();
    }

    static string PlyHeader(string format, string faceElement, string vertexType = "float", string listTypes = "uchar int") =>
        $"ply\nformat {format} 1.0\nelement vertex 8\nproperty {vertexType} x\nproperty {vertexType} y\nproperty {vertexType} z\n" +
        $"element {faceElement}\nproperty list {listTypes} vertex_indices\nend_header\n";

    static byte[] PlyAscii()
    {
        var s = new StringBuilder(PlyHeader("ascii", "face 6"));
        foreach (var c in Corners) s.Append($"{c.X} {c.Y} {c.Z}\n");
        foreach (var (q, _) in Faces) s.Append($"4 {string.Join(' ', q)}\n");
        return Encoding.ASCII.GetBytes(s.ToString());
    }

    static byte[] PlyBinary(bool littleEndian)
    {
        // Little-endian: double coordinates, uchar counts, int indices; big-endian: float, int counts, uint indices.
        var data = new List<byte>(Encoding.ASCII.GetBytes(littleEndian
            ? PlyHeader("binary_little_endian", "face 6", "float64", "uint8 int32")
            : PlyHeader("binary_big_endian", "face 6", "float", "int uint")));
        var b = new byte[8];
        foreach (var c in Corners)
            foreach (float v in new[] { c.X, c.Y, c.Z })
                if (littleEndian) { BinaryPrimitives.WriteDoubleLittleEndian(b, v); data.AddRange(b[..8]); }
                else { BinaryPrimitives.WriteSingleBigEndian(b, v); data.AddRange(b[..4]); }
        foreach (var (q, _) in Faces)
        {
            if (littleEndian) data.Add(4);
            else { BinaryPrimitives.WriteInt32BigEndian(b, 4); data.AddRange(b[..4]); }
            foreach (int i in q)
                if (littleEndian) { BinaryPrimitives.WriteInt32LittleEndian(b, i); data.AddRange(b[..4]); }
                else { BinaryPrimitives.WriteUInt32BigEndian(b, (uint)i); data.AddRange(b[..4]); }
        }
        return [.. data];
    }

    static byte[] PlyStrips()
    {
        // Quad (a,b,c,d) as the strip b c a d gives (b,c,a) and, flipped, (a,c,d): the fan's two triangles.
        var strip = string.Join(" -1 ", Faces.Select(f => $"{f.quad[1]} {f.quad[2]} {f.quad[0]} {f.quad[3]}"));
        var s = new StringBuilder(PlyHeader("ascii", "tristrips 1", "float", "int int"));
        foreach (var c in Corners) s.Append($"{c.X} {c.Y} {c.Z}\n");
        s.Append($"{strip.Split(' ').Length} {strip}\n");
        return Encoding.ASCII.GetBytes(s.ToString());
    }

    public static TheoryData<string> Formats => ["obj", "ascii", "binary_little_endian", "binary_big_endian", "tristrips"];

    static TriangleMesh Load(string format)
    {
        var dir = Reference.TempDir();
        var path = Path.Combine(dir, format == "obj" ? "cube.obj" : $"cube-{format}.ply");
        if (format == "obj") File.WriteAllText(path, Obj());
        else File.WriteAllBytes(path, format switch
        {
            "ascii" => PlyAscii(),
            "binary_little_endian" => PlyBinary(true),
            "binary_big_endian" => PlyBinary(false),
            _ => PlyStrips(),
        });
        return format == "obj" ? ObjReader.Read(path) : PlyReader.Read(path);
    }

    /// <summary>Each triangle's corners, rotated (keeping the winding) to start at the smallest, the list sorted.</summary>
    static List<string> CanonicalTriangles(TriangleMesh m)
    {
        var result = new List<string>();
        for (int t = 0; t < m.TriangleCount; t++)
        {
            var (a, b, c) = m.Triangle(t);
            var p = new[] { a, b, c }.Select(v => $"({v.X},{v.Y},{v.Z})").ToArray();
            int first = Array.IndexOf(p, p.Min(StringComparer.Ordinal));
            result.Add($"{p[first]} {p[(first + 1) % 3]} {p[(first + 2) % 3]}");
        }
        result.Sort(StringComparer.Ordinal);
        return result;
    }

    static readonly List<string> Expected = CanonicalTriangles(new TriangleMesh(Corners.ToArray(),
        Faces.SelectMany(f => new[] { f.quad[0], f.quad[1], f.quad[2], f.quad[0], f.quad[2], f.quad[3] }).ToArray()));

    [Theory]
    [MemberData(nameof(Formats))]
    public void Every_format_gives_the_same_twelve_outward_triangles(string format)
    {
        var m = Load(format);
        Assert.Equal(12, m.TriangleCount);
        Assert.Equal(0, m.DegenerateCount);
        Assert.Equal(Expected, CanonicalTriangles(m));
        // Outward winding: every geometric normal points away from the centre.
        for (int t = 0; t < 12; t++)
        {
            var (a, b, c) = m.Triangle(t);
            Assert.True(Vector3.Dot(Vector3.Cross(b - a, c - a), (a + b + c) / 3 - BoxMax / 2) > 0);
        }
    }

    [Theory]
    [MemberData(nameof(Formats))]
    public void Rays_from_outside_hit_at_the_analytic_box_distance(string format)
    {
        var set = TriangleSet.Build([Load(format)]);
        var rng = new Random(7);
        for (int i = 0; i < 2000; i++)
        {
            // From a sphere of radius 10 around the box towards a random point inside it.
            var o =
                BoxMax / 2 + 10 * Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
            var target = new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle()) * BoxMax;
            var d = Vector3.Normalize(target - o);
            var ray = new Ray(o, d);
            var hit = new Hit();
            Assert.True(set.Intersect(ref ray, ref hit));
            double expected = SlabEntry(o, d);
            Assert.Equal(expected, ray.TMax, expected * 1e-5);
            // The hit point lies on the box surface, and the barycentrics reproduce it.
            var (p0, p1, p2) = set.Corners(hit.Primitive);
            var p = (1 - hit.U - hit.V) * p0 + hit.U * p1 + hit.V * p2;
            Assert.True(Vector3.Distance(p, ray.At(ray.TMax)) < 1e-4f);
        }
        // Rays pointing away, or stopping short, miss.
        var away = new Ray(new Vector3(0.5f, 1, 5), Vector3.UnitZ);
        var h = new Hit();
        Assert.False(set.Intersect(ref away, ref h));
        var shortRay = new Ray(new Vector3(0.5f, 1, 5), -Vector3.UnitZ, 1.99f);
        Assert.False(set.Occluded(shortRay));
        shortRay.TMax = 2.01f;
        Assert.True(set.Occluded(shortRay));
    }

    /// <summary>The slab method in double: where the ray enters the box.</summary>
    static double SlabEntry(Vector3 o, Vector3 d)
    {
        double entry = double.NegativeInfinity;
        for (int a = 0; a < 3; a++)
        {
            double t0 = (0 - (double)o[a]) / d[a], t1 = (BoxMax[a] - (double)o[a]) / d[a];
            entry = Math.Max(entry, Math.Min(t0, t1));
        }
        return entry;
    }
}
