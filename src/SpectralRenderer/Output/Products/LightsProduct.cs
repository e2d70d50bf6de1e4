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
        else if (c.PathTransfer is not null) PathTransferFiles.Write(c.Scene, c.PathTransfer, c.OutDir, done);
    }

    /// <summary>A path scene's transfer: (K + 1) × F floats per pixel, and K × R × C with a fluorescent shift. A Whitted
    /// transfer's factors are known only once traced; its textured terms' texel samples (S per term and pixel, issue 26) are
    /// counted for a first hit.</summary>
    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads) => scene.Integrator is { Name: "path" }
        ? [("per-light transfer (path)", Rendering.PathTransfer.Bytes(scene, (long)scene.Camera.Width * scene.Camera.Height))]
        : Rendering.LightTransfer.TexelBytes(scene) is > 0 and var texels
            ? [("per-light transfer: texel samples of textured terms", texels)]
            : [];

    /// <summary>Shards of a path render (the only lights a shard writes): the arrays by rows, lights.json the same in each.</summary>
    public override ShardMerging Merging(string file) => file switch
    {
        "lights/" + PathTransferFiles.TransferFile => ShardMerging.PathTransfer,
        "lights/" + PathTransferFiles.ShiftFile => ShardMerging.PathShift,
        "lights/" + PathTransferFiles.IdsFile => ShardMerging.PathIds,
        "lights/lights.json" => ShardMerging.Copy,
        _ => ShardMerging.None,
    };

    public override bool Owns(string file) => file.StartsWith(LightTransferFiles.Folder + "/", StringComparison.Ordinal);
}
