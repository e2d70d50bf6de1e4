using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>Meshes in scenes: the same cube as OBJ, as PLY and as an analytic box renders the same picture.</summary>
public class MeshSceneTests
{
    /// <summary>The unit cube [−0.5, 0.5]³ as OBJ quads, outward faces (also the mesh of GeometryCacheTests).</summary>
    internal const string Obj = """
    # unit cube [-0.5, 0.5]^3, quads, outward faces
    v -0.5 -0.5 -0.5
    v  0.5 -0.5 -0.5
    v  0.5  0.5 -0.5
    v -0.5  0.5 -0.5
    v -0.5 -0.5  0.5
    v  0.5 -0.5  0.5
    v  0.5  0.5  0.5
    v -0.5  0.5  0.5
    f 1 4 3 2
    f 5 6 7 8
    f 1 2 6 5
    f 4 8 7 3
    f 1 5 8 4
    f 2 3 7 6
    """;

    static string Ply()
    {
        var lines = Obj.Split('\n').Select(l => l.Trim()).ToList();
        var v = lines.Where(l => l.StartsWith("v ")).Select(l => l[2..]).ToList();
        var f = lines.Where(l => l.StartsWith("f "))
            .Select(l => "4 " + string.Join(' ', l[2..].Split(' ', StringSplitOptions.RemoveEmptyEntries).Select(i => int.Parse(i) - 1)))
            .ToList();
        return $"ply\nformat ascii 1.0\nelement vertex {v.Count}\nproperty float x\nproperty float y\nproperty float z\nelement face "
            + $"{f.Count}\nproperty list uchar int vertex_indices\nend_header\n{string.Join('\n', v)}\n{string.Join('\n', f)}\n";
    }

    static string Scene(string obj) => $$"""
    { "camera": { "position": [2.2, 1.7, 3.1], "look_at": [0, 0, 0], "fov": 35, "width": 96, "height": 80 },
      "materials": { "m": { "diffuse": "colorchecker:7", "specular": 0.2, "shininess": 20 } },
      "ambient": 0.02,
      "lights": [ { "type": "point", "position": [3, 4, 2], "spectrum": "D65", "intensity": 0.3 } ],
      "objects": [ {{obj}},
                   { "type": "plane", "point": [0, -0.5, 0], "material": "m", "name": "floor" } ] }
    """;

