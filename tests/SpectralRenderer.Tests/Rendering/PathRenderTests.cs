using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>Path renders: the same bits for any thread count and crop; no allocation per path.</summary>
public class PathRenderTests
{
    /// <summary>A small closed room: a ceiling lamp (quad), a sphere light, a red and a green wall, a mirror ball, a glass
    /// ball, a point light and a sky through the open front — every kind of light and lobe the path tracer has.</summary>
    internal const string Room = """
    { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
      "camera": { "position": [0, 1, 3.2], "look_at": [0, 1, 0], "fov": 50, "width": 48, "height": 40, "spp": 4 },
      "background": { "name": "D65", "scale": 0.002 },
      "materials": {
        "white": { "type": "lambertian", "reflectance": 0.75 },
        "red": { "type": "lambertian", "reflectance": "colorchecker:red" },
        "green": { "type": "lambertian", "reflectance": "colorchecker:green" },
        "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 0.05 } },
        "mirror": { "diffuse": 0.05, "specular": 0.2, "shininess": 60, "mirror": 0.7 },
        "glass": { "diffuse": 0, "transmit": 1, "mirror": 1, "fresnel": true, "ior": 1.5 } },
      "lights": [ { "type": "point", "position": [0.5, 1.6, 0.5], "spectrum": "A", "intensity": 0.2 } ],
      "objects": [
        { "type": "quad", "name": "floor", "center": [0, 0, 0], "size": [2, 2], "normal": [0, 1, 0], "up": [0, 0, -1],
          "material": "white" },
        { "type": "quad", "name": "ceiling", "center": [0, 2, 0], "size": [2, 2], "normal": [0, -1, 0], "up": [0, 0, -1],
          "material": "white" },
        { "type": "quad", "name": "back", "center": [0, 1, -1], "size": [2, 2], "normal": [0, 0, 1], "material": "white" },
        { "type": "quad", "name": "left", "center": [-1, 1, 0], "size": [2, 2], "normal": [1, 0, 0], "material": "red" },
        { "type": "quad", "name": "right", "center": [1, 1, 0], "size": [2, 2], "normal": [-1, 0, 0], "material": "green" },
        { "type": "quad", "name": "lamp", "center": [0, 1.99, 0], "size": [0.5, 0.5], "normal": [0, -1, 0], "up": [0, 0, -1],
          "material": "lamp" },
        { "type": "sphere", "name": "bulb", "center": [-0.6, 1.7, -0.6], "radius": 0.08, "material": "lamp" },
        { "type": "sphere", "name": "ball", "center": [0.4, 0.3, -0.3], "radius": 0.3, "material": "mirror" },
        { "type": "sphere", "name": "lens", "center": [-0.35, 0.25, 0.2], "radius": 0.25, "material": "glass" } ] }
    """;

    [Fact]
    public void A_path_render_is_the_same_bits_on_1_and_2_threads_and_in_a_crop()
    {
        var scene = SceneText.Load(Room);
        var integrator = Integrators.Create(scene, new SceneGeometry(scene), "path");
        var one = Renderer.Render(scene, integrator, threads: 1);
        var two = Renderer.Render(scene, integrator, threads: 2);
        Assert.Equal(one.Image.Data, two.Image.Data);
        Assert.Equal(one.Xyz, two.Xyz);
        Assert.True(one.Image.Data.Any(v => v > 0), "the room is lit");
        var crop = Renderer.Render(scene, integrator, threads: 2, crop: new PixelRect(7, 5, 40, 33));
        for (int y = 5; y < 33; y++)
            for (int x = 7; x < 40; x++)
                for (int b = 0; b < scene.Bands; b++)
                    Assert.Equal(one.Image[x, y, b], crop.Image[x - 7, y - 5, b]);
    }

    [Fact]
    public void The_scene_names_its_integrator_and_the_command_line_overrides_it()
    {
        var scene = SceneText.Load(Room);
        Assert.Equal("path", scene.Integrator!.Name);
        Assert.Equal(-1, scene.Integrator.MaxDepth);
        var job = SpectralRenderer.Pipeline.RenderJob.Load(new SpectralRenderer.Pipeline.RenderRequest { Scene = scene });
        Assert.Equal("path", job.IntegratorName);
        job =
            SpectralRenderer.Pipeline.RenderJob.Load(new SpectralRenderer.Pipeline.RenderRequest { Scene = scene, Integrator = "whitted" });
        Assert.Equal("whitted", job.IntegratorName);
    }
}

/// <summary>The path tracer allocates per worker, never per path (beside <see cref="AllocationTests"/>).</summary>
[Collection("Alone")]
public class PathAllocationTests
{
    static long Measure(int size, bool dispersive)
    {
        // Dispersive: the glass ball's Cauchy index splits every path that meets it into one sub-path per band.
        string json =
            dispersive ? PathRenderTests.Room.Replace("\"ior\": 1.5", "\"ior\": { \"cauchy\": [1.5, 20000] }") : PathRenderTests.Room;
        Assert.Equal(dispersive, json.Contains("cauchy"));
        var scene = SceneText.Load(json, new SceneOverrides { Width = size, Height = size });
        var integrator = Integrators.Create(scene, new SceneGeometry(scene), "path");
        Renderer.Render(scene, integrator, 2);   // JIT, thread pool warm-up
        long allocated = long.MaxValue;
        for (int k = 0; k < 3; k++)
        {
            long before = GC.GetTotalAllocatedBytes(true);
            Renderer.Render(scene, integrator, 2);
            allocated = Math.Min(allocated, GC.GetTotalAllocatedBytes(true) - before);
        }
        long outputs = (long)size * size * (scene.Bands * 4 + 4 + 4 + 4 + 4 + 3 * 4);
        return allocated - outputs;
    }

    [SkippableTheory]
    [InlineData(false)]
    [InlineData(true)]
    public void Allocated_bytes_beyond_the_result_buffers_do_not_grow_with_paths(bool dispersive)
    {
        var debuggable = (System.Diagnostics.DebuggableAttribute?)Attribute.GetCustomAttribute(typeof(Renderer).Assembly,
            typeof(System.Diagnostics.DebuggableAttribute));
        Skip.If(debuggable?.IsJITOptimizerDisabled == true,
            "the engine is a Debug build; run the tests with -c Release as the README says");
        long small = Measure(32, dispersive), large = Measure(96, dispersive);
        Assert.True(large <= 64 * 1024, $"render loop allocated {large} bytes");
        Assert.True(large <= small + 4096, $"allocation grew from {small} to {large} bytes with 9× the pixels");
    }
}
