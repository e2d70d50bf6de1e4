using System.Diagnostics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>What a render produced: the spectral framebuffer, the object seen at each pixel, and counts.</summary>
public sealed class RenderResult
{
    public required SpectralImage Image { get; init; }
    /// <summary>Per pixel, the index of the object the centre ray hits, or −1 for background.</summary>
    public required int[] ObjectIds { get; init; }
    /// <summary>Per pixel, bit k set when light k reaches the surface the centre ray sees.</summary>
    public required LitMasks LitMasks { get; init; }
    /// <summary>Per pixel, the highlight mask at the centre ray's hit (<see cref="PixelInfo.Highlight"/>: 255 or 0), one byte
    /// where the luminances of eq. 2's specular and diffuse terms it is decided from would take eight.</summary>
    public required byte[] Highlights { get; init; }
    /// <summary>
    /// Per pixel X, Y, Z (3 floats, κ included): the colour of its spectrum as the scene's integration defines it — with
    /// <see cref="Color.BandIntegration.Exact"/> the sum of each term's exact XYZ from the tables, not eq. 3 on the band values.
    /// </summary>
    public float[]? Xyz { get; init; }
    /// <summary>Pixels whose colour fell back to eq. 3 on their band values because a term multiplied more than two spectra.</summary>
    public long FallbackPixels { get; init; }
    public required RayCounters Rays { get; init; }
    public required TimeSpan Elapsed { get; init; }
    public required int Threads { get; init; }
    public required int Tiles { get; init; }
    /// <summary>The part of the camera's film rendered (the whole film unless cropped); Image is its size.</summary>
    public required PixelRect Crop { get; init; }
    /// <summary>Whether the camera rays were traced in packets (<see cref="Acceleration.RayPacket"/>), else ray by ray.</summary>
    public bool Packets { get; init; }
}

/// <summary>Progress of a render, reported after each tile.</summary>
public readonly record struct RenderProgress(int TilesDone, int Tiles, long Rays, TimeSpan Elapsed);

/// <summary>
/// Renders a scene in square tiles on all cores. Each pixel depends only on its own position
/// (its jitter comes from a hash of x, y and the sample index), so the framebuffer is identical
/// whatever the thread count or tile order.
/// </summary>
public sealed partial class Renderer
{
    public const int TileSize = 32;

    /// <summary>
    /// Hands the garbage of scene loading and the BVH build (a mesh file's bytes, parse and build scratch: ~10 MB for the
    /// bunny) back to the OS before a render allocates its arrays, so a one-shot command's peak working set is the scene,
    /// the BVH and the render (BENCHMARKS.md). One blocking, compacting collection of a few megabytes: milliseconds.
    /// </summary>
    public static void ReturnLoadGarbage() => GC.Collect(2, GCCollectionMode.Aggressive, blocking: true, compacting: true);

    public static RenderResult Render(Scene scene, int threads = 0, Action<RenderProgress>? progress = null, CancellationToken cancel = default, PixelRect? crop = null)
    {
        var geometry = new SceneGeometry(scene);
        return Render(scene, Integrators.Create(scene, geometry), threads, progress, cancel, crop);
    }

