using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

// The per-light transfer of a path render (PathTransfer.cs): the film's walk with a sink that keeps each scene light's
// weights apart. Without fluorescence a light's share of the film is diag(T_k)·E_k. A shifted bounce maps light between
// sub-bands, so light k reaches the film through a matrix: diag(T_k)·E_k for its paths without a shift, plus B_k·E_k for
// those through one. Every such path ends (towards the light) in a shifted lobe f_s or in a shifted bounce's A = diag(g)·f_s,
// whose columns are the excitation sub-bands and rows the emission sub-bands, so B_k lives in the scene's shift block
// (ShiftSpan: the union of the shifts' non-zero rows × columns): R × C floats per light, and a relight adds B_k·E_k[C].
// The walk's decisions are the film's (none looks at a light's spectrum: β, the albedos, the roulette's gain), so the
// record equals the film for any light spectra up to float rounding.
internal sealed partial class PathIntegrator
{
    /// <summary>Does a material of the scene shift light between bands (fluorescence)?</summary>
    public bool Fluoresces => _fluoresces;

    /// <summary>The scene's shift block (empty without fluorescence): where the transfer's B_k lives.</summary>
    internal ShiftSpan ShiftBlock =>
        _materials.Aggregate(default(ShiftSpan), (a, m) => m.Shift is not { } s ? a : a.Union(s.Extent));

    /// <summary>The shift block of <paramref name="scene"/> on <paramref name="grid"/>, with no integrator (the memory estimate).</summary>
    internal static ShiftSpan ShiftBlockOf(Scene scene, SubBandGrid grid) => scene.Materials
        .Where(m => m.Fluorescence is { HasShift: true })
        .Aggregate(default(ShiftSpan), (a, m) => a.Union(new FluorescentShift(m.Fluorescence!, grid).Extent));

    /// <summary>
    /// One camera sample split by light (the per-light transfer of a path render): for each scene light k the path
    /// weights T_k,f (β·f·|cos θ|·w/(P(light)·p)·factor, without the light's spectrum) of its paths without a shifted
    /// bounce into <paramref name="groups"/> [k·padded, (k+1)·padded), and everything else — emitters and the sky, with their
    /// spectra — into the last slot [K·padded, (K+1)·padded); in a fluorescent scene the light's shifted paths' B_k, times
    /// the sample's film weight <see cref="ShiftRecord.Weight"/>, added to <paramref name="record"/>'s pixel sum. The
    /// film's walk (the same random numbers, the same decisions, none of which look at a light's spectrum), so
    /// Σ_k (T_k ⊙ E_k + B_k·E_k) + fixed is its sub-band radiance. <paramref name="groups"/> is cleared.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal int Transfer(in CameraSample sample, Span<float> groups, ShiftRecord? record, Span<float> scratch, ref RayCounters counters)
    {
        groups.Clear();
        var sink = new TransferSink(groups, _padded, _lights.Length, record);
        return Walk(ref sink, in sample, scratch, ref counters);
    }

    /// <summary>
    /// A fluorescent scene's shifted transfer of one camera sample, per scene light k: B_k (R × C of the shift block, row-major),
    /// and the walk's state that builds it — P = A_1⋯A_j on the block (j ≥ 1 shifted bounces so far) and X_k, what light k
    /// gave since the last shifted bounce as a C × C matrix on the excitation sub-bands (a next-event weight v on its
    /// diagonal, an excited shifted lobe diag(β)·f_s·s as its rows), carried to B_k += P·X_k at the next shifted bounce or
    /// the path's end. B_k is the pixel's sum: each sample adds its own times its film weight (no per-sample block to clear
    /// and add: most samples of a fluorescent surface excite it). One per thread; nothing allocated per path.
    /// </summary>
    internal sealed class ShiftRecord(int lights, ShiftSpan span)
    {
        public readonly ShiftSpan Extent = span;
        /// <summary>[k][r][c]: the pixel's Σ over its samples of weight × B_k (cleared by the caller at each pixel).</summary>
        public readonly float[] Blocks = new float[lights * span.Size];
        /// <summary>The film weight of the sample being traced (0: the centre ray of analysis, which adds nothing).</summary>
        public float Weight;
        float[] _p = new float[span.Size], _next = new float[span.Size];
        readonly float[] _kept = new float[span.Size];   // P at a dispersive split, for each band's sub-path
        readonly float[] _segment = new float[lights * span.Columns * span.Columns];
        readonly bool[] _open = new bool[lights];

