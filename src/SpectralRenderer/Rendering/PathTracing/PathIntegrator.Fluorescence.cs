using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

// Fluorescence from indirect light (issue 26): the path's continuation through a fluorescent surface's shifted lobe.
internal sealed partial class PathIntegrator
{
    // A shifted bounce re-emits at camera sub-band o what arrives at every excitation sub-band i: the light the path finds
    // beyond it reaches the film through f_s[o, i]·β[o] (FluorescentShift), not band by band. A path's throughput is then a
    // matrix (camera sub-band × current sub-band); it stays exact per band, with no wavelength sampled, by splitting the path
    // at its shifted bounces k = 1, 2, …, K: the film is
    //   L = X_0 + A_1·X_1 + A_1·A_2·X_2 + … ,   A_k = diag(g_k)·f_s(k),  g_k = β_k−1·w_k,  w = cos θ/(P_lobe·p(ω)),
    // where X_k is what the path finds between its k-th and (k+1)-th shifted bounce with a fresh throughput β_k (1 at the
    // bounce). The sink keeps collecting into its fixed slot, which holds X_k; when X_k is complete (at the next shifted bounce
    // or the path's end) it is carried to the film right to left, A_1·(A_2·(…A_k·X_k)): k products of N × (the shift's band
    // span), the factors g_k and the materials kept per bounce. Past ShiftLevels bounces (rare: Russian roulette weighs β by
    // the bounces' gain) the product is made explicit, M = A_1 ⋯ A_k (N³ per further bounce).
    // The direction is drawn cosine-weighted about the front normal, p = cos θ/π. Light sources excite the shifted lobe by
    // next-event estimation alone (NextEvent adds f_s·L_e at weight 1 for every light, emitter and the sky), so an emitter or
    // the sky reached right after a shifted bounce gets MIS weight 0 (its density is returned as 0: PowerHeuristic(0, ·) = 0);
    // the shifted bounce carries only light that arrives after further bounces. Each path of light is thus counted by exactly
    // one strategy: unbiased, and direct excitation keeps next-event estimation's low noise. A non-fluorescent material never
    // takes this branch and draws no extra random number: its paths are those of a scene without fluorescence.
    // The lobe choice at a fluorescent vertex weighs the smooth and the shifted lobe by their albedos under β (LobeShares):
    // a fixed share (≈ 0.35 for a brightened paper) gave the diagonal a weight 0.88/0.65 ≈ 1.4 per bounce, which Russian
    // roulette (survival ≤ 0.95) cannot take back — throughput grew along paths between bright surfaces (fireflies).

    /// <summary>Russian roulette's largest survival probability (PathIntegrator.cs).</summary>
    const float Survival = 0.95f;

    /// <summary>Shifted bounces of one path kept as factors; beyond, their product is made explicit.</summary>
    internal const int ShiftLevels = 16;

    /// <summary>
    /// A path's shifted bounces: how many so far (<see cref="Level"/>), whether the saved film holds light yet
    /// (<see cref="Saved"/>), and <see cref="Gain"/>, a bound of their amplification towards the film (1 without them).
    /// </summary>
    struct ShiftState(float gain)
    {
        public int Level;
        public bool Saved;
        public float Gain = gain;
    }

    /// <summary>
    /// Scratch for shifted paths (only in a fluorescent scene), after the walk's five spectra (and a split's β when the scene
    /// also disperses): the saved film, two work spectra, the materials of the bounces (ShiftLevels floats), their factors
    /// g_k (ShiftLevels spectra), M (sub-bands × padded), and with dispersion M at a split (the same).
    /// </summary>
    int ShiftScratch => _fluoresces ? (3 + ShiftLevels + (_splitsShifts ? 2 : 1) * _grid.Count) * _padded + ShiftLevels : 0;

    /// <summary>Does a material of the scene shift light between bands (fluorescence)?</summary>
    readonly bool _fluoresces;

    /// <summary>Where the shifted paths' scratch starts: after a dispersive split's β when the scene has both.</summary>
    int ShiftBase => (_splitsShifts ? 6 : 5) * _padded;