    static RenderResult RenderIn(string dir, string obj)
    {
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene(obj));
        return Integrators.Render(SceneLoader.Load(path));
    }

    [Fact]
    public void Obj_Ply_and_analytic_box_render_the_same_picture()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "cube.obj"), Obj);
        File.WriteAllText(Path.Combine(dir, "cube.ply"), Ply());
        var box = RenderIn(dir, """{ "type": "box", "name": "cube", "center": [0, 0, 0], "size": [1, 1, 1], "material": "m" }""");
        var obj = RenderIn(dir, """{ "type": "mesh", "name": "cube", "file": "cube.obj", "shading": "flat", "material": "m" }""");
        var ply = RenderIn(dir, """{ "type": "mesh", "name": "cube", "file": "cube.ply", "shading": "flat", "material": "m" }""");
        int cubePixels = 0, differing = 0;
        for (int i = 0; i < box.ObjectIds.Length; i++)
        {
            if (box.ObjectIds[i] == 0) cubePixels++;
            // A pixel whose centre ray grazes an edge may land on either face; there are few.
            if (box.ObjectIds[i] != obj.ObjectIds[i] || obj.ObjectIds[i] != ply.ObjectIds[i]) { differing++; continue; }
            for (int b = 0; b < box.Image.Bands; b++)
            {
                float a = box.Image.Data[i * box.Image.Bands + b], o = obj.Image.Data[i * box.Image.Bands + b],
                    p = ply.Image.Data[i * box.Image.Bands + b];
                Assert.Equal(o, p);   // the two files give the very same triangles
                if (Math.Abs(a - o) > 1e-4 * Math.Max(1, Math.Abs(a))) differing++;
            }
        }
        Assert.True(cubePixels > 1000, $"{cubePixels} cube pixels");
        Assert.True(differing <= cubePixels / 100, $"{differing} differing values of {cubePixels} cube pixels");
    }

    [Fact]
    public void Two_objects_on_one_file_each_get_their_own_fitted_mesh()
    {
        // The first object takes the read started with the scene; the second reads the file again (fitting changes
        // a mesh in place), so each ends up exactly in its own box.
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "cube.obj"), Obj);
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene("""
            { "type": "mesh", "name": "a", "file": "cube.obj", "fit": { "min": [-2, 0, 0], "max": [-1, 1, 1] }, "material": "m" },
            { "type": "mesh", "name": "b", "file": "cube.obj", "fit": { "min": [1, 0, 0], "max": [3, 2, 2] }, "material": "m" }
            """));
        var scene = SceneLoader.Load(path);
        var a = scene.Objects[0].Mesh!.Bounds;
        var b = scene.Objects[1].Mesh!.Bounds;
        Assert.NotSame(scene.Objects[0].Mesh, scene.Objects[1].Mesh);
        Assert.Equal(new System.Numerics.Vector3(-2, 0, 0), a.Min);
        Assert.Equal(new System.Numerics.Vector3(-1, 1, 1), a.Max);
        Assert.Equal(new System.Numerics.Vector3(1, 0, 0), b.Min);
        Assert.Equal(new System.Numerics.Vector3(3, 2, 2), b.Max);
    }

    [Fact]
    public void A_broken_mesh_read_ahead_reports_its_file_and_line()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "broken.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene("""{ "type": "mesh", "name": "x", "file": "broken.obj", "material": "m" }"""));
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => SceneLoader.Load(path));
        Assert.Contains("broken.obj:4", e.Message);
        Assert.Contains("out of range", e.Message);
    }

    [Fact]
    public void Errors_come_in_document_order_although_meshes_are_read_ahead()
    {
        // Object 0 has a bad material and object 1 a broken mesh, read ahead on the thread pool: the load reports
        // object 0, as a load in document order would.
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "broken.obj"), "v 0 0 0\nf 1 2 3\n");
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene("""
            { "type": "sphere", "name": "s", "center": [0, 0, 0], "radius": 1, "material": "nope" },
            { "type": "mesh", "name": "x", "file": "broken.obj", "material": "m" }
            """));
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => SceneLoader.Load(path));
        Assert.Contains("$.objects[0].material", e.Message);
        Assert.DoesNotContain("broken.obj", e.Message);
    }

    [Fact]
    public void A_missing_mesh_names_the_search_path()
    {
        var dir = Reference.TempDir();
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, Scene("""{ "type": "mesh", "file": "nowhere.obj", "material": "m" }"""));
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            SceneLoader.Load(path, new SceneOverrides { ModelDirectories = [dir] }));
        Assert.Contains("mesh 'nowhere.obj' not found in", e.Message);
        Assert.Contains("$SPECTRAL_MODELS", e.Message);
        Assert.Contains("--models", e.Message);
    }

    [Fact]
    public void A_missing_mesh_keeps_the_search_path_labels_however_long_the_folders()
    {
        // CI's folders are longer than a developer's: the labels must survive the message's 300-character cut.
        var dir = Reference.TempDir();
        var deep = Directory.CreateDirectory(Path.Combine(dir, new string('s', 120), new string('t', 120))).FullName;
        var models = Directory.CreateDirectory(Path.Combine(dir, new string('m', 200))).FullName;
        var path = Path.Combine(deep, "scene.json");
        File.WriteAllText(path, Scene("""{ "type": "mesh", "file": "nowhere.obj", "material": "m" }"""));
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            SceneLoader.Load(path, new SceneOverrides { ModelDirectories = [models] }));
        var line = e.Message;
        Assert.True(line.Length <= SpectralRenderer.Diagnostics.MessageText.MaxLine, line);
        Assert.Contains("not found in", line);
        Assert.Contains("--models ", line);
        Assert.Contains("$SPECTRAL_MODELS", line);
    }
}
