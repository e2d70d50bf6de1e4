namespace SpectralRenderer.Tests.Geometry;

/// <summary>
/// Finds the third-party meshes (not in the repository) through SPECTRAL_MODELS; a relative value is tried
/// against the working folder and each of its parents (CI sets it to ../shared/models from the checkout).
/// </summary>
static class ModelFiles
{
    /// <summary>The model's path, or null with the reason the test has to skip.</summary>
    public static string? Find(string name, out string reason)
    {
        var dir = Environment.GetEnvironmentVariable("SPECTRAL_MODELS");
        if (string.IsNullOrEmpty(dir))
        {
            reason = $"SPECTRAL_MODELS is not set, so {name} cannot be found (CI sets it to ../shared/models)";
            return null;
        }
        var candidates = new List<string>();
        if (Path.IsPathRooted(dir)) candidates.Add(Path.Combine(dir, name));
        else
            for (var d = new DirectoryInfo(Directory.GetCurrentDirectory()); d is not null; d = d.Parent)
                candidates.Add(Path.GetFullPath(Path.Combine(d.FullName, dir, name)));
        foreach (var c in candidates)
            if (File.Exists(c)) { reason = ""; return c; }
        reason =
            $"{name} not found under SPECTRAL_MODELS='{dir}' (tried {candidates[0]}{(candidates.Count > 1 ? " and its parents" : "")})";
        return null;
    }

    /// <summary>The model's path, or skips the test (Xunit.SkippableFact) saying why.</summary>
    public static string Require(string name)
    {
        var path = Find(name, out var reason);
        Skip.If(path is null, reason);
        return path!;
    }
}
