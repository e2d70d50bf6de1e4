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

    /// <summary>A file of the repository (the folder holding SpectralRenderer.sln), e.g. "scenes/path-cornell-room.json".</summary>
    public static string RepoFile(string relative)
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
            if (File.Exists(Path.Combine(d.FullName, "SpectralRenderer.sln"))) return Path.Combine(d.FullName, relative);
        throw new InvalidOperationException("repository root not found");
    }

    /// <summary>
    /// A new empty folder for one test, under this test run's own folder in the system's temporary folder, which is
    /// deleted when the test process ends (set SPECTRAL_KEEP_TEST_FILES=1 to keep it for a look).
    /// </summary>
    public static string TempDir()
    {
        var d = Path.Combine(RunFolder.Value, Guid.NewGuid().ToString("N")[..12]);
        Directory.CreateDirectory(d);
        return d;
    }

    static readonly Lazy<string> RunFolder = new(() =>
    {
        var root = Path.Combine(Path.GetTempPath(), "spectral-tests", $"run-{Environment.ProcessId}-{Guid.NewGuid().ToString("N")[..8]}");
        Directory.CreateDirectory(root);
        if (Environment.GetEnvironmentVariable("SPECTRAL_KEEP_TEST_FILES") != "1")
            AppDomain.CurrentDomain.ProcessExit += (_, _) =>
            {
                try { Directory.Delete(root, recursive: true); }
                catch (IOException) { }                       // a file still held: the system's temporary folder keeps it
                catch (UnauthorizedAccessException) { }
            };
        return root;
    });
}

static class InputExceptionText
{
    /// <summary>The message without its hint: "where: what".</summary>
    public static string Unhinted(this SpectralRenderer.Diagnostics.InputException e) =>
        string.IsNullOrEmpty(e.Where) ? e.What : $"{e.Where}: {e.What}";
}
