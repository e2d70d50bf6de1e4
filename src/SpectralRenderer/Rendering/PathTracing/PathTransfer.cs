using System.Diagnostics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// The per-light transfer of a path render. Light transport is linear in each light's emission, and the path integrator
/// takes no decision from a light's spectrum (lights are chosen uniformly, lobes and Russian roulette by the materials'
/// throughput, MIS weights from densities), so a pixel's radiance on the sub-band grid is
/// L_f = F_f + Σ_k (T_k,f · E_k,f + Σ_c B_k,f,c · E_k,c), with E_k the scene light k's spectrum × intensity on the grid (its
/// exact sub-band means), T_k,f the pixel's mean over its samples of the path weights of light k's next-event estimates
/// (β·f·|cos θ|·w/(P·p) × d_k·c_spot) on paths without a shifted (fluorescent) bounce, F_f the light of the emitters and
/// the sky (kept with their spectra: not relightable), and B_k the mean of light k's paths through a fluorescent shift:
/// a matrix from its excitation sub-bands c to the emission sub-bands f, held on the scene's shift block
/// (<see cref="Shift"/>, rows × columns; none without fluorescence: PathIntegrator.Transfer.cs). A relight forms L_f under
/// new E_k and reduces it to the output bands and XYZ as the film does (<see cref="SubBandGrid.Reduce"/>), so it equals a
/// render of the changed scene with the same samples up to float rounding. Stored per pixel: (K + 1) × F floats, and
/// K × rows × columns in a fluorescent scene.
/// </summary>
[CompiledAtFirstCall]
internal sealed partial class PathTransfer
{
    /// <summary>Whether it was read from a folder's lights/ (<see cref="PathTransferFiles.Read"/>), not traced.</summary>
    public bool ReadFromFiles { get; init; }

    /// <summary>The film's size, and the pixels this transfer holds (a whole render's, or a shard's strip).</summary>
    public required int FilmWidth { get; init; }
    public required int FilmHeight { get; init; }
    public required PixelRect Region { get; init; }
    /// <summary>Output bands.</summary>
    public required int Bands { get; init; }
    /// <summary>The scene's lights whose transfer is kept apart (K); group K is the emitters' and the sky's light.</summary>
    public required int Lights { get; init; }
    /// <summary>The internal grid's requested width (nm, the integrator's "spectral_grid") and its sub-bands (F).</summary>
    public required double SpectralGrid { get; init; }
    public required int SubBands { get; init; }
    /// <summary>[pixel of the region (row-major)][group k ≤ K][sub-band f]: T_k,f, and F_f for k = K.</summary>
    public required float[] Data { get; init; }
    /// <summary>The shift block B_k lives on (emission sub-bands × excitation sub-bands; empty without fluorescence).</summary>
    public ShiftSpan Shift { get; init; }
    /// <summary>
    /// [pixel of the region (row-major)][light k &lt; K][row r][column c]: B_k at sub-bands (Row0 + r, Column0 + c); empty
    /// without a shift.
    /// </summary>
    public float[] Blocks { get; init; } = [];
    /// <summary>Per pixel of the region, the object its centre ray hit (−1: none), as the render's object ids.</summary>
    public required int[] ObjectIds { get; init; }
    /// <summary>Per pixel of the region, the scene lights that reach the centre ray's surface point (bit k = light k), as traced.</summary>
    public required uint[] LitMasks { get; init; }
    public RayCounters Rays { get; init; }

    /// <summary>Floats per pixel: (K + 1) × F.</summary>
    public int PerPixel => (Lights + 1) * SubBands;

    /// <summary>The grid width the path integrator uses for <paramref name="scene"/> (its "spectral_grid", 5 nm by default).</summary>
    public static double GridWidth(Scene scene) =>
        PathIntegrator.SettingsOf(scene).SpectralGrid;

    /// <summary>Floats per pixel of the shift blocks: K × rows × columns.</summary>
    public long BlockPerPixel => (long)Lights * Shift.Size;

    /// <summary>Bytes of a transfer of <paramref name="pixels"/> pixels of <paramref name="scene"/> (for the memory estimate).</summary>
    public static long Bytes(Scene scene, long pixels)
    {
        var grid = PathIntegrator.GridOf(scene, GridWidth(scene));
        int k = scene.Lights.Count;
        long block = k > 0 ? (long)k * PathIntegrator.ShiftBlockOf(scene, grid).Size : 0;   // a fluorescent scene's B_k
        return 4L * pixels * ((k + 1) * grid.Count + block);
    }

