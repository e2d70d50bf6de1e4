namespace SpectralRenderer.Spectra;

/// <summary>Finds the project's data/ folder: $SPECTRAL_DATA, then beside the executable, then up from the working folder.</summary>
public static class DataDirectory
{
    const string Marker = "cie1931-2deg-cmf.csv";
    static string? _cached;

    public static string Path => _cached ??= Locate();

    static string Locate()
    {
        var env = Environment.GetEnvironmentVariable("SPECTRAL_DATA");
        if (!string.IsNullOrEmpty(env) && File.Exists(System.IO.Path.Combine(env, Marker))) return env;
        var beside = System.IO.Path.Combine(AppContext.BaseDirectory, "data");
        if (File.Exists(System.IO.Path.Combine(beside, Marker))) return beside;
        for (var dir = new DirectoryInfo(Directory.GetCurrentDirectory()); dir is not null; dir = dir.Parent)
        {
            var candidate = System.IO.Path.Combine(dir.FullName, "data");
            if (File.Exists(System.IO.Path.Combine(candidate, Marker))) return candidate;
        }
        throw new DirectoryNotFoundException(
            $"the spectral data folder (with {Marker}) was not found beside the executable; set "
                + $"SPECTRAL_DATA to the project's data/ folder");
    }

    public static string File_(string name) => System.IO.Path.Combine(Path, name);
}
