using System.Numerics;
using System.Text;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Mitsuba;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// The Mitsuba 3 XML reader: a small scene's converted geometry and camera against values worked out by hand (transforms
/// composed in document order, lookat, fov_axis), the report, determinism, bad XML as one line file:line:column.
/// </summary>
public class MitsubaImportTests
{
    const string Sensor = """
        <sensor type="perspective">
            <float name="fov" value="60"/>
            <string name="fov_axis" value="AXIS"/>
            <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, 0" up="0, 1, 0"/></transform>
            <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
            <film type="hdrfilm"><integer name="width" value="200"/><integer name="height" value="100"/></film>
        </sensor>
        """;

    static string Scene(string body, string axis = "x") => $"""
        <scene version="3.0.0">
            <default name="spp" value="9"/>
            {Sensor.Replace("AXIS", axis)}
            {body}
        </scene>
        """;

    static (ImportedScene Imported, string Path) Convert(string xml, bool lenient = false)
    {
        var path = System.IO.Path.Combine(Reference.TempDir(), "scene.xml");
        File.WriteAllText(path, xml);
        return (SceneFormats.Convert(path, new ImportOptions(lenient)), path);
    }

    static double[] Numbers(JsonNode? n) => [.. n!.AsArray().Select(v => v!.GetValue<double>())];

    const string Sphere = """<shape type="sphere"><float name="radius" value="0.5"/></shape>""";

