using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"exr": spectral.exr, the spectral OpenEXR layout with R, G, B and X, Y, Z.</summary>
public sealed class ExrProduct : OutputProduct
{
    public override string Name => "exr";
    public override OutputProducts Flag => OutputProducts.Exr;
    public override ProductInputs Needs => ProductInputs.BandPlanes | ProductInputs.Xyz;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height;
        yield return ("spectral.exr", 4 * n * (scene.Bands + 6) + 24 * n);
    }

    public override void Write(ProductContext c, int part, Action<string> done) =>
        SpectralFiles.WriteExr(c.Scene, c.Image, c.BandPlanes!, c.Xyz, c.Result.Crop, c.OutDir, done,
            // the noise product's standard errors as a layer beside the bands
            (c.Scene.Output.Products & OutputProducts.Noise) != 0 && c.Result.Noise is { } noise
                ? NoiseProduct.ExrChannels(c.Scene, noise, c.Image.Width * c.Image.Height) : null);

    public override bool Owns(string file) => file == "spectral.exr";
    public override ShardMerging Merging(string file) => ShardMerging.ExrChunks;
}
