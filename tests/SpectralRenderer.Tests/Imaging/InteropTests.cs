using System.Globalization;
using System.Text.Json;
using System.Text.RegularExpressions;
using SpectralRenderer.Imaging;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>
/// Our files read by the real tools: OpenEXR's exrheader, OpenImageIO's oiiotool, GDAL's gdalinfo, and a
/// standard-library-only python3 script. Each test skips, saying why, when its tool is not installed
/// (.ci/run installs Debian's openexr, openimageio-tools and gdal-bin).
/// </summary>
[Trait("Category", "Interop")]
public class InteropTests(ITestOutputHelper output)
{
    static string Require(string tool, string package)
    {
        var path = Tool.Find(tool);
        Skip.If(path is null, $"{tool} is not installed (Debian package {package}); skipping this interop test");
        return path!;
    }

    static string WriteExr(string dir, ExrOptions options)
    {
        var path = Path.Combine(dir, $"spectral-{options.Compression}-{options.PixelType}-{options.DeflateEveryChunk}.exr");
        ExrWriter.Write(path, Synthetic.Image(), options with { Colorimeter = Synthetic.Colorimeter });
        return path;
    }

    [SkippableTheory]
    [InlineData(ExrCompression.Zip, ExrPixelType.Float, "zip, multi-scanline blocks", "32-bit floating-point")]
    [InlineData(ExrCompression.None, ExrPixelType.Half, "none", "16-bit floating-point")]
    public void Exrheader_lists_every_channel_type_and_the_spectral_attributes(ExrCompression compression, ExrPixelType type,
        string compressionText, string typeText)
    {
        var exe = Require("exrheader", "openexr");
        var file = WriteExr(Reference.TempDir(), new ExrOptions { Compression = compression, PixelType = type, Xyz = true });
        var (exit, stdout, stderr) = Tool.Run(exe, [file]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, stderr);
        var channels = Regex.Matches(stdout, @"^\s{4}(\S+), (\d+-bit [a-z-]+), sampling 1 1$", RegexOptions.Multiline)
            .Select(m => (m.Groups[1].Value, m.Groups[2].Value)).ToList();
        var expected = new[] { "B", "G", "R" }.Concat(Enumerable.Range(0, 20).Select(b => ExrWriter.SpectralChannelName(390 + 20 * b)))
            .Concat(["X", "Y", "Z"]);
        Assert.Equal(expected.Select(n => (n, typeText)), channels);
        Assert.Contains("file format version: 2, flags 0x0", stdout);
        Assert.Contains($"compression (type compression): {compressionText}", stdout);
        Assert.Contains("spectralLayoutVersion (type string): \"1.0\"", stdout);
        Assert.Contains("emissiveUnits (type string): \"W.m^-2.sr^-1\"", stdout);
        Assert.Contains("spectralBandEdges (type string): \"380,400,", stdout);
        Assert.Matches(@"spectralKappa \(type double\): [0-9.e+-]+", stdout);
        Assert.Contains("dataWindow (type box2i): (0 0) - (36 22)", stdout);
        Assert.Contains("lineOrder (type lineOrder): increasing y", stdout);
    }