    /// <summary>
    /// A shapegroup of a PLY triangle (its own to_world: scale 2) and a sphere, placed by two instances (translations): the
    /// PLY becomes one prototype and an instance per placement, whose world corners are the ones worked out by hand (instance
    /// ∘ member); the sphere is copied with the composed transformation; the group itself renders nothing.
    /// </summary>
    [Fact]
    public void A_shapegroup_becomes_a_prototype_placed_by_each_instance()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(System.IO.Path.Combine(dir, "tri.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        var path = System.IO.Path.Combine(dir, "scene.xml");
        File.WriteAllText(path, Scene("""
            <shape type="shapegroup" id="group">
                <shape type="ply"><string name="filename" value="tri.ply"/>
                    <transform name="to_world"><scale value="2"/></transform></shape>
                <shape type="sphere"><float name="radius" value="0.25"/></shape>
            </shape>
            <shape type="instance" id="a"><ref id="group"/><transform name="to_world"><translate x="5"/></transform></shape>
            <shape type="instance" id="b"><ref id="group"/><transform name="to_world"><translate y="-3"/></transform></shape>
            """));
        var imported = SceneFormats.Convert(path, new ImportOptions(false));
        Assert.Single(imported.Scene["prototypes"]!.AsObject());
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        var instances = scene.Objects.Where(o => o.InstanceTransform is not null).ToList();
        Assert.Equal(2, instances.Count);
        Assert.Same(instances[0].Mesh, instances[1].Mesh);
        // tri.ply scaled by 2, then translated: (0,0,0), (2,0,0), (0,2,0) + (5,0,0) and + (0,−3,0).
        Assert.Equal([new(5, 0, 0), new(7, 0, 0), new(5, 2, 0)], instances[0].WorldMesh()!.Positions);
        Assert.Equal([new(0, -3, 0), new(2, -3, 0), new(0, -1, 0)], instances[1].WorldMesh()!.Positions);
        var spheres = scene.Objects.Where(o => o.Shape is not null).ToList();
        Assert.Equal(2, spheres.Count);
        Assert.Equal(new Vector3(5, 0, 0), Vector3.Transform(Vector3.Zero, spheres[0].Shape!.ObjectToWorld));
        Assert.Equal(new Vector3(0, -3, 0), Vector3.Transform(Vector3.Zero, spheres[1].Shape!.ObjectToWorld));
    }

    [Fact]
    public void The_camera_is_the_lookat_and_the_fov_is_made_vertical()
    {
        var camera = Convert(Scene(Sphere)).Imported.Scene["camera"]!;
        Assert.Equal([1, 2, 3], Numbers(camera["position"]));
        Assert.Equal([1, 2, 2], Numbers(camera["look_at"]));   // one unit along the view direction, towards the target
        Assert.Equal([0, 1, 0], Numbers(camera["up"]));
        Assert.Equal(200, camera["width"]!.GetValue<int>());
        Assert.Equal(100, camera["height"]!.GetValue<int>());
        Assert.Equal(9, camera["spp"]!.GetValue<int>());   // $spp from <default>
        // fov 60° across x (200 px) → vertical: 2·atan(tan 30° · 100/200) = 2·atan(0.288675) = 32.2042°.
        Assert.Equal(32.2042, camera["fov"]!.GetValue<double>(), 1e-4);
    }

    [Fact]
    public void An_envmap_becomes_our_envmap_sky_with_its_file_scale_and_to_world()
    {
        var dir = Reference.TempDir();
        File.WriteAllBytes(System.IO.Path.Combine(dir, "sky.pfm"), [.. "PF\n2 3\n-1\n"u8, .. new byte[72]]);
        var path = System.IO.Path.Combine(dir, "scene.xml");
        File.WriteAllText(path, Scene("""
            <emitter type="envmap">
                <string name="filename" value="sky.pfm"/>
                <float name="scale" value="2.5"/>
                <transform name="to_world"><rotate y="1" angle="90"/></transform>
            </emitter>
            """ + Sphere));
        var imported = SceneFormats.Convert(path, new ImportOptions(false));
        var sky = imported.Scene["sky"]!;
        Assert.Null(imported.Scene["background"]);
        Assert.Equal("envmap", sky["type"]!.GetValue<string>());
        Assert.Equal("sky.pfm", sky["file"]!.GetValue<string>());
        Assert.Equal(2.5, sky["scale"]!.GetValue<double>());
        // A 90° turn about +y, row-major for column vectors: x → −z, z → x.
        var m = Numbers(sky["transform"]!["matrix"]);
        double[] expected = [0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 0, 1];
        for (int i = 0; i < 16; i++) Assert.Equal(expected[i], m[i], 1e-9);
        Assert.Contains(imported.Report.Entries, e => e.Kind == "converted" && e.Element.Contains("envmap"));
        // The converted scene loads: the sky is the map (a black map: no sky emitter, a black background).
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        Assert.NotNull(scene.Environment);
        Assert.Equal(2.5, scene.Environment!.Scale);
    }

    [Theory]
    [InlineData("y", 60.0)]
    [InlineData("smaller", 60.0)]            // the smaller side is y here
    [InlineData("larger", 32.2042)]          // = x
    [InlineData("diagonal", 28.9550)]        // 2·atan(tan 30° · 100/√(200² + 100²)) = 2·atan(0.258199)
    public void Each_fov_axis_gives_its_vertical_fov(string axis, double vertical)
    {
        var camera = Convert(Scene(Sphere, axis)).Imported.Scene["camera"]!;
        Assert.Equal(vertical, camera["fov"]!.GetValue<double>(), 1e-4);
    }

    [Fact]
    public void Transforms_compose_in_document_order()
    {
        // scale (2, 1, 1), then rotate 90° about y, then translate (5, 0, 0): M = T·R·S. Mitsuba's rectangle corner (1, 1, 0)
        // → (2, 1, 0) → R_y(90°)(x, y, z) = (z, y, −x) → (0, 1, −2) → (5, 1, −2). Our quad is [−½, ½]², so the written
        // matrix is M·diag(2, 2, 1) = T·R·diag(4, 2, 1): rows [0 0 1 5], [0 2 0 0], [−4 0 0 0].
        var (imported, path) = Convert(Scene("""
            <shape type="rectangle" id="panel">
                <transform name="to_world"><scale x="2" y="1" z="1"/><rotate y="1" angle="90"/><translate x="5"/></transform>
            </shape>
            """));
        var quad = imported.Scene["objects"]![0]!;
        Assert.Equal("quad", quad["type"]!.GetValue<string>());
        Assert.Equal([0, 0, 1, 5, 0, 2, 0, 0, -4, 0, 0, 0, 0, 0, 0, 1], Numbers(quad["transform"]!["matrix"]));
        // and loaded by our loader, the quad's corner (½, ½, 0) lands at (5, 1, −2).
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        var corner = Vector3.Transform(new Vector3(0.5f, 0.5f, 0), scene.Objects[0].Shape!.ObjectToWorld);
        Assert.True(Vector3.Distance(new Vector3(5, 1, -2), corner) < 1e-5f, $"corner at {corner}");
    }

    [Fact]
    public void Spheres_cubes_and_matrices_are_placed_as_written()
    {
        var objects = Convert(Scene("""
            <shape type="sphere">
                <point name="center" x="1" y="0" z="0"/><float name="radius" value="2"/>
                <transform name="to_world"><translate y="3"/></transform>
            </shape>
            <shape type="cube"><transform name="to_world"><scale value="0.5"/><translate y="0.5"/></transform></shape>
            <shape type="disk"><transform name="to_world"><matrix value="1 0 0 0  0 0 1 0  0 -1 0 0  0 0 0 1"/></transform></shape>
            """)).Imported.Scene["objects"]!.AsArray();
        Assert.Equal([1, 3, 0], Numbers(objects[0]!["center"]));   // a similarity: written as centre and radius
        Assert.Equal(2, objects[0]!["radius"]!.GetValue<double>());
        // Mitsuba's cube is [−1, 1]³, ours [−½, ½]³: T(0, ½, 0)·S(½)·S(2) = T(0, ½, 0).
        Assert.Equal([1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1, 0, 0, 0, 0, 1], Numbers(objects[1]!["transform"]!["matrix"]));
        Assert.Equal([1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1], Numbers(objects[2]!["transform"]!["matrix"]));
    }

    [Fact]
    public void Materials_emitters_and_the_report_say_what_was_done()
    {
        var (imported, _) = Convert(Scene("""
            <bsdf type="roughplastic" id="coat">
                <rgb name="diffuse_reflectance" value="0.2, 0.4, 0.6"/><float name="alpha" value="0.3"/>
            </bsdf>
            <bsdf type="conductor" id="gold"><string name="material" value="Au"/></bsdf>
            <shape type="sphere"><ref id="coat"/></shape>
            <shape type="sphere"><ref id="gold"/></shape>
            <shape type="rectangle">
                <emitter type="area"><spectrum name="radiance" value="400:1, 700:2"/></emitter>
            </shape>
            <emitter type="point"><point name="position" value="0, 4, 0"/><spectrum name="intensity" value="3"/></emitter>
            """));
        var s = imported.Scene;
        Assert.Equal("physical", s["radiometry"]!.GetValue<string>());
        Assert.Equal("path", s["integrator"]!.GetValue<string>());
        var coat = s["materials"]!["coat"]!;
        Assert.Equal("plastic", coat["type"]!.GetValue<string>());
        Assert.Equal(0.3, coat["roughness"]!.GetValue<double>());
        Assert.Equal(1.5046 / 1.000277, coat["ior"]!.GetValue<double>(), 1e-9);   // Mitsuba's bk7 in air
        Assert.Equal([0.2, 0.4, 0.6], Numbers(coat["diffuse"]!["rgb"]));
        Assert.Equal("Au", s["materials"]!["gold"]!["conductor"]!.GetValue<string>());
        var light = s["objects"]![2]!["material"]!.GetValue<string>();
        Assert.Equal(2, Numbers(s["materials"]![light]!["emission"]!["spectrum"]!["values"]![1]).Last());
        Assert.Equal([0, 4, 0], Numbers(s["lights"]![0]!["position"]));
        var kinds = imported.Report.Entries.Select(e => (e.Kind, e.Element)).ToList();
        Assert.Contains(("approximated", "bsdf roughplastic 'coat'"), kinds);   // our coated model, the difference stated
        Assert.Contains(("uplifted", "bsdf roughplastic 'coat' diffuse_reflectance"), kinds);
        Assert.All(imported.Report.Entries, e => Assert.Matches(@"^scene\.xml:\d+$", e.Where));
    }

    [Fact]
    public void An_element_without_a_counterpart_fails_unless_lenient()
    {
        const string body = """<shape type="sphere"/><medium type="homogeneous" id="fog"/>""";
        var e = Assert.Throws<InputException>(() => Convert(Scene(body)));
        Assert.Matches(@"^scene\.xml:\d+:\d+: medium homogeneous 'fog': .*--lenient", e.Message);
        var lenient = Convert(Scene(body), lenient: true).Imported;
        Assert.Contains(lenient.Report.Entries, x => x.Kind == "error" && x.Element == "medium homogeneous 'fog'");
    }

    [Fact]
    public void Include_brings_in_another_files_elements_and_parameters_resolve()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(System.IO.Path.Combine(dir, "parts.xml"), """
            <scene version="3.0.0">
                <shape type="sphere" id="ball"><float name="radius" value="$r"/></shape>
            </scene>
            """);
        var path = System.IO.Path.Combine(dir, "main.xml");
        File.WriteAllText(path, Scene("""<default name="r" value="0.25"/><include filename="parts.xml"/>"""));
        var objects = SceneFormats.Convert(path, new ImportOptions()).Scene["objects"]!.AsArray();
        Assert.Equal("ball", objects[0]!["name"]!.GetValue<string>());
        Assert.Equal(0.25, objects[0]!["radius"]!.GetValue<double>());
    }

