using SpectralRenderer.Color;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>A ColorChecker patch seen in a render: its number (1–24), object, and its pixels away from the patch edges.</summary>
public sealed record ChartPatch(int Number, string Object, int[] Pixels);

/// <summary>
/// Everything the camera and the recovery take from a render folder, read in this one place: the radiance cube,
/// the scene light (render.json's reference white spectrum: the white diffuser's radiance has its band values),
/// the observer, the ColorChecker patches by object id, the ground-truth reflectance and the region masks.
/// </summary>
public sealed class CameraScene
{
    CameraScene(RenderFolder folder, RenderAovs aovs, List<ChartPatch> patches) { Folder = folder; Aovs = aovs; Patches = patches; }

    public RenderFolder Folder { get; }
    public RenderAovs Aovs { get; }
    public List<ChartPatch> Patches { get; }
    public int Width => Folder.Image.Width;
    public int Height => Folder.Image.Height;
    public BandGrid Grid => Folder.Image.Grid;
    public TabulatedSpectrum Light => Folder.ReferenceWhite;
    public string LightName => Light.Name;
    public Observer Observer => Folder.ObserverDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931;
    /// <summary>The radiometry the render used ("paper" relative, or "physical" in W·m⁻²·sr⁻¹·nm⁻¹), if it says.</summary>
    public string? Radiometry => Folder.Manifest.ResolvedScene?.Radiometry;

    public static CameraScene Open(string dir)
    {
        var folder = RenderFolder.Open(dir);
        return new CameraScene(folder, RenderAovs.Open(folder), FindPatches(folder));
    }

    /// <summary>
    /// A render's contents held in memory (libspectral's camera): the folder's cube, manifest and images without the folder.
    /// </summary>
    public static CameraScene Of(RenderFolder folder, RenderAovs aovs) => new(folder, aovs, FindPatches(folder));

    public RadianceCube Cube(double radianceScale) =>
        new(Width, Height, Grid, Folder.Image.Data, radianceScale) { FovDegrees = FovDegrees };

    /// <summary>The render camera's vertical field of view (degrees; the scene loader's default 40 when the scene gives none).</summary>
    public double FovDegrees => Folder.Manifest.ResolvedScene?.CameraFov ?? 40;

    static List<ChartPatch> FindPatches(RenderFolder folder)
    {
        var list = new List<ChartPatch>();
        int w = folder.Image.Width, h = folder.Image.Height;
        for (int o = 0; o < folder.ObjectNames.Length; o++)
        {
            var r = folder.ObjectReflectances[o];
            if (r is null || !r.StartsWith("colorchecker:", StringComparison.Ordinal)
                || !int.TryParse(r["colorchecker:".Length..], out int number))
                continue;
            // The interior: pixels whose neighbours within `margin` (3: a 4 × 4 mosaic's bilinear reach) show the same object.
            for (int margin = 3; margin >= 0; margin--)
            {
                var pixels = new List<int>();
                for (int y = margin; y < h - margin; y++)
                    for (int x = margin; x < w - margin; x++)
                    {
                        bool inside = true;
                        for (int dy = -margin; dy <= margin && inside; dy++)
                            for (int dx = -margin; dx <= margin && inside; dx++)
                                inside = folder.ObjectIds[(y + dy) * w + x + dx] == o;
                        if (inside) pixels.Add(y * w + x);
                    }
                if (pixels.Count > 0 || margin == 0)
                {
                    if (pixels.Count > 0) list.Add(new ChartPatch(number, folder.ObjectNames[o], pixels.ToArray()));
                    break;
                }
            }
        }
        list.Sort((a, b) => a.Number.CompareTo(b.Number));
        return list;
    }
}
