using System.Diagnostics;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>A small spectral image from a formula, with zeros, tiny, large and ordinary values.</summary>
static class Synthetic
{
    public const int W = 37, H = 23;

    public static SpectralImage Image(BandGrid? grid = null)
    {
        grid ??= BandGrid.Default;
        var img = new SpectralImage(W, H, grid);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int b = 0; b < grid.Count; b++)
                    img[x, y, b] = Value(x, y, b);
        return img;
    }

    public static float Value(int x, int y, int b)
    {
        int k = (x * 7 + y * 13 + b * 5) % 31;
        if ((x + 2 * y + b) % 17 == 0) return 0f;
        if (k == 3) return 1e-30f * (b + 1);                   // tiny (below half's range)
        if (k == 7) return 1.25e-7f * (1 + x);                 // half subnormal range
        if (k == 11) return 3.5e5f + 1000f * (x + y + b);      // large (beyond half's max 65504)
        return (float)(0.05 + 0.9 * (0.5 + 0.5 * Math.Sin(0.31 * x + 0.17 * y + 0.23 * b)) * (1 + (b % 3)));
    }

    static Colorimeter? _colorimeter;
    public static Colorimeter Colorimeter =>
        _colorimeter ??= new Colorimeter(BandGrid.Default, Observer.Cie1931, SpectrumLibrary.Resolve("D65"));

    public static void AssertBitExact(float[] expected, float[] actual, string what)
    {
        Assert.Equal(expected.Length, actual.Length);
        for (int i = 0; i < expected.Length; i++)
            if (BitConverter.SingleToInt32Bits(expected[i]) != BitConverter.SingleToInt32Bits(actual[i]))
                Assert.Fail($"{what}: value {i} is {actual[i]:R}, expected {expected[i]:R}");
    }
}

/// <summary>Runs an external tool with a timeout; null when it is not installed.</summary>
static class Tool
{
    public static string? Find(string name)
    {
        foreach (var dir in (Environment.GetEnvironmentVariable("PATH") ?? "").Split(Path.PathSeparator))
        {
            if (dir.Length == 0) continue;
            var p = Path.Combine(dir, name);
            if (File.Exists(p)) return p;
        }
        return null;
    }

    public static (int Exit, string Out, string Err) Run(string exe, IEnumerable<string> args, int timeoutMs = 20000,
        string? workDir = null)
    {
        var psi = new ProcessStartInfo(exe)
        {
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
            WorkingDirectory = workDir ?? Environment.CurrentDirectory,
        };
        foreach (var a in args) psi.ArgumentList.Add(a);
        using var p = Process.Start(psi)!;
        var stdout = p.StandardOutput.ReadToEndAsync();
        var stderr = p.StandardError.ReadToEndAsync();
        if (!p.WaitForExit(timeoutMs))
        {
            try { p.Kill(entireProcessTree: true); } catch (InvalidOperationException) { }
            Assert.Fail($"{Path.GetFileName(exe)} {string.Join(' ', args)} timed out after {timeoutMs} ms");
        }
        p.WaitForExit();
        return (p.ExitCode, stdout.Result, stderr.Result);
    }
}