        Span<float> Block(int k) => Blocks.AsSpan(k * Extent.Size, Extent.Size);
        Span<float> Segment(int k) => _segment.AsSpan(k * Extent.Columns * Extent.Columns, Extent.Columns * Extent.Columns);
        ReadOnlySpan<float> ShiftRow(FluorescentShift shift, int o) => shift.Row(o).Slice(Extent.Column0, Extent.Columns);

        /// <summary>Before any shifted bounce: B_k += diag(β)·f_s·s on the block (an excited lobe reaches the film as it is).</summary>
        public void Excite(int k, FluorescentShift shift, ReadOnlySpan<float> beta, float s)
        {
            var b = Block(k);
            int rows = Extent.Rows, columns = Extent.Columns;
            for (int r = 0; r < rows; r++)
            {
                float a = beta[Extent.Row0 + r] * s * Weight;
                if (a != 0) Axpy(b.Slice(r * columns, columns), ShiftRow(shift, Extent.Row0 + r), a);
            }
        }

        /// <summary>After one: X_k += diag(v), v = β ⊙ f · s on the excitation sub-bands (a next-event estimate of light k).</summary>
        public void Diagonal(int k, ReadOnlySpan<float> beta, ReadOnlySpan<float> f, float s)
        {
            var x = Segment(k);
            int columns = Extent.Columns;
            for (int c = 0; c < columns; c++) x[c * columns + c] += beta[Extent.Column0 + c] * f[Extent.Column0 + c] * s;
            _open[k] = true;
        }

        /// <summary>After one: X_k += (diag(β)·f_s·s) restricted to the excitation sub-bands (P's columns).</summary>
        public void ExciteSegment(int k, FluorescentShift shift, ReadOnlySpan<float> beta, float s)
        {
            var x = Segment(k);
            int columns = Extent.Columns;
            for (int c = 0; c < columns; c++)
            {
                float a = beta[Extent.Column0 + c] * s;
                if (a != 0) Axpy(x.Slice(c * columns, columns), ShiftRow(shift, Extent.Column0 + c), a);
            }
            _open[k] = true;
        }

        /// <summary>
        /// After <paramref name="level"/> ≥ 1 shifted bounces: B_k += weight·P·X_k for every light that gave light since the
        /// last; X_k cleared.
        /// </summary>
        public void Fold(int level)
        {
            if (level == 0) return;
            int rows = Extent.Rows, columns = Extent.Columns;
            for (int k = 0; k < _open.Length; k++)
            {
                if (!_open[k]) continue;
                var b = Block(k);
                var x = Segment(k);
                for (int r = 0; r < rows; r++)
                {
                    var br = b.Slice(r * columns, columns);
                    for (int c = 0; c < columns; c++)
                    {
                        float p = _p[r * columns + c] * Weight;
                        if (p != 0) Axpy(br, x.Slice(c * columns, columns), p);
                    }
                }
                x.Clear();
                _open[k] = false;
            }
        }