    Span<float> Saved(Span<float> scratch) => scratch.Slice(ShiftBase, _padded);
    Span<float> Work(Span<float> scratch, int k) => scratch.Slice(ShiftBase + (1 + k) * _padded, _padded);
    Span<float> Materials(Span<float> scratch) => scratch.Slice(ShiftBase + 3 * _padded, ShiftLevels);
    Span<float> Factor(Span<float> scratch, int k) => scratch.Slice(ShiftBase + (2 + k) * _padded + ShiftLevels, _padded);
    Span<float> Explicit(Span<float> scratch) =>
        scratch.Slice(ShiftBase + (3 + ShiftLevels) * _padded + ShiftLevels, _grid.Count * _padded);
    Span<float> ExplicitAtSplit(Span<float> scratch) =>
        scratch.Slice(ShiftBase + (3 + ShiftLevels + _grid.Count) * _padded + ShiftLevels, _grid.Count * _padded);

    /// <summary>
    /// The continuation through <paramref name="vertex"/>'s shifted lobe, chosen with probability
    /// <paramref name="probability"/>: ωi cosine-weighted about its front normal; the light collected since the last
    /// shifted bounce carried to the saved film; this bounce's factor g = β·w kept; β reset to 1 and the gain of
    /// <paramref name="shifts"/> (a bound of the transform's amplification, which Russian roulette multiplies into β's
    /// largest band) times ‖diag(g)·f_s‖∞.
    /// <paramref name="pdf"/> is 0: sources reached next are next-event estimation's. False when ωi leaves the lobe's hemisphere.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a fluorescent vertex only: kept out of the walk (its registers and frame)
    bool ShiftedBounce<TSink>(ref TSink sink, scoped in PathVertex vertex, float probability, Vector2 u, Span<float> beta,
        Span<float> scratch, ref ShiftState shifts, out Vector3 wi, out float pdf) where TSink : IPathSink, allows ref struct
    {
        var front = vertex.Front;
        wi = Bsdf.CosineHemisphere(front, u);
        pdf = 0;
        float density = probability * (MathF.Max(0, Vector3.Dot(front, wi)) / MathF.PI);   // cosine-weighted
        if (!(density > 0) || !FluorescentShift.Reflects(vertex.Wo, wi, vertex.Ns)) return false;
        float w = Vector3.Dot(front, wi) / density;
        var shift = vertex.Material.Shift!;
        sink.Shift(shift, beta, w);
        var film = sink.Fixed;
        if (!shifts.Saved) film.CopyTo(Saved(scratch));
        else Fold(film, scratch, shifts.Level);
        int k = shifts.Level + 1;
        if (k <= ShiftLevels)
        {
            Materials(scratch)[k - 1] = vertex.Material.Index;
            var g = Factor(scratch, k);
            for (int i = 0; i < g.Length; i++) g[i] = beta[i] * w;
        }
        else
        {
            var m = Explicit(scratch);
            if (k == ShiftLevels + 1)
            {   // M = A_1 ⋯ A_ShiftLevels from the kept factors
                var materials = Materials(scratch);
                _materials[(int)materials[0]].Shift!.Start(m, Factor(scratch, 1), 1);
                for (int j = 2; j <= ShiftLevels; j++)
                    _materials[(int)materials[j - 1]].Shift!.Chain(m, Factor(scratch, j), 1, Work(scratch, 0));
            }
            shift.Chain(m, beta, w, Work(scratch, 0));
        }
        shifts.Gain *= shift.Gain(beta, w);
        film.Clear();
        beta.Clear();
        beta[.._grid.Count].Fill(1);   // the padding stays 0
        shifts.Level = k;
        shifts.Saved = true;
        return true;
    }

