using System.Buffers;
using System.Buffers.Binary;
using System.Globalization;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Writes a <see cref="SpectralImage"/> as a single-part scanline OpenEXR 2.0 file
/// ("The OpenEXR File Layout", openexr.com/en/latest/OpenEXRFileLayout.html) in the spectral layout of
/// Fichet, Pacanowski &amp; Wilkie, "An OpenEXR Layout for Spectral Images", JCGT 10(3), 2021:
/// one channel per band named S0.&lt;λ&gt;nm (emissive, Stokes S0) or T.&lt;λ&gt;nm (reflective), λ the band
/// centre with six decimals and a comma as decimal separator, plus the attributes spectralLayoutVersion and
/// emissiveUnits. Our own attributes: spectralBandEdges (string, the Count + 1 band edges in nm,
/// comma-separated), spectralKappa (double, κ of eq. 3) and spectralIntegration (string, the band scheme).
/// Optional preview channels R, G, B (linear sRGB) and X, Y, Z.
/// </summary>
public static class ExrWriter
{
    /// <summary>File layout §"Magic Number": 20000630 as a little-endian int.</summary>
    public const int Magic = 20000630;
    /// <summary>Lines per chunk (File layout, "Compression" table): NO_COMPRESSION 1, ZIPS 1, ZIP 16.</summary>
    public static int LinesPerChunk(ExrCompression c) => c == ExrCompression.Zip ? 16 : 1;

    public const string LayoutVersion = "1.0";
    public const string EmissiveUnits = "W.m^-2.sr^-1";

    /// <summary>The JCGT 2021 channel name of a band centred on <paramref name="centreNm"/>, e.g. S0.390,000000nm.</summary>
    public static string SpectralChannelName(double centreNm, bool reflective = false) =>
        (reflective ? "T." : "S0.") + centreNm.ToString("F6", CultureInfo.InvariantCulture).Replace('.', ',') + "nm";

    public static void Write(string path, SpectralImage image, ExrOptions? options = null)
    {
        options ??= new ExrOptions();
        Validate(image.Grid, options);
        var bands = image.BandPlanes();
        AtomicFile.Write(path, s => Write(s, image.Width, image.Height, image.Grid, bands, null, options));
    }

    public static void Write(Stream stream, SpectralImage image, ExrOptions? options = null)
    {
        options ??= new ExrOptions();
        Validate(image.Grid, options);
        Write(stream, image.Width, image.Height, image.Grid, image.BandPlanes(), null, options);
    }

    /// <summary>
    /// Writes band-sequential planes (<see cref="SpectralImage.CopyBands"/>) that the caller already holds, and their
    /// <see cref="XyzPlanes"/> (of options.Colorimeter) when it has them: the R,G,B / X,Y,Z channels are made from them.
    /// </summary>
    internal static void Write(string path, int width, int height, BandGrid grid, float[] bands, XyzPlanes? xyz, ExrOptions options)
    {
        Validate(grid, options);
        AtomicFile.Write(path, s => Write(s, width, height, grid, bands, xyz, options));
    }

