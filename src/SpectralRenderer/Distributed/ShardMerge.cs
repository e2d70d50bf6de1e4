using System.Buffers.Binary;
using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;

namespace SpectralRenderer.Distributed;

/// <summary>
/// Assembles the folders of shards of one render (<c>spectral render --shard I/N</c>) into the folder a single
/// process would have written: every file byte for byte, render.json but for what describes the runs (created_utc,
/// timings_s, rays.mrays_per_s and run). Streaming: the cubes are copied by offset (ENVI band by band, NPY row
/// strips, OpenEXR chunk by chunk — a shard's chunks are the whole file's, as strips start on 16-row chunk
/// boundaries), so the merge holds at most one chunk or copy buffer of them. The 8/16-bit images are decoded and
/// encoded again whole, one image at a time (≤ 3 bytes per pixel); the band images are rescaled to the brightest
/// band value of the whole image, found in the shards' float cubes first, one float band plane at a time.
/// </summary>
public static class ShardMerge
{
    /// <summary>One shard folder with its manifest and crop.</summary>
    sealed record Part(string Dir, RenderManifest Manifest, PixelRect Crop);

    /// <summary>Merges <paramref name="shardDirs"/> into <paramref name="outDir"/>; returns the files written, render.json last.</summary>
    public static List<string> Merge(IReadOnlyList<string> shardDirs, string outDir, string commandLine, CancellationToken cancel = default)
    {
        var parts = Check(shardDirs, outDir);
        var first = parts[0].Manifest;
        int width = first.Width, height = first.Height, bands = first.Grid.Count;
        var files = first.Files!.ToList();

        // Merged into a staging folder beside OUTDIR and swapped in whole (OutputFolder), as a render is.
        var folder = OutputFolder.Begin(outDir);
        var staging = folder.Staging;
        try
        {
            // The whole image's brightest band value (render.json's band_image_scale): read from the cubes where band images
            // are rescaled to it, else the largest of the shards' own (the same maximum).
            float scale = files.Any(f => f.StartsWith("bands", StringComparison.Ordinal)) ? BandScale(parts, width, bands, cancel)
                : parts.Max(p => p.Manifest.BandImageScale);

            var bandFiles = files.Where(f => f.StartsWith("bands/", StringComparison.Ordinal)).ToList();
            bool mosaic = files.Contains("bands.png");
            if (bandFiles.Count > 0 || mosaic) MergeBands(parts, staging, width, height, bands, scale, bandFiles, mosaic, cancel);
            List<string>? photometry = null;   // the false-colour pictures, all four drawn at their first
            foreach (var f in files)
            {
                cancel.ThrowIfCancellationRequested();
                var target = Path.Combine(staging, f);
                Directory.CreateDirectory(Path.GetDirectoryName(target)!);   // lights/ of a path render
                switch (OutputProductTable.Owner(f)?.Merging(f) ?? ShardMerging.None)
                {
                    case ShardMerging.Png: MergePng(parts, f, target, width, height); break;
                    case ShardMerging.ExrChunks: MergeExr(parts, f, target, width, height); break;
                    case ShardMerging.EnviCube: MergeEnvi(parts, f, target, width, bands); break;
                    case ShardMerging.EnviHeader: MergeEnviHeader(parts[0], f, target, height); break;
                    case ShardMerging.NoiseEnvi: MergeEnvi(parts, f, target, width, bands + 1); break;
                    case ShardMerging.NoiseEnviHeader: MergeEnviHeader(parts[0], f, target, height); break;
                    case ShardMerging.NoiseNpy: MergeNpy(parts, f, target, width, height, bands + 1); break;
                    case ShardMerging.NpyCube: MergeNpy(parts, f, target, width, height, bands); break;
                    case ShardMerging.NpyColour: MergeNpy(parts, f, target, width, height, 3); break;
                    case ShardMerging.TransferRows: MergeNpy(parts, f, target, width, height, TransferRows(parts[0], f)); break;
                    case ShardMerging.Copy:
                        Directory.CreateDirectory(Path.GetDirectoryName(target)!);   // grids/NAME.csv: a subfolder
                        AtomicFile.WriteAllBytes(target, File.ReadAllBytes(Path.Combine(parts[0].Dir, f)));
                        break;
                    case ShardMerging.BandImages: break;   // above
                    case ShardMerging.FalseColour: photometry ??= MergePhotometryPictures(parts, staging, width, height); break;
                    default:
                        throw new InputException(Path.Combine(parts[0].Dir, "render.json"), $"lists '{f}', a file merge does not know",
                            "merge shards written by the same version");
                }
            }
            var manifest = Manifest(parts, scale, commandLine);
            AtomicFile.WriteAllText(Path.Combine(staging, RenderManifest.FileName), manifest.ToJsonText());
        }
        catch
        {
            folder.Abandon();
            throw;
        }
        List<string> written = [.. files, RenderManifest.FileName];
        folder.Commit(written, cancel);
        return written;
    }

