using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Reads an ENVI raster of float32 (data type 4) or float64 (5) samples, either byte order,
/// interleave bsq, bil or bip, into a <see cref="SpectralImage"/>. The band grid comes from
/// wavelength (+ fwhm when present), which must be evenly spaced in nm.
/// </summary>
public static class EnviReader
{
    /// <summary>Reads <paramref name="imagePath"/> and the .hdr beside it (or imagePath + ".hdr").</summary>
    public static SpectralImage Read(string imagePath)
    {
        var hdr = EnviWriter.HeaderPath(imagePath);
        if (!File.Exists(hdr) && File.Exists(imagePath + ".hdr")) hdr = imagePath + ".hdr";
        if (!File.Exists(hdr)) throw new InputException(imagePath, "no ENVI header beside the image", $"expected {hdr}");
        var header = ParseHeader(InputFile.ReadAllText(hdr, "ENVI header"), hdr);
        return ReadData(new MemoryStream(InputFile.ReadAllBytes(imagePath, "ENVI image")), header, imagePath);
    }

    /// <summary>Parses "key = value" lines; a value starting with '{' continues to the matching '}'. Keys are lower-cased.</summary>
    public static Dictionary<string, string> ParseHeader(string text, string where = "ENVI header")
    {
        text = text.Replace("\r\n", "\n");
        if (!text.TrimStart().StartsWith("ENVI", StringComparison.Ordinal))
            throw new InputException($"{where}: line 1", "not an ENVI header (the first line is not 'ENVI')", "an ENVI header starts with the line ENVI");
        var d = new Dictionary<string, string>(StringComparer.OrdinalIgnoreCase);
        int pos = text.IndexOf('\n');
        while (pos >= 0 && pos < text.Length)
        {
            int eol = text.IndexOf('\n', pos + 1);
            if (eol < 0) eol = text.Length;
            var line = text[(pos + 1)..eol];
            pos = eol;
            int eq = line.IndexOf('=');
            if (line.TrimStart().StartsWith(';') || eq < 0) continue;
            var key = string.Join(' ', line[..eq].Split(' ', StringSplitOptions.RemoveEmptyEntries)).ToLowerInvariant();
            var value = line[(eq + 1)..].Trim();
            if (value.StartsWith('{') && !value.Contains('}'))
            {
                int close = text.IndexOf('}', pos);
                if (close < 0) throw new InputException($"{where}: header '{key}'", $"'{key}' has an unclosed '{{'", "close the list with '}'");
                value = line[(eq + 1)..].Trim() + text[pos..(close + 1)];
                pos = text.IndexOf('\n', close);
                if (pos < 0) pos = text.Length;
            }
            if (value.StartsWith('{')) value = value[1..value.LastIndexOf('}')].Replace('\n', ' ').Trim();
            d[key] = value;
        }
        return d;
    }

