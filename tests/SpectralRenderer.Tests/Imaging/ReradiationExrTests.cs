using System.Globalization;
using System.Text;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Rendering;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>
/// Issue 26: a re-radiation matrix in Fichet et al.'s bispectral OpenEXR layout (JCGT 10(3) 2021; channel names as the
/// authors' EXRBiSpectralImage and colour-science's read_spectral_image_Fichet2021 read them): T.&lt;λ&gt;nm the diagonal,
/// T.&lt;λin&gt;nm.&lt;λout&gt;nm the re-radiation from excitation λin to emission λout, numbers with a comma. The brightened paper
/// of <see cref="FluorescenceTests"/>, rounded to float32 (an EXR FLOAT), is written here both as CSV and as EXR: the two
/// render bit for bit alike. Broken files exit 2 naming the file and the channel.
/// </summary>
public sealed class ReradiationExrTests(ITestOutputHelper output) : IDisposable
{
    static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    readonly string _dir = Directory.CreateTempSubdirectory("reradiation-exr-").FullName;

    public void Dispose() => Directory.Delete(_dir, true);

    static double[] Cells => FluorescenceTests.Cells;

    /// <summary>The paper's matrix, each value rounded to the float32 an EXR FLOAT channel holds.</summary>
    static double[] Paper() => FluorescenceTests.ObaPaper().Select(v => (double)(float)v).ToArray();

    /// <summary>The layout's number: six decimals, a comma as decimal separator (as the authors' std::to_string writes it).</summary>
    static string Fichet(double nm) => nm.ToString("F6", Inv).Replace('.', ',') + "nm";

    /// <summary>Channels of a matrix: every diagonal, every non-zero off-diagonal entry (emission o, excitation i).</summary>
    static List<(string Name, float[] Plane)> Channels(double[] d, int pixels = 1, Func<double, string>? name = null)
    {
        name ??= Fichet;
        int n = Cells.Length;
        var list = new List<(string, float[])>();
        for (int i = 0; i < n; i++)
            for (int o = 0; o < n; o++)
            {
                if (o != i && d[o * n + i] == 0) continue;
                string channel = o == i ? $"T.{name(Cells[i])}" : $"T.{name(Cells[i])}.{name(Cells[o])}";
                list.Add((channel, Enumerable.Repeat((float)d[o * n + i], pixels).ToArray()));
            }
        return list;
    }

    string WriteExr(string file, List<(string Name, float[] Plane)> channels, int width = 1, int height = 1)
    {
        var path = Path.Combine(_dir, file);
        ExrChannelWriter.Write(path, width, height, channels, new Dictionary<string, string> { ["spectralLayoutVersion"] = "1.0" });
        return path;
    }

    string WriteCsv(string file, double[] d)
    {
        var path = Path.Combine(_dir, file);
        File.WriteAllText(path, FluorescenceTests.MatrixCsv(Cells, d));
        return path;
    }

    [Fact]
    public void The_bispectral_EXR_renders_bit_for_bit_as_the_same_matrix_in_CSV()
    {
        var d = Paper();
        var csv = FluorescenceTests.Fluorescent(WriteCsv("paper.csv", d));
        // One pixel, and a uniform 3×2 image (one measurement repeated): both are the material's matrix.
        foreach (var exr in new[] { WriteExr("paper.exr", Channels(d)), WriteExr("paper-3x2.exr", Channels(d, 6), 3, 2) })
        {
            var fluorescent = FluorescenceTests.Fluorescent(exr);
            foreach (var extra in new[] { "", "\"radiometry\": \"physical\"," })
            {
                var a = SceneText.Render(FluorescenceTests.Scene(csv, extra: extra));
                var b = SceneText.Render(FluorescenceTests.Scene(fluorescent, extra: extra));
                Assert.Equal(a.Image.Data, b.Image.Data);
                Assert.Equal(a.Xyz!, b.Xyz!);
            }
            const string path = "\"radiometry\": \"physical\", \"integrator\": { \"type\": \"path\", \"max_depth\": 3 },";
            var pa = FluorescenceTests.RenderPath(FluorescenceTests.Scene(csv, extra: path));
            var pb = FluorescenceTests.RenderPath(FluorescenceTests.Scene(fluorescent, extra: path));
            Assert.Equal(pa.Image.Data, pb.Image.Data);
        }
        // And the matrix itself: every entry, by the reader, equals the CSV's (the shift is visible: the OBA emits).
        var fromCsv = ReradiationCsvReader.Read(Path.Combine(_dir, "paper.csv"));
        var fromExr = ReradiationExrReader.Read(Path.Combine(_dir, "paper.exr"));
        Assert.Equal(fromCsv.Wavelengths.ToArray(), fromExr.Wavelengths.ToArray());
        for (int o = 0; o < Cells.Length; o++)
            for (int i = 0; i < Cells.Length; i++) Assert.Equal(d[o * Cells.Length + i], fromExr[o, i]);
        Assert.True(fromExr.HasShift);
    }

