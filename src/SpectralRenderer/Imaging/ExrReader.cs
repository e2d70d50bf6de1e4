using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>A spectral OpenEXR file read back: the spectral bands, every other channel and the header.</summary>
/// <param name="Image">The spectral channels as bands, in wavelength order.</param>
/// <param name="Reflective">True when the bands came from T.&lt;λ&gt;nm (reflective) channels.</param>
/// <param name="OtherChannels">Non-spectral channels (R, G, B, X, Y, Z, …) as row-major Height × Width planes.</param>
/// <param name="ChannelTypes">Pixel type of every channel in the file (UINT channels are reported as Float).</param>
/// <param name="StringAttributes">The string attributes of the header (spectralLayoutVersion, emissiveUnits, …).</param>
/// <param name="Kappa">The spectralKappa attribute, when present.</param>
/// <param name="Compression">The compression attribute (0 none, 2 ZIPS, 3 ZIP).</param>
public sealed record ExrSpectralFile(
    SpectralImage Image,
    bool Reflective,
    IReadOnlyDictionary<string, float[]> OtherChannels,
    IReadOnlyDictionary<string, ExrPixelType> ChannelTypes,
    IReadOnlyDictionary<string, string> StringAttributes,
    double? Kappa,
    int Compression);

/// <summary>
/// Reads single-part scanline OpenEXR files ("The OpenEXR File Layout") with NO_COMPRESSION, ZIPS_COMPRESSION or
/// ZIP_COMPRESSION and HALF, FLOAT or UINT channels — everything <see cref="ExrWriter"/> writes — into a
/// <see cref="SpectralImage"/>. Spectral channels follow Fichet et al. (JCGT 10(3) 2021): S0.&lt;λ&gt;nm, else T.&lt;λ&gt;nm.
/// The band grid comes from the spectralBandEdges attribute when present, else from the (evenly spaced) channel wavelengths.
/// </summary>
public static class ExrReader
{
    static readonly Regex SpectralName = new(@"^(S0|T)\.(\d+(?:[.,]\d*)?)nm$", RegexOptions.CultureInvariant);

    public static ExrSpectralFile Read(string path)
    {
        return Read(InputFile.ReadAllBytes(path, "OpenEXR file"), path);
    }

    public static ExrSpectralFile Read(Stream stream, string where = "EXR")
    {
        var ms = new MemoryStream();
        stream.CopyTo(ms);
        return Read(ms.ToArray(), where);
    }

    public static ExrSpectralFile Read(byte[] bytes, string where = "EXR")
    {
        var (width, height, channels, planes, strings, kappa, edgeVector, compression) = ReadChannels(bytes, where);

        // Spectral channels: S0.<λ>nm (emissive) preferred, else T.<λ>nm (reflective); sorted by wavelength.
        var spectral = new List<(int Index, double Lambda, string Kind)>();
        for (int c = 0; c < channels.Count; c++)
        {
            var m = SpectralName.Match(channels[c].Name);
            if (m.Success)
                spectral.Add((c, double.Parse(m.Groups[2].Value.Replace(',', '.'), CultureInfo.InvariantCulture), m.Groups[1].Value));
        }
        string kind = spectral.Any(s => s.Kind == "S0") ? "S0" : "T";
        spectral = spectral.Where(s => s.Kind == kind).OrderBy(s => s.Lambda).ToList();
        if (spectral.Count == 0)
            throw new InputException($"{where}: header attribute 'channels'", "no spectral channels",
                "expected channels named S0.<λ>nm or T.<λ>nm (Fichet et al. 2021), e.g. S0.390,000000nm");

        var grid = Grid(spectral.Select(s => s.Lambda).ToArray(), strings.GetValueOrDefault("spectralBandEdges"), edgeVector, where);
        var image = new SpectralImage(width, height, grid);
        for (int b = 0; b < spectral.Count; b++)
        {
            var plane = planes[spectral[b].Index];
            for (int i = 0, p = b; i < plane.Length; i++, p += grid.Count) image.Data[p] = plane[i];
        }
        var used = spectral.Select(s => s.Index).ToHashSet();
        var others = new Dictionary<string, float[]>(StringComparer.Ordinal);
        for (int c = 0; c < channels.Count; c++) if (!used.Contains(c)) others[channels[c].Name] = planes[c];
        var types = channels.ToDictionary(c => c.Name, c => c.Type == 1 ? ExrPixelType.Half : ExrPixelType.Float, StringComparer.Ordinal);
        return new ExrSpectralFile(image, kind == "T", others, types, strings, kappa, compression);
    }

