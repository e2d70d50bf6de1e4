using System.Buffers.Binary;
using System.Globalization;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Writes an ENVI raster (ENVI Header Format, NV5 Geospatial "ENVI Header Files" documentation):
/// a flat binary file of float32 values (data type = 4), little-endian (byte order = 0), band-sequential
/// (interleave = bsq: band 0 row by row, then band 1, …), and a text header beside it, same name with .hdr,
/// carrying samples (width), lines (height), bands, wavelength (band centres), fwhm (band widths) and band names.
/// GDAL's ENVI driver and ENVI/spectral python read it.
/// </summary>
public static class EnviWriter
{
    /// <summary>Writes <paramref name="imagePath"/> (e.g. spectral.img) and its header (spectral.hdr).</summary>
    public static void Write(string imagePath, SpectralImage image, string? description = null) =>
        Write(imagePath, image, image.BandPlanes(), description);

    /// <summary>As <see cref="Write(string, SpectralImage, string?)"/>, from the image's band planes
    /// (<see cref="SpectralImage.CopyBands"/>) — already BSQ.</summary>
    /// <param name="extra">Further header keys (e.g. "radiometry", "data units"), written after the standard ones.</param>
    internal static void Write(string imagePath, SpectralImage image, float[] bands, string? description = null,
        IReadOnlyDictionary<string, string>? extra = null)
    {
        AtomicFile.Write(imagePath, s => WriteData(s, bands));
        AtomicFile.WriteAllText(HeaderPath(imagePath), Header(image, description, extra));
    }

    /// <summary>
    /// Band-sequential float32 planes of <paramref name="width"/> × <paramref name="height"/> with named bands and no wavelength
    /// axis (a cube whose bands are not all spectral, e.g. standard errors per band and of luminance), and its header.
    /// </summary>
    internal static void WritePlanes(string imagePath, int width, int height, float[] planes, IReadOnlyList<string> bandNames,
        string description, IReadOnlyDictionary<string, string>? extra = null)
    {
        if (planes.Length != (long)width * height * bandNames.Count)
            throw new ArgumentException($"planes hold {planes.Length} values, {width}×{height}×{bandNames.Count} expected");
        AtomicFile.Write(imagePath, s => WriteData(s, planes));
        var inv = CultureInfo.InvariantCulture;
        var sb = new StringBuilder("ENVI\n");
        sb.Append($"description = {{{description.Replace('{', '(').Replace('}', ')').Replace("\r", " ").Replace("\n", " ")}}}\n");
        sb.Append(inv, $"samples = {width}\nlines = {height}\nbands = {bandNames.Count}\n");
        sb.Append("header offset = 0\nfile type = ENVI Standard\ndata type = 4\ninterleave = bsq\nbyte order = 0\n");
        sb.Append("band names = {").AppendJoin(", ", bandNames.Select(b => b.Replace(',', ';').Replace('{', '(').Replace('}', ')')))
            .Append("}\n");
        if (extra is not null)
            foreach (var (k, v) in extra) sb.Append($"{k} = {v.Replace('{', '(').Replace('}', ')').Replace("\n", " ")}\n");
        AtomicFile.WriteAllText(HeaderPath(imagePath), sb.ToString());
    }

    /// <summary>The header path ENVI and GDAL look for: the image path with its extension replaced by .hdr.</summary>
    public static string HeaderPath(string imagePath) => Path.ChangeExtension(imagePath, ".hdr");

    /// <summary>Band-sequential planes as float32 little-endian: one large write on a little-endian machine.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void WriteData(Stream stream, ReadOnlySpan<float> bands)
    {
        if (BitConverter.IsLittleEndian) { stream.Write(MemoryMarshal.AsBytes(bands)); return; }
        var bytes = new byte[4 << 14];
        for (int at = 0; at < bands.Length; at += bytes.Length / 4)
        {
            int n = Math.Min(bytes.Length / 4, bands.Length - at);
            for (int i = 0; i < n; i++) BinaryPrimitives.WriteSingleLittleEndian(bytes.AsSpan(4 * i), bands[at + i]);
            stream.Write(bytes, 0, 4 * n);
        }
    }

    /// <summary>The header text. Keys per the ENVI header format; lists in braces; no braces inside the description.</summary>
    public static string Header(SpectralImage image, string? description = null, IReadOnlyDictionary<string, string>? extra = null)
    {
        var inv = CultureInfo.InvariantCulture;
        var g = image.Grid;
        string List(Func<int, string> item)
        {
            var list = new StringBuilder("{");
            for (int b = 0; b < g.Count; b++) list.Append(b > 0 ? ", " : "").Append(item(b));
            return list.Append('}').ToString();
        }
        description ??= $"SpectralRenderer spectral radiance, bands {g}";
        description = description.Replace('{', '(').Replace('}', ')').Replace("\r", " ").Replace("\n", " ");
        var sb = new StringBuilder();
        sb.Append("ENVI\n");
        sb.Append($"description = {{{description}}}\n");
        sb.Append(inv, $"samples = {image.Width}\n");
        sb.Append(inv, $"lines = {image.Height}\n");
        sb.Append(inv, $"bands = {image.Bands}\n");
        sb.Append("header offset = 0\n");
        sb.Append("file type = ENVI Standard\n");
        sb.Append("data type = 4\n");           // 4 = 32-bit IEEE float
        sb.Append("interleave = bsq\n");
        sb.Append("byte order = 0\n");          // 0 = little-endian (least significant byte first)
        sb.Append("wavelength units = Nanometers\n");
        sb.Append($"wavelength = {List(b => g.Centre(b).ToString("R", inv))}\n");
        sb.Append($"fwhm = {List(b => (g.Upper(b) - g.Lower(b)).ToString("R", inv))}\n");
        sb.Append($"band names = {List(b => string.Create(inv, $"{g.Lower(b):0.###}-{g.Upper(b):0.###} nm"))}\n");
        if (extra is not null)
            foreach (var (k, v) in extra) sb.Append($"{k} = {v.Replace('{', '(').Replace('}', ')').Replace("\n", " ")}\n");
        return sb.ToString();
    }
}
