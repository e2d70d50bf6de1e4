using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// A tile's camera rays in packets of 16: the pixels in 4 × 4 blocks and, per pixel, its jittered samples and
// (spp > 1) the centre ray of the analysis images, one after the other, so a packet holds the samples of one
// pixel or of neighbouring pixels. Each ray is the one the per-pixel loop traces and a pixel's samples are
// summed in the same order, so the framebuffer is the same bits.
public sealed partial class Renderer
{
    const int Block = 4;

    /// <summary>A worker's packet, its per-lane results and where each lane's ray goes, allocated once per worker.</summary>
    sealed class PacketTileState(IPacketIntegrator integrator, PixelSampling sampling, Film film, int scratch, int padded,
        CancellationToken cancel) : ITileWork
    {
        public readonly IPacketIntegrator Integrator = integrator;
        public readonly PixelSampling Sampling = sampling;
        public readonly Film Film = film;
        public readonly CancellationToken Cancel = cancel;
        // The packet and its film positions in pinned memory on a cache-line boundary (LaneMemory, PacketBlock).
        readonly byte[] _block = GC.AllocateArray<byte>(LaneMemory.Bytes<PacketBlock>(), pinned: true);
        public ref PacketBlock Block => ref LaneMemory.At<PacketBlock>(_block);
        public readonly LineFloats Results = new(RayPacket.Size * padded);
        public readonly int[] Objects = new int[RayPacket.Size];
        public readonly PixelInfo[] Infos = new PixelInfo[RayPacket.Size];
        public readonly bool[] Fallbacks = new bool[RayPacket.Size];
        /// <summary>Whether a ray of the pixel being summed fell back to eq. 3 (its samples may span two packets).</summary>
        public bool PixelFallback;
        public readonly int[] PixelX = new int[RayPacket.Size], PixelY = new int[RayPacket.Size], Sample = new int[RayPacket.Size];
        public readonly LineFloats Sum = new(padded);
        public readonly float[] Scratch = new float[scratch];
        public int Lanes;

        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters) => PacketTile(x0, y0, x1, y1, this, ref counters);
    }

    /// <summary>A worker's camera-ray packet and each lane's film position (pixels), laid out so that, placed on a cache-line
    /// boundary, every lane array starts on one (<see cref="LaneMemory"/>; a class field is only 8-byte aligned).</summary>
    internal struct PacketBlock
    {
        public PacketFloats FilmX, FilmY;
        public RayPacket Packet;
    }

    /// <summary>The tile's camera samples as <see cref="SampleTile"/> makes them (the same rays, jitter and centre rays), in
    /// packets.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void PacketTile(int x0, int y0, int x1, int y1, PacketTileState st, ref RayCounters counters)
    {
        ref readonly var sampling = ref st.Sampling;
        int spp = sampling.Spp;
        int perPixel = spp == 1 || !sampling.Analysis ? spp : spp + 1;   // the samples, then the centre ray
        ref var block = ref st.Block;
        block.Packet.Clear();
        st.Lanes = 0;
        for (int by = y0; by < y1; by += Block)
            for (int bx = x0; bx < x1; bx += Block)
                for (int y = by; y < Math.Min(by + Block, y1); y++)
                    for (int x = bx; x < Math.Min(bx + Block, x1); x++)
                        for (int s = 0, cellX = 0, cellY = 0; s < perPixel; s++)
                        {
                            float fx = x + 0.5f, fy = y + 0.5f;
                            if (s < spp && spp > 1)
                            {
                                // Sample s in cell (s mod m, s div m) = (cellX, cellY), jittered inside it (as the per-pixel loop).
                                (fx, fy) = sampling.Film(x, y, s, cellX, cellY);
                                if (++cellX == sampling.StrataX) { cellX = 0; cellY++; }
                            }
                            counters.Primary++;
                            int lane = st.Lanes++;
                            block.FilmX[lane] = fx; block.FilmY[lane] = fy;   // the film position cam.Generate takes
                            st.PixelX[lane] = x; st.PixelY[lane] = y; st.Sample[lane] = s;
                            if (st.Lanes == RayPacket.Size)
                            {   // a stop waits for one packet at most (16 camera rays, whose recursions keep their ray budget)
                                if (st.Cancel.IsCancellationRequested) st.Cancel.ThrowIfCancellationRequested();
                                Flush(st, ref counters);
                            }
                        }
        if (st.Lanes > 0) Flush(st, ref counters);
    }

    /// <summary>Traces the packet and puts each lane's radiance where it belongs: a pixel (spp = 1), a pixel's sum, or its analysis
    /// images.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Flush(PacketTileState st, ref RayCounters counters)
    {
        var film = st.Film;
        var image = film.Image;
        int spp = st.Sampling.Spp;
        // The camera rays of the packet's lanes, all at once (Camera.Generate in SIMD lanes: the same bits).
        uint lanes = st.Lanes == 32 ? uint.MaxValue : (1u << st.Lanes) - 1;
        ref var block = ref st.Block;
        LaneGeometry.CameraRays(st.Sampling.Camera, ref block.Packet, ref block.FilmX, ref block.FilmY, lanes);
        st.Integrator.Radiance(ref block.Packet, st.Results.Span, st.Objects, st.Infos, st.Fallbacks, st.Scratch, ref counters);
        int padded = st.Sum.Length, bands = image.Bands;
        float inv = st.Sampling.Weight;
        var sum = st.Sum.Span;
        var results = st.Results.Span;
        int width = image.Width;
        for (int lane = 0; lane < st.Lanes; lane++)
        {
            var result = results.Slice(lane * padded, padded);
            int x = st.PixelX[lane], y = st.PixelY[lane], s = st.Sample[lane];
            if (s == 0) st.PixelFallback = false;
            st.PixelFallback |= st.Fallbacks[lane];
            if (spp > 1 && s < spp)
            {
                // The pixel's first sample is written (0 + r/spp, as on a cleared sum), the others are added.
                if (s == 0) SpectralMath.SetScaled(sum, result, inv);
                else SpectralMath.AddScaled(sum, result, inv);
                if (s < spp - 1 || st.Sampling.Analysis) continue;
            }
            x -= film.X0; y -= film.Y0;   // film → framebuffer
            var pixel = spp == 1 ? result : sum;
            if (bands >= SpectralMath.StreamMinBands) SpectralMath.StreamBands(pixel, image.Data.AsSpan(image.Offset(x, y), bands));
            else SpectralMath.CopyBands(pixel, image.Data.AsSpan(image.Offset(x, y), bands));
            // The colour lanes follow the bands (as the per-pixel loop); eq. 3 on the band values after a fallback.
            bool centre = spp == 1 || s == spp;
            film.Finish(y * width + x, pixel, st.PixelFallback, centre ? st.Objects[lane] : -1, centre ? st.Infos[lane] : default);
        }
        if (bands >= SpectralMath.StreamMinBands) SpectralMath.StreamFence();
        block.Packet.Clear();
        st.Lanes = 0;
    }
}
