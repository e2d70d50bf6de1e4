using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>Render folders for the analysis commands: a tiny real render, and one rewritten with synthetic layers.</summary>
static class AnalysisFolder
{
    /// <summary>A green (patch 14) ball in front of a white board (reflectance 1.0) under a D65 point light.</summary>
    public const string Scene = """
    {
      "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 16, "height": 12 },
      "ambient": 0.05,
      "materials": { "green": { "diffuse": "colorchecker:14" }, "white": { "diffuse": 1.0 } },
      "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [
        { "type": "sphere", "name": "ball", "radius": 1, "material": "green" },
        { "type": "plane", "name": "board", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "white" }
      ]
    }
    """;

    public static string Render()
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        Assert.True(code == 0, err);
        return outDir;
    }

    public const int W = 16, H = 12;
    public const float ShadowScale = 0.2f, HighlightAdd = 0.3f;

    /// <summary>
    /// The render with its layers replaced: columns 0–3 are the board (radiance = white W_b), row 11 is
    /// background, the rest the ball with truth t_b (patch 14): x &lt; 10 lit (pixel = t·W), x ≥ 12 shadow
    /// (pixel = 0.2·t·W, lit by no light), x = 10–11 highlight (pixel = (t + 0.3)·W, lit).
    /// </summary>
    public static (string Dir, double[] White, double[] Truth) Synthetic()
    {
        var dir = Render();
        var npy = Path.Combine(dir, "spectral.npy");
        var grid = NpyReader.ReadImage(npy).Grid;
        int n = grid.Count;
        var white = Enumerable.Range(0, n).Select(b => (double)(float)(0.5 + 0.05 * b)).ToArray();
        var truth = SpectralRenderer.Spectra.BandProjection.Means(SpectralRenderer.Spectra.ColorChecker.Patch(14), grid)
            .Select(v => (double)(float)v).ToArray();
        var image = new SpectralImage(W, H, grid);
        var reflectance = new SpectralImage(W, H, grid);
        var ids = new ushort[W * H];
        var lit = new byte[W * H];
        var highlight = new byte[W * H];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
            {
                int i = y * W + x;
                if (y == H - 1) continue;                                  // background: id 0, all zero
                if (x < 4)
                {
                    ids[i] = 2; lit[i] = 255;                              // the board
                    for (int b = 0; b < n; b++) { image[x, y, b] = (float)white[b]; reflectance[x, y, b] = 1; }
                    continue;
                }
                ids[i] = 1;
                bool shadow = x >= 12, hl = x is 10 or 11;
                lit[i] = shadow ? (byte)0 : (byte)255;
                highlight[i] = hl ? (byte)255 : (byte)0;
                for (int b = 0; b < n; b++)
                {
                    reflectance[x, y, b] = (float)truth[b];
                    image[x, y, b] = (float)((shadow ? ShadowScale * truth[b] : hl ? truth[b] + HighlightAdd : truth[b]) * white[b]);
                }
            }
        NpyWriter.Write(npy, image);
        File.Delete(Path.Combine(dir, "spectral.exr"));
        NpyWriter.Write(Path.Combine(dir, "reflectance.npy"), reflectance);
        ExrWriter.Write(Path.Combine(dir, "reflectance.exr"), reflectance, new ExrOptions { Reflective = true, Rgb = false });
        PngWriter.WriteGray16(Path.Combine(dir, "object-id.png"), W, H, ids);
        PngWriter.WriteGray8(Path.Combine(dir, "mask-lit-0.png"), W, H, lit);
        PngWriter.WriteGray8(Path.Combine(dir, "mask-highlight.png"), W, H, highlight);
        return (dir, white, truth);
    }
}