    /// <param name="crop">Renders only these pixels of the film (--crop, --shard): the tiles are the whole film's
    /// 32 × 32 grid clipped to the crop, and each pixel is computed from its own film coordinates, so a crop holds the
    /// same values as the same pixels of a whole render.</param>
    /// <param name="packets">Trace camera rays in packets when the integrator can (<see cref="IPacketIntegrator"/>; the default); false traces every ray alone (the same image).</param>
    public static RenderResult Render(Scene scene, IIntegrator integrator, int threads = 0, Action<RenderProgress>? progress = null, CancellationToken cancel = default, PixelRect? crop = null, bool packets = true)
    {
        var cam = scene.Camera;
        var region = crop ?? PixelRect.Whole(cam.Width, cam.Height);
        if (region.X0 < 0 || region.Y0 < 0 || region.X1 > cam.Width || region.Y1 > cam.Height || region.Width < 1 || region.Height < 1)
            throw new ArgumentOutOfRangeException(nameof(crop), $"crop {region} is not inside the {cam.Width}×{cam.Height} film");
        // width × height: the framebuffer (the crop); (ox, oy): its first pixel on the film.
        int width = region.Width, height = region.Height, ox = region.X0, oy = region.Y0, bands = scene.Bands, padded = scene.PaddedBands;
        // Every pixel of these is written by its tile, so they are not zeroed first (80 MB at 1024² × 20 bands).
        var image = new SpectralImage(width, height, scene.Grid, LargeArrays.Uninitialized<float>(width * height * bands));
        var ids = GC.AllocateUninitializedArray<int>(width * height);
        var lit = new LitMasks(width * height, scene.Lights.Count);
        var highlights = GC.AllocateUninitializedArray<byte>(width * height);
        float highlightFraction = (float)scene.Output.HighlightFraction;
        var xyz = GC.AllocateUninitializedArray<float>(3 * width * height);
        long fallbackPixels = 0;
        var colorimeter = scene.Colorimeter;
        int lane = bands;   // the colour lanes follow the bands (SpectralMath.ColourLanes)
        // The film's tile grid, clipped to the crop: tile columns tx0 … and rows ty0 … that meet it.
        int tx0 = ox / TileSize, ty0 = oy / TileSize;
        int tilesX = (region.X1 + TileSize - 1) / TileSize - tx0, tilesY = (region.Y1 + TileSize - 1) / TileSize - ty0;
        int tiles = tilesX * tilesY;
        if (threads <= 0) threads = Environment.ProcessorCount;
        var total = new RayCounters();
        var gate = new object();
        int done = 0;
        var clock = Stopwatch.StartNew();
        int spp = cam.SamplesPerPixel;
        // Stratified jitter over an m × n grid of cells with m·n = spp exactly (m the largest divisor ≤ √spp),
        // so every part of the pixel is sampled equally for any spp.
        int strataX = 1;
        for (int m = (int)Math.Sqrt(spp); m >= 1; m--) if (spp % m == 0) { strataX = m; break; }
        int strataY = spp / strataX;
        float inv = 1f / spp;
        int budget = scene.RayBudget;
        bool recursive = scene.MaxDepth > 0 && scene.Materials.Any(m => m.HasMirror || m.HasTransmission);

        // One worker per thread, each with its own scratch spectra, pulling tiles from a shared counter:
        // the loop allocates per worker, never per tile, ray or pixel.
        bool packed = packets && integrator is IPacketIntegrator && !recursive;
        int next = -1;
        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        void Worker()
        {
            var state = new TileState(integrator.ScratchLength, padded);
            // Packets trace the camera rays of a tile together; a scene with mirrors or glass is traced ray by ray, where each
            // camera ray's tree has its ray budget and a stop request is seen at every pixel (bounded work, prompt SIGINT).
            var packetState = packed ? new PacketTileState(integrator.ScratchLength, padded, ox, oy) : null;
            int tile;
            while ((tile = Interlocked.Increment(ref next)) < tiles)
            {
                cancel.ThrowIfCancellationRequested();
                // Film coordinates of the tile, clipped to the crop.
                int x0 = Math.Max(region.X0, (tx0 + tile % tilesX) * TileSize), y0 = Math.Max(region.Y0, (ty0 + tile / tilesX) * TileSize);
                int x1 = Math.Min(region.X1, (tx0 + tile % tilesX + 1) * TileSize), y1 = Math.Min(region.Y1, (ty0 + tile / tilesX + 1) * TileSize);
                var counters = new RayCounters();
                var sum = state.Sum.AsSpan();
                var sample = state.Sample.AsSpan();
                var scratch = state.Scratch.AsSpan();
                if (packetState is not null)
                    PacketTile((IPacketIntegrator)integrator, cam, x0, y0, x1, y1, strataX, strataY, packetState, image, ids, lit, highlights, highlightFraction, xyz, colorimeter, ref fallbackPixels, ref counters);
                else
                    for (int y = y0; y < y1; y++)
                        for (int x = x0; x < x1; x++)
                        {
                            // Inside the tile too: one pixel's work is bounded by the ray budget, so a request to stop
                            // is seen within one pixel's time, however deep the scene's rays go.
                            cancel.ThrowIfCancellationRequested();
                            int id;
                            var info = new PixelInfo();
                            long fallbackBefore = counters.Fallback;
                            if (spp == 1)
                            {
                                counters.StartCameraRay(budget);
                                counters.Primary++;
                                id = integrator.Radiance(cam.Generate(x + 0.5f, y + 0.5f), sum, scratch, ref counters, ref info);
                                counters.EndCameraRay();
                            }
                            else
                            {
                                sum.Clear();
                                for (int s = 0; s < spp; s++)
                                {
                                    // Sample s in cell (s mod m, s div m), jittered inside it.
                                    uint h = Hash((uint)x, (uint)y, (uint)s);
                                    float jx = ((s % strataX) + (h & 0xFFFF) / 65536f) / strataX;
                                    float jy = ((s / strataX) + (h >> 16) / 65536f) / strataY;
                                    PixelInfo unused = default;
                                    counters.StartCameraRay(budget);
                                    counters.Primary++;
                                    integrator.Radiance(cam.Generate(x + jx, y + jy), sample, scratch, ref counters, ref unused);
                                    counters.EndCameraRay();
                                    SpectralMath.AddScaled(sum, sample, inv);
                                }
                                // The analysis images describe the pixel centre.
                                counters.StartCameraRay(budget);
                                counters.Primary++;
                                id = integrator.Radiance(cam.Generate(x + 0.5f, y + 0.5f), sample, scratch, ref counters, ref info);
                                counters.EndCameraRay();
                            }
                            sum[..bands].CopyTo(image.Data.AsSpan(image.Offset(x - ox, y - oy), bands));
                            int i = (y - oy) * width + (x - ox);
                            if (counters.Fallback == fallbackBefore) { xyz[3 * i] = sum[lane]; xyz[3 * i + 1] = sum[lane + 1]; xyz[3 * i + 2] = sum[lane + 2]; }
                            else
                            {   // a term multiplied more spectra than the tables hold: eq. 3 on this pixel's band values
                                var c = colorimeter.ToXyz((ReadOnlySpan<float>)sum[..bands]);
                                xyz[3 * i] = (float)c.X; xyz[3 * i + 1] = (float)c.Y; xyz[3 * i + 2] = (float)c.Z;
                                Interlocked.Increment(ref fallbackPixels);
                            }
                            ids[i] = id;
                            lit[i] = info.LitMask;
                            highlights[i] = PixelInfo.Highlight(info.SpecularY, info.DiffuseY, highlightFraction);
                        }
                lock (gate)
                {
                    total.Add(counters);
                    done++;
                    progress?.Invoke(new RenderProgress(done, tiles, total.Total, clock.Elapsed));
                }
            }
        }
        var workers = new Task[Math.Min(threads, tiles)];
        for (int w = 0; w < workers.Length; w++) workers[w] = Task.Factory.StartNew(Worker, cancel, TaskCreationOptions.None, TaskScheduler.Default);
        try { Task.WaitAll(workers); }
        catch (AggregateException e) when (e.InnerExceptions.All(x => x is OperationCanceledException)) { throw new OperationCanceledException(cancel); }

        return new RenderResult { Image = image, ObjectIds = ids, LitMasks = lit, Highlights = highlights, Xyz = xyz, FallbackPixels = fallbackPixels, Rays = total, Elapsed = clock.Elapsed, Threads = threads, Tiles = tiles, Crop = region, Packets = packed };
    }

    sealed class TileState(int scratch, int padded)
    {
        public readonly float[] Scratch = new float[scratch];
        public readonly float[] Sum = new float[padded];
        public readonly float[] Sample = new float[padded];
    }

    /// <summary>A small integer hash (lowbias32 by C. Wellons) for per-sample jitter.</summary>
    internal static uint Hash(uint x, uint y, uint s)
    {
        uint h = x * 0x9E3779B1u ^ (y + 0x7F4A7C15u) * 0x85EBCA77u ^ (s + 1) * 0xC2B2AE3Du;
        h ^= h >> 16; h *= 0x7FEB352Du; h ^= h >> 15; h *= 0x846CA68Bu; h ^= h >> 16;
        return h;
    }
}
