using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>The camera-sample loop and its sampler: what an integrator gets per sample, and what it may rely on.</summary>
public class CameraSampleTests
{
    const string Json = """
    { "camera": { "position": [0, 1, 6], "look_at": [0, 0.5, 0], "width": 45, "height": 37, "spp": SPP },
      "materials": { "m": { "diffuse": 0.5 } },
      "lights": [ { "type": "point", "position": [2, 4, 3], "spectrum": "D65", "intensity": 1 } ],
      "objects": [ { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "m" }, { "type": "plane", "material": "m" } ] }
    """;

    static SpectralRenderer.Scenes.Scene Scene(int spp) => SceneText.Load(Json.Replace("SPP", spp.ToString()));

    [Fact]
    public void The_first_2D_draw_is_the_film_jitter_hash_split_in_16_bit_halves()
    {
        for (int x = 0; x < 20; x++)
            for (int s = 0; s < 5; s++)
            {
                uint h = Renderer.Hash((uint)x, 7, (uint)s);
                var (u, v) = new Sampler(x, 7, s).Next2D();
                Assert.Equal((h & 0xFFFF) / 65536f, u);
                Assert.Equal((h >> 16) / 65536f, v);
            }
    }

    [Fact]
    public void Later_dimensions_are_uniform_uncorrelated_and_depend_only_on_pixel_sample_and_dimension()
    {
        const int n = 40000;
        double sum2 = 0, sum3 = 0, sq2 = 0, sq3 = 0, cross = 0, crossPixels = 0;
        for (int i = 0; i < n; i++)
        {
            int x = i % 200, y = i / 200 % 100, s = i / 20000;
            var a = new Sampler(x, y, s, 2);
            float d2 = a.Next1D(), d3 = a.Next1D();
            Assert.InRange(d2, 0f, 0.99999994f);
            // The same (pixel, sample, dimension) gives the same number, whatever was drawn before.
            var b = new Sampler(x, y, s);
            b.Next2D();
            Assert.Equal(d2, b.Next1D());
            float neighbour = new Sampler(x + 1, y, s, 2).Next1D();
            sum2 += d2; sum3 += d3; sq2 += d2 * d2; sq3 += d3 * d3; cross += d2 * d3; crossPixels += d2 * neighbour;
        }
        double m2 = sum2 / n, m3 = sum3 / n;
        Assert.InRange(m2, 0.49, 0.51);
        Assert.InRange(m3, 0.49, 0.51);
        Assert.InRange(sq2 / n - m2 * m2, 1 / 12.0 - 0.003, 1 / 12.0 + 0.003);   // the variance of U(0, 1)
        double r = (cross / n - m2 * m3) / (1 / 12.0);
        Assert.InRange(r, -0.02, 0.02);
        Assert.InRange((crossPixels / n - m2 * m2) / (1 / 12.0), -0.03, 0.03);
    }

    /// <summary>A stochastic integrator that knows nothing but its samples: every band of a sample is its dimension-2 draw.</summary>
    sealed class Noise(int padded, int bands) : IIntegrator
    {
        public int ScratchLength => 0;

        public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
        {
            var sampler = sample.Sampler;
            float u = sampler.Next1D();
            result[..padded].Fill(u);
            return sample.Index == CameraSample.Centre ? sample.X % 3 : -1;
        }

        public int Bands => bands;
    }

    [Theory]
    [InlineData(1)]
    [InlineData(4)]
    public void A_stochastic_integrator_gets_each_pixel_the_mean_of_its_own_samples_on_any_thread_count_and_crop(int spp)
    {
        var scene = Scene(spp);
        var noise = new Noise(scene.PaddedBands, scene.Bands);
        var one = Renderer.Render(scene, noise, threads: 1);
        var two = Renderer.Render(scene, noise, threads: 2);
        var crop = new PixelRect(13, 5, 41, 36);
        var part = Renderer.Render(scene, noise, threads: 2, crop: crop);
        Assert.Equal(one.Image.Data, two.Image.Data);
        int w = scene.Camera.Width, bands = scene.Bands;
        for (int y = 0; y < scene.Camera.Height; y++)
            for (int x = 0; x < w; x++)
            {
                // Independently: the pixel's samples 0 … spp−1 (or its centre ray alone), each drawn at dimension 2, weighted 1/spp.
                float expected;
                if (spp == 1) expected = new Sampler(x, y, CameraSample.Centre, 2).Next1D();
                else
                {
                    expected = 0;
                    for (int s = 0; s < spp; s++) expected += new Sampler(x, y, s, 2).Next1D() * (1f / spp);
                }
                int i = y * w + x;
                Assert.Equal(expected, one.Image.Data[i * bands], 6);
                // Without analysis, the object id is what the centre ray's Radiance returned, and no light is marked.
                Assert.Equal(x % 3, one.ObjectIds[i]);
                Assert.Equal(0u, one.LitMasks[i]);
                Assert.Equal(0, one.Highlights[i]);
                if (x >= crop.X0 && x < crop.X1 && y >= crop.Y0 && y < crop.Y1)
                    Assert.Equal(one.Image.Data[i * bands], part.Image.Data[((y - crop.Y0) * crop.Width + x - crop.X0) * bands]);
            }
        // One camera ray per sample, and with spp > 1 the centre ray of the analysis images.
        Assert.Equal((long)w * scene.Camera.Height * (spp == 1 ? 1 : spp + 1), one.Rays.Primary);
    }

    [Fact]
    public void Whitted_records_the_analysis_images_through_its_sink_at_the_centre_ray()
    {
        var scene = Scene(4);
        var r = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene)), threads: 2, packets: false);
        // The plane and the sphere are lit by the one light where it faces them: lit pixels exist, and only where an object is seen.
        int lit = 0;
        for (int i = 0; i < r.ObjectIds.Length; i++)
        {
            if (r.ObjectIds[i] < 0) Assert.Equal(0u, r.LitMasks[i]);
            if (r.LitMasks[i] == 1u) lit++;
        }
        Assert.True(lit > r.ObjectIds.Length / 4, $"{lit} lit pixels");
        var packed = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene)), threads: 2, packets: true);
        Assert.Equal(r.ObjectIds, packed.ObjectIds);
        Assert.Equal(r.LitMasks.ToArray(), packed.LitMasks.ToArray());
        Assert.Equal(r.Image.Data, packed.Image.Data);
    }
}
