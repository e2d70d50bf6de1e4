using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>
/// A render's output folder read back from disk: the spectral cube, the object-id image and what
/// render.json records (band grid, eq. 3 weights, reference white, object names and reflectances).
/// </summary>
public sealed class RenderFolder
{
    public required string Path { get; init; }
    public required RenderManifest Manifest { get; init; }
    public required SpectralImage Image { get; init; }
    public required int[] ObjectIds { get; init; }
    public string[] ObjectNames => Manifest.Objects.Select(o => o.Name).ToArray();
    public string?[] ObjectReflectances => Manifest.Objects.Select(o => o.Reflectance).ToArray();
    public double[] Wx => Manifest.Wx;
    public double[] Wy => Manifest.Wy;
    public double[] Wz => Manifest.Wz;
    public Xyz White => Manifest.White;
    public TabulatedSpectrum ReferenceWhite => Manifest.ReferenceWhite;
    public int ObserverDegrees => Manifest.ObserverDegrees;
    public BandIntegration Integration => Manifest.Integration;
    /// <summary>
    /// Each pixel's colour as the render computed it (spectral.exr's X, Y, Z planes, or xyz.npy when the formats left the
    /// EXR out: with exact integration the colour of the pixel's full-resolution spectrum), or null for a folder that has
    /// neither (a cube from elsewhere: then eq. 3 on the cube stands in).
    /// </summary>
    public (float[] X, float[] Y, float[] Z)? PixelXyz { get; init; }

    public static RenderFolder Open(string dir)
    {
        var (manifest, image) = OpenCube(dir);
        (float[], float[], float[])? pixelXyz = null;
        var exr = System.IO.Path.Combine(dir, "spectral.exr");
        if (File.Exists(exr))
        {
            var f = ExrReader.Read(exr);
            if (f.OtherChannels.TryGetValue("X", out var px) && f.OtherChannels.TryGetValue("Y", out var py)
                && f.OtherChannels.TryGetValue("Z", out var pz))
                pixelXyz = (px, py, pz);
        }
        else pixelXyz = ReadColour(System.IO.Path.Combine(dir, Output.Products.ColourProduct.FileName), image);
        return new RenderFolder { Path = dir, Manifest = manifest, Image = image, ObjectIds = ReadIds(dir, image), PixelXyz = pixelXyz };
    }

    /// <summary>
    /// A render folder's manifest and spectral cube, validated: render.json present and consistent with itself
    /// (a folder without one is not a render), and the cube of the size and band count it describes.
    /// </summary>
    public static (RenderManifest Manifest, SpectralImage Image) OpenCube(string dir)
    {
        if (!Directory.Exists(dir)) throw new InputException(dir, "no such render folder", "give the -o folder of a 'spectral render' run");
        var manifest = RenderManifest.Read(dir).Whole(dir);
        var grid = manifest.Grid;
        var image = SpectralFiles.Read(dir, grid);
        if (image.Width != manifest.Width || image.Height != manifest.Height || image.Bands != grid.Count)
            throw new InputException($"{System.IO.Path.Combine(dir, RenderManifest.FileName)}: $.width",
                $"describes {manifest.Width}×{manifest.Height}×{grid.Count} but the spectral cube is "
                    + $"{image.Width}×{image.Height}×{image.Bands}",
                "the folder mixes two renders; render again into an empty folder");
        return (manifest, image);
    }

    /// <summary>xyz.npy's X, Y, Z planes (null when the folder has none), checked against the cube's size.</summary>
    static (float[], float[], float[])? ReadColour(string path, SpectralImage image)
    {
        if (!File.Exists(path)) return null;
        int[] shape; float[] data;
        using (var s = File.OpenRead(path)) (shape, data) = NpyReader.Read(s, path);
        if (shape is not [var h, var w, 3] || h != image.Height || w != image.Width)
            throw new InputException(path, $"has shape ({string.Join(", ", shape)}), ({image.Height}, {image.Width}, 3) expected",
                "the render folder mixes files of different renders: render it again");
        int n = w * h;
        float[] x = new float[n], y = new float[n], z = new float[n];
        for (int i = 0; i < n; i++) { x[i] = data[3 * i]; y[i] = data[3 * i + 1]; z[i] = data[3 * i + 2]; }
        return (x, y, z);
    }

    static int[] ReadIds(string dir, SpectralImage image)
    {
        var path = System.IO.Path.Combine(dir, "object-id.png");
        if (!File.Exists(path)) throw new InputException(dir, "has no object-id.png", "render with --formats including aov");
        var png = PngReader.Read(path);
        if (png.Width != image.Width || png.Height != image.Height)
            throw new InputException(path, $"is {png.Width}×{png.Height} but the cube is {image.Width}×{image.Height}",
                "the render folder mixes files of different renders: render it again");
        var ids = new int[png.Width * png.Height];
        for (int i = 0; i < ids.Length; i++) ids[i] = png.Samples[i * png.Channels] - 1;
        return ids;
    }

    public int ObjectIndex(string name) => Array.IndexOf(ObjectNames, name);

    /// <summary>Eq. 3 with the render's own weights.</summary>
    public Xyz ToXyz(ReadOnlySpan<double> bands) => Manifest.ToXyz(bands);

    /// <summary>The mean colour of the pixels showing object <paramref name="index"/>: of the render's own pixel XYZ when it has them, else
    /// eq. 3 on the mean spectrum.</summary>
    public Xyz MeanXyz(int index)
    {
        if (PixelXyz is not { } p) return ToXyz(MeanSpectrum(index).Mean);
        double x = 0, y = 0, z = 0;
        int count = 0;
        for (int i = 0; i < ObjectIds.Length; i++)
            if (ObjectIds[i] == index) { x += p.X[i]; y += p.Y[i]; z += p.Z[i]; count++; }
        return count == 0 ? new Xyz(0, 0, 0) : new Xyz(x / count, y / count, z / count);
    }

    /// <summary>The mean spectrum of all pixels showing object <paramref name="index"/>, and their count.</summary>
    public (double[] Mean, int Pixels) MeanSpectrum(int index)
    {
        var sum = new double[Image.Bands];
        int count = 0;
        for (int i = 0; i < ObjectIds.Length; i++)
        {
            if (ObjectIds[i] != index) continue;
            var px = Image.Data.AsSpan(i * Image.Bands, Image.Bands);
            for (int b = 0; b < sum.Length; b++) sum[b] += px[b];
            count++;
        }
        if (count > 0) for (int b = 0; b < sum.Length; b++) sum[b] /= count;
        return (sum, count);
    }
}
