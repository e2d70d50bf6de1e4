using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Pbrt;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// The pbrt-v4 reader's tokenizer, graphics state and camera against values worked out by hand from the file format's
/// rules (pbrt.org/fileformat-v4, pbrt-v4 transform.cpp): each expected number is in the test, not computed by the code.
/// </summary>
public class PbrtParserTests
{
    static PbrtDocument Parse(string text, List<string>? notes = null) =>
        PbrtParser.ParseText(text, Path.Combine(Path.GetTempPath(), "test.pbrt"),
            (kind, where, element, action) => notes?.Add($"{kind} {where} {element}"));

    static void Near(double[] expected, double[] actual, double tolerance = 1e-12)
    {
        Assert.Equal(expected.Length, actual.Length);
        for (int i = 0; i < expected.Length; i++) Assert.True(Math.Abs(expected[i] - actual[i]) <= tolerance,
            $"component {i}: {actual[i]} instead of {expected[i]}");
    }

    [Fact]
    public void Tokens_keep_their_line_and_column_and_strings_their_escapes()
    {
        var t =
            PbrtTokenizer.Tokenize("# a comment\nShape \"sphere\" \"float radius\" [ 2.5 ] # more\n  \"string x\" \"a\\\"b\"", "f.pbrt");
        Assert.Equal(["Shape", "sphere", "float radius", "[", "2.5", "]", "string x", "a\"b"], t.Select(x => x.Text));
        Assert.Equal((PbrtTokenKind.Word, 2, 1), (t[0].Kind, t[0].Line, t[0].Column));
        Assert.Equal((PbrtTokenKind.String, 2, 7), (t[1].Kind, t[1].Line, t[1].Column));
        Assert.Equal((PbrtTokenKind.OpenBracket, 2, 31), (t[3].Kind, t[3].Line, t[3].Column));
        Assert.Equal((PbrtTokenKind.String, 3, 3), (t[6].Kind, t[6].Line, t[6].Column));
        Assert.Equal("f.pbrt:3:3", t[6].Where);
    }

    [Fact]
    public void Translate_rotate_scale_compose_as_pbrt_applies_them()
    {
        // CTM = T(1,2,3)·R_z(90°)·S(2): (1,0,0) → (2,0,0) → (0,2,0) → (1,4,3); (0,0,1) → (0,0,2) → (0,0,2) → (1,2,5).
        var doc = Parse("WorldBegin\nTranslate 1 2 3\nRotate 90 0 0 1\nScale 2 2 2\nShape \"sphere\"");
        var m = doc.Shapes[0].WorldFromObject;
        Near([1, 4, 3], m.Point(1, 0, 0));
        Near([1, 2, 5], m.Point(0, 0, 1));
        Assert.Equal(8, m.Determinant3, 12);
    }

    [Fact]
    public void Transform_lists_the_matrix_column_by_column_and_ConcatTransform_multiplies_on_the_right()
    {
        // Transform's 16 numbers are column-major: the translation is numbers 13–15.
        var doc = Parse("WorldBegin\nTranslate 0 0 1\nTransform [ 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 ]\nShape \"sphere\"\n"
            + "ConcatTransform [ 0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1 ]\nShape \"sphere\"");
        Near([5, 6, 7], doc.Shapes[0].WorldFromObject.Point(0, 0, 0));
        // The concatenated matrix's first column (0, 1, 0) is where x goes: (1, 0, 0) → (0, 1, 0) → (5, 7, 7).
        Near([5, 7, 7], doc.Shapes[1].WorldFromObject.Point(1, 0, 0));
    }

    [Fact]
    public void LookAt_gives_pbrts_camera_frame()
    {
        // Eye (0,0,5) looking at the origin, up +y: d = (0,0,−1), right = up × d = (−1,0,0), so the world point (1,0,5) is at
        // camera x = −1 and the origin at camera z = +5.
        var doc = Parse("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\nShape \"sphere\"");
        Near([-1, 0, 0], doc.CameraFromWorld.Point(1, 0, 5));
        Near([0, 0, 5], doc.CameraFromWorld.Point(0, 0, 0));
        Near([0, 1, 0], doc.CameraFromWorld.Point(0, 1, 5));
    }

