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
            throw new InputException($"{where}: line 1", "not an ENVI header (the first line is not 'ENVI')",
                "an ENVI header starts with the line ENVI");
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
                if (close < 0)
                    throw new InputException($"{where}: header '{key}'", $"'{key}' has an unclosed '{{'", "close the list with '}'");
                value = line[(eq + 1)..].Trim() + text[pos..(close + 1)];
                pos = text.IndexOf('\n', close);
                if (pos < 0) pos = text.Length;
            }
            if (value.StartsWith('{')) value = value[1..value.LastIndexOf('}')].Replace('\n', ' ').Trim();
            d[key] = value;
        }
        return d;
    }

    /// <summary>The cube of <paramref name="imagePath"/> (header beside it, as <see cref="Read"/>) opened for reading a block of
    /// rows at a time (<see cref="EnviCube.ReadRows"/>): header and file size checked now, no sample read yet.</summary>
    public static EnviCube Open(string imagePath)
    {
        var hdr = EnviWriter.HeaderPath(imagePath);
        if (!File.Exists(hdr) && File.Exists(imagePath + ".hdr")) hdr = imagePath + ".hdr";
        if (!File.Exists(hdr)) throw new InputException(imagePath, "no ENVI header beside the image", $"expected {hdr}");
        var layout = EnviCube.Layout(ParseHeader(InputFile.ReadAllText(hdr, "ENVI header"), hdr), imagePath);
        // The samples are read a block at a time, never whole: no size limit beyond the header's (the tables it becomes are
        // in the render's memory check).
        long length = InputFile.CheckedLength(imagePath, "ENVI image", long.MaxValue);
        layout.CheckLength(length);
        return new EnviCube(layout, imagePath);
    }

    public static SpectralImage ReadData(Stream stream, IReadOnlyDictionary<string, string> h, string where = "ENVI")
    {
        var cube = EnviCube.Layout(h, where);
        long total = (long)cube.Width * cube.Height * cube.Bands;
        if (stream.CanSeek) cube.CheckLength(stream.Length - stream.Position);
        if (total * cube.SampleBytes > Array.MaxLength)
            throw new InputException($"{where}: data", $"{cube.Width}×{cube.Height}×{cube.Bands} samples exceed 2 GiB", "split the cube");
        var bytes = new byte[total * cube.SampleBytes];
        if (cube.Offset > 0) stream.ReadExactly(new byte[cube.Offset]);
        try { stream.ReadExactly(bytes); }
        catch (EndOfStreamException) { throw cube.Truncated(); }
        var image = new SpectralImage(cube.Width, cube.Height, cube.Grid);
        cube.Convert(bytes, cube.Height, image.Data);
        return image;
    }

    /// <summary>Rounds a band edge recovered as centre ± width/2 to 1e-9 nm, undoing the last-bit error of the sum.</summary>
    internal static double Snap(double nm) => Math.Round(nm, 9);

    internal static BandGrid Grid(IReadOnlyDictionary<string, string> h, int bands, string where)
    {
        double[] Numbers(string key) => h.TryGetValue(key, out var v)
            ? v.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries).Select(s =>
                double.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out var d) ? d
                    : throw new InputException($"{where}: header '{key}'", $"'{key}' value {MessageText.Quote(s)} is not a number",
                        "list numbers separated by commas inside { }"))
                        .ToArray()
            : [];
        var centres = Numbers("wavelength");
        var fwhm = Numbers("fwhm");
        if (centres.Length != bands)
            throw new InputException($"{where}: header 'wavelength'", $"'wavelength' lists {centres.Length} values for {bands} bands",
                "give one wavelength per band");
        var units = h.GetValueOrDefault("wavelength units", "Nanometers").Trim().ToLowerInvariant();
        double scale = units switch { "nanometers" or "nm" => 1, "micrometers" or "um" or "microns" => 1000, _ => 0 };
        if (scale == 0)
            throw new InputException($"{where}: header 'wavelength units'",
                $"wavelength units {MessageText.Quote(units)} are not supported", "use Nanometers");
        for (int i = 0; i < centres.Length; i++) centres[i] *= scale;
        for (int i = 0; i < fwhm.Length; i++) fwhm[i] *= scale;
        double width = fwhm.Length == bands ? fwhm[0]
            : bands > 1 ? (centres[^1] - centres[0]) / (bands - 1)
            : throw new InputException($"{where}: header 'fwhm'", "one band and no 'fwhm': the band width is unknown",
                "add a 'fwhm' with the band width in nm");
        BandGrid grid;
        try { grid = new BandGrid(Snap(centres[0] - width / 2), Snap(centres[^1] + (fwhm.Length == bands ? fwhm[^1] : width) / 2), bands); }
        catch (ArgumentOutOfRangeException e)
        {
            throw new InputException($"{where}: header 'wavelength'", $"wavelengths: {e.Message}",
                "wavelengths must be positive and ascending");
        }
        for (int b = 0; b < bands; b++)
            if (Math.Abs(centres[b] - grid.Centre(b)) > 1e-6 * Math.Max(1, grid.Width))
                throw new InputException($"{where}: header 'wavelength'",
                    $"band {BandGrid.Number(b)} at {centres[b]} nm breaks the even spacing", "only equal-width band grids are supported");
        return grid;
    }
}

