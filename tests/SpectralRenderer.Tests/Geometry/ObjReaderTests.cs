using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Tests.Geometry;

public class ObjReaderTests
{
    static TriangleMesh Parse(string text) => ObjReader.Parse(new StringReader(text), "bad.obj");

    [Theory]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "bad.obj:4: ", "vertex index 4 out of range (3 defined so far)")]
    [InlineData("f 1 2 3\nv 0 0 0\n", "bad.obj:1: ", "vertex index 1 out of range (0 defined so far)")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad.obj:4: ", "vertex index 0 out of range")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", "bad.obj:4: ", "vertex index -4 out of range")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n", "bad.obj:4: ", "vertex index 'a' is not an integer")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "bad.obj:5: ",
        "texture coordinate index 2 out of range (1 defined so far)")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "bad.obj:5: ", "normal index 2 out of range (1 defined so far)")]
    [InlineData("# a\nv 0 0 x\n", "bad.obj:2: ", "coordinate 'x' is not a finite number")]
    [InlineData("v 0 0 nan\n", "bad.obj:1: ", "coordinate 'nan' is not a finite number")]
    [InlineData("v 0 0\n", "bad.obj:1: ", "'v' needs 3 coordinates")]
    [InlineData("v 0 0 0\nvn 0 1\n", "bad.obj:2: ", "'vn' needs 3 coordinates")]
    [InlineData("v 0 0 0\nv 1 0 0\n\nf 1 2\n", "bad.obj:4: ", "face has 2 vertices (a face needs at least 3)")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "bad.obj:3: ", "no faces before the end of the file (empty mesh)")]
    [InlineData("", "bad.obj:1: ", "no faces before the end of the file (empty mesh)")]
    [InlineData("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n", "bad.obj:5: ", "all 2 triangles are degenerate")]
    public void Broken_files_are_rejected_with_file_and_line(string text, string where, string what)
    {
        var e = Assert.Throws<InputException>(() => Parse(text));
        Assert.StartsWith(where, e.Message);
        Assert.Contains(what, e.Message);
    }

    [Fact]
    public void A_missing_file_names_the_file()
    {
        var e = Assert.Throws<InputException>(() => ObjReader.Read("/nonexistent/bunny.obj"));
        Assert.Equal("/nonexistent/bunny.obj: mesh file not found (hint: check the path)", e.Message);
    }

    [Fact]
    public void Unknown_keywords_comments_groups_and_materials_are_ignored()
    {
        var m = Parse(
            "mtllib a.mtl\r\no thing\ng part\ns 1\nusemtl red\ncstype bezier\nv 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
        Assert.Equal(1, m.TriangleCount);
        Assert.Equal([0, 1, 2], m.Indices);
    }

    [Fact]
    public void Polygons_are_fan_triangulated_and_degenerate_triangles_counted()
    {
        // A pentagon (3 triangles) and a triangle repeating a vertex (dropped).
        var m = Parse("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\nf 1 2 2\n");
        Assert.Equal(3, m.TriangleCount);
        Assert.Equal(1, m.DegenerateCount);
        Assert.Equal([0, 1, 2, 0, 2, 3, 0, 3, 4], m.Indices);
    }

    [Fact]
    public void Normals_given_per_corner_become_vertex_normals_when_consistent()
    {
        var m = Parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 0.6 0.8\nf 1//1 2//1 3//2\n");
        Assert.Equal(new Vector3(0, 0, 1), m.Normals![0]);
        Assert.Equal(new Vector3(0, 0.6f, 0.8f), m.Normals[2]);
    }

    [Fact]
    public void Conflicting_or_absent_normals_are_computed_angle_weighted()
    {
        // Corner (0,0,0) of the unit cube's three faces at the origin: each face has a 90° angle there,
        // so the angle-weighted normal is −(1,1,1)/√3 (outward), whatever the file's per-corner normals say.
        var m = Parse("""
            v 0 0 0
            v 1 0 0
            v 0 1 0
            v 0 0 1
            vn 1 0 0
            vn 0 1 0
            f 1//1 3//1 2//1
            f 1//2 2//2 4//2
            f 1 4 3
            """);
        var n = m.Normals![0];
        Assert.Equal(-1 / MathF.Sqrt(3), n.X, 5);
        Assert.Equal(-1 / MathF.Sqrt(3), n.Y, 5);
        Assert.Equal(-1 / MathF.Sqrt(3), n.Z, 5);
        // (1,0,0) lies on the faces z = 0 and y = 0, with 45° at each: −(0,1,1)/√2.
        var n1 = m.Normals[1];
        Assert.Equal(0, n1.X, 6);
        Assert.Equal(-1 / MathF.Sqrt(2), n1.Y, 6);
        Assert.Equal(-1 / MathF.Sqrt(2), n1.Z, 6);
    }

    [Fact]
    public void Fit_scales_uniformly_and_centres_in_the_box()
    {
        var m = Parse("v 0 0 0\nv 4 0 0\nv 0 2 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n");
        m.Fit(new Vector3(-1), new Vector3(1));
        var b = m.Bounds;
        // Scale 2/4 = 0.5 (x is the longest side); centred at 0.
        Assert.Equal(new Vector3(-1, -0.5f, -0.25f), b.Min);
        Assert.Equal(new Vector3(1, 0.5f, 0.25f), b.Max);
    }

    [Fact]
    public void Transform_moves_normals_with_the_inverse_transpose()
    {
        // A plane tilted 45° in x-y, with normal −(1,1,0)/√2; stretch x by 2: the normal becomes −(1,2,0)/√5
        // (inverse transpose diag(1/2,1,1), renormalised), perpendicular to the stretched plane.
        var m = Parse("v 0 0 0\nv 1 -1 0\nv 0 0 1\nf 1 2 3\n");
        m.Transform(Matrix4x4.CreateScale(2, 1, 1));
        var n = m.Normals![0];
        Assert.Equal(-1 / MathF.Sqrt(5), n.X, 6);
        Assert.Equal(-2 / MathF.Sqrt(5), n.Y, 6);
        var (p0, p1, _) = m.Triangle(0);
        Assert.Equal(0, Vector3.Dot(n, p1 - p0), 6);
    }

    static void SameAsFloatParse(string text)
    {
        var bytes = Encoding.UTF8.GetBytes(text);
        bool expectedOk = float.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out float expected);
        bool ok = ObjReader.TryParseFloat(bytes, out float value);
        Assert.True(expectedOk == ok, $"'{text}': parsed {ok}, float.TryParse {expectedOk}");
        if (ok)
            Assert.True(BitConverter.SingleToInt32Bits(expected) == BitConverter.SingleToInt32Bits(value),
                $"'{text}': {value:R} != {expected:R}");
    }

    [Theory]
    [InlineData("0"), InlineData("-0"), InlineData("+0.5"), InlineData(".5"), InlineData("5."), InlineData("-.25"), InlineData("007.50")]
    [InlineData("-0.037830"), InlineData("90.848602"), InlineData("-235.313995"), InlineData("0.1"), InlineData("0.3"),
        InlineData("3.14159265358979")]
    // Exactly halfway between two floats: ties go to even.
    [InlineData("16777217"), InlineData("16777219"), InlineData("-16777217.0"), InlineData("33554434"),
        InlineData("0.000000059604644775390625")]
    [InlineData("999999999999999"), InlineData("9999999999999999"), InlineData("123456789012345678901234567890"),
        InlineData("0.0000000000000000000001")]
    [InlineData("1e5"), InlineData("1E-5"), InlineData("-2.5e+3"), InlineData("1e39"), InlineData("1e-46"),
        InlineData("340282356779733661637539395458142568448")]
    [InlineData("Infinity"), InlineData("-Infinity"), InlineData("NaN"), InlineData("∞")]
    [InlineData(""), InlineData("-"), InlineData("+"), InlineData("."), InlineData("-."), InlineData("1.2.3"), InlineData("1-"),
        InlineData("0x10"), InlineData("1,5"), InlineData("--1"), InlineData("١")]
    public void Coordinates_parse_exactly_as_float_Parse(string text) => SameAsFloatParse(text);

    [Fact]
    public void Random_decimals_parse_exactly_as_float_Parse()
    {
        var rng = new Random(11);
        var s = new StringBuilder();
        for (int n = 0; n < 200_000; n++)
        {
            s.Clear();
            if (rng.Next(3) == 0) s.Append(rng.Next(2) == 0 ? '-' : '+');
            int digits = rng.Next(1, 19), dot = rng.Next(-1, digits + 1);
            for (int d = 0; d < digits; d++)
            {
                if (d == dot) s.Append('.');
                s.Append((char)('0' + (d == 0 && rng.Next(4) == 0 ? 0 : rng.Next(10))));
            }
            if (rng.Next(50) == 0) s.Append('e').Append(rng.Next(-40, 40));
            SameAsFloatParse(s.ToString());
        }
        // Floats printed shortest (as OBJ writers do) come back as themselves.
        for (int n = 0; n < 100_000; n++)
        {
            float f = BitConverter.Int32BitsToSingle(rng.Next()) * (rng.Next(2) == 0 ? 1 : -1);
            if (float.IsFinite(f) && MathF.Abs(f) is > 1e-6f and < 1e8f)
                SameAsFloatParse(f.ToString("0.##########", CultureInfo.InvariantCulture));
        }
    }

    [Theory]
    [InlineData("0"), InlineData("-0"), InlineData("+7"), InlineData("123456789"), InlineData("1234567890"), InlineData("2147483647"),
        InlineData("2147483648")]
    [InlineData("-2147483648"), InlineData("-2147483649"), InlineData("0000000000012"), InlineData(""), InlineData("-"), InlineData("+"),
        InlineData("1a"), InlineData("a1"), InlineData("1.0"), InlineData("١")]
    public void Indices_parse_exactly_as_int_Parse(string text)
    {
        bool expectedOk = int.TryParse(text, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out int expected);
        Assert.Equal(expectedOk, ObjReader.TryParseInt(Encoding.UTF8.GetBytes(text), out int value));
        if (expectedOk) Assert.Equal(expected, value);
    }

    [Fact]
    public void White_space_is_what_char_IsWhiteSpace_says_in_ASCII_and_Unicode()
    {
        for (int b = 0; b < 128; b++) Assert.Equal(char.IsWhiteSpace((char)b), ObjReader.IsSpace((byte)b));
        // No-break space, em space, ideographic space and tabs separate values too; a UTF-8 BOM is skipped.
        var m = Parse("\uFEFFv\u00A00\u20030\t0\nv 1\u3000 0 0\r\nv 0 1 0\nf 1 2 3\n");
        Assert.Equal(new Vector3(1, 0, 0), m.Positions[1]);
        var e = Assert.Throws<InputException>(() => Parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1é\n"));
        Assert.Equal("bad.obj:4: coordinate '1é' is not a finite number", e.Unhinted());
    }
}