    /// <summary>Traces the camera samples of <paramref name="region"/> again (the render's samples, bit for bit) recording T and
    /// F.</summary>
    public static PathTransfer Trace(Scene scene, PathIntegrator integrator, int threads = 0, CancellationToken cancel = default,
        PixelRect? region = null)
    {
        var cam = scene.Camera;
        var rect = region ?? PixelRect.Whole(cam.Width, cam.Height);
        int lights = scene.Lights.Count, sub = integrator.Grid.Count, padded = integrator.Grid.Padded;
        var shift = lights > 0 ? integrator.ShiftBlock : default;
        long size = (long)rect.Width * rect.Height * (lights + 1) * sub;
        if (size > Array.MaxLength)
            throw new InputException("--formats",
                $"the path render's per-light transfer needs {size} floats ({rect.Width}×{rect.Height} pixels × {lights + 1} groups × "
                    + $"{sub} sub-bands), more than one array holds",
                "render fewer pixels or lights with the lights output, or a coarser \"spectral_grid\"");
        long blockSize = (long)rect.Width * rect.Height * lights * shift.Size;
        if (blockSize > Array.MaxLength)
            throw new InputException("--formats",
                $"the path render's per-light transfer of its fluorescent shift needs {blockSize} floats ({rect.Width}×{rect.Height} " +
                $"pixels × {lights} lights × {shift.Rows} emission × {shift.Columns} excitation sub-bands), more than one array holds",
                "render fewer pixels or lights with the lights output, or a coarser \"spectral_grid\"");
        var data = new float[size];
        var blocks = shift.IsEmpty ? [] : new float[blockSize];
        var ids = new int[rect.Width * rect.Height];
        var lit = new uint[ids.Length];
        var sampling = new PixelSampling(cam, scene.RayBudget, analysis: true, integrator.Sampler);
        var (rays, _, _) = Renderer.RunTiles(rect, threads, null, Stopwatch.StartNew(), cancel,
            () => new TileWork(integrator, sampling, rect, lights, sub, padded, shift, data, blocks, ids, lit, cancel));
        return new PathTransfer
        {
            FilmWidth = cam.Width,
            FilmHeight = cam.Height,
            Region = rect,
            Bands = scene.Bands,
            Lights = lights,
            SpectralGrid = GridWidth(scene),
            SubBands = sub,
            Data = data,
            Shift = shift,
            Blocks = blocks,
            ObjectIds = ids,
            LitMasks = lit,
            Rays = rays,
        };
    }

    sealed class TileWork(PathIntegrator integrator, PixelSampling sampling, PixelRect rect, int lights, int sub, int padded,
        ShiftSpan shift, float[] data, float[] blocks, int[] ids, uint[] lit, CancellationToken cancel) : ITileWork
    {
        readonly float[] _scratch = new float[integrator.ScratchLength];
        readonly float[] _sample = new float[(lights + 1) * padded];
        readonly float[] _sum = new float[(lights + 1) * padded];
        // A fluorescent scene's shifted paths: the pixel's B_k, summed by the record with each sample's weight.
        readonly PathIntegrator.ShiftRecord? _record = shift.IsEmpty ? null : new PathIntegrator.ShiftRecord(lights, shift);
        readonly PathIntegrator _integrator = integrator;
        readonly PixelRect _rect = rect;
        readonly int _lights = lights, _sub = sub, _padded = padded;
        readonly float[] _data = data, _blocks = blocks;
        readonly int[] _ids = ids;
        readonly uint[] _lit = lit;
        uint _mask;

        public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
        {
            var sink = new Samples(this);
            Renderer.SampleTile(ref sink, in sampling, x0, y0, x1, y1, cancel, ref counters);
        }

        /// <summary>A pixel's samples summed with the film's weights (1/spp; the centre ray, weight 0, gives the object id).</summary>
        struct Samples(TileWork w) : ISampleSink
        {
            public readonly void BeginPixel(int x, int y, ref RayCounters counters)
            {
                w._sum.AsSpan().Clear();
                if (w._record is { } record) Array.Clear(record.Blocks);
                w._mask = 0;
            }

            [MethodImpl(MethodImplOptions.AggressiveOptimization)]
            public readonly int Sample(in CameraSample sample, float weight, bool centre, ref RayCounters counters)
            {
                if (w._record is { } record) record.Weight = weight;
                int id = w._integrator.Transfer(in sample, w._sample, w._record, w._scratch, ref counters);
                if (weight != 0) SpectralMath.AddScaled(w._sum, w._sample, weight);
                if (centre) w._mask = w._integrator.LitMask(in sample);   // as the render's centre ray records it
                return id;
            }

            public readonly void EndPixel(int x, int y, int id, ref RayCounters counters)
            {
                int i = (y - w._rect.Y0) * w._rect.Width + (x - w._rect.X0);
                w._ids[i] = id;
                w._lit[i] = w._mask;
                for (int g = 0; g <= w._lights; g++)
                    w._sum.AsSpan(g * w._padded, w._sub).CopyTo(w._data.AsSpan((i * (w._lights + 1) + g) * w._sub, w._sub));
                if (w._record is { } record) record.Blocks.CopyTo(w._blocks.AsSpan(i * record.Blocks.Length, record.Blocks.Length));
            }
        }
    }

