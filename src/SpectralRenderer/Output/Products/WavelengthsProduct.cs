using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>wavelengths.csv, the band rows beside any spectral cube (exr, envi, npy); not asked for by itself.</summary>
public sealed class WavelengthsProduct : OutputProduct
{
    public override string Name => "wavelengths";
    public override bool Wanted(OutputProducts asked) => (asked & (OutputProducts.Npy | OutputProducts.Envi | OutputProducts.Exr)) != 0;

    public override void Write(ProductContext c, int part, Action<string> done) => SpectralFiles.WriteWavelengths(c.Image, c.OutDir, done);

    public override bool Owns(string file) => file == "wavelengths.csv";
    public override ShardMerging Merging(string file) => ShardMerging.Copy;
}
