using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Reads Radiance RGBE pictures (<c>.hdr</c>, <c>.pic</c>; Ward, "Real Pixels", Graphics Gems II, 1991, and Radiance's
/// file-format notes): the text header (<c>#?RADIANCE</c> or <c>#?RGBE</c>, <c>FORMAT=32-bit_rle_rgbe</c>), the resolution line
/// <c>-Y H +X W</c> (rows top to bottom, the standard orientation; others are refused), then each scanline flat or in the
/// adaptive run-length form (a 2, 2, W/256, W%256 marker, then each of the four components as runs). A pixel (r, g, b, e)
/// is c·2^(e − 136) per component, 0 when e = 0 (the common reading, as stb_image and Walter's rgbe.c decode it). The
/// header's EXPOSURE is not applied: the values are what the file holds, as Mitsuba reads them.
/// </summary>
public static class RgbeReader
{
    /// <summary>The largest width or height accepted (the marker's 15-bit width bounds a run-length scanline).</summary>
    public const int MaxSide = 1 << 15;

    public static RgbImage Read(string path) => Read(InputFile.ReadAllBytes(path, "Radiance HDR picture"), path);

    public static RgbImage Read(byte[] bytes, string where)
    {
        int pos = 0;
        string Line()
        {
            int start = pos;
            while (pos < bytes.Length && bytes[pos] != (byte)'\n') pos++;
            if (pos >= bytes.Length)
                throw new InputException(where, "the header ends before the resolution line", "the file is truncated or not RGBE");
            var s = Encoding.ASCII.GetString(bytes, start, pos - start);
            pos++;
            return s;
        }
        var magic = Line();
        if (magic != "#?RADIANCE" && magic != "#?RGBE")
            throw new InputException(where, "not a Radiance HDR picture (no #?RADIANCE or #?RGBE first line)",
                "write the environment map as Radiance .hdr, OpenEXR or PFM");
        for (string line; (line = Line()).Length > 0;)
        {
            if (line.StartsWith("FORMAT=", StringComparison.Ordinal) && line != "FORMAT=32-bit_rle_rgbe")
                throw new InputException(where, $"pixel format '{MessageText.Escape(line[7..])}' is not supported",
                    "only 32-bit_rle_rgbe (RGB) pictures are read; convert XYZE to RGBE");
        }
        var res = Line().Split(' ', StringSplitOptions.RemoveEmptyEntries);
        if (res.Length != 4 || res[0] != "-Y" || res[2] != "+X"
            || !int.TryParse(res[1], NumberStyles.None, CultureInfo.InvariantCulture, out int height)
            || !int.TryParse(res[3], NumberStyles.None, CultureInfo.InvariantCulture, out int width))
            throw new InputException(where, $"resolution line '{MessageText.Escape(string.Join(' ', res))}' is not '-Y H +X W'",
                "only the standard orientation (rows top to bottom, left to right) is read");
        if (width < 1 || height < 1 || width >= MaxSide || height >= MaxSide)
            throw new InputException(where, $"image size {width} × {height} is outside 1–{MaxSide - 1}", "a smaller picture");
        var rgb = new float[3L * width * height <= int.MaxValue ? 3 * width * height
            : throw new InputException(where, "the image is too large", "a smaller picture")];
        var scan = new byte[4 * width];
        for (int y = 0; y < height; y++)
        {
            pos = Scanline(bytes, pos, scan, width, where, y);
            for (int x = 0; x < width; x++)
            {
                int e = scan[4 * x + 3];
                float f = e == 0 ? 0 : MathF.ScaleB(1, e - 136);
                int o = 3 * (y * width + x);
                rgb[o] = scan[4 * x] * f;
                rgb[o + 1] = scan[4 * x + 1] * f;
                rgb[o + 2] = scan[4 * x + 2] * f;
            }
        }
        return new RgbImage(width, height, rgb);
    }

    /// <summary>One scanline of <paramref name="width"/> RGBE pixels from <paramref name="pos"/> into scan; returns the next
    /// position.</summary>
    static int Scanline(byte[] bytes, int pos, byte[] scan, int width, string where, int y)
    {
        InputException Truncated() => new(where, $"scanline {y} is truncated", "the file ends early; write it again");
        bool runLength = width >= 8 && width < MaxSide && pos + 4 <= bytes.Length && bytes[pos] == 2 && bytes[pos + 1] == 2
            && (bytes[pos + 2] & 0x80) == 0;
        if (!runLength)
        {   // flat pixels (the old run-length form, a (1, 1, 1, n) repeat, is not read)
            if (pos + 4 * width > bytes.Length) throw Truncated();
            for (int i = 0; i < width; i++)
                if (bytes[pos + 4 * i] == 1 && bytes[pos + 4 * i + 1] == 1 && bytes[pos + 4 * i + 2] == 1)
                    throw new InputException(where, $"scanline {y} uses the old run-length form",
                        "re-save the picture (e.g. with pfilt or oiiotool)");
            Array.Copy(bytes, pos, scan, 0, 4 * width);
            return pos + 4 * width;
        }
        int declared = (bytes[pos + 2] << 8) | bytes[pos + 3];
        if (declared != width)
            throw new InputException(where, $"scanline {y} declares width {declared}, the picture {width}", "the file is damaged");
        pos += 4;
        for (int c = 0; c < 4; c++)
        {
            for (int x = 0; x < width;)
            {
                if (pos >= bytes.Length) throw Truncated();
                int n = bytes[pos++];
                if (n > 128)
                {   // a run: n − 128 copies of the next byte
                    n -= 128;
                    if (x + n > width)
                        throw new InputException(where, $"scanline {y}: a run passes the end of the line", "the file is damaged");
                    if (pos >= bytes.Length) throw Truncated();
                    byte v = bytes[pos++];
                    for (int k = 0; k < n; k++) scan[4 * (x++) + c] = v;
                }
                else
                {   // n literal bytes
                    if (n == 0 || x + n > width)
                        throw new InputException(where, $"scanline {y}: a literal count of {n} is invalid here", "the file is damaged");
                    if (pos + n > bytes.Length) throw Truncated();
                    for (int k = 0; k < n; k++) scan[4 * (x++) + c] = bytes[pos++];
                }
            }
        }
        return pos;
    }
}