    /// <summary>Reads and checks the shards: complete, of one scene and settings, full-width strips tiling the film once.</summary>
    static List<Part> Check(IReadOnlyList<string> dirs, string outDir)
    {
        if (dirs.Count == 0) throw new InputException("", "no shard folders given", "usage: spectral merge SHARD_DIR… -o OUTDIR");
        var parts = new List<Part>();
        foreach (var dir in dirs)
        {
            if (!Directory.Exists(dir)) throw new InputException(dir, "is not a folder", "give the folders the shards were rendered into");
            if (OutputFolder.SameFolder(dir, outDir))   // by identity: "a/", a link to a, another mount of it
                throw new InputException(dir, "is also the output folder", "merge into a new folder with -o");
            var path = Path.Combine(dir, RenderManifest.FileName);
            if (!File.Exists(path))
                throw new InputException(dir,
                    "has no render.json: the shard is half-written (its render was interrupted or is still running)",
                    "render the shard again");
            var m = RenderManifest.Read(dir);
            if (m.SceneHash is null || m.Files is null)
                throw new InputException(path, "has no scene_hash or files", "render the shards with this version of spectral");
            var crop = m.Crop ?? PixelRect.Whole(m.Width, m.Height);
            foreach (var f in m.Files)
                if (!File.Exists(Path.Combine(dir, f)))
                    throw new InputException(dir, $"lacks {f}, which its render.json lists: the shard is half-written or was changed",
                        "render the shard again");
            parts.Add(new Part(dir, m, crop));
        }

        var first = parts[0];
        string hash = first.Manifest.SceneHash!;
        foreach (var p in parts.Skip(1))
        {
            if (p.Manifest.SceneHash != hash)
                throw new InputException(p.Dir, $"is a shard of another scene or settings than {first.Dir} (scene_hash differs)",
                    "merge shards rendered from one scene file with the same options");
            if (!p.Manifest.Files!.SequenceEqual(first.Manifest.Files!))
                throw new InputException(p.Dir, $"holds other files than {first.Dir}", "render every shard with the same --formats");
        }

        int width = first.Manifest.Width, height = first.Manifest.Height;
        parts.Sort((a, b) => a.Crop.Y0.CompareTo(b.Crop.Y0));
        int next = 0;
        Part? previous = null;
        foreach (var p in parts)
        {
            if (p.Crop.X0 != 0 || p.Crop.X1 != width)
                throw new InputException(p.Dir, $"holds crop {p.Crop}, not full-width rows of the {width}-pixel film",
                    "merge assembles --shard strips");
            if (p.Crop.Y0 % 16 != 0)
                throw new InputException(p.Dir, $"starts at row {p.Crop.Y0}, not on a 16-row OpenEXR chunk boundary",
                    "merge assembles --shard strips");
            if (p.Crop.Y0 > next)
                throw new InputException(p.Dir,
                    $"starts at row {p.Crop.Y0} but rows {next}–{p.Crop.Y0 - 1} are in no shard given (a shard is missing)",
                    "give every shard folder of the render");
            if (p.Crop.Y0 < next)
                throw new InputException(p.Dir, $"overlaps {previous!.Dir} in rows {p.Crop.Y0}–{next - 1}", "give each shard once");
            next = p.Crop.Y1;
            previous = p;
        }
        if (next != height)
            throw new InputException(previous!.Dir, $"ends at row {next - 1} but the film has {height} rows (a shard is missing)",
                "give every shard folder of the render");
        return parts;
    }

    // ---- the float cubes ---------------------------------------------------------------------------------------

