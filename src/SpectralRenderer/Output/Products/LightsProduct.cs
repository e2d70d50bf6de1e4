using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// "lights": lights/, the per-light transfer that relight and view recombine, written by the integrator's transfer
/// (<see cref="ILightTransfer"/>); its format says its memory (counted by <see cref="RenderMemory"/> for the integrator
/// the render uses) and whether shards write it (then merged by rows).
/// </summary>
public sealed class LightsProduct : OutputProduct
{
    public override string Name => "lights";
    public override OutputProducts Flag => OutputProducts.Lights;

    public override void Write(ProductContext c, int part, Action<string> done) => c.Transfer?.Write(c.Scene, c.OutDir, done);

    /// <summary>Shards of a transfer its format shards: the arrays by rows, lights.json the same in each.</summary>
    public override ShardMerging Merging(string file) =>
        file == $"{TransferFormat.Folder}/{TransferFormat.Description}" ? ShardMerging.Copy
        : Owns(file) ? ShardMerging.TransferRows
        : ShardMerging.None;

    public override bool Owns(string file) => file.StartsWith(TransferFormat.Folder + "/", StringComparison.Ordinal);
}