    [Fact]
    public void Import_is_deterministic_and_writes_the_report_beside()
    {
        var xml = Repo.PathOf("scenes", "mitsuba-cornell-box.xml");
        var (code1, out1, _) = CliRunner.Run("import", xml);
        var (code2, out2, err2) = CliRunner.Run("import", xml);
        Assert.Equal(0, code1);
        Assert.Equal(0, code2);
        Assert.Equal(out1, out2);
        Assert.Single(err2.Trim().Split('\n'));   // the one-line summary
        var dir = Reference.TempDir();
        var target = System.IO.Path.Combine(dir, "sub", "cornell.json");
        Assert.Equal(0, CliRunner.Run("import", xml, "-o", target).Exit);
        var first = File.ReadAllBytes(target);
        Assert.Equal(0, CliRunner.Run("import", xml, "-o", target).Exit);
        Assert.Equal(first, File.ReadAllBytes(target));
        Assert.Equal(out1.Replace("\r\n", "\n"), Encoding.UTF8.GetString(first));   // nothing to rebase, no meshes: the same JSON
        var report = JsonNode.Parse(File.ReadAllText(System.IO.Path.Combine(dir, "sub", "import-report.json")))!;
        Assert.Equal("mitsuba", report["format"]!.GetValue<string>());
    }

