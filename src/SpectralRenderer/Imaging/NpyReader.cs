using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>Reads .npy files (format 1.0–3.0) of little- or big-endian float32/float64 in C order.</summary>
public static class NpyReader
{
    static readonly Regex Descr = new(@"'descr'\s*:\s*'([<>=|])(f)(4|8)'", RegexOptions.CultureInvariant);
    static readonly Regex Fortran = new(@"'fortran_order'\s*:\s*(True|False)", RegexOptions.CultureInvariant);
    static readonly Regex Shape = new(@"'shape'\s*:\s*\(([^)]*)\)", RegexOptions.CultureInvariant);

    /// <summary>Reads an H × W × N array with its band grid from the wavelengths.csv beside it.</summary>
    public static SpectralImage ReadImage(string path)
    {
        var csv = Path.Combine(Path.GetDirectoryName(Path.GetFullPath(path))!, "wavelengths.csv");
        if (!File.Exists(csv)) throw new InputException(path, "no wavelengths.csv beside the .npy file", "pass the band grid explicitly");
        return ReadImage(path, WavelengthsCsv.Read(csv));
    }

    /// <summary>Reads an H × W × N array as a <see cref="SpectralImage"/> on <paramref name="grid"/> (N must equal its band
    /// count).</summary>
    public static SpectralImage ReadImage(string path, BandGrid grid)
    {
        return ReadImage(new MemoryStream(InputFile.ReadAllBytes(path, "NumPy file")), grid, path);
    }

    public static SpectralImage ReadImage(Stream stream, BandGrid grid, string where = "NPY")
    {
        var (shape, data) = Read(stream, where);
        if (shape.Length != 3) throw new InputException($"{where}: header", $"array has {shape.Length} dimensions", "expected H × W × N");
        if (shape[2] != grid.Count)
            throw new InputException($"{where}: header", $"array has {shape[2]} bands, the band grid {grid} has {grid.Count}",
                "the cube must have one plane per band of wavelengths.csv");
        return new SpectralImage(shape[1], shape[0], grid, data);
    }

    public static (int[] Shape, float[] Data) Read(Stream stream, string where = "NPY")
    {
        Span<byte> pre = stackalloc byte[8];
        try { stream.ReadExactly(pre); }
        catch (EndOfStreamException)
        {
            throw new InputException($"{where}: byte 0", "not a .npy file (too short)",
                "the file was cut short: save it again with numpy.save");
        }
        if (!pre[..6].SequenceEqual(NpyWriter.Magic))
            throw new InputException($"{where}: byte 0", "not a .npy file (no \\x93NUMPY magic)", "save the array with numpy.save");
        int major = pre[6];
        if (major is not (1 or 2 or 3))
            throw new InputException($"{where}: byte 6", $".npy format version {major}.{pre[7]} is not supported",
                "save with numpy.save (format 1.0, 2.0 or 3.0)");
        // The header length: uint16 (1.0) or uint32 (2.0, 3.0), little-endian (found by fuzzing: a short or huge one).
        Span<byte> l = stackalloc byte[major == 1 ? 2 : 4];
        try { stream.ReadExactly(l); }
        catch (EndOfStreamException)
        {
            throw new InputException($"{where}: byte 8", "file is truncated (in the header length)",
                "the file was cut short: save it again with numpy.save");
        }
        long headerLength = major == 1 ? BinaryPrimitives.ReadUInt16LittleEndian(l) : BinaryPrimitives.ReadUInt32LittleEndian(l);
        if (headerLength > InputFile.MaxTextBytes || (stream.CanSeek && headerLength > stream.Length - stream.Position))
            throw new InputException($"{where}: byte 8", $"the header claims {headerLength} bytes, more than the file holds",
                "the file was cut short: save it again with numpy.save");
        var hb = new byte[headerLength];
        try { stream.ReadExactly(hb); }
        catch (EndOfStreamException)
        {
            throw new InputException($"{where}: header", "file is truncated (in the header)",
                "the file was cut short: save it again with numpy.save");
        }
        var header = (major == 3 ? Encoding.UTF8 : Encoding.Latin1).GetString(hb);

        var d = Descr.Match(header);
        if (!d.Success)
            throw new InputException($"{where}: header", $"unsupported dtype in header {MessageText.Quote(header.Trim(), 60)}",
                "only float32 (<f4) and float64 (<f8)");
        var f = Fortran.Match(header);
        if (f.Success && f.Groups[1].Value == "True")
            throw new InputException($"{where}: header", "Fortran-order arrays are not supported", "save with numpy.ascontiguousarray");
        var s = Shape.Match(header);
        if (!s.Success) throw new InputException($"{where}: header", "header has no shape", "save the array with numpy.save");
        var shape = s.Groups[1].Value.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries)
            .Select(t => int.TryParse(t.TrimEnd('L'), NumberStyles.Integer, CultureInfo.InvariantCulture, out int v) && v >= 0 ? v
                : throw new InputException($"{where}: header", $"bad shape entry {MessageText.Quote(t)}",
                    "shape entries are non-negative integers"))
                    .ToArray();
        bool big = d.Groups[1].Value == ">";
        int size = d.Groups[3].Value == "4" ? 4 : 8;
        long count = 1;  // saturates instead of overflowing: any count this large is refused below
        foreach (int v in shape) count = v == 0 ? 0 : count > long.MaxValue / 16 / v ? long.MaxValue / 16 : count * v;
        if (stream.CanSeek && count * size > stream.Length - stream.Position)
            throw new InputException($"{where}: data",
                $"the header declares shape ({string.Join(", ", shape)}): {count} values of {size} bytes, but the file holds only "
                    + $"{stream.Length - stream.Position} bytes of data",
                "the file is truncated or its header is wrong: save it again with numpy.save");
        if (count * size > Array.MaxLength)
            throw new InputException($"{where}: header", $"shape ({string.Join(", ", shape)}) is too large",
                $"at most {Array.MaxLength / size} values");
        if (size == 4 && big != BitConverter.IsLittleEndian)
        {
            // The machine's own float32 layout: read straight into the array, no second copy.
            var direct = new float[count];
            try { stream.ReadExactly(System.Runtime.InteropServices.MemoryMarshal.AsBytes(direct.AsSpan())); }
            catch (EndOfStreamException)
            {
                throw new InputException($"{where}: data", $"file is truncated: {count} values of {size} bytes expected",
                    "the file was cut short: save it again with numpy.save");
            }
            return (shape, direct);
        }
        var bytes = new byte[count * size];
        try { stream.ReadExactly(bytes); }
        catch (EndOfStreamException)
        {
            throw new InputException($"{where}: data", $"file is truncated: {count} values of {size} bytes expected",
                "the file was cut short: save it again with numpy.save");
        }
        var data = new float[count];
        for (int i = 0; i < data.Length; i++)
        {
            var b = bytes.AsSpan(i * size, size);
            data[i] = (size, big) switch
            {
                (4, false) => BinaryPrimitives.ReadSingleLittleEndian(b),
                (4, true) => BinaryPrimitives.ReadSingleBigEndian(b),
                (_, false) => (float)BinaryPrimitives.ReadDoubleLittleEndian(b),
                _ => (float)BinaryPrimitives.ReadDoubleBigEndian(b),
            };
        }
        return (shape, data);
    }
}
