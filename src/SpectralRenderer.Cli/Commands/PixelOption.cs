using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Cli.Commands;

/// <summary>A pixel named on the command line: `--pixel X,Y[:LABEL]` (0-based, x right, y down).</summary>
public sealed record PixelOption(int X, int Y, string Label)
{
    public static PixelOption Parse(string text, string command)
    {
        var spec = text;
        string? label = null;
        int colon = text.IndexOf(':');
        if (colon >= 0) { spec = text[..colon]; label = text[(colon + 1)..].Trim(); }
        var parts = spec.Split(',');
        if (parts.Length != 2 || !int.TryParse(parts[0].Trim(), NumberStyles.Integer, CultureInfo.InvariantCulture, out int x)
            || !int.TryParse(parts[1].Trim(), NumberStyles.Integer, CultureInfo.InvariantCulture, out int y))
            throw new InputException("--pixel", $"'{text}' is not X,Y[:LABEL]",
                $"e.g. --pixel 120,80:lit (see 'spectral {command} --help')");
        if (label == "") throw new InputException("--pixel", $"'{text}' has an empty label", "e.g. --pixel 120,80:lit");
        return new PixelOption(x, y, label ?? $"x{x}y{y}");
    }

    /// <summary>Parses every --pixel and checks each lies inside a <paramref name="width"/> × <paramref name="height"/> image.</summary>
    public static List<PixelOption> ParseAll(IReadOnlyList<string> values, string command, int width, int height)
    {
        var list = values.Select(v => Parse(v, command)).ToList();
        foreach (var p in list)
            if (p.X < 0 || p.Y < 0 || p.X >= width || p.Y >= height)
                throw new InputException("--pixel", $"{p.X},{p.Y} is outside the {width}×{height} image",
                    $"x in 0–{width - 1}, y in 0–{height - 1}");
        var dup = list.GroupBy(p => p.Label).FirstOrDefault(g => g.Count() > 1);
        if (dup is not null) throw new InputException("--pixel", $"label '{dup.Key}' is used twice", "give each pixel its own label");
        return list;
    }

    /// <summary>A CSV field (RFC 4180): quoted when it holds a comma, quote or line break.</summary>
    public static string Csv(string s) => s.IndexOfAny([',', '"', '\n', '\r']) >= 0 ? "\"" + s.Replace("\"", "\"\"") + "\"" : s;
}
