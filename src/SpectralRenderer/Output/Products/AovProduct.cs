using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"aov": object-id.png and the analysis images (lit and highlight masks, ground-truth reflectance.exr).</summary>
public sealed class AovProduct : OutputProduct
{
    public override string Name => "aov";
    public override OutputProducts Flag => OutputProducts.Aov;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height;
        yield return ("ground truth", 2 * 4 * n * scene.Bands);
        yield return ("masks", 2 * n + 2 * 2 * n + n + 2 * n);
    }

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        var image = c.Image;
        if (c.Reuse?.Copy("object-id.png", c.OutDir) != true)
        {
            var ids = new ushort[c.Result.ObjectIds.Length];
            for (int i = 0; i < ids.Length; i++) ids[i] = (ushort)(c.Result.ObjectIds[i] + 1);
            AtomicFile.Write(Path.Combine(c.OutDir, "object-id.png"), s => PngWriter.WriteGray16(s, image.Width, image.Height, ids));
        }
        done("object-id.png");
        AnalysisImages.Write(c.Scene, c.Result, c.OutDir, done, c.Reuse);
    }

    public override bool Owns(string file) =>
        file is "object-id.png" or "mask-highlight.png" or "reflectance.exr" || file.StartsWith("mask-lit-", StringComparison.Ordinal);

    public override ShardMerging Merging(string file) => file == "reflectance.exr" ? ShardMerging.ExrChunks : ShardMerging.Png;

    public override RelightReuse Reuse(string file) => file switch
    {
        "object-id.png" => RelightReuse.Geometry,
        "reflectance.exr" => RelightReuse.SameMaterials,
        _ when file.StartsWith("mask-lit-", StringComparison.Ordinal) => RelightReuse.Geometry,
        _ => RelightReuse.Never,
    };
}
