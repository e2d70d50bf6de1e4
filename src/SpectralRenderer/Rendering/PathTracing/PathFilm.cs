using System.Diagnostics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// A path render's <see cref="SubBandFilm"/> formed by the path tracer: its camera samples traced again (the film's walk, bit
/// for bit), or recombined from its per-light transfer without rays.
/// </summary>
[CompiledAtFirstCall]
internal static class PathFilm
{
    /// <summary>Traces the render's camera samples of the whole film again, summing each sample's sub-band radiance with its
    /// weight.</summary>
    public static SubBandFilm Trace(Scene scene, PathIntegrator integrator, int threads = 0, CancellationToken cancel = default)
    {
        var cam = scene.Camera;
        var grid = integrator.Grid;
        int sub = grid.Count;
        long size = (long)cam.Width * cam.Height * sub;
        if (size > Array.MaxLength)
            throw new InputException("camera",
                $"the path render's fine film needs {size} floats ({cam.Width}×{cam.Height} pixels × {sub} "
                    + $"sub-bands), more than one array holds",
                "a coarser \"spectral_grid\" or fewer pixels; or --signals bands");
        var data = new float[size];
        var rect = PixelRect.Whole(cam.Width, cam.Height);
        // No centre ray beyond the samples (analysis off): with spp = 1 the centre ray is the pixel's one sample, as in the render.
        var sampling = new PixelSampling(cam, scene.RayBudget, analysis: false, integrator.Sampler);
        Renderer.RunTiles(rect, threads, null, Stopwatch.StartNew(), cancel,
            () => new TileWork(integrator, sampling, cam.Width, data, cancel));
        return SubBandFilm.Of(grid, cam.Width, cam.Height, data);
    }

    /// <summary>
    /// From a path render's per-light transfer: L_f = F_f + Σ_k T_k,f·E_k,f (+ its fluorescent shift B_k·E_k) with the scene's
    /// lights (as <see cref="PathTransfer.Relight"/>).
    /// </summary>
    public static SubBandFilm FromTransfer(PathTransfer t, Scene scene)
    {
        var grid = PathIntegrator.GridOf(scene, t.SpectralGrid);
        int sub = t.SubBands, w = t.Region.Width, h = t.Region.Height;
        var e = PathTransfer.LightSpectra(scene, grid);
        var data = new float[(long)w * h * sub];
        Parallel.For(0, h, () => new float[grid.Padded], (y, _, fine) =>
        {
            for (int x = 0; x < w; x++)
            {
                int i = y * w + x;
                t.Radiance(i, e, fine);
                fine.AsSpan(0, sub).CopyTo(data.AsSpan(i * sub, sub));
            }
            return fine;
        }, _ => { });
        return SubBandFilm.Of(grid, w, h, data);
    }

    sealed class TileWork(PathIntegrator integrator, PixelSampling sampling, int width, float[] data, CancellationToken cancel) : ITileWork
    {
        readonly float[] _scratch = new float[integrator.ScratchLength];
        readonly float[] _sample = new float[integrator.Grid.Padded];
        readonly float[] _sum = new float[integrator.Grid.Padded];
        readonly PathIntegrator _integrator = integrator;
        readonly float[] _data = data;
        readonly int _width = width, _sub = integrator.Grid.Count;

        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
        {
            var sink = new Samples(this);
            Renderer.SampleTile(ref sink, in sampling, x0, y0, x1, y1, cancel, ref counters);
        }

        /// <summary>A pixel's samples summed with the film's weights (<see cref="Renderer"/>'s RadianceSamples, on the sub-band
        /// grid).</summary>
        readonly struct Samples(TileWork w) : ISampleSink
        {
            public void BeginPixel(int x, int y, ref RayCounters counters) => w._sum.AsSpan().Clear();

            [MethodImpl(MethodImplOptions.AggressiveOptimization)]
            public int Sample(in CameraSample sample, float weight, bool centre, ref RayCounters counters)
            {
                int id = w._integrator.SubBandRadiance(in sample, w._sample, w._scratch, ref counters);
                if (weight != 0) SpectralMath.AddScaled(w._sum, w._sample, weight);
                return id;
            }

            public void EndPixel(int x, int y, int id, ref RayCounters counters)
            {
                w._sum.AsSpan(0, w._sub).CopyTo(w._data.AsSpan((y * w._width + x) * w._sub, w._sub));
            }
        }
    }
}
