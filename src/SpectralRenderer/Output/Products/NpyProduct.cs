using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"npy": spectral.npy, the H × W × N NumPy array.</summary>
public sealed class NpyProduct : OutputProduct
{
    public override string Name => "npy";
    public override OutputProducts Flag => OutputProducts.Npy;

    public override void Write(ProductContext c, int part, Action<string> done) => SpectralFiles.WriteNpy(c.Image, c.OutDir, done);

    public override bool Owns(string file) => file == "spectral.npy";
    public override ShardMerging Merging(string file) => ShardMerging.NpyCube;
}
