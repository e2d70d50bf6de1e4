using System.Numerics;
using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// ARCHITECTURE's recipe, "one new file + one registration": a light type and a material model defined and registered
/// here, in the test assembly, are read by the normal loader and rendered; the pixel equals eq. 2 by hand.
/// </summary>
public class RegistrationTests
{
    /// <summary>A light that shines straight down from infinity with d = 1 (a directional light by another name).</summary>
    sealed class Overhead(LightEmission emission) : Light(emission)
    {
        public override string Type => "test-overhead";

        public override bool Illuminate(Vector3 p, out LightSample sample)
        {
            sample = new LightSample(Vector3.UnitY, float.PositiveInfinity, 1, 1);
            return true;
        }
    }

    static readonly Lazy<bool> Registered = new(() =>
    {
        LightTypes.Register("test-overhead", new LightType([], s => new Overhead(s.Emission)));
        // A grey Lambertian whose reflectance is one number.
        MaterialModels.Register("test-grey", new MaterialModel(["grey"], s =>
        {
            var rho = SpectralRenderer.Spectra.TabulatedSpectrum.Constant(s.Number("grey", 0.5, 0, 1), "grey");
            var bands = s.Bands(rho, "grey");
            return s.Diffuse(bands, rho, new LambertianBsdf(bands));
        }));
        return true;
    });

    [Fact]
    public void A_light_type_and_a_material_model_registered_from_outside_the_engine_render()
    {
        Assert.True(Registered.Value);
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes("""
        { "integration": "weighted", "bands": "400:700:3",
          "camera": { "position": [0, 5, 0.001], "look_at": [0, 0, 0], "fov": 20, "width": 8, "height": 8 },
          "materials": { "card": { "type": "test-grey", "grey": 0.25 } },
          "lights": [ { "type": "test-overhead", "spectrum": "E", "intensity": 2 } ],
          "objects": [ { "type": "plane", "material": "card" } ] }
        """), "registered.json");
        Assert.IsType<Overhead>(Assert.Single(scene.Lights));
        Assert.IsType<LambertianBsdf>(scene.Materials[0].Bsdf);
        var light = scene.Lights[0].Intensity;
        var image = Integrators.Render(scene).Image;
        // Paper radiometry, head-on: L = I·m_diff·(n·l), n·l = 1.
        for (int b = 0; b < scene.Bands; b++) Assert.Equal(light[b] * 0.25f, image[4, 4, b], light[b] * 1e-5f);
        // An unknown material type is named with the registered ones.
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => SceneLoader.Parse(Encoding.UTF8.GetBytes("""
        { "camera": { "position": [0, 5, 1], "look_at": [0, 0, 0] }, "materials": { "card": { "type": "test-gray" } }, "objects": [] }
        """), "bad.json"));
        Assert.Contains("unknown material type 'test-gray'", e.Message);
        Assert.Contains("test-grey", e.Message);
    }

    [Fact]
    public void The_lambertian_model_is_eq2s_diffuse_material()
    {
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes("""
        { "camera": { "position": [0, 5, 1], "look_at": [0, 0, 0] },
          "materials": { "a": { "type": "lambertian", "reflectance": 0.4 }, "b": { "diffuse": 0.4 },
                         "c": { "type": "eq2", "diffuse": 0.4 } },
          "objects": [] }
        """), "lambertian.json");
        var (a, b, c) = (scene.Materials[0], scene.Materials[1], scene.Materials[2]);
        Assert.Equal(b.Diffuse, a.Diffuse);
        Assert.Equal(b.Ambient, a.Ambient);
        Assert.Equal(c.Diffuse, b.Diffuse);
        Assert.False(a.HasSpecular || a.HasMirror || a.HasTransmission);
        Assert.IsType<LambertianBsdf>(a.Bsdf);
        Assert.IsType<Eq2Bsdf>(b.Bsdf);
    }
}
