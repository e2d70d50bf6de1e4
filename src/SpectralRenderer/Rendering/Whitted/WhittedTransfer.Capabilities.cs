using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Whitted;

// The Whitted transfer as a capability (IntegratorCapabilities.cs): recombined by relight and the C ABI, written by the
// lights product, and eq. 2's terms for the camera's exact route.
internal sealed partial class WhittedTransfer : ITermRoute
{
    public TransferFormat Format => WhittedTransferFiles.Format;
    public int FilmWidth => Width;
    public int FilmHeight => Height;
    public PixelRect Region => PixelRect.Whole(Width, Height);

    public string? Mismatch(Scene scene) =>
        Width != scene.Camera.Width || Height != scene.Camera.Height || Bands != scene.Bands
            ? $"its lights/ are {Width}×{Height}×{Bands} but the scene rebuilds as " +
                $"{scene.Camera.Width}×{scene.Camera.Height}×{scene.Bands}"
            : null;

    /// <summary>The relit film: the factors recombined with the scene's lights, the geometry's images as traced.</summary>
    RenderResult ILightTransfer.Relight(Scene scene)
    {
        var clock = System.Diagnostics.Stopwatch.StartNew();
        var (image, xyz, fallback) = Relight(scene);
        return new RenderResult
        {
            Image = image,
            Xyz = xyz,
            FallbackPixels = fallback,
            ObjectIds = ObjectIds,
            LitMasks = Rendering.LitMasks.From(LitMasks, scene.Lights.Count),
            Highlights = CentreHighlights(scene),
            Rays = new RayCounters(),
            Elapsed = clock.Elapsed,
            Threads = Environment.ProcessorCount,
            Tiles = 0,
            Crop = PixelRect.Whole(Width, Height),
        };
    }

    public string RelightMethod => "per-light transfer (lights/): L_b = sum_c F_c * P_c,b and XYZ = sum_c F_c * XYZ_c with P_c " +
        "rebuilt from the new lights' term tables; no rays traced";

    public IEnumerable<string> StoredFiles => StoredIn is null ? []
        : WhittedTransferFiles.ArraysOf(this).Select(f => $"{WhittedTransferFiles.Folder}/{f}");

    public void Write(Scene scene, string outDir, Action<string> done) => WhittedTransferFiles.Write(scene, this, outDir, done);
}
