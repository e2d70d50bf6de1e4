using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>Tests that measure the whole process (allocation) run alone, after the parallel ones.</summary>
[CollectionDefinition("Alone", DisableParallelization = true)]
public class AloneCollection;

/// <summary>The render loop allocates per tile-worker, never per ray or per pixel.</summary>
[Collection("Alone")]
public class AllocationTests
{
    const string Json = """
    { "camera": { "position": [0, 1, 6], "look_at": [0, 0.5, 0], "width": 64, "height": 64, "spp": 2 },
      "materials": { "m": { "diffuse": "colorchecker:14", "specular": 0.3, "mirror": 0.2 }, "glass": { "diffuse": 0, "transmit": 0.8,
        "ior": 1.5 } },
      "ambient": 0.05,
      "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65", "intensity": 0.2 } ],
      "objects": [ { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "m" },
                   { "type": "sphere", "center": [1.5, 0.5, 1], "radius": 0.5, "material": "glass" },
                   { "type": "box", "center": [-1.5, 0.5, 0], "size": [1, 1, 1], "material": "m" },
                   { "type": "plane", "material": "m" },
                   { "type": "mesh", "file": "tetra.obj", "fit": { "min": [-0.5, 1.2, 0.5], "max": [0.3, 2, 1.3] }, "material": "m" } ],
      "max_depth": 3 }
    """;

    /// <summary>A tetrahedron, so triangles are traced too (in packets, or ray by ray).</summary>
    const string Tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

    static (long Allocated, long Outputs, int Tiles, long Rays) Measure(int size, bool packets)
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "tetra.obj"), Tetra);
        File.WriteAllText(Path.Combine(dir, "scene.json"), Json);
        var scene = SceneLoader.Load(Path.Combine(dir, "scene.json"), new SceneOverrides { Width = size, Height = size });
        var integrator = Integrators.Create(scene, new SceneGeometry(scene));
        Renderer.Render(scene, integrator, 2, packets: packets);   // JIT, thread pool warm-up
        // The counter is process-wide: take the least of three renders, so a background thread's
        // allocation (a JIT rejit, another test's leftovers) cannot be charged to the render.
        long allocated = long.MaxValue;
        RenderResult r = null!;
        for (int k = 0; k < 3; k++)
        {
            long before = GC.GetTotalAllocatedBytes(true);
            r = Renderer.Render(scene, integrator, 2, packets: packets);
            allocated = Math.Min(allocated, GC.GetTotalAllocatedBytes(true) - before);
        }
        // The results themselves: the framebuffer, four per-pixel analysis arrays and the pixel colours (X, Y, Z).
        long outputs = (long)size * size * (scene.Bands * 4 + 4 + 4 + 4 + 4 + 3 * 4);
        return (allocated, outputs, r.Tiles, r.Rays.Total);
    }

    [SkippableTheory]
    [InlineData(true)]    // camera and shadow rays in packets (the default)
    [InlineData(false)]   // ray by ray
    public void Allocated_bytes_beyond_the_result_buffers_are_O_tiles_not_O_pixels(bool packets)
    {
        // An unoptimised (Debug) engine keeps structs in memory the optimiser would keep in registers.
        var debuggable = (System.Diagnostics.DebuggableAttribute?)Attribute.GetCustomAttribute(typeof(Renderer).Assembly,
            typeof(System.Diagnostics.DebuggableAttribute));
        Skip.If(debuggable?.IsJITOptimizerDisabled == true,
            "the engine is a Debug build; run the tests with -c Release as the README says");
        var small = Measure(64, packets);
        var large = Measure(256, packets);
        long smallLoop = small.Allocated - small.Outputs, largeLoop = large.Allocated - large.Outputs;
        Assert.True(large.Rays > 15 * small.Rays, $"{large.Rays} vs {small.Rays} rays");
        // 16× the pixels and rays: the loop's own allocation may grow with the tile count only (~1 KB per tile).
        // 16× the pixels and rays, the same allocation: one scratch set per worker thread, nothing per tile, ray or pixel.
        Assert.True(largeLoop <= 64 * 1024, $"render loop allocated {largeLoop} bytes for {large.Tiles} tiles ({large.Rays} rays)");
        Assert.True(largeLoop <= smallLoop + 4096, $"allocation grew from {smallLoop} to {largeLoop} bytes with 16× the pixels");
    }
}
