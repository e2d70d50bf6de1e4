using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Distributed;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// The render's own colour of every pixel (exact under "exact" integration) is kept whatever --formats says: in
/// spectral.exr's X, Y, Z channels, or in xyz.npy when the EXR is left out, so `colorcheck` never falls back to eq. 3 on
/// the bands (at 20 bands that fallback moves the §3.1 chart's sRGB codes away from the 1 nm reference).
/// </summary>
public class ExactColourKeptTests
{
    static readonly string[] Size = ["--width", "192", "--height", "128"];

    static string Render(string dir, string name, params string[] formats)
    {
        var outDir = Path.Combine(dir, name);
        string[] args = ["render", ShardMergeTests.Scene("paper-3.1-colorchecker-d65.json"), "-o", outDir, "--quiet", .. Size];
        var (code, _, err) = CliRunner.Run(formats.Length == 0 ? args : [.. args, "--formats", string.Join(',', formats)]);
        Assert.True(code == 0, err);
        return outDir;
    }

    [Fact]
    public void Without_the_exr_the_colour_is_kept_in_xyz_npy_bit_for_bit_and_colorcheck_reads_it()
    {
        var dir = Reference.TempDir();
        var full = Render(dir, "full");
        var lean = Render(dir, "lean", "npy", "aov");
        Assert.False(File.Exists(Path.Combine(full, "xyz.npy")));   // spectral.exr holds it
        Assert.False(File.Exists(Path.Combine(lean, "spectral.exr")));

        // xyz.npy holds the same float32 values as the full render's EXR X, Y, Z channels (read by the EXR reader).
        var exr = ExrReader.Read(Path.Combine(full, "spectral.exr"));
        int[] shape; float[] xyz;
        using (var s = File.OpenRead(Path.Combine(lean, "xyz.npy"))) (shape, xyz) = NpyReader.Read(s);
        Assert.Equal([128, 192, 3], shape);
        for (int i = 0; i < 128 * 192; i++)
        {
            Assert.Equal(exr.OtherChannels["X"][i], xyz[3 * i]);
            Assert.Equal(exr.OtherChannels["Y"][i], xyz[3 * i + 1]);
            Assert.Equal(exr.OtherChannels["Z"][i], xyz[3 * i + 2]);
        }

        // colorcheck gives the same rows on both, and their sRGB codes are the 1 nm reference's (±1, the table's rounding).
        var (c1, csvFull, e1) = CliRunner.Run("colorcheck", full, "--csv");
        var (c2, csvLean, e2) = CliRunner.Run("colorcheck", lean, "--csv");
        Assert.True(c1 == 0 && c2 == 0, e1 + e2);
        Assert.Equal(csvFull, csvLean);
        var rows = Reference.Rows("colorchecker-ohta-d65-2deg.csv");
        var lines = csvLean.Trim().Split('\n').Skip(1).Select(l => l.Split(',')).ToList();
        Assert.Equal(24, lines.Count);
        foreach (var r in lines)
        {
            int patch = int.Parse(r[0], System.Globalization.CultureInfo.InvariantCulture);
            for (int c = 0; c < 3; c++)
            {
                int got = int.Parse(r[9 + c], System.Globalization.CultureInfo.InvariantCulture);
                int want = (int)rows[patch - 1].D(new[] { "srgb8_r", "srgb8_g", "srgb8_b" }[c]);
                Assert.True(Math.Abs(got - want) <= 1, $"patch {patch} channel {c}: {got} vs the 1 nm reference {want}");
            }
        }
    }

    [Fact]
    public void Shards_without_the_exr_merge_their_xyz_npy_into_the_whole_renders()
    {
        var dir = Reference.TempDir();
        var whole = Render(dir, "whole", "npy", "aov");
        var shards = new List<string>();
        for (int i = 0; i < 3; i++)
        {
            shards.Add(Path.Combine(dir, $"shard-{i}"));
            var (code, _, err) =
                CliRunner.Run(["render", ShardMergeTests.Scene("paper-3.1-colorchecker-d65.json"), "-o", shards[^1], "--quiet",
                .. Size, "--formats", "npy,aov", "--shard", $"{i}/3"]);
            Assert.True(code == 0, err);
        }
        var (c, _, e) = CliRunner.Run(["merge", .. shards, "-o", Path.Combine(dir, "merged"), "--quiet"]);
        Assert.True(c == 0, e);
        ShardMergeTests.AssertSameRender(whole, Path.Combine(dir, "merged"));
    }
}
