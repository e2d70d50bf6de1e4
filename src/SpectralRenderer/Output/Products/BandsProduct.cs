using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// "bands": bands/ (one 16-bit PNG per band on the common scale) and, side by side with them, the mosaic bands.png (Fig. 2).
/// </summary>
public sealed class BandsProduct : OutputProduct
{
    public override string Name => "bands";
    public override OutputProducts Flag => OutputProducts.Bands;
    public override ProductInputs Needs => ProductInputs.BandPlanes;
    public override int Parts => 2;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height, bands = scene.Bands;
        yield return ("band PNGs", Math.Min(threads, bands) * (2 * n + 2 * 2 * n));
        yield return ("bands.png", 2 * n * bands);
    }

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        if (part == 0) { RenderOutputWriter.WriteBands(c.Scene, c.Image, c.BandPlanes!, c.BandScale, c.OutDir, done, c.Cancel); return; }
        var (mw, mh, mosaic) = BandMosaic.Build(c.Image.Width, c.Image.Height, c.BandPlanes!, c.BandScale, 256, c.Scene.Grid);
        AtomicFile.Write(Path.Combine(c.OutDir, "bands.png"), s => PngWriter.WriteGray8(s, mw, mh, mosaic));
        done("bands.png");
    }

    public override bool Owns(string file) => file == "bands.png" || file.StartsWith("bands/", StringComparison.Ordinal);
    public override ShardMerging Merging(string file) => ShardMerging.BandImages;
}