    [Fact]
    public void Wavelengths_in_other_units_and_with_a_point_read_as_nanometres()
    {
        // 302.5 and 307.5 nm as µm with a comma, as nm with a point, and as a frequency (c/λ in Hz).
        const double c = 299_792_458;
        var channels = new List<(string, float[])>
        {
            ("T.0,3025um", [0.5f]), ("T.307.5nm", [0.4f]),
            ($"T.{(c / 302.5e-9).ToString("R", Inv).Replace('.', ',')}Hz.307,5nm", [0.01f]),
            ("R", [1f]), ("G", [1f]), ("B", [1f]),
        };
        var m = ReradiationExrReader.Read(WriteExr("units.exr", channels));
        Assert.Equal(2, m.Count);
        Assert.Equal(302.5, m.Wavelengths[0], 9);
        Assert.Equal(307.5, m.Wavelengths[1], 9);
        Assert.Equal((double)0.5f, m[0, 0]);
        Assert.Equal((double)0.4f, m[1, 1]);
        Assert.Equal((double)0.01f, m[1, 0]);   // emission 307.5 nm, excitation 302.5 nm
        Assert.Equal(0, m[0, 1]);
    }

    [Fact]
    public void The_fuzz_seed_is_a_valid_bispectral_matrix()
    {
        // fuzz/seeds/matrix/bispectral.exr (the "matrix" fuzz target starts from it): 350, 400, 450 nm, three re-radiations.
        var m = ReradiationExrReader.Read(Repo.PathOf("fuzz", "seeds", "matrix", "bispectral.exr"));
        Assert.Equal([350.0, 400.0, 450.0], m.Wavelengths.ToArray());
        Assert.Equal((double)0.6f, m[1, 1]);
        Assert.Equal((double)0.1f, m[2, 0]);   // emission 450 nm, excitation 350 nm
        Assert.True(m.HasShift);
    }

