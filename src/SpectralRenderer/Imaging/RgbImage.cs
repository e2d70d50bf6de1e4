using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>A linear RGB image: <see cref="Rgb"/> holds R, G, B per pixel, rows top to bottom.</summary>
public sealed record RgbImage(int Width, int Height, float[] Rgb)
{
    /// <summary>
    /// The pixels of a high-dynamic-range file by its extension: OpenEXR (.exr: scanline, R, G and B channels of HALF, FLOAT or
    /// UINT, none, ZIPS or ZIP compression — PIZ and the others are refused with a hint), Radiance (.hdr, .pic) or PFM (.pfm).
    /// </summary>
    public static RgbImage Read(string path)
    {
        switch (Path.GetExtension(path).ToLowerInvariant())
        {
            case ".hdr" or ".pic":
                return RgbeReader.Read(path);
            case ".pfm":
                return PfmReader.Read(path);
            case ".exr":
                {
                    var (width, height, channels, planes, _, _, _, _) =
                        ExrReader.ReadChannels(InputFile.ReadAllBytes(path, "OpenEXR image"), path);
                    float[] Plane(string name)
                    {
                        int i = channels.FindIndex(c => c.Name == name);
                        return i >= 0 ? planes[i]
                            : throw new InputException(path, $"no '{name}' channel", "an RGB image has R, G and B channels");
                    }
                    var (r, g, b) = (Plane("R"), Plane("G"), Plane("B"));
                    var rgb = new float[3 * width * height];
                    for (int i = 0; i < width * height; i++) { rgb[3 * i] = r[i]; rgb[3 * i + 1] = g[i]; rgb[3 * i + 2] = b[i]; }
                    return new RgbImage(width, height, rgb);
                }
            default:
                throw new InputException(path, $"'{Path.GetExtension(path)}' is not a high-dynamic-range image format",
                    "give an OpenEXR (.exr), Radiance (.hdr) or PFM (.pfm) image");
        }
    }
}
