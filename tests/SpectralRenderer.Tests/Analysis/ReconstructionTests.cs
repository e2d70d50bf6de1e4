using System.Globalization;
using System.Xml.Linq;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>
/// `spectral reconstruct` on a synthetic folder (see <see cref="AnalysisFolder.Synthetic"/>): lit pixels give the
/// truth (c = 1), shadowed pixels c = 0.2 with zero residual, highlights the truth plus the light ÷ white.
/// </summary>
public class ReconstructionTests
{
    static List<Dictionary<string, string>> Csv(string text)
    {
        var lines = text.Trim().Split('\n');
        var h = lines[0].Split(',');
        return lines.Skip(1).Select(l => h.Zip(l.Split(',')).ToDictionary(p => p.First, p => p.Second)).ToList();
    }

    static double D(Dictionary<string, string> row, string key) => double.Parse(row[key], CultureInfo.InvariantCulture);

    [Fact]
    public void White_board_calibration_recovers_scale_and_residual_per_region()
    {
        var (dir, white, truth) = AnalysisFolder.Synthetic();
        var (code, stdout, err) = CliRunner.Run("reconstruct", dir, "--white-object", "board",
            "--pixel", "5,3:lit", "--pixel", "13,7:shadow", "--pixel", "10,2:highlight", "--csv");
        Assert.True(code == 0, err);
        var rows = Csv(stdout);
        var lit = rows.Single(r => r["kind"] == "pixel" && r["label"] == "lit");
        Assert.Equal("lit", lit["region"]);
        Assert.Equal("ball", lit["object"]);
        Assert.True(D(lit, "rmse") < 1e-6 && D(lit, "gfc") > 1 - 1e-9 && D(lit, "dE00") < 1e-4, stdout);
        Assert.Equal(1, D(lit, "c"), 6);
        Assert.True(D(lit, "residual") < 1e-6);

        var shadow = rows.Single(r => r["kind"] == "pixel" && r["label"] == "shadow");
        Assert.Equal("shadow", shadow["region"]);
        Assert.Equal(AnalysisFolder.ShadowScale, D(shadow, "c"), 6);
        Assert.True(D(shadow, "residual") < 1e-6, stdout);
        Assert.True(D(shadow, "gfc") > 1 - 1e-9);
        Assert.True(D(shadow, "dE00") > 10, "a shadow is much darker");

        // Highlight: reconstruction = truth + 0.3 (the light's spectrum ÷ the white's, a constant here).
        var hl = rows.Single(r => r["kind"] == "pixel" && r["label"] == "highlight");
        Assert.Equal("highlight", hl["region"]);
        Assert.Equal(Math.Sqrt(0.09), D(hl, "rmse"), 6);
        double tt = truth.Sum(t => t * t), ts = truth.Sum(), n = truth.Length;
        double gfc = (tt + 0.3 * ts) / Math.Sqrt(tt * (tt + 0.6 * ts + 0.09 * n));
        Assert.Equal(gfc, D(hl, "gfc"), 6);
        Assert.Equal(1 + 0.3 * ts / tt, D(hl, "c"), 6);

        // Regions: 11 rows × (6 lit + 2 highlight + 4 shadow) ball pixels; background and board excluded.
        var region = rows.Where(r => r["kind"] == "region").ToDictionary(r => r["region"]);
        Assert.Equal(["lit", "shadow", "highlight", "all"], region.Keys.ToArray());
        Assert.Equal(66, int.Parse(region["lit"]["count"]));
        Assert.Equal(44, int.Parse(region["shadow"]["count"]));
        Assert.Equal(22, int.Parse(region["highlight"]["count"]));
        Assert.Equal(132, int.Parse(region["all"]["count"]));
        Assert.Equal(AnalysisFolder.ShadowScale, D(region["shadow"], "c"), 6);
        Assert.True(D(region["shadow"], "residual") < 1e-6 && D(region["lit"], "rmse") < 1e-6);

        // The cube: reconstructed.npy / .exr (T. channels) hold pixel ÷ white band by band.
        var cube = NpyReader.ReadImage(Path.Combine(dir, "reconstructed.npy"));
        var exr = ExrReader.Read(Path.Combine(dir, "reconstructed.exr"));
        Assert.True(exr.Reflective);
        Assert.Equal(cube.Data, exr.Image.Data);
        for (int b = 0; b < truth.Length; b++)
        {
            Assert.Equal(AnalysisFolder.ShadowScale * truth[b], cube[13, 7, b], 6);
            Assert.Equal(1.0, cube[0, 0, b], 6);
        }
        var svg = XDocument.Parse(File.ReadAllText(Path.Combine(dir, "reconstruction.svg")));
        Assert.Equal(4, svg.Descendants(XName.Get("polyline", "http://www.w3.org/2000/svg")).Count()); // 3 pixels + 1 truth
        var curves = Csv(File.ReadAllText(Path.Combine(dir, "reconstruction.csv")));
        Assert.Equal(truth.Length, curves.Count);
        Assert.Equal(truth[7], D(curves[7], "lit truth"), 7);
        Assert.Equal(white[7], D(curves[7], "white"), 7);
    }