    [Fact]
    public void Attributes_restore_the_transformation_material_and_orientation()
    {
        var doc = Parse("WorldBegin\nMaterial \"diffuse\"\nAttributeBegin\nTranslate 1 0 0\nReverseOrientation\nMaterial \"conductor\"\n"
            + "Shape \"sphere\"\nAttributeEnd\nShape \"sphere\"");
        Assert.Equal((true, 1), (doc.Shapes[0].ReverseOrientation, doc.Shapes[0].Material.Anonymous));
        Assert.Equal((false, 0), (doc.Shapes[1].ReverseOrientation, doc.Shapes[1].Material.Anonymous));
        Near([1, 0, 0], doc.Shapes[0].WorldFromObject.Point(0, 0, 0));
        Near([0, 0, 0], doc.Shapes[1].WorldFromObject.Point(0, 0, 0));
    }

    [Fact]
    public void Named_coordinate_systems_and_the_camera_system_are_restored_by_CoordSysTransform()
    {
        var doc = Parse("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\nTranslate 3 0 0\nCoordinateSystem \"a\"\n"
            + "Identity\nCoordSysTransform \"a\"\nShape \"sphere\"\nCoordSysTransform \"camera\"\nShape \"sphere\"");
        Near([3, 0, 0], doc.Shapes[0].WorldFromObject.Point(0, 0, 0));
        // The camera's coordinate system is world-from-camera: its origin is the eye, its +z the view direction.
        Near([0, 0, 5], doc.Shapes[1].WorldFromObject.Point(0, 0, 0));
        Near([0, 0, 4], doc.Shapes[1].WorldFromObject.Point(0, 0, 1));
    }

    [Fact]
    public void Each_object_instance_is_a_copy_under_the_instances_transformation()
    {
        // Inside ObjectBegin the shape's own CTM is Translate(0,1,0); the instance adds Translate(10,0,0) on the left.
        var doc = Parse("WorldBegin\nObjectBegin \"o\"\nTranslate 0 1 0\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\n"
            + "AttributeBegin\nTranslate 10 0 0\nObjectInstance \"o\"\nAttributeEnd");
        Assert.Equal(2, doc.Shapes.Count);
        Near([0, 1, 0], doc.Shapes[0].WorldFromObject.Point(0, 0, 0));
        Near([10, 1, 0], doc.Shapes[1].WorldFromObject.Point(0, 0, 0));
        Assert.Equal(["o", "o"], doc.Shapes.Select(s => s.Instance));
        Assert.NotEqual(doc.Shapes[0].InstanceCopy, doc.Shapes[1].InstanceCopy);
    }

    [Fact]
    public void Include_reads_a_file_relative_to_the_including_file()
    {
        var dir = Directory.CreateTempSubdirectory("pbrt-include").FullName;
        Directory.CreateDirectory(Path.Combine(dir, "sub"));
        File.WriteAllText(Path.Combine(dir, "sub", "geometry.pbrt"), "Translate 0 0 2\nShape \"sphere\"\n");
        File.WriteAllText(Path.Combine(dir, "main.pbrt"), "WorldBegin\nInclude \"sub/geometry.pbrt\"\nShape \"disk\"\n");
        var doc = PbrtParser.Parse(Path.Combine(dir, "main.pbrt"), (_, _, _, _) => { });
        Assert.Equal(["sphere", "disk"], doc.Shapes.Select(s => s.Entity.Type));
        Assert.Equal("geometry.pbrt:2:1", doc.Shapes[0].Entity.Where);
        Near([0, 0, 2], doc.Shapes[1].WorldFromObject.Point(0, 0, 0));   // an Include shares the graphics state
    }

    static JsonObject CameraOf(string text)
    {
        var path = Path.Combine(Path.GetTempPath(), "camera.pbrt");
        var scene = new PbrtConverter(path, new ImportOptions()).ConvertText(text);
        return scene.Scene["camera"]!.AsObject();
    }

    static double[] Vec(JsonNode? a) => a!.AsArray().Select(x => x!.GetValue<double>()).ToArray();