    static void Write(Stream stream, int w, int h, BandGrid grid, float[] bands, XyzPlanes? xyz, ExrOptions options)
    {
        int n = w * h;
        if (bands.Length != n * grid.Count)
            throw new ArgumentException($"band planes hold {bands.Length} values, {w}×{h}×{grid.Count} expected");

        // Channels, each a row-major H × W plane, sorted by name in byte order as OpenEXR's ChannelList is.
        // (Plain arrays and a small sort of our own: no generic collection code to compile at startup.)
        int extra = options.ExtraChannels?.Count ?? 0;
        int count = grid.Count + (options.Rgb ? 3 : 0) + (options.Xyz ? 3 : 0) + extra;
        var names = new string[count];
        var planes = new ReadOnlyMemory<float>[count];
        int c0 = 0;
        for (int b = 0; b < grid.Count; b++, c0++)
            (names[c0], planes[c0]) = (SpectralChannelName(grid.Centre(b), options.Reflective), bands.AsMemory(b * n, n));
        for (int e = 0; e < extra; e++, c0++)
        {
            var (name, plane) = options.ExtraChannels![e];
            if (plane.Length != n) throw new ArgumentException($"EXR channel {name} holds {plane.Length} values, {w}×{h} expected");
            (names[c0], planes[c0]) = (name, plane);
        }
        if (options.Rgb || options.Xyz)
        {
            xyz ??= XyzPlanes.Compute(options.Colorimeter!, bands, n);
            var preview = new float[6][];
            for (int i = 0; i < 6; i++) preview[i] = new float[n];
            Parallel.For(0, h, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (y) =>
            {
                for (int i = y * w; i < (y + 1) * w; i++)
                {
                    var (r, g, bl) = RgbSpace.Srgb.Linear(xyz[i]);
                    preview[0][i] = (float)r; preview[1][i] = (float)g; preview[2][i] = (float)bl;
                    preview[3][i] = (float)xyz.X[i]; preview[4][i] = (float)xyz.Y[i]; preview[5][i] = (float)xyz.Z[i];
                }
            });
            string[] previewNames = ["R", "G", "B", "X", "Y", "Z"];
            for (int i = 0; i < 6; i++)
                if (i < 3 ? options.Rgb : options.Xyz) (names[c0], planes[c0++]) = (previewNames[i], preview[i]);
        }
        SortByName(names, planes);
        for (int c = 1; c < count; c++)
            if (names[c] == names[c - 1])
                throw new ArgumentException("two EXR channels have the same name (are two bands centred on the same wavelength?)");

        var header = Header(w, h, grid, options, names, out bool longNames);

        int lines = LinesPerChunk(options.Compression);
        int chunkCount = (h + lines - 1) / lines;
        int sampleBytes = options.PixelType == ExrPixelType.Float ? 4 : 2;
        // A float chunk stored raw is its planes' rows as they are in memory (little-endian): it is not kept, but
        // streamed from the planes when the file is written. Other stored chunks and all deflated ones are kept.
        bool rowsAreRaw = sampleBytes == 4 && BitConverter.IsLittleEndian;
        var chunks = new byte[]?[chunkCount];
        Parallel.For(0, chunkCount, (c) =>
        {
            int y0 = c * lines, y1 = Math.Min(h, y0 + lines);
            int size = (y1 - y0) * planes.Length * w * sampleBytes;
            if (options.Compression == ExrCompression.None && rowsAreRaw) return;
            var raw = ArrayPool<byte>.Shared.Rent(size);
            try
            {
                var chunk = raw.AsSpan(0, size);
                ScanLineBlock(planes, w, y0, y1, sampleBytes, chunk);
                byte[]? z =
                    options.Compression == ExrCompression.Zip ? ExrZip.CompressChunk(chunk, sampleBytes, options.DeflateEveryChunk) : null;
                chunks[c] = z ?? (rowsAreRaw ? null : chunk.ToArray());
            }
            finally { ArrayPool<byte>.Shared.Return(raw); }
        });

        Span<byte> word = stackalloc byte[8];
        stream.Write(word[..WriteInt32(word, Magic)]);
        // Version field: version 2 in bits 0–7; bit 10 "long names"; bits 9 (tiled), 11 (deep), 12 (multipart) clear.
        stream.Write(word[..WriteInt32(word, 2 | (longNames ? 0x400 : 0))]);
        stream.Write(header);
        // Offset table: one unsigned 64-bit file offset per chunk, in increasing y order.
        long offset = 8 + header.Length + 8L * chunkCount;
        var sizes = new int[chunkCount];
        for (int c = 0; c < chunkCount; c++)
        {
            sizes[c] = chunks[c]?.Length ?? (Math.Min(h, (c + 1) * lines) - c * lines) * planes.Length * w * 4;
            BinaryPrimitives.WriteUInt64LittleEndian(word, (ulong)offset);
            stream.Write(word);
            offset += 8 + sizes[c];
        }
        for (int c = 0; c < chunkCount; c++)
        {
            // y of the chunk's first scanline: chunks start at the data window's yMin
            BinaryPrimitives.WriteInt32LittleEndian(word, options.DataY + c * lines);
            BinaryPrimitives.WriteInt32LittleEndian(word[4..], sizes[c]); // pixel data size
            stream.Write(word);
            if (chunks[c] is { } bytes) { stream.Write(bytes); continue; }
            for (int y = c * lines; y < Math.Min(h, (c + 1) * lines); y++)
                foreach (var plane in planes) stream.Write(MemoryMarshal.AsBytes(plane.Span.Slice(y * w, w)));
        }

        static int WriteInt32(Span<byte> b, int v) { BinaryPrimitives.WriteInt32LittleEndian(b, v); return 4; }
    }

