using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

// What the path integrator can do beyond a picture (IntegratorCapabilities.cs): its per-light transfer (PathTransfer.cs,
// files in PathTransferFiles.cs, for whole renders and shards), its film on the sub-band grid for the camera's exact route
// (PathFilm.cs), and the gather of photometry and calculation grids (its radiance is every bounce).
internal sealed partial class PathIntegrator : ITransferIntegrator, ISubBandFilmIntegrator, IGatherIntegrator
{
    public TransferFormat TransferFormat => PathTransferFiles.Format;

    public ILightTransfer TraceTransfer(Scene scene, int threads, CancellationToken cancel, PixelRect? crop) =>
        PathTransfer.Trace(scene, this, threads, cancel, crop);

    /// <summary>Its settings in <paramref name="scene"/>: the scene's when it names this integrator, else the defaults.</summary>
    public static IntegratorSettings SettingsOf(Scene scene) =>
        scene.Integrator is { Name: "path" } s ? s : new IntegratorSettings("path");

    /// <summary>The sub-band grid of <paramref name="width"/> nm its paths carry in <paramref name="scene"/> (adaptive when the
    /// scene sets no "spectral_grid": SubBandGrid.Adaptive.cs).</summary>
    internal static SubBandGrid GridOf(Scene scene, double width) => new(scene, width, SettingsOf(scene).AdaptiveGrid);

    public int FilmSubBands => _grid.Count;

    public SubBandFilm TraceSubBandFilm(Scene scene, int threads, CancellationToken cancel = default) =>
        PathFilm.Trace(scene, this, threads, cancel);
}
