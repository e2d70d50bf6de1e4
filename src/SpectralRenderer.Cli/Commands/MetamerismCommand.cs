using System.Globalization;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral metamerism`: what the uplift of an sRGB texture costs under other lights (<see cref="UpliftMetamerism"/>).</summary>
public static class MetamerismCommand
{
    const string Help = """
        usage: spectral metamerism TEXTURE.png [--lights A,FL2,FL11,led-rgb,led-yag] [--csv]

        For every colour of an 8- or 16-bit sRGB PNG, two reflectances with that colour under D65:
        the smooth sigmoid-polynomial spectrum the renderer uses for RGB textures and a three-box
        one (380–490, 490–590, 590–780 nm). Prints, per light, the CIEDE2000 difference between
        them over the texture's texels (mean, 95th percentile, max): how much the colour of the
        textured object under that light depends on the choice of metamer. Colours whose box
        metamer leaves [0, 1] are counted and left out.

          --lights L,…   built-in light names (default A, FL2, FL11, led-rgb, led-yag)
          --csv          one row per colour: r,g,b,texels,ΔE00 per light
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("metamerism", argv, ["--lights"], ["--csv"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1) throw new InputException("metamerism", "expected one sRGB PNG", "see 'spectral metamerism --help'");
        var png = PngReader.Read(a.Positionals[0]);
        if (png.Channels != 3)
            throw new InputException(a.Positionals[0], $"{png.Channels} channel(s): expected an RGB PNG",
                "save the texture as RGB (no alpha)");
        var names = (a.Value("--lights") ?? string.Join(",", UpliftMetamerism.DefaultLights))
            .Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);
        var lights = names.Select(UpliftMetamerism.Under).ToArray();
        int max = (1 << png.BitDepth) - 1;
        var counts = new Dictionary<(int, int, int), int>();
        for (int i = 0; i < png.Width * png.Height; i++)
        {
            var key = ((int)png.Samples[3 * i], (int)png.Samples[3 * i + 1], (int)png.Samples[3 * i + 2]);
            counts[key] = counts.GetValueOrDefault(key) + 1;
        }
        var report = new UpliftMetamerism(new SigmoidUplift());
        var rows = new List<((int R, int G, int B) Colour, int Texels, double[] Spread)>();
        int skippedColours = 0, skippedTexels = 0;
        foreach (var (colour, n) in counts.OrderBy(c => c.Key))
        {
            var spread = report.Spread(colour.Item1, colour.Item2, colour.Item3, max, lights);
            if (spread is null) { skippedColours++; skippedTexels += n; continue; }
            rows.Add((colour, n, spread));
        }
        var inv = CultureInfo.InvariantCulture;
        if (a.Flag("--csv"))
        {
            stdout.WriteLine("r,g,b,texels," + string.Join(",", names.Select(l => $"dE00_{l}")));
            foreach (var (c, n, s) in rows)
                stdout.WriteLine(string.Create(inv, $"{c.R},{c.G},{c.B},{n},{string.Join(",", s.Select(v => v.ToString("R", inv)))}"));
            return CommandLine.Success;
        }
        stdout.WriteLine($"{a.Positionals[0]}: {png.Width}×{png.Height}, {counts.Count} colours; ΔE00 between the sigmoid and the "
            + $"three-box metamer (equal under D65)");
        if (skippedColours > 0)
            stdout.WriteLine($"left out: {skippedColours} colours ({skippedTexels} texels) whose box metamer is not a reflectance");
        stdout.WriteLine($"{"light",-10} {"mean",7} {"p95",7} {"max",7}");
        for (int k = 0; k < names.Length; k++)
        {
            var weighted = rows.SelectMany(r => Enumerable.Repeat(r.Spread[k], r.Texels)).Order().ToArray();
            if (weighted.Length == 0) { stdout.WriteLine($"{names[k],-10} (no admissible colour)"); continue; }
            double mean = weighted.Average(), p95 = weighted[(int)Math.Min(weighted.Length - 1, Math.Ceiling(0.95 * weighted.Length) - 1)],
                top = weighted[^1];
            stdout.WriteLine(string.Create(inv, $"{names[k],-10} {mean,7:F3} {p95,7:F3} {top,7:F3}"));
        }
        return CommandLine.Success;
    }
}
