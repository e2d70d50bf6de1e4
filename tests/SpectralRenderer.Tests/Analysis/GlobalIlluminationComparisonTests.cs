using System.Globalization;
using SpectralRenderer.Analysis;
using SpectralRenderer.Cli.Paper;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Distributed;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// The experiments' direct-against-global-illumination section (issue 23): its numbers are region means of the renders it
/// wrote (recomputed here from spectral.npy, object ids and the lit masks read back), and they behave as physics says —
/// the §3.1 chart alone in the dark has no light between surfaces (path = direct), and in §3.4 the white board lights
/// the bunny's shadow (path ≥ direct, lit and shadow).
/// </summary>
public class GlobalIlluminationComparisonTests
{
    static string Scenes => Path.GetDirectoryName(ShardMergeTests.Scene("paper-3.1-colorchecker-d65.json"))!;

    static bool HaveModels => Environment.GetEnvironmentVariable("SPECTRAL_MODELS") is { Length: > 0 } m
        && File.Exists(Path.Combine(m, "stanford-bunny.obj"));

    static List<string[]> Csv(string folder) =>
        File.ReadAllLines(Path.Combine(folder, "comparison.csv")).Skip(1).Select(l => l.Split(',')).ToList();

    static double D(string s) => double.Parse(s, CultureInfo.InvariantCulture);

    /// <summary>Mean Y (CIE 1931 weights of render.json applied to the band values in spectral.npy) over a region.</summary>
    static (double Mean, int Count) RegionMean(string dir, Func<int, bool> inRegion)
    {
        float[] cube;
        int[] shape;
        using (var s = File.OpenRead(Path.Combine(dir, "spectral.npy"))) (shape, cube) = NpyReader.Read(s);
        var manifest = System.Text.Json.Nodes.JsonNode.Parse(File.ReadAllText(Path.Combine(dir, "render.json")))!;
        var wy = manifest["colour"]!["weights_y"]!.AsArray()
            .Select(v => (double)v!).ToArray();
        int bands = shape[2], n = shape[0] * shape[1], count = 0;
        double sum = 0;
        for (int i = 0; i < n; i++)
        {
            if (!inRegion(i)) continue;
            count++;
            for (int b = 0; b < bands; b++) sum += wy[b] * cube[i * bands + b];
        }
        return (sum / count, count);
    }

    /// <summary>Every Y row of the CSV equals the region mean recomputed from the written files; returns them by scene, region.</summary>
    static Dictionary<(string, string), (double Direct, double Path)> CheckedRows(GlobalIlluminationComparison.Result r)
    {
        var rows = new Dictionary<(string, string), (double, double)>();
        foreach (var row in Csv(r.Folder).Where(c => c[2] == "Y"))
        {
            var (scene, region) = (row[1], row[3]);
            var direct = Path.Combine(r.Folder, scene, "direct");
            var folder = RenderFolder.Open(direct);
            var lit = RenderAovs.Open(folder).Lit!;
            bool In(int i) => folder.ObjectIds[i] >= 0 && region switch
            {
                "surface" => true,
                "lit" => lit.All(m => m[i]),
                "shadow" => !lit.Any(m => m[i]),
                _ => throw new InvalidOperationException(region),
            };
            var (md, nd) = RegionMean(direct, In);
            var (mp, _) = RegionMean(Path.Combine(r.Folder, scene, "path"), In);
            Assert.Equal(nd, int.Parse(row[4], CultureInfo.InvariantCulture));
            Assert.True(Math.Abs(D(row[5]) / md - 1) <= 1e-9 && Math.Abs(D(row[6]) / mp - 1) <= 1e-9,
                $"{scene} {region}: CSV {row[5]}, {row[6]}; files {md}, {mp}");
            Assert.True(Math.Abs(D(row[7]) - mp / md) <= 1e-9 * mp / md, $"{scene} {region}: ratio {row[7]} vs {mp / md}");
            rows[(scene, region)] = (md, mp);
        }
        return rows;
    }

    [Fact]
    public void The_chart_alone_in_the_dark_gets_no_light_from_other_surfaces()
    {
        var r = GlobalIlluminationComparison.Run(Scenes, Reference.TempDir(), 0.2, [], 0, 4, only: ["3.1"]);
        var rows = CheckedRows(r);
        var (direct, path) = rows[("paper-3.1-colorchecker-d65", "lit")];
        // A flat chart facing a directional light with nothing else in the scene: no bounce reaches it (the 5 nm grid
        // and the samplers' jitter aside).
        Assert.True(Math.Abs(path / direct - 1) <= 3e-3, $"path ÷ direct = {path / direct}");
        Assert.True(File.Exists(Path.Combine(r.Folder, "comparison.csv")));
    }

    [SkippableFact]
    public void In_section_3_4_the_white_board_lights_the_shadow_and_the_numbers_are_the_files_region_means()
    {
        Skip.IfNot(HaveModels, "SPECTRAL_MODELS does not point at the meshes (stanford-bunny.obj)");
        string models = Environment.GetEnvironmentVariable("SPECTRAL_MODELS")!;
        var r = GlobalIlluminationComparison.Run(Scenes, Reference.TempDir(), 0.15, [models], 0, 4, only: ["3.4"]);
        var rows = CheckedRows(r);
        var lit = rows[("paper-3.4-bunny-analysis", "lit")];
        var shadow = rows[("paper-3.4-bunny-analysis", "shadow")];
        Assert.True(lit.Path >= lit.Direct, $"lit: path {lit.Path} < direct {lit.Direct}");
        // The board (reflectance 1) returns light into the shadow: far more than the direct render's partly lit pixels.
        Assert.True(shadow.Path >= 2 * shadow.Direct, $"shadow: path {shadow.Path}, direct {shadow.Direct}");
        Assert.Contains(Csv(r.Folder), c => c[2] == "rmse" && c[3] == "shadow");
    }
}
