using System.Text.Json.Nodes;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Extending;

/// <summary>
/// ARCHITECTURE.md, "Extending: an integrator": a third integrator that records a per-light transfer
/// (<see cref="ITransferIntegrator"/>, its own <see cref="TransferFormat"/>) gets the lights product and `spectral relight`
/// without an engine edit. The model: a lamp albedo, L_b = m_diff,b · Σ_k I_k,b at the first hit, linear in every light's
/// band values, so its transfer is the film of m_diff (the same camera samples) and a relight is A_b · Σ_k I'_k,b.
/// </summary>
public class TransferRecipeTests
{
    const string Name = "test-lamp";

    sealed class LampIntegrator(Scene scene, SceneGeometry geometry) : ITransferIntegrator
    {
        public int ScratchLength => 0;

        public TransferFormat TransferFormat => LampFormat.Instance;

        public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
        {
            result.Clear();
            var ray = sample.Ray;
            if (!geometry.Intersect(ref ray, out var hit)) return -1;
            var m = scene.Materials[scene.Objects[hit.Object].Material].Diffuse;
            foreach (var light in scene.Lights)
                for (int b = 0; b < scene.Bands; b++) result[b] += m[b] * light.Intensity[b];
            return hit.Object;
        }

        /// <summary>The film of m_diff with the render's samples: the albedo integrator under the same renderer.</summary>
        public ILightTransfer TraceTransfer(Scene s, int threads, CancellationToken cancel, PixelRect? crop)
        {
            IntegratorRecipeTests.EnsureRegistered();
            var albedo = Renderer.Render(s, Integrators.Create(s, geometry, IntegratorRecipeTests.Name), threads, cancel: cancel);
            return new LampTransfer(albedo.Image.Width, albedo.Image.Height, s.Bands, albedo.Image.Data, albedo.ObjectIds);
        }
    }

    sealed class LampTransfer(int width, int height, int bands, float[] albedo, int[] ids) : ILightTransfer
    {
        public TransferFormat Format => LampFormat.Instance;
        public int FilmWidth => width;
        public int FilmHeight => height;
        public PixelRect Region => PixelRect.Whole(width, height);
        public int[] ObjectIds => ids;
        public string RelightMethod => "A_b * sum_k I_k,b";
        public IEnumerable<string> StoredFiles => [];

        public string? Mismatch(Scene scene) =>
            scene.Camera.Width == width && scene.Camera.Height == height && scene.Bands == bands ? null : "another film";

        public RenderResult Relight(Scene scene)
        {
            var image = new global::SpectralRenderer.Spectra.SpectralImage(width, height, scene.Grid);
            var sum = new float[bands];
            foreach (var light in scene.Lights)
                for (int b = 0; b < bands; b++) sum[b] += light.Intensity[b];
            for (int i = 0; i < width * height; i++)
                for (int b = 0; b < bands; b++) image.Data[i * bands + b] = albedo[i * bands + b] * sum[b];
            return new RenderResult
            {
                Image = image,
                ObjectIds = ids,
                LitMasks = LitMasks.From(new uint[width * height], scene.Lights.Count),
                Highlights = new byte[width * height],
                Rays = new RayCounters(),
                Elapsed = TimeSpan.Zero,
                Threads = 1,
                Tiles = 0,
                Crop = Region,
            };
        }

        public void Write(Scene scene, string outDir, Action<string> done)
        {
            var dir = Path.Combine(outDir, TransferFormat.Folder);
            Directory.CreateDirectory(dir);
            NpyWriter.Write(Path.Combine(dir, "albedo.npy"), albedo, [height, width, bands]);
            NpyWriter.Write(Path.Combine(dir, "ids.npy"), [.. ids.Select(i => (float)i)], [height, width]);
            File.WriteAllText(Path.Combine(dir, TransferFormat.Description), new JsonObject { ["kind"] = Name }.ToJsonString());
            done($"{TransferFormat.Folder}/albedo.npy");
            done($"{TransferFormat.Folder}/ids.npy");
            done($"{TransferFormat.Folder}/{TransferFormat.Description}");
        }
    }

    sealed class LampFormat : TransferFormat
    {
        public static readonly LampFormat Instance = new();
        public override string Kind => Name;
        public override string Integrator => Name;

        public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene) =>
            [("lamp transfer", 4L * scene.Camera.Width * scene.Camera.Height * scene.Bands)];

