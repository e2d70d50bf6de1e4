using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Extending;

/// <summary>
/// ARCHITECTURE.md, "Extending: an integrator": a light-transport method is one class plus one
/// <see cref="Integrators.Register"/> line. This one lives in the test assembly and the engine is not edited: an albedo
/// integrator (the diffuse reflectance m_diff of the first surface a camera ray meets, 0 where it meets nothing).
/// </summary>
public class IntegratorRecipeTests
{
    /// <summary>The example: what a G-buffer's albedo channel holds, in every band.</summary>
    sealed class AlbedoIntegrator(Scene scene, SceneGeometry geometry) : IIntegrator
    {
        readonly float[][] _diffuse = [.. scene.Objects.Select(o => scene.Materials[o.Material].Diffuse)];

        public int ScratchLength => 0;

        public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
        {
            result.Clear();
            var ray = sample.Ray;
            if (!geometry.Intersect(ref ray, out var hit)) return -1;
            _diffuse[hit.Object].AsSpan(0, scene.Bands).CopyTo(result);
            return hit.Object;
        }
    }

    internal const string Name = "test-albedo";

    internal static void EnsureRegistered()
    {
        lock (typeof(IntegratorRecipeTests))
            if (!Integrators.Has(Name)) Integrators.Register(Name, (scene, geometry) => new AlbedoIntegrator(scene, geometry));
    }

    // A sphere of reflectance 0.25 seen head-on from 10 units: its silhouette's angular radius is asin(1/10).
    const string Json = """
    { "bands": "400:700:6",
      "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 20, "width": 64, "height": 64 },
      "materials": { "grey": { "diffuse": 0.25 } },
      "lights": [ { "type": "point", "position": [0, 5, 5], "spectrum": "D65", "intensity": 1 } ],
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey" } ] }
    """;

    [Fact]
    public void A_registered_integrator_renders_by_name_without_an_engine_edit()
    {
        EnsureRegistered();
        Assert.Contains(Name, Integrators.Names);
        var scene = SceneText.Load(Json);
        var result = Renderer.Render(scene, Integrators.Create(scene, new SceneGeometry(scene), Name), threads: 2);

        // The centre pixel sees the sphere: exactly its reflectance in every band; a corner sees nothing.
        for (int b = 0; b < scene.Bands; b++)
        {
            Assert.Equal(0.25f, result.Image[32, 32, b]);
            Assert.Equal(0f, result.Image[0, 0, b]);
        }
        Assert.Equal(0, result.ObjectIds[32 * 64 + 32]);
        Assert.Equal(-1, result.ObjectIds[0]);

        // The sphere's pixels cover its silhouette: a cone of half-angle asin(r/d) on a film of vertical fov 20°
        // (pinhole: tan maps film distance), so π·(tan θ / tan 10° · 32)² pixels within the pixel boundary's slack.
        double radiusPx = Math.Tan(Math.Asin(0.1)) / Math.Tan(10 * Math.PI / 180) * 32;
        int covered = result.ObjectIds.Count(id => id == 0);
        Assert.InRange(covered, Math.PI * (radiusPx - 1) * (radiusPx - 1), Math.PI * (radiusPx + 1) * (radiusPx + 1));
    }

    [Fact]
    public void The_command_line_renders_with_it_through_the_render_job()
    {
        EnsureRegistered();
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "sphere.json");
        File.WriteAllText(scene, Json);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet", "--formats", "npy", "--integrator", Name);
        Assert.True(code == 0, err);
        using var npy = File.OpenRead(Path.Combine(outDir, "spectral.npy"));
        var (shape, data) = SpectralRenderer.Imaging.NpyReader.Read(npy);
        Assert.Equal([64, 64, 6], shape);
        for (int b = 0; b < 6; b++)
        {
            Assert.Equal(0.25f, data[(32 * 64 + 32) * 6 + b]);
            Assert.Equal(0f, data[b]);
        }
    }

    [Fact]
    public void A_name_cannot_be_registered_twice_so_the_papers_model_stays_whitted()
    {
        EnsureRegistered();
        Assert.Throws<ArgumentException>(() => Integrators.Register(Integrators.Default, (s, g) => new AlbedoIntegrator(s, g)));
        Assert.Throws<ArgumentException>(() => Integrators.Register(Name, (s, g) => new AlbedoIntegrator(s, g)));
    }
}