    /// <summary>
    /// The bytes a file of these settings starts with: magic, version field and header (the channels sorted by name),
    /// before the offset table. Two files of equal starts differ only in their pixels.
    /// </summary>
    public static byte[] FileStart(int w, int h, BandGrid grid, ExrOptions options)
    {
        Validate(grid, options);
        int count = grid.Count + (options.Rgb ? 3 : 0) + (options.Xyz ? 3 : 0) + (options.ExtraChannels?.Count ?? 0);
        var names = new string[count];
        int c = 0;
        for (int b = 0; b < grid.Count; b++) names[c++] = SpectralChannelName(grid.Centre(b), options.Reflective);
        foreach (var (name, _) in options.ExtraChannels ?? []) names[c++] = name;
        string[] previewNames = ["R", "G", "B", "X", "Y", "Z"];
        for (int i = 0; i < 6; i++) if (i < 3 ? options.Rgb : options.Xyz) names[c++] = previewNames[i];
        SortByName(names, new object[count]);
        var header = Header(w, h, grid, options, names, out bool longNames);
        var start = new byte[8 + header.Length];
        BinaryPrimitives.WriteInt32LittleEndian(start, Magic);
        BinaryPrimitives.WriteInt32LittleEndian(start.AsSpan(4), 2 | (longNames ? 0x400 : 0));
        header.CopyTo(start, 8);
        return start;
    }

    /// <summary>File layout, "Scan Line Blocks": per scanline y0 … y1 − 1, per channel (sorted), all pixels of that channel,
    /// little-endian.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ScanLineBlock(ReadOnlyMemory<float>[] planes, int w, int y0, int y1, int sampleBytes, Span<byte> raw)
    {
        int at = 0;
        for (int y = y0; y < y1; y++)
            foreach (var plane in planes)
            {
                var row = plane.Span.Slice(y * w, w);
                if (sampleBytes == 4 && BitConverter.IsLittleEndian)
                {
                    MemoryMarshal.AsBytes(row).CopyTo(raw[at..]);
                    at += 4 * w;
                    continue;
                }
                for (int x = 0; x < w; x++, at += sampleBytes)
                {
                    if (sampleBytes == 4) BinaryPrimitives.WriteSingleLittleEndian(raw[at..], row[x]);
                    else BinaryPrimitives.WriteUInt16LittleEndian(raw[at..], BitConverter.HalfToUInt16Bits((Half)row[x]));
                }
            }
    }

    static void Validate(BandGrid grid, ExrOptions options)
    {
        if (!Enum.IsDefined(options.Compression)) throw new ArgumentException($"unsupported EXR compression {options.Compression}");
        if (!Enum.IsDefined(options.PixelType)) throw new ArgumentException($"unsupported EXR pixel type {options.PixelType}");
        if ((options.Rgb || options.Xyz) && options.Colorimeter is null)
            throw new ArgumentException("EXR R,G,B / X,Y,Z channels need ExrOptions.Colorimeter (or set Rgb = false)");
        if (options.Colorimeter is { } cm && !cm.Grid.Equals(grid))
            throw new ArgumentException($"the colorimeter's band grid {cm.Grid} differs from the image's {grid}");
    }

    /// <summary>Insertion sort by name in ordinal (byte) order, <paramref name="items"/> moving with their names.</summary>
    static void SortByName<T>(string[] names, T[] items)
    {
        for (int i = 1; i < names.Length; i++)
            for (int j = i; j > 0 && string.CompareOrdinal(names[j - 1], names[j]) > 0; j--)
            {
                (names[j - 1], names[j]) = (names[j], names[j - 1]);
                (items[j - 1], items[j]) = (items[j], items[j - 1]);
            }
    }

    /// <summary>One header attribute: name, type name, value bytes.</summary>
    sealed class Attr(string name, string type, byte[] value)
    {
        public readonly string Name = name, Type = type;
        public readonly byte[] Value = value;
    }

