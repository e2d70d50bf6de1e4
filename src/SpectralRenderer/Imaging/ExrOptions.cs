using SpectralRenderer.Color;

namespace SpectralRenderer.Imaging;

/// <summary>The OpenEXR compression attribute values we write (OpenEXR file layout, "compression" attribute).</summary>
public enum ExrCompression : byte
{
    /// <summary>NO_COMPRESSION: one scanline per chunk, stored raw.</summary>
    None = 0,
    /// <summary>ZIP_COMPRESSION: 16 scanlines per chunk, byte reordering + delta predictor + zlib.</summary>
    Zip = 3,
}

/// <summary>OpenEXR channel pixel types (chlist "pixel type": 0 UINT, 1 HALF, 2 FLOAT).</summary>
public enum ExrPixelType
{
    Half = 1,
    Float = 2,
}

/// <summary>
/// How <see cref="ExrWriter"/> writes a spectral image. <see cref="Colorimeter"/> is required for the
/// <see cref="Rgb"/> and <see cref="Xyz"/> preview channels and supplies spectralKappa / spectralIntegration.
/// </summary>
public sealed record ExrOptions
{
    public ExrCompression Compression { get; init; } = ExrCompression.Zip;
    /// <summary>
    /// ZIP only: deflate every chunk (the smallest file) rather than only the chunks whose samples mostly repeat
    /// (<see cref="ExrZip.MinRepeatFraction"/>), which is several times faster on noisy radiance: the others are stored
    /// raw, as OpenEXR allows per chunk.
    /// </summary>
    public bool DeflateEveryChunk { get; init; }
    /// <summary>Pixel type of every channel (spectral and preview).</summary>
    public ExrPixelType PixelType { get; init; } = ExrPixelType.Float;
    /// <summary>Adds R, G, B: linear sRGB (IEC 61966-2-1 matrix) of each pixel's XYZ, so ordinary viewers show a picture.</summary>
    public bool Rgb { get; init; } = true;
    /// <summary>Adds X, Y, Z: each pixel's CIE XYZ (eq. 3).</summary>
    public bool Xyz { get; init; }
    /// <summary>Names spectral channels T.&lt;λ&gt;nm (reflectance) instead of S0.&lt;λ&gt;nm (emitted radiance).</summary>
    public bool Reflective { get; init; }
    public Colorimeter? Colorimeter { get; init; }
    /// <summary>
    /// A partial image (a crop or shard of a render): the file's pixels are the data window whose top-left pixel is
    /// (<see cref="DataX"/>, <see cref="DataY"/>) inside a display window of <see cref="DisplayWidth"/> ×
    /// <see cref="DisplayHeight"/> (OpenEXR "dataWindow"/"displayWindow", as pbrt's --cropwindow writes). 0: the
    /// display window is the data window.
    /// </summary>
    public int DataX { get; init; }
    public int DataY { get; init; }
    public int DisplayWidth { get; init; }
    public int DisplayHeight { get; init; }
    /// <summary>The emissiveUnits attribute of emissive files (JCGT 2021 §3), or null to omit it when the values have no unit.</summary>
    public string? EmissiveUnits { get; init; } = ExrWriter.EmissiveUnits;
    /// <summary>Further FLOAT channels (name, row-major plane of the image's size), e.g. a layer "stderr." beside the bands.</summary>
    public IReadOnlyList<(string Name, float[] Plane)>? ExtraChannels { get; init; }
    /// <summary>Extra string attributes (e.g. "software", "comments").</summary>
    public IReadOnlyDictionary<string, string>? Attributes { get; init; }
}