/// <summary>
/// An ENVI cube's layout (size, sample type and byte order, interleave, header offset, band grid) and, opened on a file
/// (<see cref="EnviReader.Open"/>), its samples read a block of rows at a time: bip and bil rows are contiguous in the
/// file (one read per block), bsq reads the block's rows of each band in turn. The bytes a block needs at most are its
/// rows' samples; nothing else of the cube is held.
/// </summary>
public sealed class EnviCube
{
    readonly string _where;
    readonly string? _path;

    EnviCube(int width, int height, int bands, int offset, int type, int order, string interleave, BandGrid grid, string where)
    {
        Width = width; Height = height; Bands = bands; Offset = offset; Type = type; Order = order; Interleave = interleave;
        Grid = grid; _where = where;
    }

    internal EnviCube(EnviCube layout, string path)
        : this(layout.Width, layout.Height, layout.Bands, layout.Offset, layout.Type, layout.Order, layout.Interleave, layout.Grid, path) =>
        _path = path;

    public int Width { get; }
    public int Height { get; }
    public int Bands { get; }
    public int Offset { get; }
    /// <summary>ENVI data type: 4 float32, 5 float64.</summary>
    public int Type { get; }
    /// <summary>ENVI byte order: 0 little-endian, 1 big-endian.</summary>
    public int Order { get; }
    /// <summary>bsq, bil or bip.</summary>
    public string Interleave { get; }
    public BandGrid Grid { get; }
    public int SampleBytes => Type == 4 ? 4 : 8;

    /// <summary>The layout a header declares, or the one-line reason it is unusable.</summary>
    internal static EnviCube Layout(IReadOnlyDictionary<string, string> h, string where)
    {
        int Int(string key, int? fallback = null)
        {
            if (h.TryGetValue(key, out var v) && int.TryParse(v, NumberStyles.Integer, CultureInfo.InvariantCulture, out int i)) return i;
            return fallback ?? throw new InputException($"{where}: header '{key}'", $"ENVI header lacks a numeric '{key}'",
                $"add '{key} = N' to the header");
        }
        int w = Int("samples"), lines = Int("lines"), bands = Int("bands"), offset = Int("header offset", 0);
        int type = Int("data type"), order = Int("byte order", 0);
        string interleave = h.GetValueOrDefault("interleave", "bsq").Trim().ToLowerInvariant();
        if (type is not (4 or 5))
            throw new InputException($"{where}: header 'data type'", $"ENVI data type {type} is not supported",
                "only 4 (float32) and 5 (float64)");
        if (interleave is not ("bsq" or "bil" or "bip"))
            throw new InputException($"{where}: header 'interleave'", $"unknown interleave {MessageText.Quote(interleave)}",
                "use bsq, bil or bip");
        if (w < 1 || lines < 1 || bands < 1 || bands > BandGrid.MaxBands)
            throw new InputException($"{where}: header 'samples', 'lines', 'bands'", $"bad size {w}×{lines}×{bands}",
                $"samples, lines and bands must be at least 1 (bands at most {BandGrid.MaxBands})");
        var grid = EnviReader.Grid(h, bands, where);
        if (offset < 0)
            throw new InputException($"{where}: header 'header offset'", $"'header offset' {offset} is negative",
                "give the number of bytes before the samples, usually 0");
        return new EnviCube(w, lines, bands, offset, type, order, interleave, grid, where);
    }

