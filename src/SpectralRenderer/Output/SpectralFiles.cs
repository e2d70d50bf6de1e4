using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

/// <summary>
/// The multispectral cubes of a render: spectral.exr (spectral OpenEXR layout), spectral.hdr/.img (ENVI),
/// spectral.npy + wavelengths.csv (NumPy), and the reader that finds whichever of them a folder holds.
/// </summary>
public static class SpectralFiles
{
    /// <param name="bands">The image's band planes (<see cref="SpectralImage.CopyBands"/>).</param>
    /// <param name="xyz">Their <see cref="XyzPlanes"/> of scene.Colorimeter when the caller has them already.</param>
    /// <param name="crop">The film pixels the image holds: the EXR's data window inside the film's display window.</param>
    /// <param name="extra">Further channels (the noise product's stderr layer), or null.</param>
    internal static void WriteExr(Scene scene, SpectralImage image, float[] bands, XyzPlanes? xyz, PixelRect crop, string outDir,
        Action<string> done,
        IReadOnlyList<(string Name, float[] Plane)>? extra = null)
    {
        ExrWriter.Write(Path.Combine(outDir, "spectral.exr"), image.Width, image.Height, image.Grid, bands, xyz, new ExrOptions
        {
            Colorimeter = scene.Colorimeter,
            Xyz = true,
            Compression = scene.Output.ExrCompression == ExrCompressionChoice.None ? ExrCompression.None : ExrCompression.Zip,
            DeflateEveryChunk = scene.Output.ExrCompression == ExrCompressionChoice.ZipAll,
            // JCGT 2021's emissiveUnits names the unit of the S0 channels: only true for physical radiometry.
            EmissiveUnits = scene.Radiometry == Radiometry.Physical ? ExrWriter.EmissiveUnits : null,
            DataX = crop.X0,
            DataY = crop.Y0,
            DisplayWidth = scene.Camera.Width,
            DisplayHeight = scene.Camera.Height,
            ExtraChannels = extra,
            Attributes = new Dictionary<string, string>
            {
                ["software"] = $"spectral {typeof(SpectralFiles).Assembly.GetName().Version?.ToString(3)}",
                ["spectralRadiometry"] = $"{scene.Radiometry.ToString().ToLowerInvariant()}: {RenderOutputWriter.RadianceUnit(scene)}",
            },
        });
        done("spectral.exr");
    }

    /// <summary>spectral.img and spectral.hdr.</summary>
    internal static void WriteEnvi(Scene scene, SpectralImage image, float[] bands, string outDir, Action<string> done)
    {
        EnviWriter.Write(Path.Combine(outDir, "spectral.img"), image, bands,
            $"SpectralRenderer render of {Path.GetFileName(scene.SourcePath)}; {scene.Radiometry.ToString().ToLowerInvariant()} "
                + $"radiometry, band values in {RenderOutputWriter.RadianceUnit(scene)}; "
                + $"{scene.Integration.ToString().ToLowerInvariant()} band integration",
            new Dictionary<string, string>
            {
                ["radiometry"] = scene.Radiometry.ToString().ToLowerInvariant(),
                ["data units"] = scene.Radiometry == Radiometry.Physical ? "W.m^-2.sr^-1.nm^-1" : "relative",
            });
        done("spectral.img");
        done("spectral.hdr");
    }

    internal static void WriteNpy(SpectralImage image, string outDir, Action<string> done)
    {
        NpyWriter.Write(Path.Combine(outDir, "spectral.npy"), image);
        done("spectral.npy");
    }

    internal static void WriteWavelengths(SpectralImage image, string outDir, Action<string> done)
    {
        WavelengthsCsv.Write(Path.Combine(outDir, "wavelengths.csv"), image.Grid);
        done("wavelengths.csv");
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