    [Fact]
    public void A_referenced_mesh_keeps_its_file_rebased_to_the_output()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(System.IO.Path.Combine(dir, "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        var path = System.IO.Path.Combine(dir, "scene.xml");
        File.WriteAllText(path, Scene("""<shape type="obj"><string name="filename" value="tri.obj"/></shape>"""));
        var output = System.IO.Path.Combine(dir, "out", "scene.json");
        Assert.Equal(0, CliRunner.Run("import", path, "-o", output).Exit);
        var mesh = JsonNode.Parse(File.ReadAllText(output))!["objects"]![0]!;
        Assert.Equal("../tri.obj", mesh["file"]!.GetValue<string>());
        Assert.Single(SceneLoader.Parse(File.ReadAllBytes(output), output).Objects);   // and it loads from there
    }

    [Fact]
    public void An_imported_mesh_written_as_PLY_reads_back()
    {
        var mesh = new ImportedMesh("m", [0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0, 4], [0, 1, 2, 0, 2, 3], Uvs: [0, 0, 1, 0, 0, 1, 1, 1]);
        var read = SpectralRenderer.Geometry.PlyReader.Parse(ImportWriter.Ply(mesh), "m.ply");
        Assert.Equal(2, read.TriangleCount);
        Assert.Equal(new Vector3(0, 0, 4), read.Positions[3]);
        Assert.Equal(new Vector2(1, 1), read.TexCoords![5]);   // triangle 1's third corner is vertex 3
    }

    [Fact]
    public void Render_converts_the_file_in_memory()
    {
        var dir = Reference.TempDir();
        var path = System.IO.Path.Combine(dir, "scene.xml");
        File.WriteAllText(path, Scene("""
            <shape type="sphere"><emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter></shape>
            """));
        var (code, _, err) = CliRunner.Run("render", path, "-o", System.IO.Path.Combine(dir, "out"), "--width", "8", "--height", "4",
            "--spp", "1", "--bands", "380:780:4", "--formats", "npy", "--quiet");
        Assert.True(code == 0, err);
        Assert.Contains("spectral import: scene.xml (mitsuba)", err);
        Assert.True(File.Exists(System.IO.Path.Combine(dir, "out", "spectral.npy")));
        var run = JsonNode.Parse(File.ReadAllText(System.IO.Path.Combine(dir, "out", "render.json")))!["run"]!;
        Assert.Equal("mitsuba", run["imported"]!["format"]!.GetValue<string>());   // render.json records the report
        Assert.EndsWith("scene.xml", run["imported"]!["source"]!.GetValue<string>());
    }
}
