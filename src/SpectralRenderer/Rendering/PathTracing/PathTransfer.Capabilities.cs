using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

// The path transfer as a capability (IntegratorCapabilities.cs): recombined by relight and the C ABI, written by the
// lights product (whole renders and shards), and the sub-band film for the camera's exact route.
internal sealed partial class PathTransfer : ISubBandFilmRoute
{
    public TransferFormat Format => PathTransferFiles.Format;

    public string? Mismatch(Scene scene) =>
        FilmWidth != scene.Camera.Width || FilmHeight != scene.Camera.Height
            ? $"its lights/ are {FilmWidth}×{FilmHeight} but the scene rebuilds as {scene.Camera.Width}×{scene.Camera.Height}"
            : null;

    /// <summary>The relit film: the transfer under the scene's lights; the object ids and lit masks as traced.</summary>
    RenderResult ILightTransfer.Relight(Scene scene)
    {
        var clock = System.Diagnostics.Stopwatch.StartNew();
        var (image, xyz) = Relight(scene);
        int n = Region.Width * Region.Height;
        // The lit masks as traced (geometry: no light's spectrum changes them); no highlights (the path tracer has no eq. 2 terms).
        var highlights = new byte[n];
        Array.Fill(highlights, PixelInfo.Highlight(0, 0, (float)scene.Output.HighlightFraction));
        return new RenderResult
        {
            Image = image,
            Xyz = xyz,
            ObjectIds = ObjectIds,
            LitMasks = Rendering.LitMasks.From(LitMasks, scene.Lights.Count),
            Highlights = highlights,
            Rays = new RayCounters(),
            Elapsed = clock.Elapsed,
            Threads = Environment.ProcessorCount,
            Tiles = 0,
            Crop = Region,
        };
    }

    /// <summary>The relight's method; the files it names only when it was read from them (not a transfer in memory).</summary>
    public string RelightMethod =>
        "per-light transfer of a path render" + (ReadFromFiles ? " (lights/transfer.npy)" : "") +
        ": on the fine grid L_f = F_f + sum_k T_k,f * E_k,f" +
        (Shift.IsEmpty ? "" : " + sum_k B_k E_k (its fluorescent shift" + (ReadFromFiles ? ", lights/shift.npy)" : ")")) +
        " with E_k the new " +
        "lights' spectra x intensities (emitters and sky F as rendered), reduced to the bands and XYZ as the film is; no rays traced";

    public IEnumerable<string> StoredFiles => [];

    public void Write(Scene scene, string outDir, Action<string> done) => PathTransferFiles.Write(scene, this, outDir, done);

    public SubBandFilm Film(Scene scene) => PathFilm.FromTransfer(this, scene);

    public string FilmMethod => "its path transfer: L_f = F_f + sum_k T_k,f * E_k,f" +
        (Shift.IsEmpty ? "" : " + sum_k B_k E_k of its fluorescent shift") + " per pixel, no rays traced";
}
