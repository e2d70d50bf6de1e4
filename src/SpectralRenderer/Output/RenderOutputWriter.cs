using System.Buffers;
using System.Buffers.Binary;
using System.Globalization;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

/// <summary>
/// Writes a render's files into its output folder (guide §6): preview.png, bands/ with bands.png,
/// the spectral cubes, object-id.png and render.json. Each file goes to a temporary name first.
/// </summary>
public static class RenderOutputWriter
{
    /// <summary>This engine build's identity (render.json "build"): the module version id of its assembly.</summary>
    public static string EngineBuild { get; } = typeof(RenderOutputWriter).Assembly.ManifestModule.ModuleVersionId.ToString("N");

    public static List<string> Write(Scene scene, RenderResult result, string outDir, ManifestRun? run = null,
        CancellationToken cancel = default,
        ILightTransfer? transfer = null, ReusedFiles? reuse = null, IReadOnlyList<OutputProduct>? named = null,
        RenderTracer? tracer = null) =>
        Write(scene, result, OutputFolder.Begin(outDir), run, cancel, transfer, reuse, named, tracer);

    /// <summary>
    /// Writes the render into <paramref name="folder"/>'s staging folder and swaps it in whole (<see cref="OutputFolder"/>).
    /// Interrupted or failed, the staged files are removed and the folder holds what it held before.
    /// </summary>
    /// <param name="reuse">Files another folder holds exactly as this render would write them (a relit render's light-independent files):
    /// copied, not encoded.</param>
    /// <param name="named">Products asked for by name beyond the scene's formats (<see cref="OutputProductTable.Named"/>).</param>
    /// <param name="tracer">The render's geometry and integrator, for products that trace rays (photometry's illuminance).</param>
    /// <param name="extra">Text files staged and swapped in with the render's (name → text), listed in render.json.</param>
    /// <param name="warning">Where a one-line warning goes (an all-black or all-white preview), or null.</param>
    /// <param name="progress">Where products that trace rays of their own report progress (photometry, grids), or null.</param>
    public static List<string> Write(Scene scene, RenderResult result, OutputFolder folder, ManifestRun? run = null,
        CancellationToken cancel = default,
        ILightTransfer? transfer = null, ReusedFiles? reuse = null, IReadOnlyList<OutputProduct>? named = null,
        RenderTracer? tracer = null, IReadOnlyDictionary<string, string>? extra = null, Action<string>? warning = null,
        Action<RenderProgress>? progress = null)
    {
        List<string> written;
        // Warnings are said once the render is swapped in: a render that fails says only why.
        var warnings = new System.Collections.Concurrent.ConcurrentQueue<string>();
        try
        {
            written = WriteFiles(scene, result, folder.Staging, run, cancel, transfer, reuse, named, tracer, extra, warnings.Enqueue,
                progress);
        }
        catch (OperationCanceledException e) when (e is not InterruptedException)
        {
            folder.Abandon();
            throw new InterruptedException($"interrupted while writing: the new render's partial files were removed; {folder.Final} "
                + $"{(folder.HoldsRender ? "still holds the previous render, unchanged" : "holds no render")}",
                e.CancellationToken);
        }
        catch
        {
            folder.Abandon();
            throw;
        }
        folder.Commit(written, cancel);
        if (warning is not null) foreach (var w in warnings) warning(w);
        return written;
    }

    /// <summary>Every number the files will show must be finite: a render with NaN or ∞ radiance writes nothing.</summary>
    static void CheckFinite(SpectralImage image)
    {
        var data = image.Data.AsSpan();
        if (AllFinite(data)) return;
        long bad = 0;
        int first = -1;
        for (int i = 0; i < data.Length; i++)
            if (!float.IsFinite(data[i])) { bad++; if (first < 0) first = i; }
        if (bad > 0)
        {
            int px = first / image.Bands;
            throw new WorkFailedException($"the render produced {bad} non-finite band values (the first at pixel "
                + $"{px % image.Width},{px / image.Width}, band {first % image.Bands}); nothing was written");
        }
    }

