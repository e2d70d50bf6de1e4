using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"envi": spectral.img and spectral.hdr, the ENVI cube (band-sequential float32).</summary>
public sealed class EnviProduct : OutputProduct
{
    public override string Name => "envi";
    public override OutputProducts Flag => OutputProducts.Envi;
    public override ProductInputs Needs => ProductInputs.BandPlanes;

    public override void Write(ProductContext c, int part, Action<string> done) =>
        SpectralFiles.WriteEnvi(c.Scene, c.Image, c.BandPlanes!, c.OutDir, done);

    public override bool Owns(string file) => file is "spectral.img" or "spectral.hdr";
    public override ShardMerging Merging(string file) => file == "spectral.hdr" ? ShardMerging.EnviHeader : ShardMerging.EnviCube;
}