    [SkippableTheory]
    [InlineData(ExrCompression.Zip, false)]
    [InlineData(ExrCompression.Zip, true)]     // every chunk deflated (the smooth synthetic image is otherwise stored raw)
    [InlineData(ExrCompression.None, false)]
    public void Oiiotool_stats_match_ours_per_channel(ExrCompression compression, bool deflateEveryChunk)
    {
        var exe = Require("oiiotool", "openimageio-tools");
        var file =
            WriteExr(Reference.TempDir(), new ExrOptions { Compression = compression, Xyz = true, DeflateEveryChunk = deflateEveryChunk });
        var (exit, stdout, stderr) = Tool.Run(exe, ["--info", "-v", "--stats", file]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, stderr);
        double[] Row(string name)
        {
            var m = Regex.Match(stdout, $@"Stats {name}: ([^(\n]+)");
            Assert.True(m.Success, $"no 'Stats {name}' line");
            return m.Groups[1].Value.Split(' ', StringSplitOptions.RemoveEmptyEntries)
                .Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray();
        }
        var (min, max, avg) = (Row("Min"), Row("Max"), Row("Avg"));

        // OIIO lists R, G, B (and X, Y, Z) first; its order is in "channel list: a, b, …" (names hold commas, not ", ").
        var order = Regex.Match(stdout, @"channel list: ([^\n]+)").Groups[1].Value.Trim().Split(", ");

        // Our values per channel.
        var read = ExrReader.Read(file);
        var img = Synthetic.Image();
        var planes = new Dictionary<string, float[]>(read.OtherChannels);
        for (int b = 0; b < img.Bands; b++)
        {
            var p = new float[img.Width * img.Height];
            img.CopyBand(b, p);
            planes[ExrWriter.SpectralChannelName(img.Grid.Centre(b))] = p;
        }
        Assert.Equal(planes.Keys.Order(StringComparer.Ordinal), order.Order(StringComparer.Ordinal));
        Assert.Equal(planes.Count, min.Length);
        for (int c = 0; c < order.Length; c++)
        {
            var (name, p) = (order[c], planes[order[c]]);
            // oiiotool prints six decimals: allow 1e-6 relative plus half of the last printed digit.
            Close(p.Min(), min[c], $"{name} min");
            Close(p.Max(), max[c], $"{name} max");
            Close(p.Average(v => (double)v), avg[c], $"{name} avg");
        }
    }

    [SkippableFact]
    public void Oiiotool_reads_a_band_image_of_huffman_coded_blocks_with_our_stats()
    {
        // libpng (through OpenImageIO) inflates the band images' encoding: two deflate blocks with their own codes.
        var exe = Require("oiiotool", "openimageio-tools");
        int w = 1024, h = 520;
        var samples = new ushort[w * h];
        for (int i = 0; i < samples.Length; i++) samples[i] = (ushort)(30000 + 20000 * Math.Sin(i * 0.0007) + i % 97);
        var file = Path.Combine(Reference.TempDir(), "band.png");
        AtomicFile.Write(file, s => PngWriter.WriteGray16(s, w, h, samples, filter: PngFilter.Sub, huffmanOnly: true));
        var (exit, stdout, stderr) = Tool.Run(exe, ["--info", "-v", "--stats", file]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, stderr);
        Assert.Contains("1024 x  520, 1 channel, uint16 png", stdout);
        int Stat(string name) =>
            int.Parse(Regex.Match(stdout, $@"Stats {name}: (\d+) \(of 65535\)").Groups[1].Value, CultureInfo.InvariantCulture);
        Assert.Equal(samples.Min(), Stat("Min"));
        Assert.Equal(samples.Max(), Stat("Max"));
        var avg = double.Parse(Regex.Match(stdout, @"Stats Avg: ([0-9.]+) \(of 65535\)").Groups[1].Value, CultureInfo.InvariantCulture);
        Assert.Equal(samples.Average(v => (double)v), avg, 0.006);
    }

    static void Close(double ours, double theirs, string what) =>
        Assert.True(Math.Abs(ours - theirs) <= 1e-6 * Math.Abs(ours) + 5.01e-7, $"{what}: ours {ours:R}, tool {theirs:R}");

    [SkippableFact]
    public void Gdalinfo_reads_the_ENVI_bands_wavelengths_and_stats()
    {
        var exe = Require("gdalinfo", "gdal-bin");
        var dir = Reference.TempDir();
        var img = Synthetic.Image();
        var file = Path.Combine(dir, "spectral.img");
        EnviWriter.Write(file, img);
        var (exit, stdout, stderr) = Tool.Run(exe, ["-json", "-stats", file]);
        Assert.True(exit == 0, stderr);
        using var doc = JsonDocument.Parse(stdout);
        var root = doc.RootElement;
        Assert.Equal("ENVI", root.GetProperty("driverShortName").GetString());
        Assert.Equal(img.Width, root.GetProperty("size")[0].GetInt32());
        Assert.Equal(img.Height, root.GetProperty("size")[1].GetInt32());
        var bands = root.GetProperty("bands");
        Assert.Equal(img.Bands, bands.GetArrayLength());
        var plane = new float[img.Width * img.Height];
        for (int b = 0; b < img.Bands; b++)
        {
            var band = bands[b];
            Assert.Equal("Float32", band.GetProperty("type").GetString());
            var md = band.GetProperty("metadata").GetProperty("");
            double D(string key) => double.Parse(md.GetProperty(key).GetString()!, CultureInfo.InvariantCulture);
            Assert.Equal(img.Grid.Centre(b), D("wavelength"));
            Assert.Equal("Nanometers", md.GetProperty("wavelength_units").GetString());
            img.CopyBand(b, plane);
            output.WriteLine($"band {b + 1}: {D("wavelength")} nm min {D("STATISTICS_MINIMUM")} max "
                + $"{D("STATISTICS_MAXIMUM")} mean {D("STATISTICS_MEAN")}");
            Close(plane.Min(), D("STATISTICS_MINIMUM"), $"band {b} min");
            Close(plane.Max(), D("STATISTICS_MAXIMUM"), $"band {b} max");
            Close(plane.Average(v => (double)v), D("STATISTICS_MEAN"), $"band {b} mean");
        }
    }