    /// <summary>
    /// The film of <paramref name="scene"/> (the render's scene with its lights changed): per pixel L_f = F_f + Σ_k T_k,f·E_k,f
    /// reduced to the bands and XYZ (the colour lanes) as the film reduces a sample, on all cores.
    /// </summary>
    public (SpectralImage Image, float[] Xyz) Relight(Scene scene)
    {
        var grid = PathIntegrator.GridOf(scene, SpectralGrid);
        if (grid.Count != SubBands || scene.Bands != Bands || scene.Lights.Count != Lights)
            throw new InputException("lights/lights.json",
                $"the transfer has {Lights} lights × {SubBands} sub-bands of {Bands} bands, the scene rebuilds as {scene.Lights.Count} "
                    + $"× {grid.Count} of {scene.Bands}",
                "the scene file changed since the render; render again");
        int padded = grid.Padded, bands = Bands, w = Region.Width;
        var e = LightSpectra(scene, grid);
        var image = new SpectralImage(Region.Width, Region.Height, scene.Grid);
        var xyz = new float[3 * Region.Width * Region.Height];
        Parallel.For(0, Region.Height, () => (new float[padded], new float[scene.PaddedBands]), (y, _, buffers) =>
        {
            var (fine, result) = buffers;
            for (int x = 0; x < w; x++)
            {
                int i = y * w + x;
                Radiance(i, e, fine);
                grid.Reduce(fine, result);
                result.AsSpan(0, bands).CopyTo(image.Data.AsSpan(i * bands, bands));
                xyz[3 * i] = result[bands]; xyz[3 * i + 1] = result[bands + 1]; xyz[3 * i + 2] = result[bands + 2];
            }
            return buffers;
        }, _ => { });
        return (image, xyz);
    }

    /// <summary>E_k: each light's spectrum × intensity on the sub-band grid (exact sub-band means), as the path integrator takes
    /// it.</summary>
    internal static float[][] LightSpectra(Scene scene, SubBandGrid grid) => scene.Lights.Select(l => grid.Resample(l.Intensity)).ToArray();

    /// <summary>
    /// Pixel <paramref name="i"/>'s radiance on the sub-band grid under light spectra <paramref name="e"/> (<see cref="LightSpectra"/>):
    /// L_f = F_f + Σ_k T_k,f·E_k,f, then + Σ_k Σ_c B_k,f,c·E_k,c on the shift block, into <paramref name="fine"/>[0, F).
    /// </summary>
    internal void Radiance(int i, float[][] e, Span<float> fine)
    {
        int sub = SubBands, k = Lights;
        var px = Data.AsSpan(i * (k + 1) * sub, (k + 1) * sub);
        px.Slice(k * sub, sub).CopyTo(fine);
        for (int l = 0; l < k; l++)
        {
            var t = px.Slice(l * sub, sub);
            var el = e[l];
            for (int f = 0; f < sub; f++) fine[f] += t[f] * el[f];
        }
        if (Shift.IsEmpty) return;
        int rows = Shift.Rows, columns = Shift.Columns, size = Shift.Size;
        for (int l = 0; l < k; l++)
        {
            var b = Blocks.AsSpan((int)(((long)i * k + l) * size), size);
            var ec = e[l].AsSpan(Shift.Column0, columns);
            for (int r = 0; r < rows; r++)
            {
                var br = b.Slice(r * columns, columns);
                float v = 0;
                for (int c = 0; c < columns; c++) v += br[c] * ec[c];
                fine[Shift.Row0 + r] += v;
            }
        }
    }
}
