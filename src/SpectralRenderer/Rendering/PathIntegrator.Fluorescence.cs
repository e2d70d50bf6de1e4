using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

// Fluorescence from indirect light (issue 26): the path's continuation through a fluorescent surface's shifted lobe.
public sealed partial class PathIntegrator
{
    // A shifted bounce re-emits at camera sub-band o what arrives at every excitation sub-band i: the light the path finds
    // beyond it reaches the film through f_s[o, i]·β[o] (FluorescentShift), not band by band. A path's throughput is then a
    // matrix (camera sub-band × current sub-band); it stays exact per band, with no wavelength sampled, by splitting the path
    // at its shifted bounces k = 1, 2, …: the film is
    //   L = X_0 + M_1·(X_1 + … ),  M_1 = diag(β_0)·f_s·w_1,  M_k+1 = M_k·diag(β_k)·f_s·w_k+1,  w = cos θ/(P_lobe·p(ω)),
    // where X_k is what the path finds between its k-th and (k+1)-th shifted bounce with a fresh throughput β_k (1 at the
    // bounce). The sink keeps collecting into its fixed slot, which holds X_k; at the next shifted bounce and at the path's end
    // it is folded into the saved film by M_k (N² products; a second shifted bounce costs one N³ product M·diag(β)·f_s).
    // The direction is drawn cosine-weighted about the front normal, p = cos θ/π. Light sources excite the shifted lobe by
    // next-event estimation alone (NextEvent adds f_s·L_e at weight 1 for every light, emitter and the sky), so an emitter or
    // the sky reached right after a shifted bounce gets MIS weight 0 (its density is returned as 0: PowerHeuristic(0, ·) = 0);
    // the shifted bounce carries only light that arrives after further bounces. Each path of light is thus counted by exactly
    // one strategy: unbiased, and direct excitation keeps next-event estimation's low noise. A non-fluorescent material never
    // takes this branch and draws no extra random number: its paths are those of a scene without fluorescence.

    /// <summary>Scratch for shifted paths: the saved film, a row, β_0·w_1, and M (sub-bands × padded) — only in a fluorescent scene.</summary>
    int ShiftScratch => Fluoresces ? (_grid.Count + 3) * _padded : 0;

    /// <summary>
    /// The continuation through the shifted lobe of <paramref name="shift"/>, chosen with probability <paramref name="probability"/>:
    /// ωi cosine-weighted about <paramref name="front"/>, the film's collected light saved (or folded into it), the transform
    /// extended by diag(β)·f_s·w, β reset to 1, <paramref name="gain"/> (a bound of the transform's amplification, which Russian
    /// roulette multiplies into β's largest band) times its ‖·‖∞. The first bounce keeps M_1 = diag(β_0·w_1)·f_s as its factors (N·span products
    /// to fold); a second one makes M explicit. <paramref name="pdf"/> is 0: sources reached next are next-event estimation's.
    /// False when ωi leaves the lobe's hemisphere (the path ends).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    bool ShiftedBounce<TSink>(ref TSink sink, FluorescentShift shift, float probability, Vector3 wo, Vector3 ns, Vector3 front, Vector2 u,
        Span<float> beta, Span<float> scratch, ref int shifted, ref FluorescentShift? firstShift, ref float gain, out Vector3 wi, out float pdf)
        where TSink : IPathSink, allows ref struct
    {
        wi = Bsdf.CosineHemisphere(front, u);
        pdf = 0;
        float density = probability * SkyPdf(front, wi);
        if (!(density > 0) || !FluorescentShift.Reflects(wo, wi, ns)) return false;
        float w = Vector3.Dot(front, wi) / density;
        int n = _padded;
        var film = sink.Fixed;
        var saved = scratch.Slice(5 * n, n);
        var row = scratch.Slice(6 * n, n);
        var beta0 = scratch.Slice(7 * n, n);
        var m = scratch.Slice(8 * n, _grid.Count * n);
        if (shifted == 0)
        {   // M_1 = diag(β_0·w_1)·f_s, kept as its factors
            film.CopyTo(saved);
            for (int i = 0; i < n; i++) beta0[i] = beta[i] * w;
            firstShift = shift;
        }
        else
        {
            if (shifted == 1)
            {
                firstShift!.AddShifted(saved, beta0, film, 1);
                firstShift.Start(m, beta0, 1);
            }
            else FluorescentShift.AddProduct(saved, m, film, _grid.Count);
            shift.Chain(m, beta, w, row);
        }
        gain *= shift.Gain(beta, w);
        film.Clear();
        beta.Clear();
        beta[.._grid.Count].Fill(1);   // the padding stays 0
        shifted++;
        return true;
    }

    /// <summary>The path's end after shifted bounces: the film is the saved film plus M·X (X what was collected since the last).</summary>
    void FinishShifted(Span<float> film, Span<float> scratch, int shifted, FluorescentShift? firstShift)
    {
        int n = _padded;
        var saved = scratch.Slice(5 * n, n);
        if (shifted == 1) firstShift!.AddShifted(saved, scratch.Slice(7 * n, n), film, 1);
        else FluorescentShift.AddProduct(saved, scratch.Slice(8 * n, _grid.Count * n), film, _grid.Count);
        saved.CopyTo(film);
    }
}
