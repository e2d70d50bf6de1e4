using System.Globalization;
using System.Xml.Linq;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Analysis;

/// <summary>`spectral probe`: pixel spectra equal the framebuffer exactly; CSV + SVG written; bad input → one line, exit 2.</summary>
public class ProbeCommandTests
{
    [Fact]
    public void Probe_prints_the_framebuffer_values_exactly_and_writes_csv_and_svg()
    {
        var dir = AnalysisFolder.Render();
        var image = NpyReader.ReadImage(Path.Combine(dir, "spectral.npy"));
        var (code, stdout, err) =
            CliRunner.Run("probe", dir, "--pixel", "8,5:ball", "--pixel", "1,1:board, corner", "--pixel", "15,11", "--csv");
        Assert.True(code == 0, err);
        Assert.Equal("", err);
        var lines = stdout.TrimEnd('\n').Split('\n');
        Assert.Equal("band,start_nm,centre_nm,end_nm,ball,\"board, corner\",x15y11", lines[0]);
        Assert.Equal(image.Bands + 1, lines.Length);
        (int X, int Y)[] px = [(8, 5), (1, 1), (15, 11)];
        for (int b = 0; b < image.Bands; b++)
        {
            var f = lines[b + 1].Split(',');
            Assert.Equal(b + 1, int.Parse(f[0], CultureInfo.InvariantCulture));   // bands are numbered from 1
            Assert.Equal(image.Grid.Centre(b), double.Parse(f[2], CultureInfo.InvariantCulture));
            // the quoted label spans one field in CSV but the values do not contain commas
            for (int k = 0; k < px.Length; k++)
                Assert.Equal(image[px[k].X, px[k].Y, b], float.Parse(f[4 + k], CultureInfo.InvariantCulture));
        }
        Assert.True(image[8, 5, 8] > 0, "the ball is lit");
        Assert.Equal(stdout, File.ReadAllText(Path.Combine(dir, "probe.csv")));
        var svg = XDocument.Parse(File.ReadAllText(Path.Combine(dir, "probe.svg")));
        Assert.Equal(3, svg.Descendants(XName.Get("polyline", "http://www.w3.org/2000/svg")).Count());
    }

    /// <summary>Issue 42: a paper render's band values are relative (eq. 2 without units): its axis names no physical unit; a
    /// physical render's names W·m⁻²·sr⁻¹·nm⁻¹.</summary>
    [Fact]
    public void The_plots_axis_names_physical_units_only_for_a_physical_render()
    {
        static string Axis(string dir)
        {
            var prefix = Path.Combine(Reference.TempDir(), "p");
            var (code, _, err) = CliRunner.Run("probe", dir, "--pixel", "1,1", "-o", prefix);
            Assert.True(code == 0, err);
            return File.ReadAllText(prefix + ".svg");
        }
        var paper = Axis(AnalysisFolder.Render());
        Assert.Contains("band value (relative units, the paper&apos;s eq. 2)".Replace("&apos;", "'"), paper.Replace("&apos;", "'")
            .Replace("&#39;", "'"));
        Assert.DoesNotContain("W·m⁻²", paper);
        var d = Reference.TempDir();
        File.WriteAllText(Path.Combine(d, "s.json"), """
            { "radiometry": "physical", "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 4, "height": 3 },
              "materials": { "m": { "diffuse": 0.5 } },
              "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65", "luminous_intensity": 10 } ],
              "objects": [ { "type": "sphere", "radius": 1, "material": "m" } ] }
            """);
        var (rc, _, re) = CliRunner.Run("render", Path.Combine(d, "s.json"), "-o", Path.Combine(d, "r"), "--formats", "npy", "--quiet");
        Assert.True(rc == 0, re);
        Assert.Contains("spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry)", Axis(Path.Combine(d, "r")));
    }

    [Fact]
    public void Output_prefix_and_table_output()
    {
        var dir = AnalysisFolder.Render();
        var prefix = Path.Combine(Reference.TempDir(), "fig6b");
        var (code, stdout, err) = CliRunner.Run("probe", dir, "--pixel", "8,5:lit", "-o", prefix);
        Assert.True(code == 0, err);
        Assert.Contains("lit", stdout);
        Assert.Contains($"wrote {prefix}.csv, {prefix}.svg", stdout);
        Assert.True(File.Exists(prefix + ".csv") && File.Exists(prefix + ".svg"));
    }

    [Theory]
    [InlineData("16,0", "--pixel: 16,0 is outside the 16×12 image (hint: x in 0–15, y in 0–11)")]
    [InlineData("3,-1", "--pixel: 3,-1 is outside the 16×12 image")]
    [InlineData("3;4", "--pixel: '3;4' is not X,Y[:LABEL]")]
    public void Bad_pixels_give_one_line_and_exit_2(string pixel, string message)
    {
        var dir = AnalysisFolder.Render();
        var (code, _, err) = CliRunner.Run("probe", dir, "--pixel", pixel);
        Assert.Equal(2, code);
        Assert.Single(err.TrimEnd('\n').Split('\n'));
        Assert.Contains(message, err);
        Assert.False(File.Exists(Path.Combine(dir, "probe.csv")));
    }

    [Fact]
    public void Missing_folder_gives_one_line_and_exit_2()
    {
        var (code, _, err) = CliRunner.Run("probe", "/nonexistent/render", "--pixel", "1,1");
        Assert.Equal(2, code);
        Assert.Equal("spectral probe: /nonexistent/render: no such render folder (hint: give the -o folder of a 'spectral render' run)\n",
            err.Replace("\r", ""));
    }
}