    /// <summary>No NaN or ∞: no value has all exponent bits set (IEEE 754 binary32), a vector of values at a time.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static bool AllFinite(ReadOnlySpan<float> data)
    {
        int i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var exponent = new Vector<uint>(0x7F800000u);
            var any = Vector<uint>.Zero;
            var bits = MemoryMarshal.Cast<float, uint>(data);
            for (; i + Vector<uint>.Count <= bits.Length; i += Vector<uint>.Count)
                any |= Vector.Equals(new Vector<uint>(bits[i..]) & exponent, exponent);
            if (any != Vector<uint>.Zero) return false;
        }
        for (; i < data.Length; i++) if (!float.IsFinite(data[i])) return false;
        return true;
    }

    /// <summary>The first JSON path in <paramref name="node"/> holding a number that is not finite, or null.</summary>
    internal static string? NonFinite(JsonNode? node, string path = "$")
    {
        switch (node)
        {
            case JsonObject o:
                foreach (var (k, v) in o) if (NonFinite(v, $"{path}.{k}") is { } p) return p;
                return null;
            case JsonArray a:
                for (int i = 0; i < a.Count; i++) if (NonFinite(a[i], $"{path}[{i}]") is { } p) return p;
                return null;
            case JsonValue v:
                if (v.TryGetValue<double>(out var d) && !double.IsFinite(d)) return path;
                if (v.TryGetValue<float>(out var f) && !float.IsFinite(f)) return path;
                return null;
            default: return null;
        }
    }

    static List<string> WriteFiles(Scene scene, RenderResult result, string outDir, ManifestRun? run, CancellationToken cancel,
        ILightTransfer? transfer, ReusedFiles? reuse, IReadOnlyList<OutputProduct>? named, RenderTracer? tracer,
        IReadOnlyDictionary<string, string>? extra, Action<string>? warning, Action<RenderProgress>? progress)
    {
        var products = OutputProductTable.For(scene.Output.Products, named);
        var needs = ProductInputs.None;
        foreach (var p in products) needs |= p.Needs;
        var writeClock = System.Diagnostics.Stopwatch.StartNew();
        var image = result.Image;
        CheckFinite(image);
        Directory.CreateDirectory(outDir);
        float scale = image.Max();
        int n = image.Width * image.Height;
        // Band-sequential planes, transposed once and shared by the band PNGs, the mosaic, spectral.exr and the ENVI cube;
        // eq. 3's XYZ of every pixel, computed once for the preview and spectral.exr's R, G, B and X, Y, Z.
        // Without a writer of planes, the preview takes XYZ from the cube itself (no second copy of the cube).
        float[]? bands = needs.HasFlag(ProductInputs.BandPlanes) ? image.BandPlanes() : null;
        // The pixels' colours are the renderer's own (exact on the tables under "exact" integration), else eq. 3 on the cube.
        bool colour = needs.HasFlag(ProductInputs.Xyz);
        var xyz = !colour ? null
            : result.Xyz is { } px ? XyzPlanes.FromPixels(px)
            : bands is not null ? XyzPlanes.Compute(scene.Colorimeter, bands, n)
            : XyzPlanes.Compute(scene.Colorimeter, image);

        var encoder = needs.HasFlag(ProductInputs.PreviewEncoder) ? PreviewEncoder(scene, xyz!) : null;
        var context = new ProductContext
        {
            Scene = scene,
            Result = result,
            OutDir = outDir,
            BandScale = scale,
            BandPlanes = bands,
            Xyz = xyz,
            Preview = encoder,
            Transfer = transfer,
            Tracer = tracer,
            Reuse = reuse,
            Cancel = cancel,
            Warning = warning,
            Progress = progress,
        };

        // The products' writers are independent files: run them side by side; each keeps its own list, in a fixed order.
        // (Plain loops: LINQ over (product, part) tuples is generic code the ReadyToRun image cannot hold, compiled at every start.)
        var groups = new List<List<string>>();
        var actions = new List<Action>();
        Action<string> Done(List<string> group) => name => { lock (group) group.Add(name); cancel.ThrowIfCancellationRequested(); };
        RenderManifest? manifest = null;
        foreach (var product in products)
            for (int part = 0; part < product.Parts; part++)
            {
                var group = new List<string>();
                groups.Add(group);
                int which = part;
                actions.Add(() => product.Write(context, which, Done(group)));
            }
        actions.Add(() => manifest = Describe(scene, result, scale, run, encoder));
        try
        {
            Parallel.Invoke(new ParallelOptions { CancellationToken = cancel }, actions.ToArray());
        }
        catch (AggregateException e)
        {
            // Report the one cause (interruption first) as if the writes had run in sequence.
            var first = e.Flatten().InnerExceptions.OrderBy(x => x is OperationCanceledException ? 0 : 1).First();
            System.Runtime.ExceptionServices.ExceptionDispatchInfo.Capture(first).Throw();
        }

        var written = new List<string>();
        foreach (var g in groups) written.AddRange(g);
        foreach (var (name, text) in extra ?? new Dictionary<string, string>())
        {
            AtomicFile.WriteAllText(Path.Combine(outDir, name), text);
            written.Add(name);
        }
        cancel.ThrowIfCancellationRequested();
        // Wall seconds from the pixels to every file but render.json written (not hashed: a timing).
        var final = manifest! with
        {
            Files = written.ToArray(),
            Run = run is null ? null : run with { WriteSeconds = writeClock.Elapsed.TotalSeconds }
        };
        if (NonFinite(final.ToJson()) is { } bad)
            throw new WorkFailedException($"render.json would hold a non-finite number at {bad}; nothing was written");
        AtomicFile.WriteAllText(Path.Combine(outDir, RenderManifest.FileName), final.ToJsonText());
        written.Add(RenderManifest.FileName);
        return written;
    }

    internal static void WritePreview(SpectralImage image, XyzPlanes xyz, DisplayEncoder encoder, string outDir, Action<string> done,
        Action<string>? warning = null)
    {
        var rgb = Preview(image.Width, image.Height, xyz, encoder);
        if (warning is not null && Blank(rgb) is { } blank)
            warning($"spectral render: warning: preview.png is all {blank} at exposure "
                + $"{encoder.Exposure.ToString("G4", CultureInfo.InvariantCulture)} (hint: give the scene "
                + $"\"output\": {{ \"exposure\": \"auto\" }} or a {(blank == "black" ? "larger" : "smaller")} exposure; "
                + "the spectral files are not affected)");
        AtomicFile.Write(Path.Combine(outDir, "preview.png"), s => PngWriter.WriteRgb8(s, image.Width, image.Height, rgb));
        done("preview.png");
    }

    /// <summary>"black" or "white" when every code of an 8-bit RGB image is 0, or every one 255; else null.</summary>
    public static string? Blank(ReadOnlySpan<byte> rgb)
    {
        if (rgb.IsEmpty) return null;
        if (!rgb.ContainsAnyExcept((byte)0)) return "black";
        if (!rgb.ContainsAnyExcept((byte)255)) return "white";
        return null;
    }

    /// <summary>The preview's encoder: the scene's exposure (or the automatic one, from the pixels' XYZ) and gamut mapping.</summary>
    public static DisplayEncoder PreviewEncoder(Scene scene, XyzPlanes xyz)
    {
        var o = scene.Output;
        double exposure = o.ExposureAuto
            ? DisplayEncoder.AutoExposure(scene.Colorimeter, o.Rgb, o.Adapt, xyz.X.Length, i => xyz[i])
            : o.Exposure;
        return new DisplayEncoder(scene.Colorimeter, o.Rgb, exposure, o.Adapt, o.Gamut);
    }

    /// <summary>bands/: one 16-bit PNG per band, all on the scale of the brightest band value.</summary>
    internal static void WriteBands(Scene scene, SpectralImage image, float[] bands, float scale, string outDir, Action<string> done,
        CancellationToken cancel)
    {
        var dir = Path.Combine(outDir, "bands");
        Directory.CreateDirectory(dir);
        int n = image.Width * image.Height;
        var names = new string[image.Bands];
        Parallel.For(0, image.Bands, new ParallelOptions { CancellationToken = cancel },
            [MethodImpl(MethodImplOptions.AggressiveOptimization)] (b) =>
        {
            var plane = bands.AsSpan(b * n, n);
            var grey = ArrayPool<byte>.Shared.Rent(2 * n);
            try
            {
                BandSamples16(plane, scale, grey.AsSpan(0, 2 * n));
                names[b] = BandFileName(scene, b);
                var text = BandText(scene, b, scale);
                AtomicFile.Write(Path.Combine(dir, names[b]),
                    s => WriteBandImage(s, image.Width, image.Height, grey.AsSpan(0, 2 * n), text));
            }
            finally { ArrayPool<byte>.Shared.Return(grey); }
        });
        foreach (var name in names) done($"bands/{name}");
    }

    /// <summary>
    /// One band image: 16-bit linear samples (gAMA 1) on the common scale, which the text chunks state with its unit. The Sub
    /// filter alone (one pass per row instead of trying all five) and deflate blocks of Huffman-coded literals
    /// (<see cref="HuffmanDeflate"/>): a band image's residuals have no long repeats for LZ77 to find, so this is about 3×
    /// faster than zlib at level 1 and the files are about a fifth smaller (BENCHMARKS.md, "Writers").
    /// </summary>
    internal static void WriteBandImage(Stream s, int width, int height, ReadOnlySpan<byte> bigEndian, Dictionary<string, string> text) =>
        PngWriter.WriteGray16BigEndian(s, width, height, bigEndian, PngFilter.Sub, text, gamma: 1.0, huffmanOnly: true);

    /// <summary>The tEXt chunks of band image b: what it shows and the scale from its samples to band values.</summary>
    internal static Dictionary<string, string> BandText(Scene scene, int b, float scale) =>
        BandText(scene.Grid, b, scale, scene.Radiometry.ToString().ToLowerInvariant(), RadianceUnit(scene));

    /// <summary>As above, from the band grid, the radiometry's name and the unit of a band value (as render.json states them).</summary>
    internal static Dictionary<string, string> BandText(BandGrid g, int b, float scale, string radiometry, string unit)
    {
        var inv = CultureInfo.InvariantCulture;
        return new Dictionary<string, string>
        {
            ["Title"] = string.Create(inv, $"band {b + 1} of {g.Count}: {g.Lower(b):0.###}-{g.Upper(b):0.###} nm"),
            ["Software"] = $"spectral {typeof(RenderOutputWriter).Assembly.GetName().Version?.ToString(3)}",
            ["Scale"] = string.Create(inv,
                $"band value = sample / 65535 * {scale:R} {unit} (linear samples, gAMA 1.0; values above the scale clip)"),
            ["Radiometry"] = radiometry,
        };
    }

    /// <summary>What a band value is, in ASCII: spectral radiance in W m^-2 sr^-1 nm^-1 (physical) or eq. 2's relative units
    /// (paper).</summary>
    /// <summary>render.json's "sampling", or null for the independent sampler of seed 0 without per-pixel statistics.</summary>
    static ManifestSampling? Sampling(Scene scene, RenderResult result, Colorimeter c)
    {
        if (result.Sampler == SamplerSettings.Independent && result.Noise is null) return null;
        var noise = result.Noise is { } n && result.Xyz is { } xyz
            ? ManifestNoise.Of(n, xyz, scene.Bands, RadianceUnit(scene),
                c.Absolute && scene.Radiometry == Radiometry.Physical ? "cd/m^2" : "Y as radiometry.xyz states it")
            : null;
        var adaptive = result.SamplesUsed is { } used ? ManifestAdaptive.Of(result.TargetError, scene.Camera.SamplesPerPixel, used) : null;
        return new ManifestSampling(Samplers.Name(result.Sampler.Kind), result.Sampler.Seed, noise, adaptive);
    }

    public static string RadianceUnit(Scene scene) => scene.Radiometry == Radiometry.Physical
        ? "W.m^-2.sr^-1.nm^-1 (spectral radiance, band mean)"
        : "relative units (paper radiometry: eq. 2 without units; a white diffuser lit head-on by the reference white at "
            + "intensity 1 has band value E_b)";

    /// <summary>
    /// A band image's 16-bit samples RgbSpace.To16(clamp(v / scale, 0, 1)) (0 when scale is not positive), big-endian as PNG
    /// §7.1 stores them. Vectorised: for a float f in [0, 1], 65535·f is exact in double (≤ 40 significant bits), so
    /// floor(65535·f + ½) is exact too and equals To16's rounding half away from zero; NaN gives 0 as To16 does.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void BandSamples16(ReadOnlySpan<float> plane, float scale, Span<byte> bigEndian)
    {
        var samples = MemoryMarshal.Cast<byte, ushort>(bigEndian[..(2 * plane.Length)]);
        if (!(scale > 0)) { samples.Clear(); return; }
        int i = 0;
        if (Vector.IsHardwareAccelerated && BitConverter.IsLittleEndian)
        {
            var s = new Vector<float>(scale);
            var half = new Vector<double>(0.5);
            var full = new Vector<double>(65535.0);
            var magic = new Vector<double>(4503599627370496.0);   // 2⁵²: an integer t < 2³² added to it sits in the low bits
            for (; i + 2 * Vector<float>.Count <= plane.Length; i += 2 * Vector<float>.Count)
            {
                var a = Clamp01(new Vector<float>(plane[i..]) / s);
                var b = Clamp01(new Vector<float>(plane[(i + Vector<float>.Count)..]) / s);
                Vector.Widen(a, out var a0, out var a1);
                Vector.Widen(b, out var b0, out var b1);
                var q = Vector.Narrow(Vector.Narrow(Bits(a0), Bits(a1)), Vector.Narrow(Bits(b0), Bits(b1)));
                ((q << 8) | (q >>> 8)).CopyTo(samples[i..]);   // big-endian
            }

            Vector<ulong> Bits(Vector<double> f) => Vector.AsVectorUInt64(Vector.Floor(f * full + half) + magic);
        }
        for (; i < plane.Length; i++)
            BinaryPrimitives.WriteUInt16BigEndian(bigEndian[(2 * i)..], RgbSpace.To16(Math.Clamp(plane[i] / scale, 0, 1)));

        static Vector<float> Clamp01(Vector<float> v) =>
            Vector.ConditionalSelect(Vector.Equals(v, v), Vector.Min(Vector.Max(v, Vector<float>.Zero), Vector<float>.One),
                Vector<float>.Zero);
    }

    public static string BandFileName(Scene scene, int b) =>
        string.Create(CultureInfo.InvariantCulture,
            $"band-{Spectra.BandGrid.Number(b):00}-{scene.Grid.Lower(b):0.###}-{scene.Grid.Upper(b):0.###}nm.png");

    public static byte[] Preview(SpectralImage image, DisplayEncoder encoder) =>
        Preview(image.Width, image.Height, XyzPlanes.Compute(encoder.Colorimeter, image), encoder);

    /// <summary>8-bit display RGB, from the pixels' XYZ (of the encoder's colorimeter).</summary>
    public static byte[] Preview(int width, int height, XyzPlanes xyz, DisplayEncoder encoder)
    {
        var rgb = new byte[width * height * 3];
        Parallel.For(0, height, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (y) =>
        {
            for (int i = y * width; i < (y + 1) * width; i++)
            {
                var (r, g, b) = encoder.Encode8(xyz[i]);
                rgb[3 * i] = r; rgb[3 * i + 1] = g; rgb[3 * i + 2] = b;
            }
        });
        return rgb;
    }

    internal static RenderManifest Describe(Scene scene, RenderResult result, float bandScale, ManifestRun? run, DisplayEncoder? preview)
    {
        var c = scene.Colorimeter;
        var objects = new ManifestObject[scene.Objects.Count];
        for (int i = 0; i < objects.Length; i++)
        {
            var o = scene.Objects[i];
            var m = scene.Materials[o.Material];
            double[]? normal = null;
            // A flat shape's world normal (front side +), so analysis can tell a head-on lit chart from a shaded one.
            if (o.Shape is { Kind: Geometry.ShapeKind.Quad or Geometry.ShapeKind.Plane } shape)
            {
                var nrm = System.Numerics.Vector3.Normalize(System.Numerics.Vector3.TransformNormal(
                    shape.Kind == Geometry.ShapeKind.Quad ? System.Numerics.Vector3.UnitZ : System.Numerics.Vector3.UnitY,
                        shape.NormalToWorld));
                normal = [nrm.X, nrm.Y, nrm.Z];
            }
            objects[i] = new ManifestObject(i + 1, o.Name, m.Name, m.DiffuseSpectrum?.Name, normal);
        }
        var lights = new ManifestLight[scene.Lights.Count];
        for (int k = 0; k < lights.Length; k++)
        {
            var l = scene.Lights[k];
            var d = l.Describe(scene.Radiometry);
            lights[k] = new ManifestLight(k, l.Name, d.Type, l.Spectrum?.Name, l.Scale, d.Unit, l.HasAmbient,
                d.Position, d.Direction, d.Attenuation, l.Spectrum, l.Photometric is { } p
                    ? new ManifestPhotometry(p.Quantity, p.Value, p.Unit, p.RadiometricScale, p.LuminousPerUnit) : null);
        }
        var manifest = new RenderManifest
        {
            Version = typeof(RenderOutputWriter).Assembly.GetName().Version?.ToString(3),
            Build = EngineBuild,
            Scene = scene.SourcePath,
            CreatedUtc = RenderManifest.Now(),
            // The film's size; a crop or shard holds the pixels of Crop only.
            Width = scene.Camera.Width,
            Height = scene.Camera.Height,
            SamplesPerPixel = scene.Camera.SamplesPerPixel,
            Grid = scene.Grid,
            BandImageScale = bandScale,
            Integration = scene.Integration,
            ObserverDegrees = c.Observer.Degrees,
            ReferenceWhite = scene.ReferenceWhite,
            Kappa = c.Kappa,
            White = c.White,
            Wx = c.Wx,
            Wy = c.Wy,
            Wz = c.Wz,
            Rgb = scene.Output.Rgb.Name,
            Exposure = preview?.Exposure ?? scene.Output.Exposure,
            ExposureMode = scene.Output.ExposureAuto
                ? "auto (99th percentile of the display-linear maximum channel of non-black pixels → 1)"
                : "fixed",
            Gamut = scene.Output.Gamut.ToString().ToLowerInvariant(),
            Radiometry = scene.Radiometry.ToString().ToLowerInvariant(),
            BandUnit = RadianceUnit(scene),
            XyzUnit = c.Absolute
                ? (scene.Radiometry == Radiometry.Physical
                    ? "absolute: Y in cd/m^2 (683 lm/W)"
                    : "absolute: κ = 683 applied to relative radiance (no photometric unit)")
                : "relative: Y = 1 for a perfect white diffuser lit head-on by the reference white at intensity 1",
            PixelXyz = scene.Integration == BandIntegration.Exact
                ? "exact: each term's κ∫x̄·E·m dλ on the full tables (spectral.exr X Y Z, R G B and preview.png); the weights give the "
                    + "cube's own colour, which differs"
                : "eq. 3 on the band values with the weights",
            FallbackPixels = result.FallbackPixels,
            GlobalAmbient = scene.HasGlobalAmbient,
            Adapt = scene.Output.Adapt,
            Objects = objects,
            Lights = lights,
            HighlightFraction = scene.Output.HighlightFraction,
            RenderSeconds = result.Elapsed.TotalSeconds,
            Rays = new ManifestRays(result.Rays.Primary, result.Rays.Shadow, result.Rays.Secondary, result.Rays.Total,
                result.Rays.Total / Math.Max(1e-9, result.Elapsed.TotalSeconds) / 1e6),
            Threads = result.Threads,
            Tiles = result.Tiles,
            Run = run,
            ResolvedScene = scene.Resolved is { } resolved ? new ManifestScene(resolved) : null,
            Crop = result.Crop.IsWhole(scene.Camera.Width, scene.Camera.Height) ? null : result.Crop,
            Sampling = Sampling(scene, result, c),
        };
        return manifest with { SceneHash = Output.SceneHash.Of(manifest.ToJson(), scene.Output.Products, scene.Output.ExrCompression) };
    }
}
