using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// xyz.npy: every pixel's colour as the render computed it (H × W × 3 float32 X, Y, Z, κ included; with "exact" band
/// integration the colour of each term's full-resolution spectrum, not eq. 3 on the bands), kept with every render whose
/// formats leave out spectral.exr (which holds the same values in its X, Y, Z channels), so that `colorcheck`, the report
/// and every analysis of a render folder read the render's own colour whatever --formats said.
/// </summary>
public sealed class ColourProduct : OutputProduct
{
    public const string FileName = "xyz.npy";

    public override string Name => "xyz";
    public override bool Wanted(OutputProducts asked) => (asked & OutputProducts.Exr) == 0;
    public override ProductInputs Needs => ProductInputs.Xyz;

    public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads)
    {
        yield return (FileName, 12L * scene.Camera.Width * scene.Camera.Height);
    }

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        var xyz = c.Xyz!;
        int w = c.Image.Width, h = c.Image.Height, n = w * h;
        var data = new float[3 * n];
        // The same float32 values as spectral.exr's X, Y, Z channels (ExrWriter), interleaved per pixel.
        for (int i = 0; i < n; i++) { data[3 * i] = (float)xyz.X[i]; data[3 * i + 1] = (float)xyz.Y[i]; data[3 * i + 2] = (float)xyz.Z[i]; }
        AtomicFile.Write(Path.Combine(c.OutDir, FileName), s => NpyWriter.Write(s, [h, w, 3], data));
        done(FileName);
    }

    public override bool Owns(string file) => file == FileName;
    public override ShardMerging Merging(string file) => ShardMerging.NpyColour;
}
