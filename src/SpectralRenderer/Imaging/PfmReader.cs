using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Reads Portable FloatMap pictures (<c>.pfm</c>): <c>PF</c> (colour) or <c>Pf</c> (grey, copied to R, G and B), the width and
/// height, then a scale whose sign gives the byte order (negative: little-endian), then 32-bit floats with the rows stored
/// bottom to top (returned top to bottom).
/// </summary>
public static class PfmReader
{
    public static RgbImage Read(string path) => Read(InputFile.ReadAllBytes(path, "PFM picture"), path);

    public static RgbImage Read(byte[] bytes, string where)
    {
        int pos = 0;
        string Token()
        {
            while (pos < bytes.Length && char.IsWhiteSpace((char)bytes[pos])) pos++;
            int start = pos;
            while (pos < bytes.Length && !char.IsWhiteSpace((char)bytes[pos])) pos++;
            if (pos >= bytes.Length) throw new InputException(where, "the header is truncated", "the file is not a PFM picture");
            return Encoding.ASCII.GetString(bytes, start, pos - start);
        }
        var magic = Token();
        if (magic != "PF" && magic != "Pf")
            throw new InputException(where, "not a PFM picture (no PF or Pf first word)",
                "write the environment map as PFM, .hdr or OpenEXR");
        int channels = magic == "PF" ? 3 : 1;
        if (!int.TryParse(Token(), NumberStyles.None, CultureInfo.InvariantCulture, out int width)
            | !int.TryParse(Token(), NumberStyles.None, CultureInfo.InvariantCulture, out int height)
            || width < 1 || height < 1 || width > RgbeReader.MaxSide || height > RgbeReader.MaxSide)
            throw new InputException(where, "the width or height is not a number in 1–32768", "the header is W H after PF");
        if (!double.TryParse(Token(), NumberStyles.Float, CultureInfo.InvariantCulture, out double scale) || scale == 0
            || !double.IsFinite(scale))
            throw new InputException(where, "the scale is not a non-zero number", "its sign gives the byte order (−1: little-endian)");
        pos++;   // the single whitespace byte after the scale
        long need = 4L * channels * width * height;
        if (pos + need > bytes.Length)
            throw new InputException(where, $"the pixels need {need} bytes, the file has {bytes.Length - pos}", "the file is truncated");
        var rgb = new float[3 * width * height];
        for (int row = 0; row < height; row++)
            for (int x = 0; x < width; x++)
                for (int c = 0; c < 3; c++)
                {
                    var b = bytes.AsSpan(pos + 4 * (channels * (row * width + x) + Math.Min(c, channels - 1)), 4);
                    float v = scale < 0 ? BinaryPrimitives.ReadSingleLittleEndian(b) : BinaryPrimitives.ReadSingleBigEndian(b);
                    rgb[3 * ((height - 1 - row) * width + x) + c] = v;
                }
        return new RgbImage(width, height, rgb);
    }
}