    /// <summary>Bad input unless <paramref name="available"/> bytes (after the header offset's start) hold every sample.</summary>
    internal void CheckLength(long available)
    {
        long total = (long)Width * Height * Bands;
        if (total * SampleBytes + Offset > available)
            throw new InputException($"{_where}: data",
                $"the header declares {Width}×{Height}×{Bands} samples of {SampleBytes} bytes, but the image "
                    + $"file holds only {available} bytes",
                "the image is truncated or the header does not belong to it");
    }

    internal InputException Truncated() => new($"{_where}: data",
        $"file is truncated: {Width}×{Height}×{Bands} samples of {SampleBytes} bytes expected",
        "the image file is shorter than the header says: copy it again");

    /// <summary>Rows <paramref name="y0"/> … + <paramref name="rows"/> − 1 from the file into <paramref name="dst"/>, pixel-major
    /// (sample b of pixel x of the block's row r at (r·width + x)·bands + b).</summary>
    public void ReadRows(int y0, int rows, Span<float> dst)
    {
        if (_path is null) throw new InvalidOperationException("a layout without a file");
        int size = SampleBytes;
        long rowBytes = (long)Width * Bands * size;
        var bytes = new byte[checked(rows * rowBytes)];
        using var file = File.OpenHandle(_path, FileMode.Open, FileAccess.Read, FileShare.ReadWrite | FileShare.Delete);
        if (Interleave == "bsq")
        {
            int plane = checked(rows * Width * size);
            for (int b = 0; b < Bands; b++)
                ReadAt(file, bytes.AsSpan(b * plane, plane), Offset + ((long)b * Height + y0) * Width * size);
        }
        else ReadAt(file, bytes, Offset + y0 * rowBytes);
        Convert(bytes, rows, dst);
    }

    void ReadAt(Microsoft.Win32.SafeHandles.SafeFileHandle file, Span<byte> dst, long at)
    {
        while (dst.Length > 0)
        {
            int n = RandomAccess.Read(file, dst, at);
            if (n == 0) throw Truncated();
            dst = dst[n..]; at += n;
        }
    }

    /// <summary>The samples of a block of <paramref name="rows"/> rows in <paramref name="bytes"/> (the file's order: bsq the
    /// block's rows of band 0, then of band 1, …; bil and bip as in the file) into pixel-major floats.</summary>
    internal void Convert(ReadOnlySpan<byte> bytes, int rows, Span<float> dst)
    {
        int w = Width, bands = Bands, size = SampleBytes;
        for (int y = 0; y < rows; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < bands; b++)
                {
                    long i = Interleave switch
                    {
                        "bsq" => ((long)b * rows + y) * w + x,
                        "bil" => ((long)y * bands + b) * w + x,
                        _ => ((long)y * w + x) * bands + b,
                    };
                    var s = bytes.Slice((int)(i * size), size);
                    double v = (Type, Order) switch
                    {
                        (4, 0) => BinaryPrimitives.ReadSingleLittleEndian(s),
                        (4, _) => BinaryPrimitives.ReadSingleBigEndian(s),
                        (_, 0) => BinaryPrimitives.ReadDoubleLittleEndian(s),
                        _ => BinaryPrimitives.ReadDoubleBigEndian(s),
                    };
                    dst[(int)(((long)y * w + x) * bands + b)] = (float)v;
                }
    }
}
