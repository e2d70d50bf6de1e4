using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// Dispersion in the path tracer: a refracting material whose index varies over the bands (Cauchy or Sellmeier,
/// <see cref="Scenes.RefractiveIndex"/>) bends every wavelength its own way, so one direction cannot serve all bands. At
/// the first vertex of such a material the path splits deterministically into one sub-path per output band: sub-path b is
/// the same walk (PathIntegrator.cs) carrying β on band b's sub-bands only (the others 0), and from there on follows its
/// own Fresnel reflection and refraction with band b's index at its centre wavelength (the index the scene gives that band,
/// as the Whitted integrator uses it), at this and at every later vertex; its next-event estimation, lobe choice, textures,
/// fluorescent lobes and Russian roulette are the walk's. The bands together are the whole path's estimate (β is their sum), each band
/// weighted by its own Fresnel factors, so there is no wavelength sampling and no chromatic noise.
/// Per output band, not per sub-band of the sub-band grid: the output keeps one index per band (docs/scene-format.md), and a
/// sub-path costs a whole path's spectral work, so splitting per sub-band would cost <see cref="SubBandGrid.PerBand"/> times
/// as much after the split for a refraction resolved finer than the film's bands.
/// Random numbers: every sub-path starts from a copy of the path's <see cref="Sampler"/> at the split, so all bands draw the
/// same dimensions (common random numbers: their noise is correlated, hence colourless) and the picture depends on the
/// camera sample only — the same for any thread count or shard. A path that meets no dispersive vertex draws exactly as
/// before.
/// A dispersive material without transmission (a Fresnel mirror) needs no split: its direction is the same in every band
/// and <see cref="Scenes.Bsdf.SampleMirror"/> weights each band by its own F.
/// Fluorescence: a sub-path's shifted bounce sets β to 1 in every band (the light beyond it is at the excitation
/// wavelengths), so the sub-path carries every band again; at a later dispersive vertex it does not split a second time
/// (that would multiply its cost by the bands again) but goes on with one output band b drawn with probability
/// P_b ∝ Σ_b β·c (c: what each band carries to the film through the shifted bounce) and β_b/P_b (<see cref="Narrow"/>):
/// unbiased, the one place a wavelength is sampled. The shifted bounces'
/// state (PathIntegrator.Fluorescence.cs) is the split's for every sub-path: a sub-path's own shifted bounces carry what it
/// found to the saved film when it ends, and the next band starts again from the split's level (IPathSink.Rejoin).
/// </summary>
internal sealed partial class PathIntegrator
{
    /// <summary>A band's β after a dispersive split, in the scratch after the walk's five spectra.</summary>
    Span<float> BandBeta(Span<float> scratch) => scratch.Slice(5 * _padded, _padded);

    /// <summary>Has the scene a dispersive and a fluorescent material (the split's β and the shifted paths' scratch apart)?</summary>
    readonly bool _splitsShifts;

    /// <summary>
    /// Splits the path at <paramref name="hit"/> (reached along <paramref name="ray"/> in <paramref name="medium"/> at
    /// <paramref name="depth"/>, its emission already counted) into one sub-path per output band that β reaches, each the
    /// walk of that band's sub-bands.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a dispersive vertex only: kept out of the walk (its frame)
    void Disperse<TSink>(ref TSink sink, scoped in SurfaceHit hit, Ray ray, int medium, int depth, Span<float> beta,
        Sampler sampler, ref ShiftState shifts, Span<float> scratch, ref RayCounters counters)
        where TSink : IPathSink, allows ref struct
    {
        int width = _grid.PerBand;
        var bandBeta = BandBeta(scratch);
        bool keepExplicit = shifts.Level > ShiftLevels;   // M = A_1 ⋯ A_k is the split's: a sub-path chains onto it
        if (keepExplicit) Explicit(scratch).CopyTo(ExplicitAtSplit(scratch));
        sink.Branch();
        for (int lo = 0; lo < _grid.Count; lo += width)
        {
            var part = beta.Slice(lo, width);
            if (!part.ContainsAnyExcept(0f)) continue;   // nothing of this band left to carry
            bandBeta.Clear();
            part.CopyTo(bandBeta.Slice(lo, width));
            var sub = shifts;
            Walk(ref sink, ray, medium, depth, in hit, lo, bandBeta, sampler, ref sub, scratch, ref counters);
            shifts.Saved = sub.Saved;
            if (sub.Level > shifts.Level)
            {   // saved film += A_1⋯A_j·X_j of its last shifted bounce j; the film (X of the split's level) starts empty again
                var film = sink.Fixed;
                Fold(film, scratch, sub.Level);
                film.Clear();
                sink.Rejoin();
                if (keepExplicit) ExplicitAtSplit(scratch).CopyTo(Explicit(scratch));
            }
        }
    }

    /// <summary>
    /// A dispersive vertex met by a sub-path that carries every band again (after <paramref name="level"/> ≥ 1 shifted
    /// bounces): output band b with probability P_b = Σ_b β·c/Σ β·c for <paramref name="u"/>, where c_i = Σ_o A[o, i] is
    /// how much of sub-band i reaches the film through the last shifted bounce's A = diag(g)·f_s (past ShiftLevels, through
    /// M = A_1⋯A_k), then β ← β_b/P_b on its sub-bands and 0 elsewhere. A band of c = 0 carries nothing to the film, so
    /// leaving it out stays unbiased. Returns b's first sub-band, or −1 when β carries nothing to the film.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a fluorescent and dispersive scene only
    int Narrow(Span<float> beta, float u, int level, Span<float> scratch)
    {
        var c = Work(scratch, 0);
        c.Clear();
        if (level <= ShiftLevels)
        {
            var shift = _materials[(int)Materials(scratch)[level - 1]].Shift!;
            var g = Factor(scratch, level);
            for (int o = shift.Extent.Row0; o < shift.Extent.Row0 + shift.Extent.Rows; o++)
                if (g[o] != 0) AddScaled(c, shift.Row(o), g[o]);
        }
        else
        {
            var m = Explicit(scratch);
            for (int o = 0; o < _grid.Count; o++) AddScaled(c, m.Slice(o * _padded, _padded), 1);
        }
        int width = _grid.PerBand, chosen = -1;
        float total = Dot(beta, c), share = 0;
        if (!(total > 0) || !float.IsFinite(total)) return -1;
        float x = u * total;
        for (int lo = 0; lo < _grid.Count; lo += width)
        {
            float s = 0;
            for (int i = lo; i < lo + width; i++) s += beta[i] * c[i];
            if (!(s > 0)) continue;
            chosen = lo;   // the last band that carries any: the choice if rounding leaves x beyond every band
            share = s;
            if (x < s) break;
            x -= s;
        }
        if (chosen < 0) return -1;
        float scale = total / share;
        for (int i = 0; i < beta.Length; i++) beta[i] = i >= chosen && i < chosen + width ? beta[i] * scale : 0;
        return chosen;
    }

    /// <summary>dst += x·a (padded spectra).</summary>
    static void AddScaled(Span<float> dst, ReadOnlySpan<float> x, float a)
    {
        for (int i = 0; i < dst.Length; i++) dst[i] += x[i] * a;
    }
}
