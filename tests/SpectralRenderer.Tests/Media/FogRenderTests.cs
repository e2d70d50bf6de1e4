using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Distributed;
using SpectralRenderer.Tests.Relight;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// A room in chromatic fog rendered by the path tracer: the picture is the same bits on 1 and 2 threads and from 4 shards
/// merged (every random number of the free flights comes from the camera sample's sampler), and a relight of its per-light
/// transfer to another bulb equals a render with that bulb (the tracking decisions depend on the throughput only, so the
/// transport stays linear in each light's emission).
/// </summary>
public class FogRenderTests
{
    /// <summary>
    /// A floor and a back wall in a fog whose scattering falls as λ⁻⁴ (Rayleigh-like, σ_s = 0.4 per unit at 400 nm),
    /// a box of absorbing, scattering liquid (index-matched) on the floor, lit by a point bulb and an emitting panel.
    /// </summary>
    static string Room(string spectrum, double intensity, int height = 16) => $$"""
        { "radiometry": "physical", "bands": "400:700:6", "integrator": { "type": "path", "rr_depth": 3 },
          "medium": { "sigma_s": [[400, 0.4], [450, 0.2497], [500, 0.1638], [550, 0.1119], [600, 0.0790], [650, 0.0573], [700, 0.0426]],
                      "sigma_a": 0.02, "phase": { "type": "hg", "g": 0.6 } },
          "camera": { "position": [0, 1, 3], "look_at": [0, 0.5, 0], "width": 16, "height": {{height}}, "spp": 4 },
          "lights": [ { "type": "point", "name": "bulb", "position": [0.5, 1.6, 0.5],
                        "spectrum": "{{spectrum}}", "intensity": {{intensity}} } ],
          "materials": { "floor": { "type": "lambertian", "reflectance": 0.7 }, "boundary": { "transmit": 1, "ior": 1 },
                         "panel": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 0.01 } } },
          "objects": [ { "type": "plane", "material": "floor" },
                       { "type": "quad", "center": [0, 1, -1], "size": 2, "normal": [0, 0, 1], "material": "panel" },
                       { "type": "box", "center": [-0.4, 0.3, 0], "size": [0.5, 0.6, 0.5], "material": "boundary",
                         "medium": { "sigma_a": [[400, 2], [700, 0.1]], "sigma_s": 1.5, "phase": { "type": "hg", "g": 0.3 } } } ] }
        """;

    [Fact]
    public void A_foggy_render_is_the_same_bits_on_1_and_2_threads_and_from_4_shards_merged()
    {
        var dir = Reference.TempDir();
        var scene = PathRelightTests.Write(dir, "fog.json", Room("A", 2, height: 128));
        var two = Path.Combine(dir, "two");
        ShardMergeTests.Render(scene, two, "--formats", "npy,exr", "--threads", "2");
        var one = Path.Combine(dir, "one");
        ShardMergeTests.Render(scene, one, "--formats", "npy,exr", "--threads", "1");
        ShardMergeTests.AssertSameRender(two, one);
        var shards = new List<string>();
        for (int i = 0; i < 4; i++)
        {
            shards.Add(Path.Combine(dir, $"shard-{i}"));
            ShardMergeTests.Render(scene, shards[^1], "--formats", "npy,exr", "--shard", $"{i}/4");
        }
        var merged = Path.Combine(dir, "merged");
        var (code, _, err) = CliRunner.Run(["merge", .. shards, "-o", merged]);
        Assert.True(code == 0, err);
        ShardMergeTests.AssertSameRender(two, merged);
        Assert.Contains(PathRelightTests.Npy(one, "spectral.npy"), v => v > 0);
    }

    [Fact]
    public void A_foggy_render_relit_to_another_bulb_equals_a_render_with_that_bulb()
    {
        PathRelightTests.RelitToD65EqualsRerender(Room("A", 2), Room("D65", 0.5));
    }
}