    [SkippableFact]
    public void Python_stdlib_decodes_our_npy_and_pngs()
    {
        var exe = Require("python3", "python3");
        var dir = Reference.TempDir();
        var img = Synthetic.Image();
        var npy = Path.Combine(dir, "spectral.npy");
        NpyWriter.Write(npy, img);
        var values = new List<long[]>();
        foreach (var (x, y, b) in new[] { (0, 0, 0), (5, 3, 7), (36, 22, 19), (20, 10, 4), (1, 2, 3), (12, 0, 11) })
            values.Add([y, x, b, (uint)BitConverter.SingleToInt32Bits(img[x, y, b])]);

        var pngs = new List<object>();
        int W = Synthetic.W, H = Synthetic.H;
        foreach (var f in Enum.GetValues<PngFilter>())
        {
            var p = Path.Combine(dir, $"rgb-{f}.png");
            PngWriter.WriteRgb8(p, W, H, PngTests.Rgb(), filter: f);
            pngs.Add(new { path = p, width = W, height = H, depth = 8, colour = 2, samples = PngTests.Rgb().Select(v => (int)v) });
        }
        var g16 = Path.Combine(dir, "gray16.png");
        PngWriter.WriteGray16(g16, W, H, PngTests.Gray16(), new Dictionary<string, string> { ["Software"] = "SpectralRenderer" });
        pngs.Add(new { path = g16, width = W, height = H, depth = 16, colour = 0, samples = PngTests.Gray16().Select(v => (int)v) });
        var g8 = Path.Combine(dir, "gray8.png");
        PngWriter.WriteGray8(g8, W, H, PngTests.Gray8(), filter: PngFilter.Paeth);
        pngs.Add(new { path = g8, width = W, height = H, depth = 8, colour = 0, samples = PngTests.Gray8().Select(v => (int)v) });

        // Deflate blocks of Huffman-coded literals (the band images' encoding): small (one block) and over 1 MiB of
        // rows (two blocks, each with its own code, split across IDAT chunks), decoded by python's zlib (Adler-32 checked).
        foreach (var (w, h) in new[] { (W, H), (1024, 520) })
        {
            var samples = new ushort[w * h];
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    samples[y * w + x] = (ushort)(20000 + 9000 * Math.Sin(x * 0.01) * Math.Cos(y * 0.013) + (x * 7919 + y * 104729) % 61);
            var p = Path.Combine(dir, $"huffman-{w}x{h}.png");
            AtomicFile.Write(p, s => PngWriter.WriteGray16(s, w, h, samples, filter: PngFilter.Sub, huffmanOnly: true));
            pngs.Add(new { path = p, width = w, height = h, depth = 16, colour = 0, samples = samples.Select(v => (int)v) });
        }

        var manifest = Path.Combine(dir, "manifest.json");
        File.WriteAllText(manifest,
            JsonSerializer.Serialize(new { npy = new { path = npy, shape = new[] { H, W, img.Bands }, values }, pngs }));
        var script = Path.Combine(AppContext.BaseDirectory, "Imaging", "check_outputs.py");
        var (exit, stdout, stderr) = Tool.Run(exe, [script, manifest]);
        output.WriteLine(stdout);
        Assert.True(exit == 0, $"python3 check failed: {stderr}");
        Assert.Contains("npy ok: shape (23, 37, 20) dtype <f4, 6 values", stdout);
        Assert.Contains("filters seen: 0,1,2,3,4", stdout);
        Assert.Equal(pngs.Count, Regex.Matches(stdout, "^png ok", RegexOptions.Multiline).Count);
    }
}