    /// <summary>Band b of a shard as a row-major plane of its crop: from spectral.img (BSQ, by offset) or spectral.npy (H×W×N).</summary>
    static void ReadBand(Part p, int width, int bands, int b, Span<float> plane)
    {
        int h = p.Crop.Height;
        var img = Path.Combine(p.Dir, "spectral.img");
        if (File.Exists(img))
        {
            using var fs = new FileStream(img, FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
            if (fs.Length != 4L * width * h * bands)
                throw new InputException(img, $"has {fs.Length} bytes, {4L * width * h * bands} expected (half-written shard)",
                    "the shard was not finished: render it again");
            fs.Position = 4L * b * width * h;
            fs.ReadExactly(System.Runtime.InteropServices.MemoryMarshal.AsBytes(plane));
            if (!BitConverter.IsLittleEndian) throw new PlatformNotSupportedException("merging shards needs a little-endian machine");
            return;
        }
        var npy = Path.Combine(p.Dir, "spectral.npy");
        if (File.Exists(npy))
        {
            using var fs = new FileStream(npy, FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
            long start = NpyWriter.Preamble([h, width, bands]).Length;
            if (fs.Length != start + 4L * width * h * bands)
                throw new InputException(npy, $"has {fs.Length} bytes, {start + 4L * width * h * bands} expected (half-written shard)",
                    "the shard was not finished: render it again");
            fs.Position = start;
            var row = new float[width * bands];
            for (int y = 0; y < h; y++)
            {
                fs.ReadExactly(System.Runtime.InteropServices.MemoryMarshal.AsBytes(row.AsSpan()));
                for (int x = 0; x < width; x++) plane[y * width + x] = row[x * bands + b];
            }
            return;
        }
        throw new InputException(p.Dir,
            "holds no float cube (spectral.img or spectral.npy) to rebuild the band images on the whole image's scale",
            "render the shards with envi or npy in --formats");
    }

    /// <summary>
    /// The band images' common scale: the brightest band value over all pixels of all shards, as the single render's
    /// <see cref="Spectra.SpectralImage.Max()"/> (values greater than 0 taken, NaN skipped). The maximum of the shards' maxima.
    /// </summary>
    static float BandScale(List<Part> parts, int width, int bands, CancellationToken cancel)
    {
        float max = 0;
        foreach (var p in parts)
        {
            var plane = new float[p.Crop.Width * p.Crop.Height];
            for (int b = 0; b < bands; b++)
            {
                cancel.ThrowIfCancellationRequested();
                ReadBand(p, width, bands, b, plane);
                foreach (float v in plane) if (v > max) max = v;
            }
        }
        return max;
    }

    /// <summary>bands/*.png and bands.png of the whole image, one band plane at a time.</summary>
    static void MergeBands(List<Part> parts, string outDir, int width, int height, int bands, float scale, List<string> bandFiles,
        bool mosaic, CancellationToken cancel)
    {
        if (bandFiles.Count > 0 && bandFiles.Count != bands)
            throw new InputException(parts[0].Dir, $"lists {bandFiles.Count} band images for {bands} bands",
                "the shards come from different renders: render them again with the same scene");
        if (bandFiles.Count > 0) Directory.CreateDirectory(Path.Combine(outDir, "bands"));
        var full = new float[width * height];
        var grey = new byte[2 * width * height];
        var grid = parts[0].Manifest.Grid;
        var thumbs = mosaic ? BandMosaic.Blank(width, height, bands, 256, grid) : default;
        for (int b = 0; b < bands; b++)
        {
            cancel.ThrowIfCancellationRequested();
            foreach (var p in parts) ReadBand(p, width, bands, b, full.AsSpan(p.Crop.Y0 * width, p.Crop.Height * width));
            if (bandFiles.Count > 0)
            {
                RenderOutputWriter.BandSamples16(full, scale, grey);
                var m = parts[0].Manifest;
                var text = RenderOutputWriter.BandText(grid, b, scale, m.Radiometry, m.BandUnit ?? "");
                AtomicFile.Write(Path.Combine(outDir, bandFiles[b]), s => RenderOutputWriter.WriteBandImage(s, width, height, grey, text));
            }
            if (mosaic) BandMosaic.Draw(thumbs, width, height, bands, b, full, scale, 256, grid);
        }
        if (mosaic)
            AtomicFile.Write(Path.Combine(outDir, "bands.png"), s => PngWriter.WriteGray8(s, thumbs.Width, thumbs.Height, thumbs.Pixels));
    }

    /// <summary>
    /// luminance.png, illuminance.png and their legends: the shards' photometry.exr rows assembled into the whole image's
    /// planes, then drawn as a whole render draws them (the scale spans the whole image's values).
    /// </summary>
    static List<string> MergePhotometryPictures(List<Part> parts, string outDir, int width, int height)
    {
        var luminance = new float[width * height];
        var illuminance = new float[width * height];
        foreach (var p in parts)
        {
            var path = Path.Combine(p.Dir, PhotometryProduct.Exr);
            var (window, channels) = ExrChannelWriter.Read(path);
            if (window != new ExrChannelWriter.PixelWindow(p.Crop.X0, p.Crop.Y0, p.Crop.Width, p.Crop.Height)
                || !channels.TryGetValue("luminance", out var l) || !channels.TryGetValue("illuminance", out var e))
                throw new InputException(path, $"does not hold luminance and illuminance of the shard's rows {p.Crop.Y0}–{p.Crop.Y1 - 1}",
                    "the shard was changed or not finished: render it again");
            l.CopyTo(luminance, p.Crop.Y0 * width);
            e.CopyTo(illuminance, p.Crop.Y0 * width);
        }
        var written = new List<string>();
        PhotometryProduct.WritePictures(outDir, width, height, luminance, illuminance, written.Add);
        return written;
    }

    /// <summary>spectral.img (noise.img): per band, each shard's rows of that band at their offset in the band's plane.</summary>
    static void MergeEnvi(List<Part> parts, string file, string target, int width, int bands)
    {
        var buffer = new byte[1 << 22];
        AtomicFile.Write(target, output =>
        {
            var sources = parts.Select(p =>
                new FileStream(Path.Combine(p.Dir, file), FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16))
                .ToList();
            try
            {
                for (int i = 0; i < parts.Count; i++)
                    if (sources[i].Length != 4L * width * parts[i].Crop.Height * bands)
                        throw new InputException(sources[i].Name,
                            $"has {sources[i].Length} bytes, {4L * width * parts[i].Crop.Height * bands} expected (half-written shard)",
                            "the shard was not finished: render it again");
                for (int b = 0; b < bands; b++)
                    for (int i = 0; i < parts.Count; i++)
                    {
                        long bytes = 4L * width * parts[i].Crop.Height;
                        sources[i].Position = b * bytes;
                        Copy(sources[i], output, bytes, buffer);
                    }
            }
            finally { foreach (var s in sources) s.Dispose(); }
        });
    }

    /// <summary>spectral.hdr (noise.hdr): the shard's header with the whole image's line count (the only line that differs).</summary>
    static void MergeEnviHeader(Part p, string file, string target, int height)
    {
        var text = File.ReadAllText(Path.Combine(p.Dir, file));
        var merged =
            Regex.Replace(text, @"^lines = \d+$", string.Create(CultureInfo.InvariantCulture, $"lines = {height}"), RegexOptions.Multiline);
        AtomicFile.WriteAllText(target, merged);
    }

    /// <summary>
    /// A shard's transfer array lights/NAME per pixel, as the format of the shard's lights/ reads it from its lights.json
    /// (<see cref="TransferFormat.RowShape"/>).
    /// </summary>
    static int[] TransferRows(Part p, string file)
    {
        var format = TransferFiles.FormatOf(p.Dir);
        string name = file[(TransferFormat.Folder.Length + 1)..];
        return (format is { Shards: true } ? format.RowShape(name, Path.Combine(p.Dir, TransferFormat.Folder)) : null)
            ?? throw new InputException(Path.Combine(p.Dir, "render.json"), $"lists '{file}', a file merge does not know",
                "merge shards written by the same version");
    }

    /// <summary>
    /// spectral.npy and the other H × W × … float32 arrays: the whole array's header, then the shards' C-order rows in order
    /// (each shard is whole rows), copied by offset.
    /// </summary>
    static void MergeNpy(List<Part> parts, string file, string target, int width, int height, params int[] inner)
    {
        var buffer = new byte[1 << 22];
        long perPixel = inner.Aggregate(1L, (a, b) => a * b);
        AtomicFile.Write(target, output =>
        {
            output.Write(NpyWriter.Preamble([height, width, .. inner]));
            foreach (var p in parts)
            {
                using var fs = new FileStream(Path.Combine(p.Dir, file), FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
                long start = NpyWriter.Preamble([p.Crop.Height, width, .. inner]).Length, bytes = 4L * width * p.Crop.Height * perPixel;
                if (fs.Length != start + bytes)
                    throw new InputException(fs.Name, $"has {fs.Length} bytes, {start + bytes} expected (half-written shard)",
                        "the shard was not finished: render it again");
                fs.Position = start;
                Copy(fs, output, bytes, buffer);
            }
        });
    }

    static void Copy(Stream from, Stream to, long bytes, byte[] buffer)
    {
        while (bytes > 0)
        {
            int n = (int)Math.Min(buffer.Length, bytes);
            from.ReadExactly(buffer, 0, n);
            to.Write(buffer, 0, n);
            bytes -= n;
        }
    }

    // ---- OpenEXR -----------------------------------------------------------------------------------------------

    /// <summary>A shard's EXR: its header bytes (the dataWindow value at <see cref="WindowAt"/>), chunk offsets and sizes.</summary>
    sealed record ExrParts(byte[] Head, int WindowAt, int LinesPerChunk, long[] Offsets, int[] Sizes);

    /// <summary>
    /// The whole image's EXR: the shards' common header with the full dataWindow (the only attribute that differs:
    /// every shard has the full displayWindow), a new offset table, then the shards' chunks copied as they are (their
    /// y coordinates are already the film's).
    /// </summary>
    static void MergeExr(List<Part> parts, string name, string target, int width, int height)
    {
        var exrs = parts.Select(p => ReadExrLayout(Path.Combine(p.Dir, name), p.Crop)).ToList();
        var head = (byte[])exrs[0].Head.Clone();
        var window = head.AsSpan(exrs[0].WindowAt, 16);
        BinaryPrimitives.WriteInt32LittleEndian(window, 0);
        BinaryPrimitives.WriteInt32LittleEndian(window[4..], 0);
        BinaryPrimitives.WriteInt32LittleEndian(window[8..], width - 1);
        BinaryPrimitives.WriteInt32LittleEndian(window[12..], height - 1);
        for (int i = 1; i < exrs.Count; i++)
        {
            var other = (byte[])exrs[i].Head.Clone();
            window.CopyTo(other.AsSpan(exrs[i].WindowAt, 16));
            if (!other.AsSpan().SequenceEqual(head))
                throw new InputException(Path.Combine(parts[i].Dir, name), $"has another header than {Path.Combine(parts[0].Dir, name)}",
                    "the shards come from different renders: render them again with the same scene");
        }
        int chunks = exrs.Sum(e => e.Offsets.Length);
        int lines = exrs[0].LinesPerChunk;
        if (chunks != (height + lines - 1) / lines)
            throw new InputException(Path.Combine(parts[0].Dir, name),
                $"the shards hold {chunks} chunks, {(height + lines - 1) / lines} expected",
                "a shard is missing or incomplete: render it again");
        var buffer = new byte[1 << 20];
        AtomicFile.Write(target, output =>
        {
            output.Write(head);
            Span<byte> word = stackalloc byte[8];
            long offset = head.Length + 8L * chunks;
            foreach (var e in exrs)
                foreach (int size in e.Sizes)
                {
                    BinaryPrimitives.WriteUInt64LittleEndian(word, (ulong)offset);
                    output.Write(word);
                    offset += 8 + size;
                }
            for (int i = 0; i < parts.Count; i++)
            {
                using var fs = new FileStream(Path.Combine(parts[i].Dir, name), FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
                for (int c = 0; c < exrs[i].Offsets.Length; c++)
                {
                    fs.Position = exrs[i].Offsets[c];
                    Copy(fs, output, 8 + exrs[i].Sizes[c], buffer);
                }
            }
        });
    }

    /// <summary>Parses the header of a shard's scanline EXR, checks its dataWindow is the shard's crop, and reads its chunk
    /// table.</summary>
    static ExrParts ReadExrLayout(string path, PixelRect crop)
    {
        using var fs = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
        var r = new BinaryReader(fs);
        InputException Bad(string what) => new(path, what, "render the shard again");
        try
        {
            if (r.ReadInt32() != ExrWriter.Magic) throw Bad("is not an OpenEXR file");
            r.ReadInt32();   // version and flags: copied with the header
            int windowAt = -1, lines = 0;
            PixelRect? data = null;
            while (true)
            {
                string attr = CString(r);
                if (attr.Length == 0) break;
                string type = CString(r);
                int size = r.ReadInt32();
                long at = fs.Position;
                var value = r.ReadBytes(size);
                if (value.Length != size) throw Bad("is truncated in its header (half-written shard)");
                if (attr == "dataWindow" && type == "box2i" && size == 16)
                {
                    windowAt = (int)at;
                    data = new PixelRect(BinaryPrimitives.ReadInt32LittleEndian(value),
                        BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(4)),
                        BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(8)) + 1,
                            BinaryPrimitives.ReadInt32LittleEndian(value.AsSpan(12)) + 1);
                }
                if (attr == "compression" && size == 1)
                    lines =
                        value[0] switch { 0 or 2 => 1, 3 => 16, _ => throw Bad($"has compression {value[0]}, which merge does not copy") };
            }
            if (windowAt < 0 || lines == 0) throw Bad("has no dataWindow or compression");
            if (data != crop) throw Bad($"has data window {data}, not its crop {crop}");
            int headLength = (int)fs.Position;
            int chunks = (crop.Height + lines - 1) / lines;
            var offsets = new long[chunks];
            for (int c = 0; c < chunks; c++) offsets[c] = (long)r.ReadUInt64();
            var sizes = new int[chunks];
            for (int c = 0; c < chunks; c++)
            {
                if (offsets[c] <= headLength || offsets[c] + 8 > fs.Length)
                    throw Bad($"is truncated (chunk {c} of {chunks} is missing: half-written shard)");
                fs.Position = offsets[c];
                int y = r.ReadInt32();
                sizes[c] = r.ReadInt32();
                if (y != crop.Y0 + c * lines) throw Bad($"chunk {c} starts at row {y}, not {crop.Y0 + c * lines}");
                if (sizes[c] < 0 || offsets[c] + 8 + sizes[c] > fs.Length) throw Bad($"is truncated in chunk {c} (half-written shard)");
            }
            fs.Position = 0;
            var head = new byte[headLength];
            fs.ReadExactly(head);
            return new ExrParts(head, windowAt, lines, offsets, sizes);
        }
        catch (EndOfStreamException) { throw Bad("is truncated (half-written shard)"); }

        static string CString(BinaryReader r)
        {
            var sb = new StringBuilder();
            for (byte c; (c = r.ReadByte()) != 0;) sb.Append((char)c);
            return sb.ToString();
        }
    }

    // ---- PNG ---------------------------------------------------------------------------------------------------

    /// <summary>An 8/16-bit image of the whole film: the shards' decoded rows, encoded again as the writer does it.</summary>
    static void MergePng(List<Part> parts, string name, string target, int width, int height)
    {
        PngImage? first = null;
        ushort[]? samples = null;
        foreach (var p in parts)
        {
            var png = PngReader.Read(Path.Combine(p.Dir, name));
            if (png.Width != width || png.Height != p.Crop.Height)
                throw new InputException(Path.Combine(p.Dir, name),
                    $"is {png.Width}×{png.Height}, not the shard's {p.Crop.Width}×{p.Crop.Height}",
                    "the shards come from different renders: render them again with the same scene");
            first ??= png;
            if (png.BitDepth != first.BitDepth || png.Channels != first.Channels)
                throw new InputException(Path.Combine(p.Dir, name), "has another pixel format than the first shard's",
                    "the shards come from different renders: render them again with the same scene");
            samples ??= new ushort[(long)width * height * first.Channels > Array.MaxLength
                ? throw new InputException(name, "is too large to merge", "render fewer pixels, or merge fewer formats")
                : width * height * first.Channels];
            png.Samples.CopyTo(samples, (long)p.Crop.Y0 * width * first.Channels);
        }
        // The writer's calls (RenderOutputWriter, AnalysisImages): RGB 8-bit preview, 16-bit object ids, 8-bit masks; adaptive filter, no
        // text.
        AtomicFile.Write(target, s =>
        {
            switch (first!.BitDepth, first.Channels)
            {
                case (8, 3): PngWriter.WriteRgb8(s, width, height, Array.ConvertAll(samples!, v => (byte)v)); break;
                case (8, 1): PngWriter.WriteGray8(s, width, height, Array.ConvertAll(samples!, v => (byte)v)); break;
                case (16, 1): PngWriter.WriteGray16(s, width, height, samples!); break;
                default:
                    throw new InputException(name, $"has {first.BitDepth}-bit samples × {first.Channels}, which merge does not write",
                        "merge 8- or 16-bit grey or RGB images");
            }
        });
    }

    // ---- render.json -------------------------------------------------------------------------------------------

    /// <summary>
    /// The first shard's manifest as the whole render's: the band images' scale of the whole image, ray counts,
    /// tiles and pixels whose colour fell back to the bands summed (each pixel's rays are the same wherever it is rendered), threads the
    /// most any shard used, the crop removed; timings_s.render is the shards' summed render time and run the merge's.
    /// </summary>
    static RenderManifest Manifest(List<Part> parts, float scale, string commandLine)
    {
        var first = parts[0].Manifest;
        double render = parts.Sum(p => p.Manifest.RenderSeconds);
        long Sum(Func<ManifestRays, long> f) => parts.Sum(p => f(p.Manifest.Rays));
        long total = Sum(r => r.Total);
        // The first shard's run with the merge's command line, no shard, and each time the longest any shard took.
        double? Longest(Func<ManifestRun, double?> seconds) =>
            first.Run is { } r0 && seconds(r0) is not null ? parts.Max(p => (p.Manifest.Run is { } r ? seconds(r) : null) ?? 0) : null;
        var run = (first.Run ?? new ManifestRun()) with
        {
            CommandLine = commandLine,
            MergedShards = parts.Count,
            Shard = null,
            LoadSeconds = Longest(r => r.LoadSeconds),
            BuildSeconds = Longest(r => r.BuildSeconds),
            LightTransferSeconds = Longest(r => r.LightTransferSeconds),
            WriteSeconds = Longest(r => r.WriteSeconds),
        };
        return first with
        {
            CreatedUtc = RenderManifest.Now(),
            BandImageScale = scale,
            RenderSeconds = render,
            Rays = new ManifestRays(Sum(r => r.Primary), Sum(r => r.Shadow), Sum(r => r.Secondary), total,
                total / Math.Max(1e-9, render) / 1e6),
            Threads = parts.Max(p => p.Manifest.Threads),
            Tiles = parts.Sum(p => p.Manifest.Tiles),
            FallbackPixels = parts.Sum(p => p.Manifest.FallbackPixels),
            Run = run,
            Crop = null,
            Sampling = Sampling(parts),
        };
    }

    /// <summary>
    /// The shards' "sampling" as the whole render's: the relative errors' mean weighted by each shard's pixels, the largest of
    /// their maxima; adaptive sampling's spp mean weighted by each shard's area, the extremes of theirs.
    /// </summary>
    static ManifestSampling? Sampling(List<Part> parts)
    {
        if (parts[0].Manifest.Sampling is not { } first) return null;
        ManifestNoise? noise = null;
        if (first.Noise is { } n0)
        {
            var noises = parts.Select(p => p.Manifest.Sampling?.Noise).OfType<ManifestNoise>().ToList();
            long pixels = noises.Sum(n => n.Pixels);
            double? mean = pixels > 0 ? noises.Sum(n => (n.MeanRelative ?? 0) * n.Pixels) / pixels : null;
            double? max = pixels > 0 ? noises.Max(n => n.MaxRelative ?? 0) : null;
            noise = n0 with { MeanRelative = mean, MaxRelative = max, Pixels = pixels };
        }
        ManifestAdaptive? adaptive = null;
        if (first.Adaptive is { } a0)
        {
            var all = parts.Select(p => (p.Manifest.Sampling?.Adaptive, Area: (double)p.Crop.Width * p.Crop.Height)).ToList();
            double area = all.Sum(x => x.Area);
            adaptive = a0 with
            {
                Min = all.Min(x => x.Adaptive?.Min ?? 0),
                Max = all.Max(x => x.Adaptive?.Max ?? 0),
                Mean = all.Sum(x => (x.Adaptive?.Mean ?? 0) * x.Area) / area,
            };
        }
        return first with { Noise = noise, Adaptive = adaptive };
    }
}
