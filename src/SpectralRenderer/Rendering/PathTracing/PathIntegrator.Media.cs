using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// Participating media in the walk (PathIntegrator.cs). Every ray segment travels in one medium (<see cref="Medium"/>; −1:
/// vacuum): a camera ray in the scene's "medium"; a ray that leaves a vertex of an object that names an interior medium
/// travels in that medium when it goes into the object (against its outward geometric normal) and in the scene's medium
/// when it goes out; any other vertex keeps the medium its ray came in (a surface that names no medium is no boundary,
/// as pbrt-v4's primitives without a MediumInterface). <see cref="PathVertex.Medium"/> is the medium of the ray that
/// reached a vertex and <see cref="PathVertex.Interior"/> its object's interior, so next-event estimation knows its
/// shadow ray's.
/// <para>
/// A medium that only absorbs: the walk multiplies β by the segment's transmittance T per band (Medium.Attenuate: the
/// segment from one vertex to the next; +∞ for a ray that escapes), exact, and next-event estimation multiplies f by T
/// along the shadow ray (a shadow ray is blocked by any surface, so it crosses no boundary) — in f, not in the light's
/// spectrum, so the per-light transfer keeps T and a relight stays exact.
/// </para>
/// <para>
/// A medium that scatters: free-flight sampling by spectral tracking (Kutz et al. 2017, "Spectral and decomposition tracking
/// for rendering heterogeneous volumes", §5.2) — one majorant for every band, σ̄ = max_λ σ_t(λ); tentative collisions at
/// exponential distances of rate σ̄; at each, absorption, scattering or a null collision is chosen with probabilities
/// P_x = ‖σ_x ⊙ β‖∞ / Σ_y ‖σ_y ⊙ β‖∞ (history-aware: by the path's throughput, so no band's weight grows without bound),
/// and β ⊙= σ_x/(σ̄·P_x) — so every band's estimate is unbiased although all share one distance, and no wavelength is
/// sampled (no colour noise from wavelengths). Absorption ends the path (the medium emits nothing); scattering makes a
/// vertex whose "BSDF" is the phase function: next-event estimation there (f = p(ωo, ωi)·T along the shadow ray, the exact
/// Beer–Lambert T of a homogeneous medium in place of ratio tracking) with MIS (power heuristic) against phase sampling,
/// which Henyey–Greenstein does exactly (f/pdf = 1), then Russian roulette on β as at a surface. The sky is not drawn
/// from a vertex in a medium (it has no hemisphere: p_sky = 0 there), so phase samples that escape see it with weight 1.
/// A ray that escapes in a scattering medium is tracked to the edge of the media's extent (a sphere about the scene's
/// bounds and the camera, <see cref="_extentCentre"/>, radius <see cref="_extentRadius"/>) and only attenuated beyond it
/// (exp(−σ_t·∞): 0 in a band that attenuates, 1 in one that does not) — scattering far outside the scene is not followed.
/// Every random number of the tracking comes from the camera sample's sampler, so a picture is the same on any thread
/// count or shard; the decisions depend on β only, never on a light's spectrum, so transport stays linear in each light's
/// emission and a relight stays exact. Without media (every scene without a "medium") no medium is read and no number
/// changes: the pictures are the same bit for bit.
/// </para>
/// </summary>
internal sealed partial class PathIntegrator
{
    /// <summary>The scene's media on the sub-band grid (empty: none).</summary>
    Medium[] _media = [];
    /// <summary>Each object's interior medium (−1: its surface bounds none), null without media.</summary>
    int[]? _interiorOf;
    /// <summary>The medium around the objects, where the camera is (−1: vacuum).</summary>
    int _sceneMedium = -1;