        public override ILightTransfer Read(string outDir, Scene scene)
        {
            (int[] Shape, float[] Data) Load(string file)
            {
                using var s = File.OpenRead(Path.Combine(outDir, TransferFormat.Folder, file));
                return NpyReader.Read(s);
            }
            var (shape, albedo) = Load("albedo.npy");
            var ids = Load("ids.npy").Data.Select(v => (int)v).ToArray();
            return new LampTransfer(shape[1], shape[0], shape[2], albedo, ids);
        }
    }

    static void EnsureRegistered()
    {
        lock (typeof(TransferRecipeTests))
            if (!Integrators.Has(Name))
                Integrators.Register(new IntegratorEntry(Name, (scene, geometry) => new LampIntegrator(scene, geometry))
                {
                    Transfer = LampFormat.Instance,
                });
    }

    // A grey and a green sphere under two lights; spp 2 so the transfer must repeat the render's jittered samples.
    const string Json = """
    { "bands": "400:700:6",
      "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 25, "width": 24, "height": 20, "spp": 2 },
      "materials": { "grey": { "diffuse": 0.25 }, "green": { "diffuse": "colorchecker:14" } },
      "lights": [ { "type": "point", "name": "key", "position": [0, 5, 5], "spectrum": "LIGHT", "intensity": 1 },
                  { "type": "point", "name": "fill", "position": [4, 0, 5], "spectrum": "D65", "intensity": 0.5 } ],
      "objects": [ { "type": "sphere", "center": [-1, 0, 0], "radius": 1, "material": "grey" },
                   { "type": "sphere", "center": [1.2, 0, 0], "radius": 0.8, "material": "green" } ] }
    """;

    static float[] Npy(string dir)
    {
        using var s = File.OpenRead(Path.Combine(dir, "spectral.npy"));
        return NpyReader.Read(s).Data;
    }

    [Fact]
    public void Its_lights_and_relight_go_through_its_transfer_capability()
    {
        EnsureRegistered();
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "d65.json"), Json.Replace("LIGHT", "D65"));
        File.WriteAllText(Path.Combine(dir, "a.json"), Json.Replace("LIGHT", "A"));
        var (code, _, err) = CliRunner.Run("render", Path.Combine(dir, "d65.json"), "-o", Path.Combine(dir, "r"), "--quiet",
            "--formats", "npy,lights", "--integrator", Name);
        Assert.True(code == 0, err);
        Assert.True(File.Exists(Path.Combine(dir, "r", TransferFormat.Folder, "albedo.npy")));   // written by its transfer

        (code, _, err) = CliRunner.Run("relight", Path.Combine(dir, "r"), "--light", "key=A", "-o", Path.Combine(dir, "relit"), "--quiet");
        Assert.True(code == 0, err);
        // The second method: the changed scene rendered by the integrator itself (light transport is linear in each light).
        (code, _, err) = CliRunner.Run("render", Path.Combine(dir, "a.json"), "-o", Path.Combine(dir, "direct"), "--quiet",
            "--formats", "npy", "--integrator", Name);
        Assert.True(code == 0, err);
        float[] relit = Npy(Path.Combine(dir, "relit")), direct = Npy(Path.Combine(dir, "direct")), before = Npy(Path.Combine(dir, "r"));
        Assert.Equal(direct.Length, relit.Length);
        Assert.True(direct.Count(v => v > 0) > direct.Length / 10, "the spheres cover the film");
        for (int i = 0; i < direct.Length; i++) Assert.Equal(direct[i], relit[i], 1e-5f * Math.Max(1, Math.Abs(direct[i])));
        Assert.Contains(before.Zip(relit), p => Math.Abs(p.First - p.Second) > 1e-3f * Math.Abs(p.First));   // A is not D65
        // The memory check counts its transfer by its format, for the integrator the request names (the scene names none).
        var scene = SceneText.Load(Json.Replace("LIGHT", "D65"));
        var lights = global::SpectralRenderer.Output.Products.OutputProductTable.Named(["lights"]);
        Assert.Contains(("lamp transfer", 4L * 24 * 20 * 6), global::SpectralRenderer.Output.RenderMemory.Estimate(scene, 1, lights, Name));
        Assert.DoesNotContain(global::SpectralRenderer.Output.RenderMemory.Estimate(scene, 1, lights), p => p.Part == "lamp transfer");
    }
}
