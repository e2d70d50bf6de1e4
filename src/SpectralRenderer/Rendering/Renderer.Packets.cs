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
    sealed class PacketTileState(int scratch, int padded, int filmX0, int filmY0)
    {
        /// <summary>The framebuffer's first pixel on the film (a crop's corner; 0, 0 for a whole render).</summary>
        public readonly int FilmX0 = filmX0, FilmY0 = filmY0;
        public RayPacket Packet;
        /// <summary>Per lane, the film position of its camera ray (pixels).</summary>
        public PacketFloats FilmX, FilmY;
        public readonly float[] Results = new float[RayPacket.Size * padded];
        public readonly int[] Objects = new int[RayPacket.Size];
        public readonly PixelInfo[] Infos = new PixelInfo[RayPacket.Size];
        public readonly bool[] Fallbacks = new bool[RayPacket.Size];
        /// <summary>Whether a ray of the pixel being summed fell back to eq. 3 (its samples may span two packets).</summary>
        public bool PixelFallback;
        public readonly int[] PixelX = new int[RayPacket.Size], PixelY = new int[RayPacket.Size], Sample = new int[RayPacket.Size];
        public readonly float[] Sum = new float[padded];
        public readonly float[] Scratch = new float[scratch];
        public int Lanes;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void PacketTile(IPacketIntegrator integrator, Scenes.Camera cam, int x0, int y0, int x1, int y1, int strataX, int strataY,
        PacketTileState st, SpectralImage image, int[] ids, LitMasks lit, byte[] highlights, float highlightFraction, float[] xyz, Colorimeter colorimeter,
        ref long fallbackPixels, ref RayCounters counters)
    {
        int spp = cam.SamplesPerPixel;
        int perPixel = spp == 1 ? 1 : spp + 1;   // the samples, then the centre ray
        st.Packet.Clear();
        st.Lanes = 0;
        for (int by = y0; by < y1; by += Block)
            for (int bx = x0; bx < x1; bx += Block)
                for (int y = by; y < Math.Min(by + Block, y1); y++)
                    for (int x = bx; x < Math.Min(bx + Block, x1); x++)
                        for (int s = 0, cellX = 0, cellY = 0; s < perPixel; s++)
                        {
                            float jx = 0.5f, jy = 0.5f;
                            if (s < spp && spp > 1)
                            {
                                // Sample s in cell (s mod m, s div m) = (cellX, cellY), jittered inside it (as the per-pixel loop).
                                uint h = Hash((uint)x, (uint)y, (uint)s);
                                jx = (cellX + (h & 0xFFFF) / 65536f) / strataX;
                                jy = (cellY + (h >> 16) / 65536f) / strataY;
                                if (++cellX == strataX) { cellX = 0; cellY++; }
                            }
                            counters.Primary++;
                            int lane = st.Lanes++;
                            st.FilmX[lane] = x + jx; st.FilmY[lane] = y + jy;   // the film position cam.Generate takes
                            st.PixelX[lane] = x; st.PixelY[lane] = y; st.Sample[lane] = s;
                            if (st.Lanes == RayPacket.Size) Flush(integrator, cam, spp, st, image, ids, lit, highlights, highlightFraction, xyz, colorimeter, ref fallbackPixels, ref counters);
                        }
        if (st.Lanes > 0) Flush(integrator, cam, spp, st, image, ids, lit, highlights, highlightFraction, xyz, colorimeter, ref fallbackPixels, ref counters);
    }

    /// <summary>Traces the packet and puts each lane's radiance where it belongs: a pixel (spp = 1), a pixel's sum, or its analysis images.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Flush(IPacketIntegrator integrator, Scenes.Camera cam, int spp, PacketTileState st, SpectralImage image, int[] ids, LitMasks lit, byte[] highlights, float highlightFraction,
        float[] xyz, Colorimeter colorimeter, ref long fallbackPixels, ref RayCounters counters)
    {
        // The camera rays of the packet's lanes, all at once (Camera.Generate in SIMD lanes: the same bits).
        LaneGeometry.CameraRays(cam, ref st.Packet, ref st.FilmX, ref st.FilmY, st.Lanes == 32 ? uint.MaxValue : (1u << st.Lanes) - 1);
        integrator.Radiance(ref st.Packet, st.Results, st.Objects, st.Infos, st.Fallbacks, st.Scratch, ref counters);
        int padded = st.Sum.Length, bands = image.Bands;
        float inv = 1f / spp;
        var sum = st.Sum.AsSpan();
        int width = image.Width;
        for (int lane = 0; lane < st.Lanes; lane++)
        {
            var result = st.Results.AsSpan(lane * padded, padded);
            int x = st.PixelX[lane], y = st.PixelY[lane], s = st.Sample[lane];
            if (s == 0) st.PixelFallback = false;
            st.PixelFallback |= st.Fallbacks[lane];
            if (spp > 1 && s < spp)
            {
                // The pixel's first sample is written (0 + r/spp, as on a cleared sum), the others are added.
                if (s == 0) SpectralMath.SetScaled(sum, result, inv);
                else SpectralMath.AddScaled(sum, result, inv);
                continue;
            }
            x -= st.FilmX0; y -= st.FilmY0;   // film → framebuffer
            var pixel = spp == 1 ? result : sum;
            if (bands >= SpectralMath.StreamMinBands) SpectralMath.StreamBands(pixel, image.Data.AsSpan(image.Offset(x, y), bands));
            else SpectralMath.CopyBands(pixel, image.Data.AsSpan(image.Offset(x, y), bands));
            int i = y * width + x;
            // The colour lanes follow the bands (as the per-pixel loop); eq. 3 on the band values after a fallback.
            if (!st.PixelFallback) { xyz[3 * i] = pixel[bands]; xyz[3 * i + 1] = pixel[bands + 1]; xyz[3 * i + 2] = pixel[bands + 2]; }
            else
            {
                var c = colorimeter.ToXyz((ReadOnlySpan<float>)pixel[..bands]);
                xyz[3 * i] = (float)c.X; xyz[3 * i + 1] = (float)c.Y; xyz[3 * i + 2] = (float)c.Z;
                Interlocked.Increment(ref fallbackPixels);
            }
            ids[i] = st.Objects[lane];
            lit[i] = st.Infos[lane].LitMask;
            highlights[i] = PixelInfo.Highlight(st.Infos[lane].SpecularY, st.Infos[lane].DiffuseY, highlightFraction);
        }
        if (bands >= SpectralMath.StreamMinBands) SpectralMath.StreamFence();
        st.Packet.Clear();
        st.Lanes = 0;
    }
}
