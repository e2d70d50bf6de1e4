using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Pipeline;

/// <summary>How much of the run a render records in render.json's "run" besides what the caller gives.</summary>
public enum RunDetail
{
    /// <summary>Only the caller's <see cref="RenderRequest.Run"/> (experiments: none; relight: its source and changes).</summary>
    None,
    /// <summary>Also the triangle count (sweep jobs).</summary>
    Geometry,
    /// <summary>Load and build times, triangles, ray pruning, the shard, the transfer's time and the overrides (`render`).</summary>
    Full,
}

/// <summary>The film pixels to render: a crop, or a shard's strip (computed from the film's size once the scene is loaded).</summary>
/// <param name="Rectangle">The pixels for a film of the given width and height.</param>
/// <param name="Shard">The shard's description for render.json ("I/N (source)"), null for a crop.</param>
public sealed record RenderRegion(Func<int, int, PixelRect> Rectangle, string? Shard = null)
{
    /// <summary>A crop "X0,Y0,X1,Y1" (--crop).</summary>
    public static RenderRegion Crop(string text) => new((w, h) => PixelRect.Parse(text, w, h));
}

/// <summary>
/// A render's result taken from a per-light transfer instead of traced rays (relight): the transfer recombined for the
/// scene's lights, and the files of the source folder that no light changes, copied.
/// </summary>
public sealed record TransferSource(ILightTransfer Transfer, ReusedFiles? Reuse = null);

/// <summary>
/// What to render and where: the scene (a file, its bytes, or a loaded scene) and what overrides it (size, bands, spp,
/// formats, …), the integrator by name, the region, the threads, the output folder. <see cref="RenderJob"/> carries it out.
/// </summary>
public sealed record RenderRequest
{
    /// <summary>
    /// The scene file; with <see cref="SceneText"/> the name it is parsed under (its relative paths resolve from its folder).
    /// </summary>
    public string ScenePath { get; init; } = "";
    /// <summary>The scene file's bytes, when they are not read from <see cref="ScenePath"/> (standard input, a sweep job's edit).</summary>
    public byte[]? SceneText { get; init; }
    /// <summary>
    /// A scene already loaded (relight's changed scene); then <see cref="ScenePath"/>, <see cref="SceneText"/> are not read.
    /// </summary>
    public Scene? Scene { get; init; }
    /// <summary>Size, bands, spp, colour, formats, model folders: the command line's changes to the scene file.</summary>
    public SceneOverrides Overrides { get; init; } = new();
    /// <summary>The integrator's registered name (<see cref="Rendering.Registry.Integrators"/>); null: the scene's "integrator", else
    /// whitted.</summary>
    public string? Integrator { get; init; }
    /// <summary>A crop or shard; null renders the whole film.</summary>
    public RenderRegion? Region { get; init; }
    /// <summary>Worker threads (0: all cores); the output is the same for any count.</summary>
    public int Threads { get; init; }
    /// <summary>Camera rays in SIMD packets (the same bits as ray by ray).</summary>
    public bool Packets { get; init; } = true;
    /// <summary>The output folder; null writes nothing (bench).</summary>
    public string? OutDir { get; init; }
    /// <summary>BVHs shared with earlier renders of this process (experiments, sweeps).</summary>
    public GeometryCache? Geometries { get; init; }
    /// <summary>
    /// Registered output products asked for by name beyond the scene's formats (<see cref="Output.Products.OutputProductTable"/>).
    /// </summary>
    public IReadOnlyList<string> Products { get; init; } = [];
    /// <summary>The result from a per-light transfer instead of rays (relight).</summary>
    public TransferSource? FromTransfer { get; init; }
    /// <summary>
    /// The caller's part of render.json's "run" (command line, sweep job, relit source); null with <see cref="RunDetail.None"/> records
    /// no run.
    /// </summary>
    public ManifestRun? Run { get; init; }
    /// <summary>What the job adds to <see cref="Run"/>.</summary>
    public RunDetail Detail { get; init; } = RunDetail.Full;
}