    [Fact]
    public void A_white_rectangle_works_like_the_board_and_representatives_stand_in_for_pixels()
    {
        var (dir, _, _) = AnalysisFolder.Synthetic();
        var (code, stdout, err) = CliRunner.Run("reconstruct", dir, "--white-region", "0,0,4,11");
        Assert.True(code == 0, err);
        Assert.Contains("white reference: region 0,0,4,11 (columns 0–3, rows 0–10), 44 pixels", stdout);
        Assert.Matches(@"shadow\s+44\s+\S+\s+1\.000000\s+\S+\s+0\.20000", stdout);
        Assert.Matches(@"lit\s+66\s+\S+\s+1\.000000\s+0\.000\s+1\.00000", stdout);
        var svg = XDocument.Parse(File.ReadAllText(Path.Combine(dir, "reconstruction.svg")));
        Assert.Equal(4, svg.Descendants(XName.Get("polyline", "http://www.w3.org/2000/svg")).Count()); // lit, shadow, highlight + truth
    }

    [Theory]
    [InlineData(new[] { "--white-object", "bord" }, "--white-object: no object 'bord' in", "did you mean 'board'?")]
    [InlineData(new[] { "--white-object", "board", "--pixel", "16,3" }, "--pixel: 16,3 is outside the 16×12 image", "x in 0–15")]
    [InlineData(new[] { "--white-region", "0,0,3,13" }, "--white-region: 0,0,3,13 is not a non-empty rectangle inside the 16×12 image",
        "X1 and Y1 are exclusive (as for --crop)")]
    [InlineData(new[] { "--white-region", "3,0,3,5" }, "--white-region: 3,0,3,5 is not a non-empty rectangle", "0 ≤ X0 < X1 ≤ 16")]
    [InlineData(new[] { "--white-region", "0,0,3" }, "'0,0,3' is not X0,Y0,X1,Y1", "four whole pixel numbers")]
    [InlineData(new[] { "--white-region", "0,11,4,12" }, "region 0,11,4,12 (columns 0–3, rows 11–11) is black", "must be lit")]
    [InlineData(new string[0], "give exactly one of --white-object NAME and --white-region", "--white-object board")]
    [InlineData(new[] { "--white-object", "board", "--white-objet", "x" }, "unknown option '--white-objet'",
        "did you mean '--white-object'?")]
    public void Bad_input_gives_one_line_and_exit_2(string[] options, string what, string hint)
    {
        var (dir, _, _) = AnalysisFolder.Synthetic();
        var (code, _, err) = CliRunner.Run(["reconstruct", dir, .. options]);
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains(what, err);
        Assert.Contains(hint, err);
        Assert.False(File.Exists(Path.Combine(dir, "reconstructed.npy")));
    }

    [Fact]
    public void Missing_folder_and_missing_truth_give_one_line_and_exit_2()
    {
        var (code, _, err) = CliRunner.Run("reconstruct", "/nonexistent/render", "--white-object", "board");
        Assert.Equal(2, code);
        Assert.Contains("no such render folder", err);
        var dir = AnalysisFolder.Render(); // a render without reflectance.npy (until the aov layers land)
        foreach (var f in new[] { "reflectance.npy", "reflectance.exr" }) File.Delete(Path.Combine(dir, f));
        (code, _, err) = CliRunner.Run("reconstruct", dir, "--white-object", "board");
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains("has no ground-truth reflectance", err);
    }
}
