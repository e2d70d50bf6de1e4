using System.Buffers.Binary;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Geometry;

public class PlyReaderTests
{
    const string TriangleVertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

    static byte[] Le(params float[] values)
    {
        var b = new byte[4 * values.Length];
        for (int i = 0; i < values.Length; i++) BinaryPrimitives.WriteSingleLittleEndian(b.AsSpan(4 * i), values[i]);
        return b;
    }

    static byte[] LeInts(params int[] values)
    {
        var b = new byte[4 * values.Length];
        for (int i = 0; i < values.Length; i++) BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4 * i), values[i]);
        return b;
    }

    static byte[] File(string header, params byte[][] body) =>
        [.. Encoding.ASCII.GetBytes(header), .. body.SelectMany(x => x)];

    static InputException Fails(byte[] data)
    {
        // Through a real file, as the renderer reads it.
        var path = Path.Combine(Reference.TempDir(), "bad.ply");
        System.IO.File.WriteAllBytes(path, data);
        var e = Assert.Throws<InputException>(() => PlyReader.Read(path));
        Assert.StartsWith(path, e.Message);
        return e;
    }

    static string Tail(InputException e) => e.Unhinted()[(e.Unhinted().IndexOf("bad.ply", StringComparison.Ordinal) + "bad.ply".Length)..];

    [Theory]
    [InlineData("plx\nformat ascii 1.0\nend_header\n", ":1: not a PLY file")]
    [InlineData("ply\nformat binary_middle_endian 1.0\nend_header\n", ":2: unknown format 'binary_middle_endian'")]
    [InlineData("ply\nformat ascii 1.0\nelement vertex 3\nproperty float16 x\nend_header\n", ":4: unknown property type 'float16'")]
    [InlineData("ply\nformat ascii 1.0\nelement vertex 3\nproperty list float int x\nend_header\n",
        ":4: list count type 'float' is not an integer type")]
    [InlineData("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 0\nproperty list uchar "
        + "int vertex_indices\nend_header\n",
        ":3: element 'vertex' has no scalar property 'z'")]
    [InlineData("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n", ":5: the header has no 'end_header' line")]
    [InlineData("ply\nformat ascii 1.0\n" + TriangleVertices + "end_header\n0 0 0 1 0 0 0 1 0\n",
        ": header: the header declares no 'face' or 'tristrips' element")]
    [InlineData("ply\nformat ascii 1.0\n" + TriangleVertices + "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
        ":7: element 'face': vertex indices must have an integer type")]
    [InlineData("ply\nformat ascii 1.0\n" + TriangleVertices
        + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n3 0 1 2\nfoo",
        "")]
    public void Broken_headers_are_rejected_with_file_and_line(string text, string tail)
    {
        if (tail == "") { Assert.Equal(1, PlyReader.Parse(Encoding.ASCII.GetBytes(text), "ok.ply").TriangleCount); return; }
        Assert.StartsWith(tail, Tail(Fails(Encoding.ASCII.GetBytes(text))));
    }

    const string BinaryTriangle = "ply\nformat binary_little_endian 1.0\n" + TriangleVertices +
                                  "element face 2\nproperty list uchar int vertex_indices\nend_header\n";

    [Fact]
    public void A_vertex_index_out_of_range_names_element_instance_and_byte()
    {
        int start = BinaryTriangle.Length;
        var e = Fails(File(BinaryTriangle, Le(0, 0, 0, 1, 0, 0, 0, 1, 0), [3], LeInts(0, 1, 2), [3], LeInts(0, 7, 2)));
        // Face #1 starts after 36 bytes of vertices and 13 of face #0; its count byte, then index 0, then the 7.
        int at = start + 36 + 13 + 1 + 4;
        Assert.Equal($": element 'face' #1 at byte {at}: vertex index 7 out of range (3 vertices)", Tail(e));
    }

    [Fact]
    public void Truncated_binary_data_is_reported()
    {
        int start = BinaryTriangle.Length;
        var e = Fails(File(BinaryTriangle, Le(0, 0, 0, 1, 0, 0, 0, 1)));
        Assert.Equal($": element 'vertex' #2 at byte {start + 32}: unexpected end of file (truncated data: needs 4 more bytes, 0 left)",
            Tail(e));
        e = Fails(File(BinaryTriangle, Le(0, 0, 0, 1, 0, 0, 0, 1, 0), [3], LeInts(0, 1, 2), [3], LeInts(0, 1)));
        Assert.Equal(
            $": element 'face' #1 at byte {start + 36 + 13 + 9}: unexpected end of file (truncated data: needs 4 more bytes, 0 left)",
            Tail(e));
    }

    [Fact]
    public void Ascii_errors_give_the_byte_of_the_bad_value()
    {
        var text = "ply\nformat ascii 1.0\n" + TriangleVertices
            + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n";
        var e = Fails(Encoding.ASCII.GetBytes(text));
        Assert.Equal($": element 'vertex' #1 at byte {text.IndexOf("abc", StringComparison.Ordinal)}: 'abc' is not a number", Tail(e));

        text = "ply\nformat ascii 1.0\n" + TriangleVertices
            + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n";
        e = Fails(Encoding.ASCII.GetBytes(text));
        Assert.Contains("element 'face' #0 at byte", e.Message);
        Assert.EndsWith("face has 2 vertices (a face needs at least 3)", e.Unhinted());

        text = "ply\nformat ascii 1.0\n" + TriangleVertices
            + "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n";
        Assert.EndsWith("list 'vertex_indices' has negative length -3", Fails(Encoding.ASCII.GetBytes(text)).Unhinted());

        text = "ply\nformat ascii 1.0\n" + TriangleVertices
            + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n";
        Assert.EndsWith($"element 'face' #0 at byte {text.Length}: unexpected end of file (truncated data)",
            Fails(Encoding.ASCII.GetBytes(text)).Unhinted());
    }

    [Fact]
    public void Strip_indices_out_of_range_and_absurd_counts_are_reported()
    {
        var header = "ply\nformat binary_little_endian 1.0\n" + TriangleVertices
            + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
        var e = Fails(File(header, Le(0, 0, 0, 1, 0, 0, 0, 1, 0), LeInts(4, 0, 1, -1, 3)));
        Assert.Equal($": element 'tristrips' #0 at byte {header.Length + 36 + 16}: vertex index 3 out of range (3 vertices)", Tail(e));

        var huge = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty float "
            + "z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
        Assert.Contains("element 'vertex' #0 at byte", Fails(File(huge, Le(0, 0, 0))).Message);
        Assert.Contains("2000000000 instances cannot fit", Fails(File(huge, Le(0, 0, 0))).Message);
    }

    [Fact]
    public void Unknown_elements_and_properties_are_skipped_including_lists()
    {
        var header = "ply\nformat binary_big_endian 1.0\ncomment skip me\nobj_info x\n" +
                     "element vertex 3\nproperty uint8 red\nproperty double z\nproperty list uchar short "
                         + "junk\nproperty float64 y\nproperty int16 x\n" +
                     "element material 2\nproperty list uint int16 names\nproperty float shine\n" +
                     "element face 1\nproperty int flags\nproperty list uint16 uint32 vertex_index\nproperty uchar tag\nend_header\n";
        var body = new List<byte>();
        void D(double v) { var b = new byte[8]; BinaryPrimitives.WriteDoubleBigEndian(b, v); body.AddRange(b); }
        void S(short v) { var b = new byte[2]; BinaryPrimitives.WriteInt16BigEndian(b, v); body.AddRange(b); }
        void I(int v) { var b = new byte[4]; BinaryPrimitives.WriteInt32BigEndian(b, v); body.AddRange(b); }
        (short x, double y, double z)[] v = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5)];
        foreach (var (x, y, z) in v) { body.Add(9); D(z); body.Add(2); S(7); S(8); D(y); S(x); }
        I(3); S(1); S(2); S(3); I(0);   // material #0: 3 names, shine
        I(0); I(0);                     // material #1: no names, shine
        I(42); S(3); I(0); I(1); I(2); body.Add(1);
        var m = PlyReader.Parse(File(header, body.ToArray()), "skip.ply");
        Assert.Equal(1, m.TriangleCount);
        Assert.Equal(new System.Numerics.Vector3(0, 1, 0.5f), m.Positions[2]);
        Assert.Equal([0, 1, 2], m.Indices);
    }

    [Fact]
    public void Triangle_strips_alternate_winding_restart_at_minus_one_and_count_degenerates()
    {
        // Strip 0 1 2 3 → (0,1,2), (2,1,3); restart; strip 3 2 2 0 → (3,2,2) and (2,2,0) are degenerate (swap pattern).
        var header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n" +
                     "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
        var m = PlyReader.Parse(Encoding.ASCII.GetBytes(header + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n9 0 1 2 3 -1 3 2 2 0\n"), "strip.ply");
        Assert.Equal([0, 1, 2, 2, 1, 3], m.Indices);
        Assert.Equal(2, m.DegenerateCount);
    }

    /// <summary>A binary body writer for the tests below.</summary>
    sealed class Body(bool littleEndian)
    {
        readonly List<byte> _bytes = [];
        public byte[] Bytes => [.. _bytes];
        public int Length => _bytes.Count;
        public Body Value(string type, double v)
        {
            var b = new byte[8];
            int n = type switch { "char" or "uchar" => 1, "short" or "ushort" => 2, "double" => 8, _ => 4 };
            switch (type)
            {
                case "char": b[0] = (byte)(sbyte)v; break;
                case "uchar": b[0] = (byte)v; break;
                case "short":
                    if (littleEndian) BinaryPrimitives.WriteInt16LittleEndian(b, (short)v);
                    else BinaryPrimitives.WriteInt16BigEndian(b, (short)v);
                    break;
                case "ushort":
                    if (littleEndian) BinaryPrimitives.WriteUInt16LittleEndian(b, (ushort)v);
                    else BinaryPrimitives.WriteUInt16BigEndian(b, (ushort)v);
                    break;
                case "int":
                    if (littleEndian) BinaryPrimitives.WriteInt32LittleEndian(b, (int)v);
                    else BinaryPrimitives.WriteInt32BigEndian(b, (int)v);
                    break;
                case "uint":
                    if (littleEndian) BinaryPrimitives.WriteUInt32LittleEndian(b, (uint)v);
                    else BinaryPrimitives.WriteUInt32BigEndian(b, (uint)v);
                    break;
                case "float":
                    if (littleEndian) BinaryPrimitives.WriteSingleLittleEndian(b, (float)v);
                    else BinaryPrimitives.WriteSingleBigEndian(b, (float)v);
                    break;
                default:
                    if (littleEndian) BinaryPrimitives.WriteDoubleLittleEndian(b, v);
                    else BinaryPrimitives.WriteDoubleBigEndian(b, v);
                    break;
            }
            _bytes.AddRange(b[..n]);
            return this;
        }
    }

    // Four vertices of the unit square (z = 0) and, for strips, two strips: 0 1 2 3 and 3 2 1.
    static readonly float[] Square = [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0];

    [Theory]
    [InlineData("char"), InlineData("uchar"), InlineData("short"), InlineData("ushort"), InlineData("int"), InlineData("uint")]
    public void Binary_strips_and_faces_of_every_index_type_and_byte_order_triangulate_alike(string type)
    {
        foreach (bool le in new[] { true, false })
        {
            string format = le ? "binary_little_endian" : "binary_big_endian";
            string vertices = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
            // Unsigned 8/16-bit lists cannot hold −1: there each strip is its own instance.
            bool restarts = type is "char" or "short" or "int" or "uint";
            var strips = new Body(le);
            foreach (float v in Square) strips.Value("float", v);
            int[][] lists = restarts ? [[0, 1, 2, 3, -1, 3, 2, 1]] : [[0, 1, 2, 3], [3, 2, 1]];
            foreach (var list in lists)
            {
                strips.Value("uchar", list.Length);
                foreach (int i in list) strips.Value(type, i == -1 && type == "uint" ? uint.MaxValue : i);
            }
            var m = PlyReader.Parse(File($"ply\nformat {format} 1.0\n{vertices}element tristrips {lists.Length}\nproperty list uchar "
                + $"{type} vertex_indices\nend_header\n",
                strips.Bytes),
                "s.ply");
            Assert.Equal([0, 1, 2, 2, 1, 3, 3, 2, 1], m.Indices);

            // A quad and a triangle as faces, with a scalar before and a list after the indices.
            var faces = new Body(le);
            foreach (float v in Square) faces.Value("float", v);
            foreach (int[] face in new[] { new[] { 0, 1, 3, 2 }, new[] { 3, 2, 1 } })
            {
                faces.Value("short", 7).Value("uint", face.Length);
                foreach (int i in face) faces.Value(type, i);
                faces.Value("ushort", 2).Value("double", 1).Value("double", 2);
            }
            m = PlyReader.Parse(File($"ply\nformat {format} 1.0\n{vertices}element face 2\nproperty short flags\nproperty list uint {type} "
                + $"vertex_indices\nproperty list ushort double junk\nend_header\n",
                faces.Bytes),
                "f.ply");
            Assert.Equal([0, 1, 3, 0, 3, 2, 3, 2, 1], m.Indices);
        }
    }

    [Fact]
    public void Binary_vertices_that_are_not_finite_name_the_property_and_its_byte()
    {
        // Three floats per vertex (read as they lie in memory), and with normals and a double (read value by value).
        var header = "ply\nformat binary_little_endian 1.0\n" + TriangleVertices
            + "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
        var e = Fails(File(header, Le(0, 0, 0, 1, float.NaN, 0, 0, 1, 0), [3], LeInts(0, 1, 2)));
        Assert.Equal($": element 'vertex' #1 at byte {header.Length + 16}: property 'y' is NaN, not a finite number", Tail(e));

        header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty double z\nproperty "
            + "float nx\nproperty float ny\nproperty float nz\n" +
                 "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
        var body = new Body(true);
        foreach (var (x, y, z) in new[] { (0.0, 0.0, 0.0), (1.0, 0.0, 1e300), (0.0, 1.0, 0.0) })
            body.Value("float", x).Value("float", y).Value("double", z).Value("float", 0).Value("float", 0).Value("float", 2);
        body.Value("uchar", 3).Value("int", 0).Value("int", 1).Value("int", 2);
        e = Fails(File(header, body.Bytes));
        Assert.StartsWith($": element 'vertex' #1 at byte {header.Length + 28 + 8}: property 'z' is ", Tail(e));
        Assert.EndsWith(", not a finite number", Tail(e));
        var m = PlyReader.Parse(File(header, body.Bytes.Select((b, i) => i >= 36 && i < 44 ? (byte)0 : b).ToArray()), "n.ply");
        Assert.Equal(new System.Numerics.Vector3(0, 0, 1), m.Normals![1]);
    }

    [Fact]
    public void A_uint32_index_past_int_range_is_reported_as_written()
    {
        var header = "ply\nformat binary_big_endian 1.0\n" + TriangleVertices
            + "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
        var body = new Body(false);
        foreach (float v in Square[..9]) body.Value("float", v);
        body.Value("uchar", 3).Value("uint", 0).Value("uint", 3_000_000_000).Value("uint", 2);
        Assert.Equal($": element 'face' #0 at byte {header.Length + 36 + 1 + 4}: vertex index 3000000000 out of range (3 vertices)",
            Tail(Fails(File(header, body.Bytes))));
    }
}
