using System.Text;
using SpectralRenderer.Imaging;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>
/// Our baseline JPEG decoder against the Independent JPEG Group's, as libjpeg-turbo's <c>djpeg</c> (Debian's
/// libjpeg-turbo-progs, installed by .ci/run): images made here as PNM, compressed by <c>cjpeg</c> with each sampling,
/// restart interval, optimised and standard Huffman tables, one scan or one per component, and decoded by
/// <c>djpeg -dct int -nosmooth</c> — the integer "islow" inverse DCT our decoder computes in the same fixed point, and
/// chroma upsampled by replication, which is what -nosmooth selects (djpeg's default "fancy" upsampling is a triangle
/// filter across chroma pixels, not T.81's replication). Every sample must be equal: the issue allowed ±1 (T.81 lets a
/// decoder use any IDCT within IEEE 1180's accuracy), but we compute djpeg's fixed point and the YCbCr products with its
/// rounding, so there is nothing to round differently; a difference of 1 here would mean one of the two changed.
/// Progressive and arithmetic-coded files, made by cjpeg too, are refused in one line.
/// </summary>
[Trait("Category", "Interop")]
public class JpegInteropTests(ITestOutputHelper output)
{
    static string Require(string tool)
    {
        var path = Tool.Find(tool);
        Skip.If(path is null, $"{tool} is not installed (Debian package libjpeg-turbo-progs); skipping the JPEG interop test");
        return path!;
    }

    /// <summary>A test picture with smooth gradients, hard edges and noise (a deterministic hash), so every coefficient and
    /// code length is exercised; grey when <paramref name="channels"/> is 1.</summary>
    static byte[] Pnm(int width, int height, int channels)
    {
        var header = Encoding.ASCII.GetBytes($"{(channels == 1 ? "P5" : "P6")}\n{width} {height}\n255\n");
        var pixels = new byte[width * height * channels];
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++)
                for (int c = 0; c < channels; c++)
                {
                    uint h = (uint)(x * 73856093 ^ y * 19349663 ^ c * 83492791);
                    h ^= h >> 13; h *= 0x5bd1e995; h ^= h >> 15;
                    double v = c switch { 0 => 255.0 * x / width, 1 => 255.0 * y / height, _ => 128 + 100 * Math.Sin(x * 0.3 + y * 0.2) };
                    if ((x / 7 + y / 5) % 3 == 0) v = 255 - v;         // edges
                    v += (h % 41) - 20;                                  // noise
                    pixels[(y * width + x) * channels + c] = (byte)Math.Clamp((int)v, 0, 255);
                }
        return [.. header, .. pixels];
    }

    /// <summary>A binary PNM (P5/P6, maxval 255) as width, height, channels and samples.</summary>
    static (int Width, int Height, int Channels, byte[] Samples) ReadPnm(byte[] file)
    {
        int pos = 0;
        string Token()
        {
            while (char.IsWhiteSpace((char)file[pos])) pos++;
            int start = pos;
            while (!char.IsWhiteSpace((char)file[pos])) pos++;
            return Encoding.ASCII.GetString(file, start, pos - start);
        }
        var magic = Token();
        int w = int.Parse(Token()), h = int.Parse(Token()), max = int.Parse(Token());
        Assert.Equal(255, max);
        pos++;
        int channels = magic == "P5" ? 1 : 3;
        return (w, h, channels, file[pos..(pos + w * h * channels)]);
    }

    public static TheoryData<string, int, int, int, string> Cases => new()
    {
        { "420", 64, 48, 3, "-quality 75 -sample 2x2" },
        { "422", 61, 37, 3, "-quality 90 -sample 2x1" },
        { "444", 40, 24, 3, "-quality 95 -sample 1x1" },
        { "440", 33, 50, 3, "-quality 80 -sample 1x2" },
        { "grey", 45, 29, 1, "-quality 85 -grayscale" },
        { "q100-optimised", 50, 30, 3, "-quality 100 -optimize" },
        { "q10", 72, 40, 3, "-quality 10" },
        { "restart-rows", 80, 64, 3, "-quality 75 -restart 1" },
        { "restart-blocks", 57, 41, 3, "-quality 75 -sample 2x2 -restart 3B" },
        { "restart-grey", 40, 40, 1, "-quality 60 -restart 2B" },
        { "rgb", 30, 20, 3, "-quality 90 -rgb" },
        { "one-scan-per-component", 52, 44, 3, "-quality 80 -sample 2x2 -scans SCANS" },
        { "tiny", 1, 1, 3, "-quality 75" },
    };

    [SkippableTheory]
    [MemberData(nameof(Cases))]
    public void Our_decoder_equals_djpeg_islow_without_fancy_upsampling(string name, int width, int height, int channels,
        string options)
    {
        var cjpeg = Require("cjpeg");
        var djpeg = Require("djpeg");
        var dir = Reference.TempDir();
        var pnm = Path.Combine(dir, $"{name}.pnm");
        File.WriteAllBytes(pnm, Pnm(width, height, channels));
        // A sequential scan script: each component its own full scan (non-interleaved, T.81 A.2.2).
        File.WriteAllText(Path.Combine(dir, "scans.txt"), "0: 0 63 0 0;\n1: 0 63 0 0;\n2: 0 63 0 0;\n");
        var jpeg = Path.Combine(dir, $"{name}.jpg");
        var args = options.Replace("SCANS", Path.Combine(dir, "scans.txt"), StringComparison.Ordinal).Split(' ')
            .Concat(["-outfile", jpeg, pnm]);
        var (exit, _, err) = Tool.Run(cjpeg, args);
        Assert.True(exit == 0, $"cjpeg {options}: {err}");
        var decoded = Path.Combine(dir, $"{name}.djpeg.pnm");
        (exit, _, err) = Tool.Run(djpeg, ["-dct", "int", "-nosmooth", "-pnm", "-outfile", decoded, jpeg]);
        Assert.True(exit == 0, $"djpeg: {err}");
        Assert.True(err.Length == 0, $"djpeg warned: {err}");
        var reference = ReadPnm(File.ReadAllBytes(decoded));

        var ours = JpegReader.Read(jpeg);
        Assert.Equal((reference.Width, reference.Height, reference.Channels), (ours.Width, ours.Height, ours.Channels));
        int worst = 0, differing = 0;
        for (int i = 0; i < ours.Samples.Length; i++)
        {
            int d = Math.Abs(ours.Samples[i] - reference.Samples[i]);
            worst = Math.Max(worst, d);
            if (d != 0) differing++;
        }
        output.WriteLine($"{name} ({options}): {ours.Samples.Length} samples, {differing} differ, largest difference {worst}");
        Assert.True(worst == 0, $"{name}: {differing} samples differ from djpeg's, by up to {worst}");
    }

    [SkippableTheory]
    [InlineData("-progressive", "progressive JPEG is not supported")]
    [InlineData("-arithmetic", "arithmetic-coded JPEG is not supported")]
    public void Progressive_and_arithmetic_files_are_refused_in_one_line(string option, string what)
    {
        var cjpeg = Require("cjpeg");
        var dir = Reference.TempDir();
        var pnm = Path.Combine(dir, "in.pnm");
        File.WriteAllBytes(pnm, Pnm(16, 16, 3));
        var jpeg = Path.Combine(dir, "out.jpg");
        var (exit, _, err) = Tool.Run(cjpeg, [option, "-outfile", jpeg, pnm]);
        Assert.True(exit == 0, $"cjpeg {option}: {err}");
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => JpegReader.Read(jpeg));
        Assert.Contains(what, e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }
}