        /// <summary>A shifted bounce after <paramref name="level"/> others: P ← P·diag(β·w)·f_s (the first: P = diag(β·w)·f_s).</summary>
        public void Chain(int level, FluorescentShift shift, ReadOnlySpan<float> beta, float w)
        {
            int rows = Extent.Rows, columns = Extent.Columns;
            if (level == 0)
            {
                for (int r = 0; r < rows; r++)
                {
                    var pr = _p.AsSpan(r * columns, columns);
                    pr.Clear();
                    float a = beta[Extent.Row0 + r] * w;
                    if (a != 0) Axpy(pr, ShiftRow(shift, Extent.Row0 + r), a);
                }
                return;
            }
            Array.Clear(_next);
            for (int r = 0; r < rows; r++)
            {
                var nr = _next.AsSpan(r * columns, columns);
                for (int c = 0; c < columns; c++)
                {
                    float a = _p[r * columns + c] * beta[Extent.Column0 + c] * w;
                    if (a != 0) Axpy(nr, ShiftRow(shift, Extent.Column0 + c), a);
                }
            }
            (_p, _next) = (_next, _p);
        }

        /// <summary>A dispersive split after shifted bounces: keep P, which its sub-paths' own shifted bounces chain onto.</summary>
        public void Keep() => _p.CopyTo(_kept, 0);

        /// <summary>A sub-path's end (its X_k folded): P back to the split's.</summary>
        public void Restore() => _kept.CopyTo(_p, 0);

        /// <summary>dst += x·a (any length: whole vectors, then the rest).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        static void Axpy(Span<float> dst, ReadOnlySpan<float> x, float a)
        {
            int n = dst.Length, w = Vector<float>.Count, i = 0;
            if (n >= w)
            {
                var d = MemoryMarshal.Cast<float, Vector<float>>(dst);
                var v = MemoryMarshal.Cast<float, Vector<float>>(x[..n]);
                var va = new Vector<float>(a);
                for (int j = 0; j < d.Length; j++) d[j] += v[j] * va;
                i = d.Length * w;
            }
            for (; i < n; i++) dst[i] += x[i] * a;
        }
    }

    /// <summary>The transfer's sink: each scene light's weights apart (<see cref="Transfer"/>), its shifted paths in the record.</summary>
    ref struct TransferSink(Span<float> groups, int padded, int lights, ShiftRecord? record) : IPathSink
    {
        readonly Span<float> _groups = groups;
        int _level, _split;   // the path's shifted bounces so far, and at its dispersive split
        public readonly bool FirstEmission => true;

        public readonly void Emitted(Span<float> beta, ReadOnlySpan<float> le, float w) =>
            AddProduct(_groups.Slice(lights * padded, padded), beta, le, w);

        public readonly void NextEvent(int light, Span<float> beta, Span<float> f, ReadOnlySpan<float> radiance, float s)
        {
            if (light < 0) AddProduct3(_groups.Slice(lights * padded, padded), beta, f, radiance, s);
            else if (_level == 0) AddProduct2(_groups.Slice(light * padded, padded), beta, f, s);
            else record!.Diagonal(light, beta, f, s);
        }

        // Emitters and the sky (fixed spectra) enter the fixed slot, which the walk carries through its shifted bounces.
        public readonly void Shifted(int light, FluorescentShift shift, Span<float> beta, ReadOnlySpan<float> radiance, float s)
        {
            if (light < 0) shift.AddEmitted(_groups.Slice(lights * padded, padded), beta, radiance, s);
            else if (_level == 0) record!.Excite(light, shift, beta, s);
            else record!.ExciteSegment(light, shift, beta, s);
        }

        public readonly Span<float> Fixed => _groups.Slice(lights * padded, padded);

        public void Shift(FluorescentShift shift, Span<float> beta, float w)
        {
            if (record is not null)
            {
                record.Fold(_level);
                record.Chain(_level, shift, beta, w);
            }
            _level++;
        }

        public readonly void End() => record?.Fold(_level);

        public void Branch()
        {
            _split = _level;
            if (_level > 0) record?.Keep();
        }

        public void Rejoin()
        {
            if (_level == _split) return;
            record?.Fold(_level);
            _level = _split;
            if (_level > 0) record?.Restore();
        }
    }
}
