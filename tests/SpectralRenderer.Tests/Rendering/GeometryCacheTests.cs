using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Scenes rendered one after another with a shared <see cref="GeometryCache"/> (as `experiments` and `sweep` do) against
/// each scene rendered on its own, with a BVH built for it alone: the same bits when the triangles are the same, and
/// no reuse when a vertex has moved.
/// </summary>
public class GeometryCacheTests
{
    const string Obj = MeshSceneTests.Obj;

    static Scene Load(string dir, string light, string transform)
    {
        var path = Path.Combine(dir, $"scene-{Guid.NewGuid():N}.json");
        File.WriteAllText(path, $$"""
        { "camera": { "position": [2.2, 1.7, 3.1], "look_at": [0, 0, 0], "fov": 35, "width": 64, "height": 48 },
          "materials": { "m": { "diffuse": "colorchecker:7", "specular": 0.2, "shininess": 20 } },
          "lights": [ { "type": "point", "position": [3, 4, 2], "spectrum": "{{light}}", "intensity": 0.3 } ],
          "objects": [ { "type": "mesh", "name": "cube", "file": "cube.obj", "material": "m", "transform": {{transform}} },
                       { "type": "plane", "point": [0, -0.5, 0], "material": "m", "name": "floor" } ] }
        """);
        return SceneLoader.Load(path);
    }

    static float[] Render(Scene scene, GeometryCache? cache) =>
        Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene, cache)), 2).Image.Data;

    [Fact]
    public void The_same_triangles_reuse_the_BVH_and_render_the_same_bits_a_moved_vertex_does_not()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "cube.obj"), Obj);
        const string turned = """{ "rotate": [0, 30, 0] }""", moved = """{ "rotate": [0, 30, 0], "translate": [0.1, 0, 0] }""";
        var cache = new GeometryCache();

        var first = Load(dir, "D65", turned);
        Assert.Equal(Render(first, null), Render(first, cache));
        Assert.Equal(0, cache.Reused);

        // Another light, the same mesh where it was: the first scene's BVH.
        var relit = Load(dir, "A", turned);
        Assert.Equal(Render(relit, null), Render(relit, cache));
        Assert.Equal(1, cache.Reused);

        // Moved by 0.1: its own BVH (reusing the first would put the cube where it was).
        var shifted = Load(dir, "D65", moved);
        var alone = Render(shifted, null);
        Assert.Equal(alone, Render(shifted, cache));
        Assert.Equal(1, cache.Reused);
        Assert.NotEqual(Render(first, null), alone);
    }

    [Fact]
    public void Holds_the_last_few_meshes_the_least_recently_used_dropped_first()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "cube.obj"), Obj);
        var cache = new GeometryCache();
        var scenes = Enumerable.Range(0, GeometryCache.Capacity + 1)
            .Select(k => Load(dir, "D65",
                $$"""{ "translate": [{{(k * 0.05).ToString(System.Globalization.CultureInfo.InvariantCulture)}}, 0, 0] }"""))
            .ToList();
        foreach (var s in scenes) _ = new SceneGeometry(s, cache);
        Assert.Equal(0, cache.Reused);
        _ = new SceneGeometry(scenes[^1], cache);   // the newest is held
        Assert.Equal(1, cache.Reused);
        _ = new SceneGeometry(scenes[0], cache);    // the oldest was dropped: built again
        Assert.Equal(1, cache.Reused);
    }
}
