namespace SpectralRenderer.Scenes;

/// <summary>
/// The light-transport method a scene asks for (<c>"integrator"</c>): its registered name and, for a path tracer, the
/// maximum path depth (−1: unbounded), the depth from which Russian roulette may end a path, and the width in nm of the
/// internal spectral grid its paths carry (<c>"spectral_grid"</c>), and its sampler (<c>"sampler"</c>: null for the
/// integrator's own default) with its seed (<c>"seed"</c>), and whether a path tracer chooses among many emitters by a light
/// tree (<c>"light_tree"</c>: null for its own rule, by their number).
/// </summary>
public sealed record IntegratorSettings(string Name, int MaxDepth = -1, int RrDepth = IntegratorSettings.DefaultRrDepth,
    double SpectralGrid = IntegratorSettings.DefaultSpectralGrid, SamplerKind? Sampler = null, uint Seed = 0, bool? LightTree = null)
{
    public const int DefaultRrDepth = 5;
    /// <summary>The keys the scene's "integrator" object gave beside "type", each with where it stands ("file:line:col: $.path").</summary>
    public IReadOnlyList<(string Key, string Where)> Keys { get; init; } = [];
    public const double DefaultSpectralGrid = 5;
    /// <summary>
    /// No "spectral_grid" given: the grid of the default width is adaptive (its sub-bands where the scene's spectra need
    /// them, Rendering/SubBandGrid.Adaptive.cs); a width given is a uniform grid.
    /// </summary>
    public bool AdaptiveGrid { get; init; } = true;
}