    /// <summary>Each broken file: the one-line message names the file and the channel, and the CLI exits 2.</summary>
    [Fact]
    public void A_broken_bispectral_file_exits_2_naming_the_file_and_the_channel()
    {
        var d = Paper();
        var good = Channels(d);
        string middle = $"T.{Fichet(Cells[40])}", first = $"T.{Fichet(Cells[0])}";
        string shiftedFromFirst = good.First(c => c.Name.StartsWith(first + ".", StringComparison.Ordinal)).Name;
        string someShift = good.First(c => c.Name.StartsWith($"T.{Fichet(Cells[13])}.", StringComparison.Ordinal)).Name;
        var cases = new (string File, List<(string Name, float[] Plane)> Channels, int W, int H, string Channel, string What)[]
        {
            ("no-middle-diagonal.exr", good.Where(c => c.Name != middle).ToList(), 1, 1, $"T.{Fichet(Cells[41])}",
                "no diagonal channel at 502.5 nm"),
            ("no-first-diagonal.exr", good.Where(c => c.Name != first).ToList(), 1, 1, shiftedFromFirst,
                "excitation 302.5 nm has no diagonal"),
            ("malformed.exr", [.. good, ("T.550nm.600", [0f])], 1, 1, "T.550nm.600", "is not a reflective channel name"),
            ("malformed-number.exr", [.. good, ("T.abcnm", [0f])], 1, 1, "T.abcnm", "is not a reflective channel name"),
            ("nan.exr", good.Select(c => c.Name == someShift ? (c.Name, new[] { float.NaN }) : c).ToList(), 1, 1, someShift,
                "is not finite"),
            ("infinite.exr", good.Select(c => c.Name == middle ? (c.Name, new[] { float.PositiveInfinity }) : c).ToList(), 1, 1, middle,
                "is not finite"),
            ("negative.exr", good.Select(c => c.Name == someShift ? (c.Name, new[] { -1e-3f }) : c).ToList(), 1, 1, someShift,
                "is negative"),
            ("twice.exr", [.. good, ($"{middle}.{Fichet(Cells[40])}", [0.5f])], 1, 1, middle, "a second time"),
            ("varying.exr", Channels(d, 4).Select(c => c.Name == middle ? (c.Name, new[] { 0.5f, 0.5f, 0.5f, 0.6f }) : c).ToList(), 2, 2,
                middle,
                "differs between pixels (0, 0) and (1, 1)"),
            ("bright.exr", good.Select(c => c.Name == someShift ? (c.Name, new[] { 0.9f }) : c).ToList(), 1, 1, $"T.{Fichet(Cells[13])}",
                "re-emits"),
        };
        foreach (var (file, channels, w, h, channel, what) in cases)
        {
            var path = WriteExr(file, channels, w, h);
            var e = Assert.Throws<InputException>(() => SceneText.Load(FluorescenceTests.Scene(FluorescenceTests.Fluorescent(path))));
            output.WriteLine(e.Message);
            Assert.Contains($"{file}: channel '{channel}", e.Message, StringComparison.Ordinal);
            Assert.Contains(what, e.Message, StringComparison.Ordinal);
            Assert.Contains("(hint: ", e.Message, StringComparison.Ordinal);
            Assert.DoesNotContain('\n', e.Message);
        }
        // Through the command line: exit 2, the line on stderr names the file and the channel.
        var scene = Path.Combine(_dir, "scene.json");
        File.WriteAllText(scene, FluorescenceTests.Scene(FluorescenceTests.Fluorescent("nan.exr")));
        var (code, _, err) = Cli.CliRunner.Run("render", scene, "-o", Path.Combine(_dir, "out"), "--quiet");
        Assert.Equal(2, code);
        Assert.Contains($"nan.exr: channel '{someShift}'", err, StringComparison.Ordinal);
        // A file with no T. channels at all says what the layout is.
        var none = WriteExr("rgb.exr", [("R", [1f]), ("G", [1f]), ("B", [1f])]);
        var ex = Assert.Throws<InputException>(() => ReradiationExrReader.Read(none));
        Assert.Contains("no reflective diagonal channels", ex.Message, StringComparison.Ordinal);
    }

    static string Require(string tool, string package)
    {
        var path = Tool.Find(tool);
        Skip.If(path is null, $"{tool} is not installed (Debian package {package}); skipping this interop test");
        return path!;
    }

    /// <summary>
    /// OpenEXR's exrheader lists the bispectral channels we write; OpenImageIO's oiiotool (the OpenEXR library) re-saves
    /// the file ZIP-compressed, and our reader gives the same matrix from the library's file.
    /// </summary>
    [SkippableFact]
    [Trait("Category", "Interop")]
    public void Exrheader_lists_the_bispectral_channels_and_a_file_the_OpenEXR_library_wrote_reads_the_same()
    {
        var exrheader = Require("exrheader", "openexr");
        var d = Paper();
        var channels = Channels(d);
        var path = WriteExr("paper.exr", channels);
        var (exit, stdout, stderr) = Tool.Run(exrheader, [path]);
        Assert.True(exit == 0, stderr);
        var listed = Regex.Matches(stdout, @"^\s{4}(T\.\S+), 32-bit floating-point, sampling 1 1$", RegexOptions.Multiline)
            .Select(m => m.Groups[1].Value);
        Assert.Equal(channels.Select(c => c.Name).Order(StringComparer.Ordinal), listed);
        output.WriteLine($"exrheader lists {listed.Count()} T. channels, e.g. {channels[1].Name}");

        var oiiotool = Require("oiiotool", "openimageio-tools");
        var zip = Path.Combine(_dir, "paper-zip.exr");
        (exit, _, stderr) = Tool.Run(oiiotool, [path, "--compression", "zip", "-o", zip]);
        Assert.True(exit == 0, stderr);
        Assert.Equal(3, ExrReader.ReadChannels(File.ReadAllBytes(zip), zip).Compression);
        var ours = ReradiationExrReader.Read(path);
        var library = ReradiationExrReader.Read(zip);
        for (int o = 0; o < Cells.Length; o++)
            for (int i = 0; i < Cells.Length; i++) Assert.Equal(ours[o, i], library[o, i]);
    }
}