    [Fact]
    public void The_camera_keeps_pbrts_picture_fov_of_the_shorter_axis_and_a_mirror_for_a_left_handed_frame()
    {
        // Landscape: pbrt's fov is vertical. LookAt's frame is left-handed (right = up × d): the world is mirrored in x, so a
        // sphere at x = 1 lands at x = −1 and the eye on the axis stays where it is.
        var text = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\nFilm \"rgb\" \"integer xresolution\" 200 "
            + "\"integer yresolution\" 100\nWorldBegin\nTranslate 1 0 0\nShape \"sphere\" \"float radius\" 0.5";
        var path = Path.Combine(Path.GetTempPath(), "camera.pbrt");
        var scene = new PbrtConverter(path, new ImportOptions()).ConvertText(text).Scene;
        var camera = scene["camera"]!.AsObject();
        Assert.Equal(30, camera["fov"]!.GetValue<double>(), 9);
        Near([0, 0, 5], Vec(camera["position"]), 1e-9);
        Near([0, 0, 4], Vec(camera["look_at"]), 1e-9);
        Near([0, 1, 0], Vec(camera["up"]), 1e-9);
        Assert.Equal((200, 100), (camera["width"]!.GetValue<int>(), camera["height"]!.GetValue<int>()));
        Near([-1, 0, 0], Vec(scene["objects"]![0]!["center"]), 1e-9);

        // Portrait: pbrt's fov is horizontal; vertical = 2·atan(tan(15°)·200/100) = 56.373570864°. "Scale -1 1 1" before
        // LookAt makes pbrt's frame right-handed: no mirror.
        var portrait = CameraOf("Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\nFilm \"rgb\" "
            + "\"integer xresolution\" 100 \"integer yresolution\" 200\nWorldBegin\nTranslate 1 0 0\nShape \"sphere\"");
        Assert.Equal(56.373570864, portrait["fov"]!.GetValue<double>(), 6);
        var unmirrored = new PbrtConverter(path, new ImportOptions()).ConvertText("Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\n"
            + "Camera \"perspective\"\nWorldBegin\nTranslate 1 0 0\nShape \"sphere\"").Scene;
        Near([1, 0, 0], Vec(unmirrored["objects"]![0]!["center"]), 1e-9);
        Assert.Equal(90, unmirrored["camera"]!["fov"]!.GetValue<double>(), 9);   // pbrt's default fov, 1280 × 720
    }

    [Fact]
    public void A_mesh_is_wound_to_pbrts_orientation_under_ReverseOrientation_and_mirrors()
    {
        // One triangle in the z = 0 plane, counter-clockwise seen from +z: pbrt's normal is +z. The mirrored world (x → −x)
        // keeps it +z when the winding is swapped; ReverseOrientation turns it to −z, and so does a transformation that
        // mirrors (pbrt-v4 shapes.h: the normal is negated when reverseOrientation ^ transformSwapsHandedness).
        const string Tri = "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ] \"integer indices\" [ 0 1 2 ]";
        double NormalZ(string text)
        {
            var s = new PbrtConverter(Path.Combine(Path.GetTempPath(), "t.pbrt"), new ImportOptions()).ConvertText(text);
            var m = s.Meshes[0];
            var p = m.Positions;
            int a = m.Indices[0], b = m.Indices[1], c = m.Indices[2];
            double ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1], vx = p[3 * c] - p[3 * a], vy = p[3 * c + 1] - p[3 * a + 1];
            return ux * vy - uy * vx;
        }
        Assert.True(NormalZ("Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\n" + Tri) > 0);
        Assert.True(NormalZ("LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\n" + Tri) > 0);
        Assert.True(NormalZ("LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\nReverseOrientation\n" + Tri) < 0);
        Assert.True(NormalZ("Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\nScale 1 1 -1\n" + Tri) < 0);
    }

    [Theory]
    [InlineData("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 ", "test.pbrt:2:16", "not closed by ']'")]
    [InlineData("WorldBegin\nShpe \"sphere\"", "test.pbrt:2:1", "did you mean 'Shape'")]
    [InlineData("WorldBegin\nShape \"sphere\" \"flot radius\" 1", "test.pbrt:2:16", "did you mean 'float'")]
    [InlineData("WorldBegin\nShape \"sphere\" \"float radius\" \"big\"", "test.pbrt:2:31", "expects numbers")]
    [InlineData("WorldBegin\nAttributeBegin\nShape \"sphere\"", "test.pbrt:2:1", "not closed by AttributeEnd")]
    [InlineData("WorldBegin\nAttributeEnd", "test.pbrt:2:1", "without a matching begin")]
    [InlineData("WorldBegin\nObjectInstance \"nothing\"", "test.pbrt:2:1", "unknown object")]
    [InlineData("WorldBegin\nShape \"sphere\" \"string name", "test.pbrt:2:16", "not closed")]
    [InlineData("Translate 1 2\nWorldBegin", "test.pbrt:2:1", "expects 3 numbers")]
    [InlineData("LookAt 0 0 0  0 0 0  0 1 0", "test.pbrt:1:1", "LookAt")]
    public void Bad_input_is_one_line_with_file_line_and_column(string text, string where, string what)
    {
        var e = Assert.Throws<InputException>(() => Parse(text));
        Assert.StartsWith(where, e.Message);
        Assert.Contains(what, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }
}
