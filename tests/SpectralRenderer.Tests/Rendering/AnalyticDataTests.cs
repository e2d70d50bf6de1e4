using System.Text;
using System.Text.Json.Nodes;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The closed-form scenes of tests/data/analytic (README there): each scene rendered by the renderer's
/// integrator (exact band integration), each check's band values against scale × the band mean of the product
/// of the named spectra, integrated numerically here.
/// </summary>
public class AnalyticDataTests
{
    static string Folder => Repo.PathOf("tests", "data", "analytic");

    public static TheoryData<string> Files()
    {
        var data = new TheoryData<string>();
        foreach (var f in Directory.GetFiles(Folder, "*.json").Order()) data.Add(Path.GetFileName(f));
        return data;
    }

    /// <summary>
    /// (1/Δλ)∫ Π S_i(λ) dλ over [lo, hi] by the midpoint rule on 0.01 nm steps (the product of piecewise-linear
    /// tables is piecewise quadratic: relative error ~1e-7), independently of the engine's exact integration.
    /// </summary>
    static double BandMeanOfProduct(List<TabulatedSpectrum> spectra, double lo, double hi)
    {
        int steps = (int)Math.Ceiling((hi - lo) / 0.01);
        double h = (hi - lo) / steps, sum = 0;
        for (int k = 0; k < steps; k++)
        {
            double l = lo + (k + 0.5) * h, v = 1;
            foreach (var s in spectra) v *= s.Evaluate(l);
            sum += v;
        }
        return sum / steps;
    }

    [Fact]
    public void The_analytic_scenes_are_there() => Assert.True(Files().Count >= 5);

    [Theory]
    [MemberData(nameof(Files))]
    public void Renders_equal_the_closed_form(string file)
    {
        var doc = JsonNode.Parse(File.ReadAllText(Path.Combine(Folder, file)))!.AsObject();
        Assert.False(string.IsNullOrWhiteSpace((string?)doc["formula"]), $"{file}: no formula");
        var scene = SceneLoader.Parse(Encoding.UTF8.GetBytes(doc["scene"]!.ToJsonString()), Path.Combine(Folder, file));
        var result = Integrators.Render(scene);
        int w = result.Image.Width, n = scene.Bands;
        var checks = doc["checks"]!.AsArray();
        Assert.NotEmpty(checks);
        foreach (var check in checks.Select(c => c!.AsObject()))
        {
            double scale = (double)check["scale"]!, tolerance = (double)check["tolerance"]!;
            var spectra = check["spectra"]!.AsArray().Select(s => s!.GetValueKind() == System.Text.Json.JsonValueKind.Number
                ? TabulatedSpectrum.Constant((double)s) : SpectrumLibrary.Resolve((string)s!)).ToList();
            var expected = new double[n];
            for (int b = 0; b < n; b++) expected[b] = scale * BandMeanOfProduct(spectra, scene.Grid.Lower(b), scene.Grid.Upper(b));
            List<int> pixels;
            string where;
            if (check["pixel"] is JsonArray p) { pixels = [(int)p[1]! * w + (int)p[0]!]; where = $"pixel ({p[0]}, {p[1]})"; }
            else
            {
                var name = (string)check["object"]!;
                int id = scene.Objects.FindIndex(o => o.Name == name);
                Assert.True(id >= 0, $"{file}: no object '{name}'");
                pixels = Enumerable.Range(0, result.ObjectIds.Length).Where(i => result.ObjectIds[i] == id).ToList();
                Assert.True(pixels.Count >= 4, $"{file}: object '{name}' is seen at only {pixels.Count} pixels");
                where = $"object {name}";
            }
            foreach (int i in pixels)
            {
                var pixel = result.Image.Data.AsSpan(i * n, n);
                for (int b = 0; b < n; b++)
                    Assert.True(Math.Abs(pixel[b] - expected[b]) <= tolerance * Math.Max(Math.Abs(expected[b]), 1e-6),
                        $"{file}, {where}, pixel {i % w},{i / w}, band {BandGrid.Number(b)}: expected {expected[b]:G9}, got {pixel[b]:G9}");
                if (check["Y"] is { } y)
                {
                    double actualY = scene.Colorimeter.ToXyz(pixel).Y;
                    Assert.True(Math.Abs(actualY - (double)y) <= (double)check["tolerance_Y"]!,
                        $"{file}, {where}: Y = {actualY:G9}, expected {(double)y}");
                }
            }
        }
    }
}