    /// <summary>The scene's media on the sub-band grid, or bad input naming what the path integrator cannot carry through one.</summary>
    void TakeMedia(Scene scene)
    {
        if (scene.Media.Count == 0) return;
        if (_fluoresces)
            throw new InputException($"{scene.SourcePath}: $.medium",
                "the path integrator does not carry fluorescent light through participating media yet (issue 41)",
                "remove the medium or the fluorescent material");
        _media = scene.Media.Select(m => m.Resampled(_grid.Resample)).ToArray();
        _scattering = _media.Select(m => m.Scattering).ToArray();
        _interiorOf = scene.Objects.Select(o => o.Medium).ToArray();
        _sceneMedium = scene.Medium;
        var clear = scene.Objects.Select(o => IsNullBoundary(scene.Materials[o.Material], scene.Grid.Count)).ToArray();
        _nullBoundary = clear.Any(c => c) ? clear : null;
        // The media's extent: a sphere about the finite geometry and the camera, twice as wide as both.
        _extentCentre = _geometry.BoundingCentre;
        _extentRadius = 2 * MathF.Max(MathF.Max(_geometry.BoundingRadius, Vector3.Distance(scene.Camera.Position, _extentCentre)), 1e-3f);
    }

    /// <summary>
    /// Which objects are null boundaries, surfaces that change nothing but the medium (index-matched and clear:
    /// <see cref="IsNullBoundary"/>), which shadow rays cross; null: none, or a scene without media.
    /// </summary>
    bool[]? _nullBoundary;

    /// <summary>
    /// Is <paramref name="m"/> a null boundary: eq. 2's lobes with nothing but k_t = 1 and n = 1 in every band (no diffuse,
    /// specular or mirror lobe, no emission, fluorescence or texture), so that light crosses it unchanged and unbent?
    /// </summary>
    static bool IsNullBoundary(Material m, int bands)
    {
        if (m.Bsdf is not Eq2Bsdf || m.HasSpecular || m.HasMirror || m.Emission is not null || m.Fluorescence is not null
            || m.DiffuseTexture is not null || m.SpecularTexture is not null || m.Dispersive) return false;
        for (int b = 0; b < bands; b++)
            if (m.Diffuse[b] != 0 || m.Transmit[b] != 1 || m.Ior[b] != 1) return false;
        return true;
    }

    /// <summary>
    /// The shadow ray from <paramref name="p"/> (geometric normal <paramref name="ng"/>; zero in a medium) along
    /// <paramref name="wi"/> for <paramref name="distance"/>, leaving in <paramref name="medium"/>: false when a surface
    /// blocks it, else true with f ⊙= T of the media along it. Without null boundaries any surface blocks it (and f ⊙= T of
    /// its one medium); with them it crosses each null boundary it meets, its medium changing there as a path's does
    /// (<see cref="MediumToward"/>), and T is the product over its segments — index-matched shadow rays.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a scene with media only: kept out of the walk's frame
    bool ShadowThrough(Vector3 p, Vector3 ng, Vector3 wi, float distance, int medium, Span<float> f)
    {
        float epsilon = _geometry.Epsilon;
        var ray = Visibility.ShadowRay(p, ng, wi, distance, epsilon);
        if (_nullBoundary is not { } clear)
        {
            if (_geometry.OccludedScattered(ray)) return false;
            if (medium >= 0) Attenuate(medium, p, wi, distance, f);
            return true;
        }
        var target = p + distance * wi;
        var from = p;
        for (int crossings = 0; crossings < MaxNullCrossings; crossings++)
        {
            var probe = ray;
            if (!_geometry.IntersectScattered(ref probe, out var hit))
            {
                if (medium >= 0)
                    Attenuate(medium, from, wi, float.IsInfinity(distance) ? distance : Vector3.Distance(from, target), f);
                return true;
            }
            if (!clear[hit.Object]) return false;
            if (medium >= 0) Attenuate(medium, from, wi, Vector3.Distance(from, hit.Position), f);
            if (InteriorOf(hit.Object) is var interior and >= 0)
                medium = Vector3.Dot(hit.GeometricNormal, wi) < 0 ? interior : _sceneMedium;
            from = hit.Position;
            ray = Visibility.ShadowRay(from, hit.GeometricNormal, wi,
                float.IsInfinity(distance) ? distance : Vector3.Distance(from, target), epsilon);
        }
        return false;   // (more null boundaries than any scene stacks: treated as blocked)
    }

