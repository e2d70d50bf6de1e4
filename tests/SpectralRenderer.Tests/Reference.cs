using System.Globalization;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests;

/// <summary>Reads the independent reference tables in data/reference (copied from ../shared/data/reference).</summary>
static class Reference
{
    public static List<Dictionary<string, string>> Rows(string file)
    {
        var lines = File.ReadAllLines(Path.Combine(DataDirectory.Path, "reference", file));
        var header = lines[0].Split(',');
        return lines.Skip(1).Where(l => l.Length > 0)
            .Select(l => header.Zip(l.Split(',')).ToDictionary(p => p.First, p => p.Second)).ToList();
    }

    public static double D(this Dictionary<string, string> row, string key) => double.Parse(row[key], CultureInfo.InvariantCulture);

    public static string TempDir()
    {
        var d = Path.Combine(Path.GetTempPath(), "spectral-tests", Guid.NewGuid().ToString("N")[..12]);
        Directory.CreateDirectory(d);
        return d;
    }
}

static class InputExceptionText
{
    /// <summary>The message without its hint: "where: what".</summary>
    public static string Unhinted(this SpectralRenderer.Diagnostics.InputException e) => string.IsNullOrEmpty(e.Where) ? e.What : $"{e.Where}: {e.What}";
}
