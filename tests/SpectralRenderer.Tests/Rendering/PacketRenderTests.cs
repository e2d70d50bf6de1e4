using System.Globalization;
using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Whitted;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Camera and shadow rays traced in packets give the picture the ray-by-ray loop gives, bit for bit: the
/// framebuffer and the four analysis images, for 1 and 2 threads and for one and several samples per pixel.
/// </summary>
public class PacketRenderTests
{
    /// <summary>A UV sphere of 48 × 24 quads (2,208 triangles), as OBJ text.</summary>
    static string SphereObj()
    {
        var sb = new StringBuilder();
        const int slices = 48, stacks = 24;
        for (int i = 0; i <= stacks; i++)
            for (int j = 0; j < slices; j++)
            {
                double th = Math.PI * i / stacks, ph = 2 * Math.PI * j / slices;
                sb.AppendLine(string.Create(CultureInfo.InvariantCulture,
                    $"v {Math.Sin(th) * Math.Cos(ph):R} {Math.Cos(th):R} {Math.Sin(th) * Math.Sin(ph):R}"));
            }
        for (int i = 0; i < stacks; i++)
            for (int j = 0; j < slices; j++)
            {
                int a = i * slices + j + 1, b = i * slices + (j + 1) % slices + 1, c = a + slices, d = b + slices;
                if (i > 0) sb.AppendLine($"f {a} {b} {d}");
                if (i < stacks - 1) sb.AppendLine($"f {a} {d} {c}");
            }
        return sb.ToString();
    }

    /// <param name="mirror">With a mirror sphere the renderer traces ray by ray (a Whitted recursion); without, every camera
    /// ray goes through the packet path (camera rays, plane tests, point-light terms and shadow rays in lanes).</param>
    /// <param name="copies">How many times the three lights are repeated (shifted): more than 8 lights take the packet
    /// path's other way of summing eq. 2's terms (at once, not listed).</param>
    /// <param name="bands">The band grid ("S:E:N"); 128 bands and more take the framebuffer's streaming stores.</param>
    static Scene Load(int spp, bool mirror, int copies = 1, string bands = "380:780:20")
    {
        var lights = string.Join(", ", Enumerable.Range(0, copies).Select(i => string.Create(CultureInfo.InvariantCulture, $$"""
                      { "type": "point", "position": [{{2.5 - i}}, 5, 4], "spectrum": "D65", "intensity": {{1.0 / copies}} },
                      { "type": "spot", "position": [-3, 4, {{2 - 0.5 * i}}], "look_at": [0, 0.5, 0], "cutoff": 25, "exponent": 8,
                        "spectrum": "A", "intensity": 0.7 },
                      { "type": "directional", "direction": [-0.3, -1, {{-0.2 + 0.1 * i}}], "spectrum": "D65", "intensity": 0.3 }
            """)));
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "sphere.obj"), SphereObj());
        var path = Path.Combine(dir, "scene.json");
        File.WriteAllText(path, $$"""
        { "bands": "{{bands}}",
          "camera": { "position": [0.4, 1.6, 5.2], "look_at": [0, 0.6, 0], "fov": 40, "width": 83, "height": 61, "spp": {{spp}} },
          "materials": { "shiny": { "diffuse": "colorchecker:14", "specular": 0.4, "shininess": 30 },
                         "phong": { "diffuse": "colorchecker:7", "specular": 0.3, "shininess": 12, "model": "phong" },
                         "mirror": { "diffuse": 0.1{{(mirror ? ", \"mirror\": 0.6" : ", \"specular\": 0.5, \"shininess\": 60")}} },
                         "floor": { "diffuse": "colorchecker:neutral-6.5" } },
          "ambient": 0.05,
          "lights": [ {{lights}} ],
          "objects": [ { "type": "mesh", "file": "sphere.obj", "fit": { "min": [-1.6, 0, -1], "max": [0.4, 2, 1] }, "material": "shiny" },
                       { "type": "mesh", "file": "sphere.obj", "shading": "flat", "fit": { "min": [0.6, 0, 0.2], "max": [1.6, 1, 1.2] },
                         "material": "phong" },
                       { "type": "sphere", "center": [1.4, 0.4, -1.2], "radius": 0.4, "material": "mirror" },
                       { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" } ],
          "max_depth": 2 }
        """);
        return SceneLoader.Load(path);
    }

    static void AssertSame(RenderResult a, RenderResult b)
    {
        Assert.True(a.Image.Data.AsSpan().SequenceEqual(b.Image.Data), "framebuffer");
        Assert.Equal(a.ObjectIds, b.ObjectIds);
        Assert.Equal(a.LitMasks.ToArray(), b.LitMasks.ToArray());
        Assert.True(a.Highlights.AsSpan().SequenceEqual(b.Highlights), "highlight mask");
        Assert.True(a.Xyz.AsSpan().SequenceEqual(b.Xyz), "XYZ");
        Assert.Equal(a.FallbackPixels, b.FallbackPixels);
        Assert.Equal(a.Rays.Primary, b.Rays.Primary);
        Assert.Equal(a.Rays.Shadow, b.Rays.Shadow);
    }

    [Theory]
    [InlineData(1, false)]
    [InlineData(3, false)]
    [InlineData(16, false)]
    [InlineData(1, true)]
    [InlineData(3, true)]
    [InlineData(1, false, 3)]
    [InlineData(1, false, 1, "380:780:401")]
    [InlineData(3, false, 1, "400:700:137")]
    public void Packets_render_the_ray_by_ray_picture_bit_for_bit(int spp, bool mirror, int copies = 1, string bands = "380:780:20")
    {
        var scene = Load(spp, mirror, copies, bands);
        var integrator = new WhittedIntegrator(scene, new SceneGeometry(scene));
        var single = Renderer.Render(scene, integrator, threads: 1, packets: false);
        var packed1 = Renderer.Render(scene, integrator, threads: 1);
        var packed2 = Renderer.Render(scene, integrator, threads: 2);
        Assert.False(single.Packets);
        Assert.Equal(!mirror, packed1.Packets);   // the recursion of a mirror is traced ray by ray
        AssertSame(single, packed1);
        AssertSame(single, packed2);
        // A crop (a shard) whose corner is not on the 4 × 4 blocks of the whole film: its pixels are the whole render's.
        var crop = new PixelRect(13, 7, 70, 45);
        var part = Renderer.Render(scene, integrator, threads: 2, crop: crop);
        for (int y = crop.Y0; y < crop.Y1; y++)
            for (int x = crop.X0; x < crop.X1; x++)
            {
                Assert.True(part.Image.Pixel(x - crop.X0, y - crop.Y0).SequenceEqual(single.Image.Pixel(x, y)), $"pixel {x},{y}");
                Assert.Equal(single.ObjectIds[y * single.Image.Width + x], part.ObjectIds[(y - crop.Y0) * crop.Width + x - crop.X0]);
            }
        // Not vacuous: every object is seen, the spot lights part of the floor, some pixels are in shadow.
        Assert.Equal(4, single.ObjectIds.Where(i => i >= 0).Distinct().Count());
        Assert.Contains(single.LitMasks.ToArray(), m => (m & 2) != 0);
        Assert.Contains(single.LitMasks.ToArray(), m => m == 0);
    }
}
