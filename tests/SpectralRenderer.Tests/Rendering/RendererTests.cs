using System.Numerics;
using SpectralRenderer.Color;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Rendering;

public class RendererTests
{
    static string ScenePath(string name)
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
        {
            var p = Path.Combine(d.FullName, "scenes", name);
            if (File.Exists(p)) return p;
        }
        throw new FileNotFoundException(name);
    }

    [Theory]
    [InlineData("weighted")]
    [InlineData("paper")]
    public void Rendering_the_chart_adds_no_colour_error(string integration)
    {
        var scene = SceneLoader.Load(ScenePath("paper-3.1-colorchecker-d65.json"),
            new SceneOverrides { Width = 180, Height = 120, Integration = integration });
        var result = Integrators.Render(scene);
        var c = scene.Colorimeter;
        int checkedPatches = 0;
        for (int p = 1; p <= 24; p++)
        {
            int obj = scene.Objects.FindIndex(o => o.Name == $"patch-{p:00}");
            var sum = new double[scene.Bands];
            int n = 0;
            for (int i = 0; i < result.ObjectIds.Length; i++)
            {
                if (result.ObjectIds[i] != obj) continue;
                for (int b = 0; b < scene.Bands; b++) sum[b] += result.Image.Data[i * scene.Bands + b];
                n++;
            }
            Assert.True(n > 100, $"patch {p} covers {n} pixels");
            for (int b = 0; b < sum.Length; b++) sum[b] /= n;
            var rendered = c.ToXyz(sum);
            var expected = c.OfReflectance(ColorChecker.Patch(p));
            Assert.True(Math.Abs(rendered.X / expected.X - 1) < 1e-5 && Math.Abs(rendered.Y / expected.Y - 1) < 1e-5
                && Math.Abs(rendered.Z / expected.Z - 1) < 1e-5,
                $"patch {p}: rendered {rendered} vs {expected}");
            checkedPatches++;
        }
        Assert.Equal(24, checkedPatches);
    }

    [Fact]
    public void One_thread_and_all_threads_give_byte_identical_bands()
    {
        const string json = """
        { "bands": "400:700:12",
          "camera": { "position": [0, 1, 6], "look_at": [0, 0.5, 0], "width": 67, "height": 45, "spp": 3 },
          "materials": { "glass": { "diffuse": 0.05, "specular": 1, "shininess": 40, "mirror": 0.2, "transmit": 0.7,
            "ior": { "cauchy": [1.5, 8000] } },
                         "floor": { "diffuse": "colorchecker:14", "mirror": 0.1 } },
          "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65", "intensity": 0.2, "attenuation": [1, 0.1, 0.01] },
                      { "type": "spot", "position": [-2, 4, 1], "look_at": [0, 0, 0], "cutoff": 25, "exponent": 4, "spectrum": "A",
                        "intensity": 0.1 } ],
          "ambient": 0.02,
          "objects": [ { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass" },
                       { "type": "plane", "material": "floor" } ],
          "max_depth": 4 }
        """;
        var one = SceneText.Render(json, threads: 1);
        var all = SceneText.Render(json, threads: Math.Max(2, Environment.ProcessorCount));
        Assert.Equal(one.Image.Data.Length, all.Image.Data.Length);
        Assert.True(one.Image.Data.AsSpan().SequenceEqual(all.Image.Data), "band data differ between 1 and N threads");
        Assert.Equal(one.ObjectIds, all.ObjectIds);
        Assert.True(one.Image.Max() > 0);
    }

    [Fact]
    public void Absolute_scaling_gives_683_lm_per_W_luminance()
    {
        var json = """
        { "scaling": "absolute", "white": "E",
          "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "width": 5, "height": 5, "fov": 10 },
          "materials": { "white": { "diffuse": 1 } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "constant:0.01" } ],
          "objects": [ { "type": "quad", "size": 10, "material": "white" } ] }
        """;
        var scene = SceneText.Load(json);
        Assert.Equal(683.0, scene.Colorimeter.Kappa);
        var img = Integrators.Render(scene).Image;
        // L = 0.01 W·m⁻²·sr⁻¹·nm⁻¹ at every wavelength → Y = 683 · 0.01 · ∫ȳ dλ over 380–780 nm.
        double integral = SpectralRenderer.Color.Observer.Cie1931.YBar.Integrate(380, 780);
        Assert.Equal(683 * 0.01 * integral, scene.Colorimeter.ToXyz(img.Pixel(2, 2)).Y, 3);
    }

    [Theory]
    [InlineData(2)]
    [InlineData(4)]
    [InlineData(8)]
    public void Stratified_samples_cover_the_pixel_evenly(int spp)
    {
        // A lit quad whose lower edge runs exactly through the middle of pixel row 10: with samples spread
        // evenly over the pixel, every pixel of that row is half covered.
        var probe = SceneText.Load(Json(0, spp));
        var ray = probe.Camera.Generate(16, 10.5f);
        float edge = ray.Origin.Y + ray.Direction.Y * (-ray.Origin.Z / ray.Direction.Z);
        var scene = SceneText.Load(Json(edge, spp));
        var img = Integrators.Render(scene).Image;
        for (int x = 2; x < 30; x++)
            for (int b = 0; b < scene.Bands; b++)
                Assert.Equal(0.5 * img[x, 5, b], img[x, 10, b], 5);

        static string Json(float edge, int spp) => $$"""
        { "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 20, "width": 32, "height": 24, "spp": {{spp}} },
          "materials": { "m": { "diffuse": 0.5 } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "E" } ],
          "objects": [ { "type": "quad", "center": [0, {{(edge + 50).ToString(System.Globalization.CultureInfo.InvariantCulture)}}, 0],
            "size": [100, 100], "material": "m" } ] }
        """;
    }
}