    /// <summary>
    /// Every channel of a file, whatever its name: the data window's size, the channels (name, pixel type 0 UINT, 1 HALF,
    /// 2 FLOAT) in the header's order with their row-major planes, the string attributes, spectralKappa, the spectralBandEdges
    /// float vector and the compression. The spectral readers (<see cref="Read(byte[], string)"/>, the bispectral
    /// re-radiation matrix) name their channels from it.
    /// </summary>
    public static (int Width, int Height, List<(string Name, int Type)> Channels, float[][] Planes, Dictionary<string, string> Strings,
        double? Kappa, float[]? EdgeVector, int Compression) ReadChannels(byte[] bytes, string where)
    {
        var r = new Cursor(bytes, where);
        // Magic number and version field.
        if (bytes.Length < 8 || BinaryPrimitives.ReadInt32LittleEndian(bytes) != ExrWriter.Magic)
            throw new InputException($"{where}: byte 0", "not an OpenEXR file (no magic number 20000630)",
                "is this an OpenEXR image? it must start with 76 2f 31 01");
        r.Pos = 4;
        int version = r.Int();
        if ((version & 0xff) != 2)
            throw new InputException($"{where}: byte 4", $"OpenEXR version {version & 0xff} is not supported", "only version 2");
        if ((version & 0x200) != 0)
            throw new InputException($"{where}: byte 4", "tiled OpenEXR files are not supported", "write scanline images");
        if ((version & 0x1800) != 0)
            throw new InputException($"{where}: byte 4", "multi-part or deep OpenEXR files are not supported",
                "only single-part scanline images");

        // Header: attributes until an empty name.
        var channels = new List<(string Name, int Type)>();
        int? compression = null;
        int xMin = 0, yMin = 0, xMax = -1, yMax = -1;
        bool haveWindow = false;
        var strings = new Dictionary<string, string>(StringComparer.Ordinal);
        double? kappa = null;
        float[]? edgeVector = null;
        while (true)
        {
            string name = r.CString();
            if (name.Length == 0) break;
            string type = r.CString();
            int size = r.Int();
            if (size < 0) throw r.Truncated();
            var value = r.Bytes(size);
            switch (type)
            {
                case "chlist" when name == "channels":
                    var c = new Cursor(value, where);
                    while (true)
                    {
                        string ch = c.CString();
                        if (ch.Length == 0) break;
                        int pixelType = c.Int();
                        c.Pos += 4;                              // pLinear + reserved
                        int xs = c.Int(), ys = c.Int();
                        if (xs != 1 || ys != 1)
                            throw new InputException($"{where}: header attribute 'channels'", $"channel {ch} is subsampled ({xs}×{ys})",
                                "only full-resolution channels are supported");
                        if (pixelType is < 0 or > 2)
                            throw new InputException($"{where}: header attribute 'channels'",
                                $"channel {ch} has unknown pixel type {pixelType}", "pixel types are 0 (UINT), 1 (HALF) or 2 (FLOAT)");
                        if (channels.Any(c => c.Name == ch))   // found by fuzzing
                            throw new InputException($"{where}: header attribute 'channels'",
                                $"channel {MessageText.Quote(ch)} appears twice", "the file is corrupt: write it again");
                        channels.Add((ch, pixelType));
                    }
                    break;
                case "compression" when name == "compression":
                    compression = value.Length == 1 ? value[0] : throw r.Truncated();
                    break;
                case "box2i" when name == "dataWindow":
                    if (value.Length != 16) throw r.Truncated();
                    xMin = BinaryPrimitives.ReadInt32LittleEndian(value);
                    yMin = BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(4));
                    xMax = BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(8));
                    yMax = BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(12));
                    haveWindow = true;
                    break;
                case "string":
                    strings[name] = Encoding.UTF8.GetString(value);
                    break;
                case "double" when name == "spectralKappa" && value.Length == 8:
                    kappa = BinaryPrimitives.ReadDoubleLittleEndian(value);
                    break;
                case "float" when name == "spectralKappa" && value.Length == 4:
                    kappa = BinaryPrimitives.ReadSingleLittleEndian(value);
                    break;
                case "floatvector" when name == "spectralBandEdges":
                    edgeVector = new float[value.Length / 4];
                    for (int i = 0; i < edgeVector.Length; i++)
                        edgeVector[i] = BinaryPrimitives.ReadSingleLittleEndian(value.AsSpan(4 * i));
                    break;
            }
        }
        if (channels.Count == 0 || compression is null || !haveWindow)
            throw new InputException($"{where}: header", "the header lacks channels, compression or dataWindow",
                "the file is not a complete OpenEXR image: write it again");
        int lines = compression switch
        {
            0 or 2 => 1,
            3 => 16,
            _ => throw new InputException($"{where}: header attribute 'compression'",
                $"OpenEXR compression {CompressionName(compression.Value)} is not supported",
                "re-save with ZIP or no compression, e.g. oiiotool in.exr --compression zip -o out.exr"),
        };
        long w = (long)xMax - xMin + 1, h = (long)yMax - yMin + 1;
        if (w < 1 || h < 1 || w * h * channels.Count > Array.MaxLength)
            throw new InputException($"{where}: header attribute 'dataWindow'", $"data window {w}×{h} is empty or too large",
                "the dataWindow attribute is damaged: write the file again");
        int width = (int)w, height = (int)h;
        // Declared sizes against the file, before anything is allocated: every sample takes at least 2 bytes
        // uncompressed, and deflate shrinks data at most 1032:1 (RFC 1951: 258 bytes per 2-bit code, with headers).
        long rawBytes = 2L * w * h * channels.Count;
        long chunkTable = 8L * ((h + lines - 1) / lines);
        if (chunkTable > bytes.Length || rawBytes > (compression == 0 ? 1 : ExrZip.MaxRatio) * (long)bytes.Length)
            throw new InputException($"{where}: header attribute 'dataWindow'",
                $"the header declares {w}×{h} pixels of {channels.Count} channels, more than the {bytes.Length}-byte file can hold",
                "the file is truncated or its dataWindow is damaged: write it again");

        // Line offset table, then the chunks: y, data size, data.
        int chunkCount = (height + lines - 1) / lines;
        var offsets = new long[chunkCount];
        for (int i = 0; i < chunkCount; i++) offsets[i] = r.Long();
        int[] sampleBytes = channels.Select(c => c.Type == 1 ? 2 : 4).ToArray();
        long lineBytesLong = (long)sampleBytes.Sum() * width;
        if (lineBytesLong * lines > int.MaxValue)
            throw new InputException($"{where}: header attribute 'dataWindow'",
                $"a chunk of {lines} scanlines of {width} pixels × {channels.Count} channels exceeds 2 GiB", "write smaller images");
        int lineBytes = (int)lineBytesLong;
        var planes = channels.Select(_ => new float[width * height]).ToArray();
        var done = new bool[chunkCount];
        for (int i = 0; i < chunkCount; i++)
        {
            if (offsets[i] <= 0 || offsets[i] >= bytes.Length)
                throw new InputException($"{where}: chunk {i}", $"file is truncated or incomplete (chunk {i} of {chunkCount} is missing)",
                    "the file was cut short: write it again");
            r.Pos = offsets[i];
            int y = r.Int();
            int size = r.Int();
            long rel = (long)y - yMin;
            if (rel < 0 || rel >= height || rel % lines != 0)
                throw new InputException($"{where}: chunk {i}", $"chunk {i} has invalid y coordinate {y}",
                    "the file is corrupt: write it again");
            int chunk = (int)(rel / lines);
            int n = Math.Min(lines, height - (int)rel);
            int expected = n * lineBytes;
            if (size < 0) throw r.Truncated();
            var data = r.Bytes(size);
            byte[] raw;
            if (size == expected) raw = data;            // stored raw (always for NO_COMPRESSION)
            else if (compression != 0 && size < expected)
            {
                raw = new byte[expected];
                if (!ExrZip.TryDecompress(data, raw))
                    throw new InputException($"{where}: chunk {i}",
                        $"chunk at y = {y} does not decompress to {expected} bytes (corrupt file)", "the file is corrupt: write it again");
            }
            else
                throw new InputException($"{where}: chunk {i}", $"chunk at y = {y} has {size} bytes, {expected} expected",
                    "the file is corrupt: write it again");
            int at = 0;
            for (int line = 0; line < n; line++)
            {
                int row = ((int)rel + line) * width;
                for (int c = 0; c < channels.Count; c++)
                {
                    var plane = planes[c];
                    switch (channels[c].Type)
                    {
                        case 2:
                            for (int x = 0; x < width; x++, at += 4)
                                plane[row + x] = BinaryPrimitives.ReadSingleLittleEndian(raw.AsSpan(at));
                            break;
                        case 1:
                            for (int x = 0; x < width; x++, at += 2)
                                plane[row + x] =
                                    (float)BitConverter.UInt16BitsToHalf(BinaryPrimitives.ReadUInt16LittleEndian(raw.AsSpan(at)));
                            break;
                        default:
                            for (int x = 0; x < width; x++, at += 4)
                                plane[row + x] = BinaryPrimitives.ReadUInt32LittleEndian(raw.AsSpan(at));
                            break;
                    }
                }
            }
            done[chunk] = true;
        }
        if (done.Any(d => !d))
            throw new InputException($"{where}: chunk table", "some scanlines have no chunk (incomplete file)",
                "the file was cut short: write it again");
        return (width, height, channels, planes, strings, kappa, edgeVector, compression.Value);
    }

    /// <summary>The band grid: Count + 1 edges from spectralBandEdges, else evenly spaced centres.</summary>
    static BandGrid Grid(double[] centres, string? edgeText, float[]? edgeVector, string where)
    {
        int n = centres.Length;
        double[]? edges = null;
        if (edgeText is not null)
        {
            var parts = edgeText.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries);
            edges = new double[parts.Length];
            for (int i = 0; i < parts.Length; i++)
                if (!double.TryParse(parts[i], NumberStyles.Float, CultureInfo.InvariantCulture, out edges[i]))
                    throw new InputException($"{where}: header attribute 'spectralBandEdges'",
                        $"spectralBandEdges value '{parts[i]}' is not a number",
                        "spectralBandEdges lists band edges in nm separated by commas");
        }
        else if (edgeVector is not null) edges = edgeVector.Select(e => (double)e).ToArray();

        BandGrid grid;
        if (edges is not null)
        {
            if (edges.Length != n + 1)
                throw new InputException($"{where}: header attribute 'spectralBandEdges'",
                    $"spectralBandEdges has {edges.Length} edges for {n} spectral channels",
                    "give one more edge than there are spectral channels");
            try { grid = new BandGrid(edges[0], edges[^1], n); }
            catch (ArgumentOutOfRangeException e)
            {
                throw new InputException($"{where}: header attribute 'spectralBandEdges'", $"spectralBandEdges: {e.Message}",
                    "band edges must be positive and ascending");
            }
            for (int i = 0; i <= n; i++)
                if (Math.Abs(edges[i] - grid.Edges()[i]) > 1e-6 * grid.Width)
                    throw new InputException($"{where}: header attribute 'spectralBandEdges'", "spectralBandEdges are not evenly spaced",
                        "only equal-width band grids are supported");
        }
        else
        {
            if (n < 2)
                throw new InputException($"{where}: header attribute 'channels'",
                    "one spectral channel and no spectralBandEdges attribute: the band width is unknown",
                    "add a spectralBandEdges attribute");
            double width = (centres[^1] - centres[0]) / (n - 1);
            // Names carry 6 decimals, so the recovered edges are good to ~1e-6 nm: round them to 1e-5 nm.
            try { grid = new BandGrid(Math.Round(centres[0] - width / 2, 5), Math.Round(centres[^1] + width / 2, 5), n); }
            catch (ArgumentOutOfRangeException e)
            {
                throw new InputException($"{where}: header attribute 'channels'", $"spectral channels: {e.Message}",
                    "spectral channels are named S0.<λ>nm at evenly spaced wavelengths");
            }
        }
        // The channel names carry centres with 6 decimals.
        for (int b = 0; b < n; b++)
            if (Math.Abs(centres[b] - grid.Centre(b)) > Math.Max(1e-5, 1e-3 * grid.Width))
                throw new InputException($"{where}: header attribute 'channels'",
                    $"spectral channel at {centres[b]} nm is not the centre of band {BandGrid.Number(b)} ({grid.Centre(b)} nm)",
                    "only evenly spaced bands are supported");
        return grid;
    }

    static string CompressionName(int c) => c switch
    {
        1 => "RLE",
        4 => "PIZ",
        5 => "PXR24",
        6 => "B44",
        7 => "B44A",
        8 => "DWAA",
        9 => "DWAB",
        _ => $"#{c}",
    };

    /// <summary>Bounds-checked little-endian reading; running off the end is a truncated file.</summary>
    sealed class Cursor(byte[] bytes, string where)
    {
        public long Pos;

        public InputException Truncated() =>
            new($"{where}: byte {Pos}", "file is truncated or corrupt", "the OpenEXR data ends early: write the file again");

        public ReadOnlySpan<byte> Take(int n)
        {
            if (n < 0 || Pos + n > bytes.Length) throw Truncated();
            var s = bytes.AsSpan((int)Pos, n);
            Pos += n;
            return s;
        }

        public byte[] Bytes(int n) => Take(n).ToArray();
        public int Int() => BinaryPrimitives.ReadInt32LittleEndian(Take(4));
        public long Long()
        {
            ulong v = BinaryPrimitives.ReadUInt64LittleEndian(Take(8));
            return v > long.MaxValue ? -1 : (long)v;
        }

        public string CString()
        {
            if (Pos >= bytes.Length) throw Truncated();
            int end = Array.IndexOf(bytes, (byte)0, (int)Pos);
            if (end < 0 || end - Pos > 255) throw Truncated();
            var s = Encoding.UTF8.GetString(bytes, (int)Pos, end - (int)Pos);
            Pos = end + 1;
            return s;
        }
    }
}
