using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Imaging;

/// <summary>
/// The multispectral cubes of a render: spectral.exr (spectral OpenEXR layout), spectral.hdr/.img (ENVI),
/// spectral.npy + wavelengths.csv (NumPy), and the reader that finds whichever of them a folder holds.
/// </summary>
public static class SpectralFiles
{
    public static void Write(Scene scene, SpectralImage image, string outDir, IReadOnlySet<string> formats, Action<string> done) =>
        Write(scene, image, null, null, outDir, formats, done);

    /// <param name="bands">The image's band planes (<see cref="SpectralImage.CopyBands"/>) when the caller has them already.</param>
    /// <param name="xyz">Their <see cref="XyzPlanes"/> of scene.Colorimeter, likewise.</param>
    internal static void Write(Scene scene, SpectralImage image, float[]? bands, XyzPlanes? xyz, string outDir, IReadOnlySet<string> formats, Action<string> done)
    {
        if (bands is null && (formats.Contains("exr") || formats.Contains("envi"))) bands = image.BandPlanes();
        if (formats.Contains("exr"))
        {
            ExrWriter.Write(Path.Combine(outDir, "spectral.exr"), image.Width, image.Height, image.Grid, bands!, xyz, new ExrOptions
            {
                Colorimeter = scene.Colorimeter,
                Xyz = true,
                Attributes = new Dictionary<string, string> { ["software"] = $"spectral {typeof(SpectralFiles).Assembly.GetName().Version?.ToString(3)}" },
            });
            done("spectral.exr");
        }
        if (formats.Contains("envi"))
        {
            EnviWriter.Write(Path.Combine(outDir, "spectral.img"), image, bands!, $"SpectralRenderer render of {Path.GetFileName(scene.SourcePath)}; spectral radiance, {scene.Integration.ToString().ToLowerInvariant()} band integration");
            done("spectral.img");
            done("spectral.hdr");
        }
        if (formats.Contains("npy"))
        {
            NpyWriter.Write(Path.Combine(outDir, "spectral.npy"), image);
            done("spectral.npy");
        }
        if (formats.Contains("npy") || formats.Contains("envi") || formats.Contains("exr"))
        {
            WavelengthsCsv.Write(Path.Combine(outDir, "wavelengths.csv"), image.Grid);
            done("wavelengths.csv");
        }
    }

    /// <summary>Reads the spectral cube of a render folder: spectral.npy, else spectral.exr, else spectral.img.</summary>
    public static SpectralImage Read(string outDir, Spectra.BandGrid grid)
    {
        var npy = Path.Combine(outDir, "spectral.npy");
        if (File.Exists(npy)) return NpyReader.ReadImage(npy, grid);
        var exr = Path.Combine(outDir, "spectral.exr");
        if (File.Exists(exr)) return ExrReader.Read(exr).Image;
        var img = Path.Combine(outDir, "spectral.img");
        if (File.Exists(img)) return EnviReader.Read(img);
        throw new Diagnostics.InputException(outDir, "holds no spectral cube (spectral.npy, spectral.exr or spectral.img)",
            "render with --formats including npy, exr or envi");
    }
}