    public static SpectralImage ReadData(Stream stream, IReadOnlyDictionary<string, string> h, string where = "ENVI")
    {
        int Int(string key, int? fallback = null)
        {
            if (h.TryGetValue(key, out var v) && int.TryParse(v, NumberStyles.Integer, CultureInfo.InvariantCulture, out int i)) return i;
            return fallback ?? throw new InputException($"{where}: header '{key}'", $"ENVI header lacks a numeric '{key}'", $"add '{key} = N' to the header");
        }
        int w = Int("samples"), lines = Int("lines"), bands = Int("bands"), offset = Int("header offset", 0);
        int type = Int("data type"), order = Int("byte order", 0);
        string interleave = h.GetValueOrDefault("interleave", "bsq").Trim().ToLowerInvariant();
        if (type is not (4 or 5)) throw new InputException($"{where}: header 'data type'", $"ENVI data type {type} is not supported", "only 4 (float32) and 5 (float64)");
        if (interleave is not ("bsq" or "bil" or "bip")) throw new InputException($"{where}: header 'interleave'", $"unknown interleave {MessageText.Quote(interleave)}", "use bsq, bil or bip");
        if (w < 1 || lines < 1 || bands < 1 || bands > BandGrid.MaxBands) throw new InputException($"{where}: header 'samples', 'lines', 'bands'", $"bad size {w}×{lines}×{bands}", $"samples, lines and bands must be at least 1 (bands at most {BandGrid.MaxBands})");

        var grid = Grid(h, bands, where);
        int size = type == 4 ? 4 : 8;
        long total = (long)w * lines * bands;
        if (offset < 0) throw new InputException($"{where}: header 'header offset'", $"'header offset' {offset} is negative", "give the number of bytes before the samples, usually 0");
        if (stream.CanSeek && total * size + offset > stream.Length - stream.Position)
            throw new InputException($"{where}: data", $"the header declares {w}×{lines}×{bands} samples of {size} bytes, but the image file holds only {stream.Length - stream.Position} bytes",
                "the image is truncated or the header does not belong to it");
        if (total * size > Array.MaxLength) throw new InputException($"{where}: data", $"{w}×{lines}×{bands} samples exceed 2 GiB", "split the cube");
        var bytes = new byte[total * size];
        if (offset > 0) stream.ReadExactly(new byte[offset]);
        try { stream.ReadExactly(bytes); }
        catch (EndOfStreamException) { throw new InputException($"{where}: data", $"file is truncated: {w}×{lines}×{bands} samples of {size} bytes expected", "the image file is shorter than the header says: copy it again"); }

        var image = new SpectralImage(w, lines, grid);
        for (int y = 0; y < lines; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < bands; b++)
                {
                    long i = interleave switch
                    {
                        "bsq" => ((long)b * lines + y) * w + x,
                        "bil" => ((long)y * bands + b) * w + x,
                        _ => ((long)y * w + x) * bands + b,
                    };
                    var s = bytes.AsSpan((int)(i * size), size);
                    double v = (type, order) switch
                    {
                        (4, 0) => BinaryPrimitives.ReadSingleLittleEndian(s),
                        (4, _) => BinaryPrimitives.ReadSingleBigEndian(s),
                        (_, 0) => BinaryPrimitives.ReadDoubleLittleEndian(s),
                        _ => BinaryPrimitives.ReadDoubleBigEndian(s),
                    };
                    image[x, y, b] = (float)v;
                }
        return image;
    }

    /// <summary>Rounds a band edge recovered as centre ± width/2 to 1e-9 nm, undoing the last-bit error of the sum.</summary>
    internal static double Snap(double nm) => Math.Round(nm, 9);

    static BandGrid Grid(IReadOnlyDictionary<string, string> h, int bands, string where)
    {
        double[] Numbers(string key) => h.TryGetValue(key, out var v)
            ? v.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries).Select(s =>
                double.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out var d) ? d
                    : throw new InputException($"{where}: header '{key}'", $"'{key}' value {MessageText.Quote(s)} is not a number", "list numbers separated by commas inside { }")).ToArray()
            : [];
        var centres = Numbers("wavelength");
        var fwhm = Numbers("fwhm");
        if (centres.Length != bands) throw new InputException($"{where}: header 'wavelength'", $"'wavelength' lists {centres.Length} values for {bands} bands", "give one wavelength per band");
        var units = h.GetValueOrDefault("wavelength units", "Nanometers").Trim().ToLowerInvariant();
        double scale = units switch { "nanometers" or "nm" => 1, "micrometers" or "um" or "microns" => 1000, _ => 0 };
        if (scale == 0) throw new InputException($"{where}: header 'wavelength units'", $"wavelength units {MessageText.Quote(units)} are not supported", "use Nanometers");
        for (int i = 0; i < centres.Length; i++) centres[i] *= scale;
        for (int i = 0; i < fwhm.Length; i++) fwhm[i] *= scale;
        double width = fwhm.Length == bands ? fwhm[0]
            : bands > 1 ? (centres[^1] - centres[0]) / (bands - 1)
            : throw new InputException($"{where}: header 'fwhm'", "one band and no 'fwhm': the band width is unknown", "add a 'fwhm' with the band width in nm");
        BandGrid grid;
        try { grid = new BandGrid(Snap(centres[0] - width / 2), Snap(centres[^1] + (fwhm.Length == bands ? fwhm[^1] : width) / 2), bands); }
        catch (ArgumentOutOfRangeException e) { throw new InputException($"{where}: header 'wavelength'", $"wavelengths: {e.Message}", "wavelengths must be positive and ascending"); }
        for (int b = 0; b < bands; b++)
            if (Math.Abs(centres[b] - grid.Centre(b)) > 1e-6 * Math.Max(1, grid.Width))
                throw new InputException($"{where}: header 'wavelength'", $"band {BandGrid.Number(b)} at {centres[b]} nm breaks the even spacing", "only equal-width band grids are supported");
        return grid;
    }
}