    /// <summary>File layout §"Header": attributes (name, type name, size, value) sorted by name, then a null byte.</summary>
    static byte[] Header(int width, int height, BandGrid grid, ExrOptions options, string[] channelNames, out bool longNames)
    {
        var attrs = new List<Attr>();

        // chlist: per channel name\0, int pixel type, uchar pLinear, 3 reserved zero bytes, int xSampling, int ySampling; then \0.
        var chlist = new MemoryStream();
        var cw = new BinaryWriter(chlist);
        foreach (var name in channelNames)
        {
            cw.Write(Encoding.UTF8.GetBytes(name)); cw.Write((byte)0);
            cw.Write((int)options.PixelType);
            cw.Write(0);                     // pLinear + 3 reserved bytes
            cw.Write(1); cw.Write(1);        // x and y sampling
        }
        cw.Write((byte)0);
        attrs.Add(new("channels", "chlist", chlist.ToArray()));
        attrs.Add(new("compression", "compression", [(byte)options.Compression]));
        attrs.Add(new("dataWindow", "box2i", Box(options.DataX, options.DataY, options.DataX + width - 1, options.DataY + height - 1)));
        attrs.Add(new("displayWindow", "box2i", options.DisplayWidth > 0
            ? Box(0, 0, options.DisplayWidth - 1, options.DisplayHeight - 1) : Box(0, 0, width - 1, height - 1)));
        attrs.Add(new("lineOrder", "lineOrder", [0]));          // INCREASING_Y
        attrs.Add(new("pixelAspectRatio", "float", Floats(1f)));
        attrs.Add(new("screenWindowCenter", "v2f", Floats(0f, 0f)));
        attrs.Add(new("screenWindowWidth", "float", Floats(1f)));
        if (options.Rgb)  // R, G, B are linear sRGB: ITU-R BT.709 primaries, D65 white (x, y pairs R, G, B, W).
            attrs.Add(new("chromaticities", "chromaticities", Floats(0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f)));

        // JCGT 2021 §3: the layout version and, for emissive images, the radiometric units.
        attrs.Add(new("spectralLayoutVersion", "string", Encoding.UTF8.GetBytes(LayoutVersion)));
        if (!options.Reflective && options.EmissiveUnits is { } units)
            attrs.Add(new("emissiveUnits", "string", Encoding.UTF8.GetBytes(units)));
        var edges = new StringBuilder();
        foreach (double e in grid.Edges()) edges.Append(edges.Length > 0 ? "," : "").Append(e.ToString("R", CultureInfo.InvariantCulture));
        attrs.Add(new("spectralBandEdges", "string", Encoding.UTF8.GetBytes(edges.ToString())));
        if (options.Colorimeter is { } cm)
        {
            attrs.Add(new("spectralKappa", "double", BitConverter.GetBytes(cm.Kappa)));
            attrs.Add(new("spectralIntegration", "string", Encoding.UTF8.GetBytes(
                $"{cm.Scheme.ToString().ToLowerInvariant()}; observer {cm.Observer.Name}; reference light {cm.ReferenceLight.Name}; "
                    + $"{(cm.Absolute ? "absolute" : "relative")}")));
        }
        if (options.Attributes is not null)
            foreach (var (k, v) in options.Attributes)
            {
                bool taken = false;
                foreach (var a in attrs) taken |= a.Name == k;
                if (!taken) attrs.Add(new(k, "string", Encoding.UTF8.GetBytes(v)));
            }
        var sorted = attrs.ToArray();
        SortByName(Array.ConvertAll(sorted, a => a.Name), sorted);

        longNames = false;
        foreach (var name in channelNames) longNames |= Encoding.UTF8.GetByteCount(name) > 31;
        foreach (var a in sorted) longNames |= Encoding.UTF8.GetByteCount(a.Name) > 31 || Encoding.UTF8.GetByteCount(a.Type) > 31;
        var ms = new MemoryStream();
        var bw = new BinaryWriter(ms);
        foreach (var a in sorted)
        {
            if (Encoding.UTF8.GetByteCount(a.Name) > 255)
                throw new ArgumentException($"EXR attribute name '{a.Name}' is longer than 255 bytes");
            bw.Write(Encoding.UTF8.GetBytes(a.Name)); bw.Write((byte)0);
            bw.Write(Encoding.ASCII.GetBytes(a.Type)); bw.Write((byte)0);
            bw.Write(a.Value.Length);
            bw.Write(a.Value);
        }
        bw.Write((byte)0);
        return ms.ToArray();
    }

    static byte[] Box(int xMin, int yMin, int xMax, int yMax)
    {
        var b = new byte[16];
        BinaryPrimitives.WriteInt32LittleEndian(b, xMin);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4), yMin);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8), xMax);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(12), yMax);
        return b;
    }

    static byte[] Floats(params float[] v)
    {
        var b = new byte[4 * v.Length];
        for (int i = 0; i < v.Length; i++) BinaryPrimitives.WriteSingleLittleEndian(b.AsSpan(4 * i), v[i]);
        return b;
    }
}
