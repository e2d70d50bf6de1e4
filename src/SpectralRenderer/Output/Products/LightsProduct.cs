using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>"lights": lights/, the per-light transfer that relight and view recombine (whole renders only: not merged).</summary>
public sealed class LightsProduct : OutputProduct
{
    public override string Name => "lights";
    public override OutputProducts Flag => OutputProducts.Lights;

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        if (c.Transfer is not null) LightTransferFiles.Write(c.Scene, c.Transfer, c.OutDir, done);
    }

    public override bool Owns(string file) => file.StartsWith(LightTransferFiles.Folder + "/", StringComparison.Ordinal);
}