    /// <summary>
    /// The lobe choice at a fluorescent vertex, between the smooth lobes (albedo a = m_diff + m_spec: the reflective diagonal,
    /// its texels when textured) and the shifted one (albedo S·1 under flat light), each weighed by the path's throughput β:
    /// Ā = Σβ·a/Σβ, B̄ = Σβ·S·1/Σβ (band sums) and Â = max(β·a)/max β, B̂ = max(β·S·1)/max β (largest bands). The shifted lobe
    /// takes P = max(B̄/(Ā + B̄), min(B̂/(Â + B̂), 1 − Â/0.95)): at most 1 − Â/0.95, so the smooth lobes' weight a/(1 − P)
    /// stays ≤ 0.95 in β's largest band — Russian roulette's largest survival, so β/q does not grow along paths between bright
    /// fluorescent surfaces (a fixed share gave the diagonal 0.88/0.65 ≈ 1.4 per bounce, a heavy tail: issue 26); below
    /// that, the share that balances both lobes' largest band weights (as the
    /// fixed share did), so a shift into a few bands is not starved; and never below the albedos' proportion, so the lobe
    /// keeps a probability wherever it carries light (unbiased). The two shares sum to Ā + B̄, the vertex's albedo under β,
    /// beside a delta lobe's share. Returns the shifted share and sets <paramref name="smoothShare"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a fluorescent vertex only: kept out of the walk
    float LobeShares(scoped in PathVertex vertex, Span<float> beta, scoped ref float smoothShare)
    {
        var material = vertex.Material;
        var texels = vertex.Texels;
        var shift = material.Shift!;
        float sum = Sum(beta), top = Max(beta);
        if (!(sum > 0 && top > 0) || !float.IsFinite(sum)) return shift.Share;   // a spent path: the fixed shares
        float bSum = Dot(beta, shift.Flat) / sum, bMax = MaxProduct(beta, shift.Flat, default) / top;
        if (!material.Smooth) return bSum;
        ReadOnlySpan<float> d = texels.Diffuse.IsEmpty ? material.AlbedoDiffuse : texels.Diffuse;
        ReadOnlySpan<float> s = texels.Specular.IsEmpty ? material.AlbedoSpecular : texels.Specular;
        float aSum = (Dot(beta, d) + Dot(beta, s)) / sum, aMax = MaxProduct(beta, d, s) / top;
        if (!(bSum > 0)) return 0;   // β carries nothing the shift emits: the lobe would add 0
        float p = MathF.Max(bSum / (aSum + bSum), MathF.Min(bMax / (aMax + bMax), 1 - aMax / Survival));
        float combined = aSum + bSum;
        smoothShare = MathF.Max(combined * (1 - p), 1e-6f);
        return combined * p;
    }

    /// <summary>max_o β[o]·(x[o] + y[o]) (<paramref name="y"/> may be empty).</summary>
    static float MaxProduct(Span<float> beta, ReadOnlySpan<float> x, ReadOnlySpan<float> y)
    {
        var vb = V(beta);
        var vx = RV(x[..beta.Length]);
        var m = Vector<float>.Zero;
        if (y.IsEmpty) for (int i = 0; i < vb.Length; i++) m = Vector.Max(m, vb[i] * vx[i]);
        else
        {
            var vy = RV(y[..beta.Length]);
            for (int i = 0; i < vb.Length; i++) m = Vector.Max(m, vb[i] * (vx[i] + vy[i]));
        }
        float r = 0;
        for (int i = 0; i < Vector<float>.Count; i++) r = MathF.Max(r, m[i]);
        return r;
    }

    /// <summary>Σ a (padded: the padding is 0).</summary>
    static float Sum(Span<float> a)
    {
        var v = V(a);
        var s = Vector<float>.Zero;
        for (int i = 0; i < v.Length; i++) s += v[i];
        return Vector.Sum(s);
    }

    /// <summary>Σ a ⊙ b over a's padded length.</summary>
    static float Dot(Span<float> a, ReadOnlySpan<float> b)
    {
        var va = V(a);
        var vb = RV(b[..a.Length]);
        var s = Vector<float>.Zero;
        for (int i = 0; i < va.Length; i++) s += va[i] * vb[i];
        return Vector.Sum(s);
    }

    /// <summary>Saved film += A_1·(A_2·(…A_k·x)) for the k = <paramref name="shifted"/> bounces so far (or M·x past ShiftLevels).</summary>
    void Fold(Span<float> x, Span<float> scratch, int shifted)
    {
        var saved = Saved(scratch);
        if (shifted > ShiftLevels)
        {
            FluorescentShift.AddProduct(saved, Explicit(scratch), x, _grid.Count);
            return;
        }
        Span<float> v = Work(scratch, 0), t = Work(scratch, 1);
        x.CopyTo(v);
        var materials = Materials(scratch);
        for (int j = shifted; j >= 1; j--)
        {
            t.Clear();
            _materials[(int)materials[j - 1]].Shift!.AddShifted(t, Factor(scratch, j), v, 1);
            var swap = v; v = t; t = swap;
        }
        FluorescentShift.Add(saved, v);
    }

    /// <summary>The path's end after shifted bounces: the film is the saved film plus the light collected since the last,
    /// carried.</summary>
    void FinishShifted(Span<float> film, Span<float> scratch, int shifted)
    {
        Fold(film, scratch, shifted);
        Saved(scratch).CopyTo(film);
    }
}
