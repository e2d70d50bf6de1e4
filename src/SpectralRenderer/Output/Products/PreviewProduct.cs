using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"png": preview.png, eq. 3 then eq. 4 / sRGB, 8 bits.</summary>
public sealed class PreviewProduct : OutputProduct
{
    public override string Name => "png";
    public override OutputProducts Flag => OutputProducts.Png;
    public override ProductInputs Needs => ProductInputs.Xyz | ProductInputs.PreviewEncoder;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height;
        yield return ("preview.png", 3 * n + 2 * 3 * n);
    }

    public override void Write(ProductContext c, int part, Action<string> done) =>
        RenderOutputWriter.WritePreview(c.Image, c.Xyz!, c.Preview!, c.OutDir, done, c.Warning);

    public override bool Owns(string file) => file == "preview.png";
    public override ShardMerging Merging(string file) => ShardMerging.Png;
}
