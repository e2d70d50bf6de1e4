using System.Globalization;
using System.Numerics;
using SpectralRenderer.Analysis;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// The paper's §3.4 findings on an analytic scene rendered with the real masks: a patch-14 sphere (constant
/// specular) before a white board (reflectance 1.0) that faces a D65 directional light, plus a D65 ambient
/// a_glob = 0.05·D65. White-board calibration gets a lit pixel right, a shadowed pixel is the truth times
/// a_glob / (a_glob + I) (eq. 2: ambient only vs the board's ambient + diffuse), and a highlight is the truth
/// plus the light ÷ white.
/// </summary>
[Trait("Category", "Slow")]
public class PaperReconstructionTests
{
    const double Ambient = 0.05;
    const string Scene = """
    {
      "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 40, "width": 160, "height": 120 },
      "ambient": { "name": "D65", "scale": 0.05 },
      "materials": {
        "green": { "diffuse": "colorchecker:14", "specular": 0.5, "shininess": 200 },
        "white": { "diffuse": 1.0 }
      },
      "lights": [ { "type": "directional", "name": "sun", "direction": [0, -0.6, -0.8], "spectrum": "D65" } ],
      "objects": [
        { "type": "sphere", "name": "bunny", "radius": 1, "material": "green" },
        { "type": "plane", "name": "board", "point": [0, 0, -2], "normal": [0, 0.6, 0.8], "material": "white" }
      ]
    }
    """;

    static double[] Column(List<string[]> rows, string[] header, string name)
    {
        int k = Array.IndexOf(header, name);
        Assert.True(k >= 0, name);
        return rows.Select(r => double.Parse(r[k], CultureInfo.InvariantCulture)).ToArray();
    }

    [Fact]
    public void Lit_is_exact_shadow_is_a_scale_and_highlight_adds_the_light()
    {
        var dir = Reference.TempDir();
        var scenePath = Path.Combine(dir, "scene.json");
        File.WriteAllText(scenePath, Scene);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scenePath, "-o", outDir, "--quiet");
        Assert.True(code == 0, err);

        // Pixels by geometry: n = l (lit head-on, like the board), n = h (the highlight), n·l < 0 (self-shadow).
        var camera = SceneLoader.Load(scenePath).Camera;
        var l = Vector3.Normalize(new Vector3(0, 0.6f, 0.8f));
        var h = l;
        for (int i = 0; i < 20; i++) h = Vector3.Normalize(l + Vector3.Normalize(camera.Position - h));
        string Px(Vector3 p, string label) { var q = camera.Project(p)!.Value; return $"{(int)q.X},{(int)q.Y}:{label}"; }
        (code, var stdout, err) = CliRunner.Run("reconstruct", outDir, "--white-region", "0,0,20,10",
            "--pixel", Px(l, "lit"), "--pixel", Px(Vector3.Normalize(new Vector3(0, -0.95f, 0.3f)), "shadow"), "--pixel",
                Px(h, "highlight"), "--csv");
        Assert.True(code == 0, err);
        var metrics = stdout.Trim().Split('\n').Skip(1).Select(r => r.Split(',')).Where(r => r[0] == "pixel").ToDictionary(r => r[1]);
        Assert.Equal("lit", metrics["lit"][5]);
        Assert.Equal("shadow", metrics["shadow"][5]);
        Assert.Equal("highlight", metrics["highlight"][5]);
        var lines = File.ReadAllLines(Path.Combine(outDir, "reconstruction.csv"));
        var header = lines[0].Split(',');
        var rows = lines.Skip(1).Select(r => r.Split(',')).ToList();
        var truth = Column(rows, header, "lit truth");
        var white = Column(rows, header, "white");

        // The white rectangle sees ambient + the light head-on: (a + 1)·D65.
        var d65 = BandProjection.Means(SpectrumLibrary.Resolve("D65"), BandGrid.Default);
        for (int b = 0; b < d65.Length; b++) Assert.True(Math.Abs(white[b] / ((Ambient + 1) * d65[b]) - 1) < 1e-6, $"band {b}: {white[b]}");

        // Lit: the truth (RMSE ≤ 1e-3, GFC ≥ 0.9999).
        var lit = Column(rows, header, "lit");
        Assert.True(SpectralMetrics.Rmse(lit, truth) <= 1e-3, $"lit RMSE {SpectralMetrics.Rmse(lit, truth)}");
        Assert.True(SpectralMetrics.Gfc(lit, truth) >= 0.9999);

        // Shadow: c × truth, c = a_glob / (a_glob + I) of eq. 2, residual ≤ 1e-3.
        var (c, residual) = SpectralMetrics.Scale(truth, Column(rows, header, "shadow"));
        Assert.Equal(Ambient / (Ambient + 1), c, 4);
        Assert.True(residual <= 1e-3, $"shadow residual {residual}");
        Assert.Equal(c, double.Parse(metrics["shadow"][10], CultureInfo.InvariantCulture), 12);

        // Highlight: reconstruction = α·truth + β·(light ÷ white); the error beyond α·truth has GFC ≥ 0.99 with light ÷ white.
        var hl = Column(rows, header, "highlight");
        var ratio = d65.Select((e, b) => e / white[b]).ToArray();
        var (alpha, beta) = TwoComponentFit(hl, truth, ratio);
        Assert.True(beta > 0.05, $"the highlight adds the light: β = {beta}");
        var error = hl.Select((v, b) => v - alpha * truth[b]).ToArray();
        Assert.True(SpectralMetrics.Gfc(error, ratio) >= 0.99, $"GFC {SpectralMetrics.Gfc(error, ratio)}");
        Assert.True(SpectralMetrics.Gfc(hl, truth) < 0.99, "white-board calibration fails in the highlight");
    }

    /// <summary>Least squares v ≈ α·a + β·b (2 × 2 normal equations).</summary>
    static (double Alpha, double Beta) TwoComponentFit(double[] v, double[] a, double[] b)
    {
        double aa = 0, ab = 0, bb = 0, va = 0, vb = 0;
        for (int i = 0; i < v.Length; i++)
        {
            aa += a[i] * a[i];
            ab += a[i] * b[i];
            bb += b[i] * b[i];
            va += v[i] * a[i];
            vb += v[i] * b[i];
        }
        double det = aa * bb - ab * ab;
        return ((va * bb - vb * ab) / det, (vb * aa - va * ab) / det);
    }
}