    /// <summary>The null boundaries a shadow ray crosses at most.</summary>
    const int MaxNullCrossings = 64;

    /// <summary>Each medium's scattering (null: it only absorbs), on the sub-band grid.</summary>
    MediumScattering?[] _scattering = [];
    Vector3 _extentCentre;
    float _extentRadius;

    /// <summary>How a segment's free flight ended.</summary>
    enum Flight { Passed, Scattered, Absorbed }

    /// <summary>
    /// Spectral tracking (Kutz et al. 2017, §5.2) of the segment of <paramref name="ray"/> up to <paramref name="end"/> (+∞: it
    /// escapes) in medium <paramref name="medium"/>, β weighted on the way: <see cref="Flight.Passed"/> (β ⊙= the null
    /// collisions' weights, and for an escaping ray exp(−σ_t·∞) beyond the extent), <see cref="Flight.Scattered"/> at
    /// <paramref name="at"/> (β ⊙= also σ_s/(σ̄·P_s)), or <see cref="Flight.Absorbed"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a scene with scattering media only: kept out of the walk's frame
    Flight Track(MediumScattering m, int medium, Ray ray, float end, Span<float> beta, ref Sampler sampler, out Vector3 at)
    {
        if (m.Density is { } density) return TrackDensity(m, density, ray, end, beta, ref sampler, out at);
        at = default;
        float majorant = m.Majorant, tEnd = end;
        bool escapes = float.IsPositiveInfinity(end);
        if (escapes) tEnd = ExitOfExtent(ray);
        if (majorant > 0)
        {
            var vb = V(beta);
            ReadOnlySpan<Vector<float>> va = RV(m.SigmaA), vs = RV(m.SigmaS), vn = RV(m.SigmaN);
            float t = 0;
            for (; ; )
            {
                t -= MathF.Log(1 - sampler.Next1D()) / majorant;   // p(t) = σ̄·exp(−σ̄·t)
                if (!(t < tEnd)) break;
                Vector<float> ma = Vector<float>.Zero, ms = Vector<float>.Zero, mn = Vector<float>.Zero;
                for (int i = 0; i < vb.Length; i++)
                {
                    ma = Vector.Max(ma, va[i] * vb[i]);
                    ms = Vector.Max(ms, vs[i] * vb[i]);
                    mn = Vector.Max(mn, vn[i] * vb[i]);
                }
                float pa = MaxLane(ma), ps = MaxLane(ms), pn = MaxLane(mn), c = pa + ps + pn;
                if (!(c > 0)) return Flight.Absorbed;
                float x = sampler.Next1D() * c;
                if (x < pa) return Flight.Absorbed;   // absorbed: the medium emits nothing
                if (x < pa + ps)
                {
                    Multiply(beta, m.SigmaS, c / (majorant * ps));
                    at = ray.Origin + t * ray.Direction;
                    return Flight.Scattered;
                }
                Multiply(beta, m.SigmaN, c / (majorant * pn));   // a null collision: on along the ray
            }
        }
        if (escapes) Attenuate(medium, ray.Origin, ray.Direction, float.PositiveInfinity, beta);
        return Flight.Passed;
    }

