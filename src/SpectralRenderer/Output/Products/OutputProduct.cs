using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output.Products;

/// <summary>What a product's writer takes from the render, prepared once for all the products that need it.</summary>
[Flags]
public enum ProductInputs
{
    None = 0,
    /// <summary>The band-sequential planes of the cube (<see cref="ProductContext.BandPlanes"/>).</summary>
    BandPlanes = 1,
    /// <summary>The pixels' XYZ (<see cref="ProductContext.Xyz"/>).</summary>
    Xyz = 2,
    /// <summary>The preview's encoder with its exposure (<see cref="ProductContext.Preview"/>, recorded in render.json).</summary>
    PreviewEncoder = 4,
}

/// <summary>How `spectral merge` assembles a file of the shards into the whole render's.</summary>
public enum ShardMerging
{
    /// <summary>Not in shards (a whole render's product only).</summary>
    None,
    /// <summary>An 8/16-bit PNG: the strips decoded and encoded again.</summary>
    Png,
    /// <summary>The band images and mosaic, rescaled to the whole image's brightest band value.</summary>
    BandImages,
    /// <summary>An OpenEXR whose chunks are the whole file's: copied chunk by chunk.</summary>
    ExrChunks,
    /// <summary>The ENVI cube, band by band by offset; its header with the whole height.</summary>
    EnviCube,
    EnviHeader,
    /// <summary>The NumPy cube, row strips by offset.</summary>
    NpyCube,
    /// <summary>The NumPy H × W × 3 colour array (xyz.npy), row strips by offset.</summary>
    NpyColour,
    /// <summary>The same in every shard: the first one's copied.</summary>
    Copy,
    /// <summary>noise.npy (H × W × (N + 1)), row strips by offset.</summary>
    NoiseNpy,
    /// <summary>noise.img, the N + 1 planes by offset; noise.hdr with the whole height.</summary>
    NoiseEnvi,
    NoiseEnviHeader,
    /// <summary>
    /// An array of a per-light transfer written by shards (lights/…: H × W × …, the per-pixel shape its format reads from
    /// the shard's lights.json, <see cref="TransferFormat.RowShape"/>), row strips by offset.
    /// </summary>
    TransferRows,
    /// <summary>A false-colour picture and legend of photometry.exr's channels, drawn again from the shards' EXRs assembled.</summary>
    FalseColour,
}

/// <summary>Whether a relit render may copy a file from its source folder (written by the same build) instead of writing it.</summary>
public enum RelightReuse
{
    /// <summary>No: the lights change it.</summary>
    Never,
    /// <summary>Yes: it depends on the geometry only (which object and which lights each centre ray sees).</summary>
    Geometry,
    /// <summary>When the materials' band values and the file's header are the source's (the ground-truth reflectance).</summary>
    SameMaterials,
}

/// <summary>The render and what is prepared for the writers, shared by every product of one render.</summary>
public sealed class ProductContext
{
    public required Scene Scene { get; init; }
    public required RenderResult Result { get; init; }
    public SpectralImage Image => Result.Image;
    /// <summary>The folder the files go to (the staging folder).</summary>
    public required string OutDir { get; init; }
    /// <summary>The brightest band value: what band PNG level 65535 stands for.</summary>
    public float BandScale { get; init; }
    public float[]? BandPlanes { get; init; }
    public XyzPlanes? Xyz { get; init; }
    public DisplayEncoder? Preview { get; init; }
    /// <summary>The integrator's per-light transfer (the lights product), or null.</summary>
    public ILightTransfer? Transfer { get; init; }
    /// <summary>The render's ray queries and integrator, for products that trace rays of their own (photometry); null in a
    /// relight.</summary>
    public RenderTracer? Tracer { get; init; }
    /// <summary>Files another folder holds exactly as this render would write them (relight): copied, not encoded.</summary>
    public ReusedFiles? Reuse { get; init; }
    public CancellationToken Cancel { get; init; }
    /// <summary>Where a product says something is probably not what the user meant (one line each), or null.</summary>
    public Action<string>? Warning { get; init; }
    /// <summary>Where a product that traces rays of its own (the photometry gather, the grids) reports its progress, or null.</summary>
    public Action<RenderProgress>? Progress { get; init; }

    /// <summary>
    /// A (rows done, rows) reporter for <paramref name="stage"/> on <see cref="Progress"/>, timed from now; null without one.
    /// </summary>
    public Action<int, int>? StageProgress(string stage)
    {
        if (Progress is not { } progress) return null;
        var clock = System.Diagnostics.Stopwatch.StartNew();
        return (done, total) => progress(new RenderProgress(done, total, 0, clock.Elapsed, stage));
    }
}

/// <summary>The scene's ray queries and the integrator the render used, and the threads it may use.</summary>
public sealed record RenderTracer(SceneGeometry Geometry, IIntegrator Integrator, int Threads);

/// <summary>
/// One output product of a render (guide §6): its name in --formats and "output.formats", the files it writes, what it
/// adds to a render's memory (<see cref="RenderMemory"/>), its writer, how `spectral merge` assembles its files from
/// shards and whether a relight may copy them. One file per product, registered in <see cref="OutputProductTable"/>.
/// </summary>
public abstract class OutputProduct
{
    /// <summary>The name --formats and a scene's "output.formats" use.</summary>
    public abstract string Name { get; }

    /// <summary>
    /// The scene's flag for it; <see cref="OutputProducts.None"/> for a product asked for by name only (<see
    /// cref="OutputProductTable.Named"/>).
    /// </summary>
    public virtual OutputProducts Flag => OutputProducts.None;

    /// <summary>Whether a render asking for <paramref name="asked"/> writes it.</summary>
    public virtual bool Wanted(OutputProducts asked) => (asked & Flag) != 0;

    public virtual ProductInputs Needs => ProductInputs.None;

    /// <summary>Writers that may run side by side; each reports its files in order.</summary>
    public virtual int Parts => 1;

    /// <summary>What its writers hold at once beyond the shared inputs, in bytes, by part.</summary>
    public virtual IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads) => [];

    /// <summary>
    /// Writes part <paramref name="part"/> of its files into <see cref="ProductContext.OutDir"/>, calling <paramref name="done"/> with
    /// each file's relative name.
    /// </summary>
    public abstract void Write(ProductContext context, int part, Action<string> done);

    /// <summary>Whether <paramref name="file"/> (relative, as render.json lists it) is one of its files.</summary>
    public abstract bool Owns(string file);

    /// <summary>How shards of its file are merged.</summary>
    public virtual ShardMerging Merging(string file) => ShardMerging.None;

    /// <summary>Whether a relit render may copy its file from the source.</summary>
    public virtual RelightReuse Reuse(string file) => RelightReuse.Never;
}
