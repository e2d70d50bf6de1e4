using SpectralRenderer.Acceleration;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Extending;

/// <summary>
/// ARCHITECTURE.md, "Extending: an integrator": a light-transport method is one class plus one
/// <see cref="Integrators.Register(IntegratorEntry)"/> line. This one lives in the test assembly and the engine is not edited: an albedo
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

    /// <summary>
    /// A third integrator that takes the capability routes (IntegratorCapabilities.cs): a white furnace, uniform radiance L
    /// along every ray in every band, which gathers (<see cref="IGatherIntegrator"/>) and traces camera rays in packets for
    /// scenes of more than four bands (<see cref="IPacketIntegrator.PrefersPackets"/>). Registered with a settings key.
    /// </summary>
    sealed class FurnaceIntegrator(Scene scene, SceneGeometry geometry) : IPacketIntegrator, IGatherIntegrator
    {
        public const float L = 0.02f, Y = 7f;

        public int ScratchLength => 0;

        public bool PrefersPackets(Scene s) => s.Bands > 4;

        public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
        {
            Fill(result);
            var ray = sample.Ray;
            return geometry.Intersect(ref ray, out var hit) ? hit.Object : -1;
        }

        public void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks,
            Span<float> scratch, ref RayCounters counters)
        {
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                if ((packet.Active & (1u << lane)) == 0) continue;
                Fill(results.Slice(lane * scene.PaddedBands, scene.PaddedBands));
                var ray = packet.Ray(lane);
                objects[lane] = geometry.Intersect(ref ray, out var hit) ? hit.Object : -1;
                infos[lane] = default;
                fallbacks[lane] = false;
            }
        }

        void Fill(Span<float> result)
        {
            result.Clear();
            result[..scene.Bands].Fill(L);
            result[scene.Bands + 1] = Y;   // the colour lanes' Y: what the luminance reads when the observer's ȳ is V
        }
    }

    const string Furnace = "test-furnace";

    static void EnsureFurnace()
    {
        lock (typeof(IntegratorRecipeTests))
            if (!Integrators.Has(Furnace))
                Integrators.Register(new IntegratorEntry(Furnace, (scene, geometry) => new FurnaceIntegrator(scene, geometry))
                {
                    Keys = ["seed"],
                });
    }

    const string FurnaceJson = """
    { "bands": "400:700:BANDS", "radiometry": "physical",
      "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 20, "width": 16, "height": 16 },
      "materials": { "grey": { "diffuse": 0.25 } },
      "lights": [],
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey" } ] }
    """;

    [Fact]
    public void A_third_integrator_gets_the_gather_and_packets_through_their_capabilities()
    {
        EnsureFurnace();
        var scene = SceneText.Load(FurnaceJson.Replace("BANDS", "6"));
        var geometry = new SceneGeometry(scene);
        var integrator = Integrators.Create(scene, geometry, Furnace);

        // Packets: asked of the integrator for the scene (6 bands: yes; 3 bands: no), the same picture either way.
        var packed = Renderer.Render(scene, integrator, threads: 2);
        Assert.True(packed.Packets);
        Assert.Equal(FurnaceIntegrator.L, packed.Image[8, 8, 0]);
        var few = SceneText.Load(FurnaceJson.Replace("BANDS", "3"));
        Assert.False(Renderer.Render(few, Integrators.Create(few, new SceneGeometry(few), Furnace), threads: 2).Packets);

        // The gather of photometry and calculation grids, through the capability as the products take it: with no light,
        // a surface in a uniform radiance field L receives E = ∫ L cos θ dω = π·L_v (a white furnace), whatever the rays.
        var illuminance = new Illuminance(scene, geometry);
        float[] radiance = new float[scene.PaddedBands];
        radiance.AsSpan(0, scene.Bands).Fill(FurnaceIntegrator.L);
        double expected = Math.PI * illuminance.Luminance(radiance.AsSpan(0, scene.Bands), FurnaceIntegrator.Y);
        Assert.True(expected > 0);
        var floor = new CalculationGrid("floor", new System.Numerics.Vector3(-3, -3, -2), new System.Numerics.Vector3(6, 0, 0),
            new System.Numerics.Vector3(0, 6, 0), 3, 3);
        var lux = illuminance.OnGrid(floor, integrator as IGatherIntegrator, threads: 2);
        Assert.All(lux, e => Assert.Equal(expected, e, expected * 1e-6));
        // The photometry product says how its illuminance was found by asking the same capability.
        var tracer = new RenderTracer(geometry, integrator, 2);
        Assert.Contains("gather", PhotometryProduct.Method(tracer, scene), StringComparison.Ordinal);
        // Without the capability (the albedo integrator) the grid gets the lights' share only: none.
        EnsureRegistered();
        var albedo = Integrators.Create(scene, geometry, Name);
        Assert.All(illuminance.OnGrid(floor, albedo as IGatherIntegrator, threads: 2), e => Assert.Equal(0, e));
    }

    [Fact]
    public void Its_registration_names_the_settings_keys_a_scene_may_give_it()
    {
        EnsureFurnace();
        var dir = Reference.TempDir();
        foreach (var (integrator, ok) in new[] { ("{ \"type\": \"test-furnace\", \"seed\": 3 }", true),
            ("{ \"type\": \"test-furnace\", \"max_depth\": 3 }", false), ("{ \"type\": \"whitted\", \"seed\": 3 }", false) })
        {
            var scene = Path.Combine(dir, "furnace.json");
            var text = FurnaceJson.Replace("BANDS", "6").Replace("\"lights\": []", $"\"lights\": [], \"integrator\": {integrator}");
            File.WriteAllText(scene, text);
            var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(dir, "out"), "--quiet", "--formats", "npy");
            Assert.True(ok ? code == 0 : code == 2, $"{integrator}: {code} {err}");
            if (!ok) Assert.Contains("furnace.json:", err, StringComparison.Ordinal);   // the key's file:line:column
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
