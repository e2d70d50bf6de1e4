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
    /// <summary>
    /// Per pixel (N + 1 floats, pixel-interleaved as <see cref="Image"/>): the standard error of the pixel's mean from its own
    /// samples, per band (the band unit) and of luminance Y (the unit of <see cref="Xyz"/>'s Y), by the sampler's method
    /// (Renderer.Statistics.cs: Sobol from its independent randomisations, independent samples from the stratified cells or
    /// s/√n); null unless the noise product or adaptive sampling was asked for.
    /// </summary>
    public float[]? Noise { get; init; }
    /// <summary>Per pixel, the samples adaptive sampling took (<see cref="TargetError"/> &gt; 0), else null.</summary>
    public int[]? SamplesUsed { get; init; }
    /// <summary>The relative standard error of luminance at which adaptive sampling stopped a pixel (0: off).</summary>
    public double TargetError { get; init; }
    /// <summary>The sampler of the camera samples.</summary>
    public SamplerSettings Sampler { get; init; }
}

/// <summary>
/// Progress of a render, reported after each tile; with a <paramref name="Stage"/> (e.g. "photometry gather"), of a product
/// that traces rays of its own after the render, its units rows of pixels or grid points (<paramref name="Rays"/> 0: not
/// counted).
/// </summary>
public readonly record struct RenderProgress(int TilesDone, int Tiles, long Rays, TimeSpan Elapsed, string? Stage = null);

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

    /// <param name="crop">Renders only these pixels of the film (--crop, --shard): the tiles are the whole film's
    /// 32 × 32 grid clipped to the crop, and each pixel is computed from its own film coordinates, so a crop holds the
    /// same values as the same pixels of a whole render.</param>
    /// <param name="packets">Trace camera rays in packets when the integrator can (<see cref="IPacketIntegrator"/>; the default); false
    /// traces every ray alone (the same image).</param>
    /// <param name="noise">Record each pixel's standard error (<see cref="RenderResult.Noise"/>); also on with the scene's
    /// <see cref="Scene.TargetError"/> (adaptive sampling, spp the cap).</param>
    public static RenderResult Render(Scene scene, IIntegrator integrator, int threads = 0, Action<RenderProgress>? progress = null,
        CancellationToken cancel = default, PixelRect? crop = null, bool packets = true,
        bool noise = false)
    {
        var cam = scene.Camera;
        var region = crop ?? PixelRect.Whole(cam.Width, cam.Height);
        if (region.X0 < 0 || region.Y0 < 0 || region.X1 > cam.Width || region.Y1 > cam.Height || region.Width < 1 || region.Height < 1)
            throw new ArgumentOutOfRangeException(nameof(crop), $"crop {region} is not inside the {cam.Width}×{cam.Height} film");
        var film = new Film(scene, region);
        var clock = Stopwatch.StartNew();
        // The analysis images come from the centre rays: with spp > 1 each pixel traces one more ray (weight 0).
        double target = scene.TargetError;
        bool statistics = noise || target > 0;
        if (statistics && cam.SamplesPerPixel < 2)
            throw new ArgumentException("a pixel's standard error needs at least 2 samples per pixel", nameof(noise));
        var sampler = integrator.Sampler;
        var sampling = new PixelSampling(cam, scene.RayBudget, analysis: true, sampler, adaptive: target > 0);
        // Packets trace the camera rays of a tile together, for the scenes the integrator says (IPacketIntegrator.PrefersPackets).
        // Per-pixel statistics and samplers other than the independent one go ray by ray.
        bool packed = packets && integrator is IPacketIntegrator p && p.PrefersPackets(scene) && !statistics
            && sampler.Kind == SamplerKind.Independent;
        int padded = scene.PaddedBands;
        var errors = statistics ? new float[region.Width * region.Height * (scene.Bands + 1)] : null;
        var spp = target > 0 ? new int[region.Width * region.Height] : null;
        var (rays, tiles, used) = RunTiles(region, threads, progress, clock, cancel, statistics
            ? () => new StatisticsTileState(integrator, sampling, film, padded, errors!, spp, target, cancel)
            : packed
            ? () => new PacketTileState((IPacketIntegrator)integrator, sampling, film, integrator.ScratchLength, padded, cancel)
            : () => new TileState(integrator, sampling, film, padded, cancel));
        return new RenderResult
        {
            Image = film.Image,
            ObjectIds = film.Ids,
            LitMasks = film.Lit,
            Highlights = film.Highlights,
            Xyz = film.Xyz,
            FallbackPixels = film.FallbackPixels,
            Rays = rays,
            Elapsed = clock.Elapsed,
            Threads = used,
            Tiles = tiles,
            Crop = region,
            Packets = packed,
            Noise = errors,
            SamplesUsed = spp,
            TargetError = target,
            Sampler = sampler,
        };
    }

    /// <summary>A render's outputs for the pixels of its crop, and how a pixel's spectrum is written into them.</summary>
    sealed class Film
    {
        public readonly SpectralImage Image;
        public readonly int[] Ids;
        public readonly LitMasks Lit;
        public readonly byte[] Highlights;
        public readonly float[] Xyz;
        public readonly float HighlightFraction;
        public readonly Color.Colorimeter Colorimeter;
        /// <summary>The framebuffer's first pixel on the film (a crop's corner; 0, 0 for a whole render).</summary>
        public readonly int X0, Y0;
        public long FallbackPixels;

        public Film(Scene scene, PixelRect region)
        {
            int width = region.Width, height = region.Height;
            // Every pixel of these is written by its tile, so they are not zeroed first (80 MB at 1024² × 20 bands).
            Image = new SpectralImage(width, height, scene.Grid, LargeArrays.Uninitialized<float>(width * height * scene.Bands));
            Ids = GC.AllocateUninitializedArray<int>(width * height);
            Lit = new LitMasks(width * height, scene.Lights.Count);
            Highlights = GC.AllocateUninitializedArray<byte>(width * height);
            HighlightFraction = (float)scene.Output.HighlightFraction;
            Xyz = GC.AllocateUninitializedArray<float>(3 * width * height);
            Colorimeter = scene.Colorimeter;
            X0 = region.X0; Y0 = region.Y0;
        }

        /// <summary>The colour of pixel i from the colour lanes of its spectrum (which follow the bands), or, after a fallback,
        /// eq. 3 on its band values; then what its centre ray saw.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Finish(int i, ReadOnlySpan<float> pixel, bool fallback, int id, in PixelInfo info)
        {
            int bands = Image.Bands;
            if (!fallback) { Xyz[3 * i] = pixel[bands]; Xyz[3 * i + 1] = pixel[bands + 1]; Xyz[3 * i + 2] = pixel[bands + 2]; }
            else
            {   // a term multiplied more spectra than the tables hold: eq. 3 on this pixel's band values
                var c = Colorimeter.ToXyz(pixel[..bands]);
                Xyz[3 * i] = (float)c.X; Xyz[3 * i + 1] = (float)c.Y; Xyz[3 * i + 2] = (float)c.Z;
                Interlocked.Increment(ref FallbackPixels);
            }
            Ids[i] = id;
            Lit[i] = info.LitMask;
            Highlights[i] = PixelInfo.Highlight(info.SpecularY, info.DiffuseY, HighlightFraction);
        }
    }

    /// <summary>A worker's tile of camera rays one at a time: its scratch spectra, allocated once per worker.</summary>
    sealed class TileState(IIntegrator integrator, PixelSampling sampling, Film film, int padded, CancellationToken cancel) : ITileWork
    {
        readonly float[] _scratch = new float[integrator.ScratchLength];
        readonly float[] _sum = new float[padded];
        readonly float[] _sample = new float[padded];

        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
        {
            var sink = new RadianceSamples(integrator, integrator as IAnalysisIntegrator, film, _sum, _sample, _scratch, sampling.Spp);
            SampleTile(ref sink, in sampling, x0, y0, x1, y1, cancel, ref counters);
        }
    }

    /// <summary>The integrator's radiance per camera sample, summed with weight 1/spp into the pixel; the centre ray (with
    /// spp = 1 the pixel's only ray) records the analysis data when the integrator can (<see cref="IAnalysisIntegrator"/>).</summary>
    struct RadianceSamples(IIntegrator integrator, IAnalysisIntegrator? analysing, Film film,
        float[] sum, float[] sample, float[] scratch, int spp) : ISampleSink
    {
        PixelInfo _info;
        long _fallbackBefore;

        public void BeginPixel(int x, int y, ref RayCounters counters)
        {
            _info = default;
            _fallbackBefore = counters.Fallback;
            if (spp > 1) sum.AsSpan().Clear();
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public int Sample(in CameraSample s, float weight, bool centre, ref RayCounters counters)
        {
            if (!centre)
            {
                integrator.Radiance(in s, sample, scratch, ref counters);
                SpectralMath.AddScaled(sum, sample, weight);
                return -1;
            }
            // The centre ray: the pixel itself (weight 1, spp = 1), or, weighing 0, the analysis images only.
            var target = weight == 0 ? sample : sum;
            return analysing is not null ? analysing.Radiance(in s, target, scratch, ref counters, ref _info)
                : integrator.Radiance(in s, target, scratch, ref counters);
        }

        public readonly void EndPixel(int x, int y, int id, ref RayCounters counters)
        {
            var image = film.Image;
            int bands = image.Bands;
            x -= film.X0; y -= film.Y0;   // film → framebuffer
            sum.AsSpan(0, bands).CopyTo(image.Data.AsSpan(image.Offset(x, y), bands));
            film.Finish(y * image.Width + x, sum, counters.Fallback != _fallbackBefore, id, in _info);
        }
    }

    /// <summary>A small integer hash (lowbias32 by C. Wellons) for per-sample jitter.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static uint Hash(uint x, uint y, uint s)
    {
        uint h = x * 0x9E3779B1u ^ (y + 0x7F4A7C15u) * 0x85EBCA77u ^ (s + 1) * 0xC2B2AE3Du;
        h ^= h >> 16; h *= 0x7FEB352Du; h ^= h >> 15; h *= 0x846CA68Bu; h ^= h >> 16;
        return h;
    }
}
