using System.Diagnostics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>A worker thread's way through a tile (film coordinates [x0, x1) × [y0, y1)); allocated once per worker.</summary>
internal interface ITileWork
{
    void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters);
}

/// <summary>What is done with each camera sample of a pixel (<see cref="Renderer.SampleTile"/>): a struct, so the loop is
/// compiled for it.</summary>
internal interface ISampleSink
{
    void BeginPixel(int x, int y, ref RayCounters counters);
    /// <summary>Camera sample <paramref name="sample"/> of the pixel, weighing <paramref name="weight"/> in it (1/spp; 1 for the
    /// only ray at spp = 1; 0 for the centre ray of the analysis images at spp &gt; 1). Returns the object its ray hits, or −1.</summary>
    int Sample(in CameraSample sample, float weight, bool centre, ref RayCounters counters);
    /// <summary>The pixel is done; <paramref name="id"/> is what its centre ray hit (−1: nothing, or no centre ray).</summary>
    void EndPixel(int x, int y, int id, ref RayCounters counters);
}

/// <summary>
/// A pixel's camera samples: spp jittered rays, stratified over an m × n grid of cells with m·n = spp exactly (m the largest
/// divisor ≤ √spp) so every part of the pixel is sampled equally for any spp, each jittered inside its cell by the
/// sample's first 2D draw (<see cref="Sampler"/>); for spp = 1 the one ray through the pixel centre. With the Sobol sampler
/// (its first 2D draws are a net over the pixel already) and for adaptive sampling (a pixel may stop at any sample) the
/// samples are not put in cells: the film position is the pixel corner plus the first 2D draw.
/// </summary>
internal readonly struct PixelSampling
{
    public readonly Scenes.Camera Camera;
    public readonly int Spp, StrataX, StrataY, Budget;
    /// <summary>1/spp, the weight of each jittered sample.</summary>
    public readonly float Weight;
    /// <summary>Trace the centre ray of the analysis images (spp &gt; 1)?</summary>
    public readonly bool Analysis;
    /// <summary>The sampler the camera samples carry.</summary>
    public readonly SamplerSettings Sampler;

    public PixelSampling(Scenes.Camera camera, int budget, bool analysis, SamplerSettings sampler = default, bool adaptive = false)
    {
        Camera = camera;
        Spp = camera.SamplesPerPixel;
        Sampler = sampler;
        StrataX = 1;
        if (sampler.Kind == SamplerKind.Independent && !adaptive)
            for (int m = (int)Math.Sqrt(Spp); m >= 1; m--) if (Spp % m == 0) { StrataX = m; break; }
        StrataY = sampler.Kind == SamplerKind.Independent && !adaptive ? Spp / StrataX : 1;
        Weight = 1f / Spp;
        Budget = budget;
        Analysis = analysis;
    }

    /// <summary>The film position of sample s of pixel (x, y): cell (s mod m, s div m), jittered inside it.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public (float X, float Y) Film(int x, int y, int s, int cellX, int cellY)
    {
        var (u, v) = new Sampler(x, y, s, 0, Sampler).Next2D();
        if (StrataX * StrataY != Spp) return (x + u, y + v);   // no cells (Sobol, adaptive)
        return (x + (cellX + u) / StrataX, y + (cellY + v) / StrataY);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public CameraSample Sample(int x, int y, int s)
    {
        var (fx, fy) = Film(x, y, s, s % StrataX, s / StrataX);
        return new CameraSample(x, y, s, Camera.Generate(fx, fy), Sampler);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public CameraSample Centre(int x, int y) => new(x, y, CameraSample.Centre, Camera.Generate(x + 0.5f, y + 0.5f), Sampler);
}

public sealed partial class Renderer
{
    /// <summary>
    /// The one tile loop: the film's 32 × 32 tile grid clipped to <paramref name="region"/>, pulled from a shared counter
    /// by one worker per thread (each made once by <paramref name="worker"/>: nothing is allocated per tile, ray or pixel),
    /// the ray counts summed per tile, progress reported after each. Every pixel depends only on its own position, so the
    /// result is the same whatever the thread count or tile order.
    /// </summary>
    internal static (RayCounters Rays, int Tiles, int Threads) RunTiles(PixelRect region, int threads, Action<RenderProgress>? progress,
        Stopwatch clock, CancellationToken cancel, Func<ITileWork> worker)
    {
        // The film's tile grid, clipped to the crop: tile columns tx0 … and rows ty0 … that meet it.
        int tx0 = region.X0 / TileSize, ty0 = region.Y0 / TileSize;
        int tilesX = (region.X1 + TileSize - 1) / TileSize - tx0, tilesY = (region.Y1 + TileSize - 1) / TileSize - ty0;
        int tiles = tilesX * tilesY;
        if (threads <= 0) threads = Environment.ProcessorCount;
        var total = new RayCounters();
        var gate = new object();
        int done = 0, next = -1;
        void Work()
        {
            var work = worker();
            int tile;
            while ((tile = Interlocked.Increment(ref next)) < tiles)
            {
                cancel.ThrowIfCancellationRequested();
                // Film coordinates of the tile, clipped to the crop.
                int tx = tx0 + tile % tilesX, ty = ty0 + tile / tilesX;
                int x0 = Math.Max(region.X0, tx * TileSize), y0 = Math.Max(region.Y0, ty * TileSize);
                int x1 = Math.Min(region.X1, (tx + 1) * TileSize), y1 = Math.Min(region.Y1, (ty + 1) * TileSize);
                var counters = new RayCounters();
                work.Tile(x0, y0, x1, y1, ref counters);
                lock (gate)
                {
                    total.Add(counters);
                    done++;
                    progress?.Invoke(new RenderProgress(done, tiles, total.Total, clock.Elapsed));
                }
            }
        }
        var workers = new Task[Math.Min(threads, tiles)];
        for (int w = 0; w < workers.Length; w++)
            workers[w] = Task.Factory.StartNew(Work, cancel, TaskCreationOptions.None, TaskScheduler.Default);
        try { Task.WaitAll(workers); }
        catch (AggregateException e) when (e.InnerExceptions.All(x => x is OperationCanceledException))
        {
            throw new OperationCanceledException(cancel);
        }
        return (total, tiles, threads);
    }

    /// <summary>
    /// The one camera-sample loop over a tile's pixels, ray by ray: per pixel its spp samples of weight 1/spp, then (spp &gt; 1,
    /// analysis wanted) the centre ray of weight 0; each camera ray with its ray budget (bounded work) and a stop request seen
    /// before every camera ray, so a stop waits for one ray's tree at most (at most the budget's rays), however deep the
    /// scene's rays go or however many samples a pixel takes.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void SampleTile<TSink>(ref TSink sink, in PixelSampling sampling, int x0, int y0, int x1, int y1,
        CancellationToken cancel, ref RayCounters counters) where TSink : struct, ISampleSink
    {
        int spp = sampling.Spp, budget = sampling.Budget;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++)
            {
                cancel.ThrowIfCancellationRequested();
                sink.BeginPixel(x, y, ref counters);
                int id = -1;
                if (spp == 1) id = Camera(ref sink, sampling.Centre(x, y), 1f, true, budget, ref counters);
                else
                {
                    for (int s = 0; s < spp; s++)
                    {
                        if (cancel.IsCancellationRequested) cancel.ThrowIfCancellationRequested();
                        Camera(ref sink, sampling.Sample(x, y, s), sampling.Weight, false, budget, ref counters);
                    }
                    // The analysis images describe the pixel centre.
                    if (sampling.Analysis) id = Camera(ref sink, sampling.Centre(x, y), 0f, true, budget, ref counters);
                }
                sink.EndPixel(x, y, id, ref counters);
            }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static int Camera<TSink>(ref TSink sink, in CameraSample sample, float weight, bool centre, int budget, ref RayCounters counters)
        where TSink : struct, ISampleSink
    {
        counters.StartCameraRay(budget);
        counters.Primary++;
        int id = sink.Sample(in sample, weight, centre, ref counters);
        counters.EndCameraRay();
        return id;
    }
}
