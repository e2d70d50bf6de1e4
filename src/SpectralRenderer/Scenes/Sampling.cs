namespace SpectralRenderer.Scenes;

/// <summary>How a camera sample's random numbers are made (the renderer's sampler), each a pure function of (pixel x, pixel y,
/// sample index, dimension, seed), so any thread count, tile order or shard gives the same picture.</summary>
public enum SamplerKind
{
    /// <summary>"independent": a counter-based hash per (pixel, sample, dimension); the film jitter stratified on an m × n grid.</summary>
    Independent,
    /// <summary>"sobol": Owen-scrambled Sobol points, padded per dimension pair (Burley 2020), progressive in the sample index.</summary>
    Sobol,
}

/// <summary>A render's sampler and its seed (0: the one every render before seeds used).</summary>
public readonly record struct SamplerSettings(SamplerKind Kind, uint Seed = 0)
{
    public static readonly SamplerSettings Independent = new(SamplerKind.Independent);
}

/// <summary>The samplers by name (a scene's <c>"integrator": { "sampler": … }</c>).</summary>
public static class Samplers
{
    public static readonly IReadOnlyList<(SamplerKind Kind, string Name)> ByName =
        [(SamplerKind.Independent, "independent"), (SamplerKind.Sobol, "sobol")];

    public static string[] Names => ByName.Select(s => s.Name).ToArray();

    public static string Name(SamplerKind kind) => ByName.First(s => s.Kind == kind).Name;

    public static bool TryParse(string name, out SamplerKind kind)
    {
        foreach (var (k, n) in ByName)
            if (n == name) { kind = k; return true; }
        kind = default;
        return false;
    }
}