    /// <summary>
    /// Spectral tracking in a heterogeneous medium (<see cref="MediumScattering.Density"/>): as <see cref="Track"/>, over the
    /// segment's overlap with the grid's box (the density is 0 outside it, so the rest passes with T = 1), against the
    /// majorant σ̄ = max d · max_λ σ_t(λ); at a tentative collision at x the coefficients are d(x)·σ_a, d(x)·σ_s and
    /// σ_n = σ̄ − d(x)·σ_t ≥ 0 per band (Kutz et al. 2017, §5.2, with null collisions: unbiased for any majorant ≥ σ_t).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    static Flight TrackDensity(MediumScattering m, DensityGrid density, Ray ray, float end, Span<float> beta, ref Sampler sampler,
        out Vector3 at)
    {
        at = default;
        float majorant = m.Majorant;
        if (!(majorant > 0) || !density.Clip(ray.Origin, ray.Direction, end, out float t, out float tEnd)) return Flight.Passed;
        var vb = V(beta);
        ReadOnlySpan<Vector<float>> va = RV(m.SigmaA), vs = RV(m.SigmaS);
        var vMajorant = new Vector<float>(majorant);
        for (; ; )
        {
            t -= MathF.Log(1 - sampler.Next1D()) / majorant;   // p(t) = σ̄·exp(−σ̄·t)
            if (!(t < tEnd)) return Flight.Passed;
            var x = ray.Origin + t * ray.Direction;
            float d = density.Density(x);
            var vd = new Vector<float>(d);
            Vector<float> ma = Vector<float>.Zero, ms = Vector<float>.Zero, mn = Vector<float>.Zero;
            for (int i = 0; i < vb.Length; i++)
            {
                ma = Vector.Max(ma, va[i] * vb[i]);
                ms = Vector.Max(ms, vs[i] * vb[i]);
                mn = Vector.Max(mn, Vector.Max(Vector<float>.Zero, vMajorant - vd * (va[i] + vs[i])) * vb[i]);
            }
            float pa = d * MaxLane(ma), ps = d * MaxLane(ms), pn = MaxLane(mn), c = pa + ps + pn;
            if (!(c > 0)) return Flight.Absorbed;
            float u = sampler.Next1D() * c;
            if (u < pa) return Flight.Absorbed;   // absorbed: the medium emits nothing
            if (u < pa + ps)
            {
                Multiply(beta, m.SigmaS, d * c / (majorant * ps));
                at = x;
                return Flight.Scattered;
            }
            var scale = new Vector<float>(c / (majorant * pn));   // a null collision: β ⊙= σ_n(x)·c/(σ̄·P_n), on along the ray
            for (int i = 0; i < vb.Length; i++) vb[i] *= Vector.Max(Vector<float>.Zero, vMajorant - vd * (va[i] + vs[i])) * scale;
        }
    }

    /// <summary>The largest lane of <paramref name="v"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float MaxLane(Vector<float> v)
    {
        float r = 0;
        for (int i = 0; i < Vector<float>.Count; i++) r = MathF.Max(r, v[i]);
        return r;
    }

    /// <summary>Where <paramref name="ray"/> leaves the media's extent (0: it does not cross it).</summary>
    float ExitOfExtent(Ray ray)
    {
        var oc = ray.Origin - _extentCentre;
        float b = Vector3.Dot(oc, ray.Direction), c = oc.LengthSquared() - _extentRadius * _extentRadius;
        float discriminant = b * b - c;
        return discriminant > 0 ? MathF.Max(0, -b + MathF.Sqrt(discriminant)) : 0;
    }

    /// <summary>
    /// A vertex at <paramref name="p"/> in medium <paramref name="medium"/> with phase function <paramref name="phase"/>, reached
    /// along <paramref name="ray"/> (ωo = <paramref name="wo"/>): next-event estimation of one emitter, then the next ray drawn
    /// from the phase function (β unchanged: f/pdf = 1), Russian roulette on β. False: the path ends.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    bool Scatter<TSink>(ref TSink sink, HenyeyGreenstein phase, int medium, Vector3 p, Vector3 wo, ref Ray ray, Span<float> beta,
        Span<float> f, ref Sampler sampler, int depth, Span<float> scratch, ref ShiftState shifts, ref RayCounters counters,
        out float phasePdf) where TSink : IPathSink, allows ref struct
    {
        phasePdf = 0;
        // The dimensions of a surface vertex, in its order (light, point on it, lobe — unused here —, direction, roulette).
        int dLight = sampler.Reserve1D(), dPoint = sampler.Reserve2D();
        sampler.Reserve1D();
        int dDirection = sampler.Reserve2D(), dRoulette = sampler.Reserve1D();
        if (_emitters.Count > 0)
        {
            float uLight = _emitters.Count > 1 ? sampler.At1D(dLight) : 0;
            var uPoint = sampler.At2D(dPoint);
            MediumNextEvent(ref sink, phase, medium, p, wo, uLight, new Vector2(uPoint.U, uPoint.V), beta, f, scratch, ref counters);
        }
        var u = sampler.At2D(dDirection);
        var wi = phase.Sample(wo, new Vector2(u.U, u.V));
        phasePdf = phase.Evaluate(wo, wi);
        if (depth + 1 >= _rrDepth)
        {
            float q = MathF.Min(Survival, Max(beta) * shifts.Gain);
            if (!(q > 0) || sampler.At1D(dRoulette) >= q) return false;
            Scale(beta, 1 / q);
        }
        ray = new Ray(p, wi);
        counters.Secondary++;
        return true;
    }

    /// <summary>
    /// L += β·p(ωo, ωi)·T·L_e·w/(P(k)·p_k) for one sample of emitter k, chosen by <paramref name="uLight"/>, seen from
    /// <paramref name="p"/> in <paramref name="medium"/>: w = 1 for a delta light, else the power heuristic against the phase
    /// function's density; T along the shadow ray (exact for a homogeneous medium), which any surface blocks.
    /// </summary>
    void MediumNextEvent<TSink>(ref TSink sink, HenyeyGreenstein phase, int medium, Vector3 p, Vector3 wo, float uLight, Vector2 u,
        Span<float> beta, Span<float> f, Span<float> scratch, ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        int k = _emitters.Choose(p, Vector3.Zero, uLight, out float pick);
        if (k < 0) return;
        var emitter = _emitters[k];
        if (!emitter.Sample(p, Vector3.Zero, u, out var sample)) return;
        var wi = sample.Direction;
        float distance = sample.Distance, factor = sample.Factor, pdf = sample.Pdf;
        if (!(pdf > 0) || !(factor > 0)) return;   // (the sky: p = 0 from a point in a medium)
        var radiance = emitter.Texture is null ? emitter.Radiance
            : EmittedAt(emitter, sample.Face, sample.Point, sample.Normal, wi, distance, scratch.Slice(TextureBase + 2 * _padded, _padded));
        counters.Shadow++;
        float density = phase.Evaluate(wo, wi);
        f.Clear();
        f[.._grid.Count].Fill(density);
        if (!ShadowThrough(p, Vector3.Zero, wi, distance, medium, f)) return;
        float w = sample.IsDelta ? 1 : PowerHeuristic(pick * pdf, density);
        sink.NextEvent(emitter.SceneLight, beta, f, radiance, factor * w / (pick * pdf));
    }

    /// <summary>The interior medium of object <paramref name="o"/> (−1: none, or a scene without media).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    int InteriorOf(int o) => _interiorOf is { } interior ? interior[o] : -1;

    /// <summary>The medium a ray leaving <paramref name="vertex"/> along <paramref name="wi"/> travels in.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    int MediumToward(scoped in PathVertex vertex, Vector3 wi) =>
        vertex.Interior < 0 ? vertex.Medium : Vector3.Dot(vertex.Ng, wi) < 0 ? vertex.Interior : _sceneMedium;

    /// <summary>
    /// values ⊙= T of medium <paramref name="medium"/> (≥ 0) along the segment from <paramref name="origin"/> along
    /// <paramref name="direction"/> for <paramref name="distance"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // a scene with media only: kept out of the walk's frame
    void Attenuate(int medium, Vector3 origin, Vector3 direction, float distance, Span<float> values) =>
        _media[medium].Attenuate(origin, direction, distance, values);
}
