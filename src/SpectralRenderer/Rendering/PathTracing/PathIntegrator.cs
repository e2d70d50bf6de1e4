using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// Unidirectional path tracing of the rendering equation (Kajiya 1986) in physical radiometry, every band on every path:
/// the throughput β and the radiance L are spectra on a internal sub-band grid (<see cref="SubBandGrid"/>, 5 nm by default),
/// multiplied band by band in SIMD lanes and reduced to the output bands (exact band means) and to XYZ only at the film.
/// At each vertex one light, chosen by power (Emitters/EmitterSet.cs), is sampled (next-event estimation) and the BSDF is
/// sampled to continue; both estimates of light that arrives from surfaces that emit, and from the sky, are combined by multiple importance
/// sampling with the power heuristic w_a = p_a²/(p_a² + p_b²) (Veach &amp; Guibas 1995). Delta lights (point, spot,
/// directional) are reached by next-event estimation only, delta lobes (mirror, Fresnel dielectric) by the BSDF only. One
/// walk (Walk) carries a set of bands: all of them, or after its first dispersive glass one output band's sub-bands, in a
/// sub-path of the same walk per band (PathIntegrator.Dispersion.cs).
/// A lobe is chosen by a luminance-like channel (<see cref="SubBandGrid.Luminance"/>), and Russian roulette ends a path from
/// depth <see cref="IntegratorSettings.RrDepth"/> on with survival probability min(0.95, max_λ β·gain) (the largest band,
/// so no band's light is starved; gain bounds a fluorescent path's shifted bounces, 1 without them); each band keeps its
/// own f·cos/pdf, so no wavelength is ever sampled. The sky is the scene's <c>background</c>: the radiance of every escaping
/// ray, sampled cosine-weighted about the shading normal; or an environment map's radiance of the ray's direction, sampled
/// by the map's luminance (Emitters/EnvironmentEmitter.cs). Depth is unbounded unless <c>max_depth</c> is given (1: direct
/// light only). Every random number comes from the camera sample's <see cref="Sampler"/>, so the picture is the same on
/// any thread count, tile order or shard; nothing is allocated per path.
/// </summary>
[CompiledAtFirstCall]
[SkipLocalsInit]   // the walk's locals are all written before read: no 0.7 KB of stack cleared per camera sample
internal sealed partial class PathIntegrator : IAnalysisIntegrator
{
    readonly SceneGeometry _geometry;
    readonly SubBandGrid _grid;
    readonly int _maxDepth, _rrDepth, _padded;
    readonly int[] _objectMaterial;
    readonly PathMaterial[] _materials;   // per scene material: what the walk reads of it (PathMaterial.cs)
    readonly Light[] _lights;
    readonly EmitterSet _emitters;   // every light, emitting object and the sky, in one index space (Emitters/EmitterSet.cs)
    readonly float[] _background;
    readonly EnvironmentEmitter? _environment;   // the sky's image, when it has one: its radiance is looked up per direction

    public PathIntegrator(Scene scene, SceneGeometry geometry)
    {
        string where = scene.SourcePath;
        if (scene.Radiometry != Radiometry.Physical)
            throw new InputException($"{where}: $.radiometry",
                "the path integrator needs physical radiometry (eq. 2's paper units are not radiance)",
                "add \"radiometry\": \"physical\" to the scene, or render it with the whitted integrator");
        var settings = SettingsOf(scene);
        _geometry = geometry;
        _grid = GridOf(scene, settings.SpectralGrid);
        _padded = _grid.Padded;
        _maxDepth = settings.MaxDepth;
        Sampler = new SamplerSettings(settings.Sampler ?? SamplerKind.Sobol, settings.Seed);
        _rrDepth = settings.RrDepth;
        _materials = new PathMaterial[scene.Materials.Count];
        for (int m = 0; m < _materials.Length; m++) _materials[m] = new PathMaterial(scene, m, _grid);
        TakeTextures(scene);   // PathIntegrator.Textures.cs
        _fluoresces = _materials.Any(x => x.Shift is not null);
        _splitsShifts = _fluoresces && _materials.Any(x => x.Dispersive);
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _emitters = new EmitterSet(scene, _grid, geometry.BoundingRadius, m => _materials[m].EmissionTexture,
            settings.LightTree switch { true => 1, false => int.MaxValue, null => EmitterSet.TreeThreshold });
        _lights = [.. scene.Lights];
        _background = _emitters.Background;
        _environment = _emitters.Environment;
        foreach (var material in _materials) material.Shift?.Prepare(_emitters.All.Select(e => e.Radiance));
        TakeMedia(scene);   // PathIntegrator.Media.cs
        _textureBase = 5 * _padded + Math.Max(_padded, ShiftBase - 5 * _padded + ShiftScratch);
    }

    /// <summary>The scene's emitters, one index space: scene lights, emitting objects, the sky (Emitters/EmitterSet.cs).</summary>
    internal EmitterSet Emitters => _emitters;

    /// <summary>The sampler of its camera samples: Owen-scrambled Sobol unless the scene's "sampler" says otherwise.</summary>
    public SamplerSettings Sampler { get; }

    /// <summary>The internal grid's sub-bands per output band (0: an adaptive grid, its own count per band).</summary>
    public int SubBands => _grid.PerBand;

    /// <summary>
    /// Scratch: L, β, f and the two delta lobes' weights, each a sub-band spectrum; then a band's β after a dispersive split
    /// (<see cref="BandBeta"/>) and a fluorescent scene's shifted paths' (<see cref="ShiftScratch"/>), which share their
    /// place unless the scene has both; then a textured vertex's texels (<see cref="TextureBase"/>).
    /// </summary>
    public int ScratchLength => TextureBase + TextureScratch + (_environment is null ? 0 : _padded);

    /// <summary>Where an environment map's radiance of one direction goes (after the texels), when the sky has a map.</summary>
    Span<float> SkyScratch(Span<float> scratch) => _environment is null ? default : scratch.Slice(TextureBase + TextureScratch, _padded);

    /// <summary>Where a textured vertex's texels start in the scratch: after the dispersive split's and the shifted paths' part.</summary>
    int TextureBase => _textureBase;
    readonly int _textureBase;

    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
    {
        var l = scratch[.._padded];
        l.Clear();
        var sink = new FilmSink(l, firstEmission: true);
        int first = Walk(ref sink, in sample, scratch, ref counters);
        _grid.Reduce(l, result);
        return first;
    }

    /// <summary>The walk of <see cref="Radiance(in CameraSample, Span{float}, Span{float}, ref RayCounters)"/> without the
    /// light of its first vertex's emitter or of the sky it escapes to (<see cref="IGatherIntegrator.Reflected"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Reflected(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
    {
        var l = scratch[.._padded];
        l.Clear();
        var sink = new FilmSink(l, firstEmission: false);
        int first = Walk(ref sink, in sample, scratch, ref counters);
        _grid.Reduce(l, result);
        return first;
    }

    /// <summary>
    /// The centre ray: its radiance as <see cref="Radiance(in CameraSample, Span{float}, Span{float}, ref RayCounters)"/>,
    /// and the lit masks (<see cref="LitMask"/>). The path tracer has no eq. 2 terms, so no highlight.
    /// </summary>
    public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info)
    {
        int first = Radiance(in sample, result, scratch, ref counters);
        info.LitMask = LitMask(in sample);
        return first;
    }
    /// <summary>
    /// The scene lights (bit k = light k, the first 32) that reach the camera ray's first surface point directly, as the
    /// Whitted model's masks say it (mask-lit-K.png, the recovery's lit and shadow regions): the light's centre on the
    /// ray's side of the surface, inside its cone, the shadow ray unblocked. Its rays are not counted (analysis only).
    /// </summary>
    internal uint LitMask(in CameraSample sample)
    {
        var traced = sample.Ray;
        if (_lights.Length == 0 || !_geometry.Intersect(ref traced, out var hit)) return 0;
        var p = hit.Position;
        var ng = hit.GeometricNormal;
        var wo = -sample.Ray.Direction;
        var front = Vector3.Dot(hit.Normal, wo) >= 0 ? hit.Normal : -hit.Normal;
        uint mask = 0;
        for (int k = 0; k < Math.Min(_lights.Length, 32); k++)
        {
            if (!_lights[k].Sample(p, new Vector2(0.5f, 0.5f), out var inc) || !(inc.Factor > 0) || Vector3.Dot(front, inc.Direction) <= 0)
                continue;
            if (!_geometry.Occluded(Visibility.ShadowRay(p, ng, inc.Direction, inc.Distance, _geometry.Epsilon))) mask |= 1u << k;
        }
        return mask;
    }

    /// <summary>Scene lights whose spectra a relight may change (their transfer is kept apart): the scene's lights, in order.</summary>
    public int TransferLights => _lights.Length;

    /// <summary>The sub-band grid's sub-bands (the transfer's spectral resolution).</summary>
    internal SubBandGrid Grid => _grid;

    /// <summary>What a path does with the light it finds: a film sums it; the per-light transfer keeps each scene light's apart.</summary>
    interface IPathSink
    {
        /// <summary>β ⊙ L_e · w: an emitter or the sky reached by the path.</summary>
        void Emitted(Span<float> beta, ReadOnlySpan<float> le, float w);
        /// <summary>β ⊙ f ⊙ E · s: next-event estimation of light <paramref name="light"/> (−1: an emitter or the sky).</summary>
        void NextEvent(int light, Span<float> beta, Span<float> f, ReadOnlySpan<float> radiance, float s);
        /// <summary>β ⊙ (S·E) · s: a fluorescent surface's shifted lobe S excited by next-event light <paramref name="light"/>.</summary>
        void Shifted(int light, FluorescentShift shift, Span<float> beta, ReadOnlySpan<float> radiance, float s);
        /// <summary>Where emitters and the sky go: a path continued through a shifted lobe remaps it
        /// (PathIntegrator.Fluorescence.cs).</summary>
        Span<float> Fixed { get; }
        /// <summary>
        /// A shifted bounce through <paramref name="shift"/> with factor g = β·<paramref name="w"/>: what the path finds from
        /// here on reaches the film through A = diag(g)·f_s more (PathIntegrator.Fluorescence.cs; the fixed slot is carried by
        /// the walk itself).
        /// </summary>
        void Shift(FluorescentShift shift, Span<float> beta, float w);
        /// <summary>The end of a path that took a shifted bounce.</summary>
        void End();
        /// <summary>A dispersive split (PathIntegrator.Dispersion.cs): keep the shifted bounces' state its sub-paths start from.</summary>
        void Branch();
        /// <summary>A sub-path's end after shifted bounces of its own: carry what it found since its last, back to the split's.</summary>
        void Rejoin();
        /// <summary>Whether the light the path's first vertex emits (or the sky its first ray escapes to) counts: false for
        /// a gather's reflected share (<see cref="Reflected"/>).</summary>
        bool FirstEmission { get; }
    }

    ref struct FilmSink(Span<float> l, bool firstEmission) : IPathSink
    {
        readonly Span<float> _l = l;
        public readonly bool FirstEmission => firstEmission;
        public readonly void Emitted(Span<float> beta, ReadOnlySpan<float> le, float w) => AddProduct(_l, beta, le, w);
        public readonly void NextEvent(int light, Span<float> beta, Span<float> f, ReadOnlySpan<float> radiance, float s) =>
            AddProduct3(_l, beta, f, radiance, s);
        public readonly void Shifted(int light, FluorescentShift shift, Span<float> beta, ReadOnlySpan<float> radiance, float s) =>
            shift.AddEmitted(_l, beta, radiance, s);
        public readonly Span<float> Fixed => _l;
        public readonly void Shift(FluorescentShift shift, Span<float> beta, float w) { }   // the walk carries the film
        public readonly void End() { }
        public readonly void Branch() { }
        public readonly void Rejoin() { }   // the walk folds the film (PathIntegrator.Dispersion.cs)
    }

    /// <summary>The path of one camera sample; the light it finds goes to <paramref name="sink"/>. Returns the first object hit.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Walk<TSink>(ref TSink sink, in CameraSample sample, Span<float> scratch, ref RayCounters counters)
        where TSink : IPathSink, allows ref struct
    {
        var beta = scratch.Slice(_padded, _padded);
        beta.Clear();
        beta[.._grid.Count].Fill(1);   // the padding stays 0
        var shifts = new ShiftState(1);
        SurfaceHit none = default;
        int first = Walk(ref sink, sample.Ray, _sceneMedium, 0, in none, -1, beta, sample.Sampler, ref shifts, scratch, ref counters);
        if (shifts.Saved)
        {
            FinishShifted(sink.Fixed, scratch, shifts.Level);
            sink.End();
        }
        return first;
    }

    /// <summary>
    /// The walk, carrying the bands of <paramref name="beta"/>: every band (<paramref name="band"/> −1) from
    /// <paramref name="ray"/> (travelling in <paramref name="medium"/>, −1: vacuum; PathIntegrator.Media.cs) at
    /// <paramref name="depth"/> on; or, as a sub-path of a dispersive split (PathIntegrator.Dispersion.cs), one output band's
    /// sub-bands (<paramref name="band"/> its first) from the split's vertex <paramref name="split"/>, reached along
    /// <paramref name="ray"/>, its emission already counted. Returns the first object hit (−1: none, or a sub-path).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Walk<TSink>(ref TSink sink, Ray ray, int medium, int depth, scoped in SurfaceHit split, int band, Span<float> beta,
        Sampler sampler, ref ShiftState shifts, Span<float> scratch, ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        int n = _padded;
        var f = scratch.Slice(2 * n, n);
        var mirror = scratch.Slice(3 * n, n);
        var transmit = scratch.Slice(4 * n, n);
        bool subPath = band >= 0, resume = subPath;   // a sub-path starts at its split's vertex
        var hit = split;
        bool deltaBounce = true;     // the last bounce was a delta lobe (or the camera): emitters seen count in full
        float bsdfPdf = 0;           // the last bounce's solid-angle density (lobe choice included), for MIS
        Vector3 previous = default, previousFront = default;
        int first = -1;
        for (; ; depth++)
        {
            var wo = -ray.Direction;
            PathMaterial material;
            if (resume)
            {
                material = _materials[_objectMaterial[hit.Object]];
                resume = false;
            }
            else
            {
                var traced = ray;
                bool reached = _geometry.IntersectScattered(ref traced, out hit);
                if (depth == 0 && reached) first = hit.Object;   // (also when the camera ray scatters before it)
                // β ⊙= T of the segment's medium, from the last vertex (the camera) to this one; in a medium that scatters,
                // free-flight sampling along it, which may end the path or scatter it there (PathIntegrator.Media.cs).
                if (medium >= 0)
                {
                    if (_scattering[medium] is { } scattering)
                    {
                        var flight = Track(scattering, medium, ray, reached ? hit.T : float.PositiveInfinity, beta, ref sampler,
                            out var at);
                        if (flight == Flight.Absorbed) break;
                        if (flight == Flight.Scattered)
                        {   // a vertex in the medium: its phase function in place of a BSDF
                            if (_maxDepth >= 0 && depth >= _maxDepth) break;
                            if (counters.BudgetSpent) { counters.OverBudget = true; break; }
                            if (!Scatter(ref sink, scattering.Phase, medium, at, wo, ref ray, beta, f, ref sampler, depth, scratch,
                                ref shifts, ref counters, out bsdfPdf)) break;
                            deltaBounce = false;
                            previous = at;
                            previousFront = Vector3.Zero;   // no surface: the sky is not drawn from here (p_sky = 0)
                            continue;
                        }
                    }
                    else
                        Attenuate(medium, ray.Origin, ray.Direction, !reached ? float.PositiveInfinity
                            : depth == 0 ? hit.T : Vector3.Distance(previous, hit.Position), beta);
                }
                if (!reached)
                {
                    Escaped(ref sink, ray.Direction, depth, deltaBounce, bsdfPdf, previous, previousFront, beta, scratch);
                    break;
                }
                material = _materials[_objectMaterial[hit.Object]];
                if ((depth > 0 || sink.FirstEmission) && _emitters.OfObject(hit.Object) is int e and >= 0)
                    Seen(ref sink, e, in hit, ray.Direction, material, deltaBounce, bsdfPdf, previous, previousFront, beta, scratch);
                if (_maxDepth >= 0 && depth >= _maxDepth) break;
                if (counters.BudgetSpent) { counters.OverBudget = true; break; }
                if (material.Dispersive && band < 0)
                {   // every band at a dispersive vertex: split into the bands' sub-paths (PathIntegrator.Dispersion.cs)
                    if (!subPath)
                    {
                        Disperse(ref sink, in hit, ray, medium, depth, beta, sampler, ref shifts, scratch, ref counters);
                        break;
                    }
                    if ((band = Narrow(beta, sampler.Next1D(), shifts.Level, scratch)) < 0) break;
                }
            }

            var bsdf = material.Bsdf;
            var ns = hit.Normal;
            // The lobes' shares of the continuation, by the channel: smooth (m_diff + m_spec), mirror, transmission.
            float smoothShare = material.Smooth ? material.SmoothChannel : 0;
            var vertex = new PathVertex(in hit, wo, material,
                _textured ? Texels(material, in hit, wo, scratch, ref smoothShare) : default, medium, InteriorOf(hit.Object));
            // (a BSDF without a delta lobe is not asked for one: both answers would be "none")
            float mirrorShare = 0, transmitShare = 0;
            Vector3 wiMirror = default, wiTransmit = default;
            if (material.Delta)
                DeltaLobes(bsdf, wo, ns, band, mirror, transmit, out mirrorShare, out transmitShare, out wiMirror, out wiTransmit);
            // A fluorescent vertex weighs the smooth and the shifted lobe by their albedos under β (PathIntegrator.Fluorescence.cs).
            float shiftShare = material.Shift is not null ? LobeShares(in vertex, beta, ref smoothShare) : 0;
            float total = smoothShare + mirrorShare + transmitShare + shiftShare;
            float smoothProbability = total > 0 ? smoothShare / total : 0;

            // Each vertex takes the same five dimensions (light, point on it, lobe, direction, roulette); a number is drawn
            // only where it is used (Sampler.Reserve1D), so skipping one changes no other.
            int dLight = sampler.Reserve1D(), dPoint = sampler.Reserve2D(), dLobe = sampler.Reserve1D();
            int dDirection = sampler.Reserve2D(), dRoulette = sampler.Reserve1D();

            // Next-event estimation: one light chosen by the set's selection pdf (by power), one point on it.
            if ((material.Smooth || shiftShare > 0) && _emitters.Count > 0)
            {
                float uLight = _emitters.Count > 1 ? sampler.At1D(dLight) : 0;   // one light: no choice
                var uPoint = sampler.At2D(dPoint);
                NextEvent(ref sink, in vertex, uLight, new Vector2(uPoint.U, uPoint.V), smoothProbability, beta, f, SkyScratch(scratch),
                    ref counters);
            }

            // Continue: choose a lobe, then a direction from it; β gains f·|cos θ|/pdf per band.
            if (!(total > 0)) break;
            Vector3 wi;
            float x = smoothShare == total ? 0 : sampler.At1D(dLobe) * total;   // the smooth lobes alone: no choice
            if (x < smoothShare)
            {
                var u = sampler.At2D(dDirection);
                if (!bsdf.Sample(wo, ns, new Vector2(u.U, u.V), f, out var bs)) break;
                if (vertex.Texels.Any) Evaluate(bsdf, in vertex.Texels, wo, bs.Wi, ns, f);
                wi = bs.Wi;
                float cos = MathF.Abs(Vector3.Dot(ns, wi));
                bsdfPdf = bs.Pdf * smoothProbability;
                Multiply(beta, f, cos / bsdfPdf);
                deltaBounce = false;
            }
            else if (x < smoothShare + mirrorShare)
            {
                wi = wiMirror;
                Multiply(beta, mirror, total / mirrorShare);
                deltaBounce = true;
            }
            else if (shiftShare > 0 && x >= smoothShare + mirrorShare + transmitShare)
            {
                var u = sampler.At2D(dDirection);
                if (!ShiftedBounce(ref sink, in vertex, shiftShare / total, new Vector2(u.U, u.V), beta, scratch, ref shifts,
                    out wi, out bsdfPdf)) break;
                deltaBounce = false;
                band = -1;   // β is 1 in every band again: the light beyond is at the shift's excitation wavelengths
            }
            else
            {
                wi = wiTransmit;
                Multiply(beta, transmit, total / transmitShare);
                deltaBounce = true;
            }
            previous = vertex.P;
            previousFront = vertex.Front;
            if (vertex.Interior >= 0) medium = MediumToward(in vertex, wi);   // a medium's boundary (PathIntegrator.Media.cs)

            // Russian roulette on the throughput's channel value.
            if (depth + 1 >= _rrDepth)
            {
                float q = MathF.Min(Survival, Max(beta) * shifts.Gain);
                if (!(q > 0) || sampler.At1D(dRoulette) >= q) break;
                Scale(beta, 1 / q);
            }
            ray = Visibility.Leaving(vertex.P, hit.GeometricNormal, wi, _geometry.Epsilon);
            counters.Secondary++;
        }
        return first;
    }

    // The walk's rarer steps are methods of their own, never inlined into it: the JIT stops inlining into a method once its
    // inlining budget is spent, and the walk's hot loop (the band arithmetic, the vector maths) must keep it
    // (BENCHMARKS.md, "The path walk's inlining").

    /// <summary>
    /// A ray that escapes, leaving along <paramref name="direction"/>: the sky's (background's) radiance, MIS-weighted
    /// against its own sampling from the last vertex (after a delta bounce or from the camera: weight 1);
    /// an environment map's of the direction, a CIE overcast sky's times its gradation there (EmitterSet.SkySeen).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    void Escaped<TSink>(ref TSink sink, Vector3 direction, int depth, bool deltaBounce, float bsdfPdf, Vector3 previous,
        Vector3 previousFront, Span<float> beta, Span<float> scratch) where TSink : IPathSink, allows ref struct
    {
        if (depth == 0)
        {
            if (sink.FirstEmission)
                sink.Emitted(beta, _environment is null ? _background : _environment.Lookup(direction, SkyScratch(scratch)),
                    _emitters.SkySeen(direction));
        }
        else if (_emitters.Sky is int s and >= 0)
        {
            var sky = _emitters[s];
            float w = deltaBounce ? 1 : PowerHeuristic(bsdfPdf,
                _emitters.SelectionPdf(s, previous, previousFront) * sky.Pdf(previous, previousFront, direction, default, default));
            sink.Emitted(beta, _environment is null ? sky.Radiance : _environment.Lookup(direction, SkyScratch(scratch)),
                w * sky.Emitted(default, -direction));
        }
    }

    /// <summary>
    /// Light emitter <paramref name="e"/>'s surface at <paramref name="hit"/> sends back along the ray (L_e), MIS-weighted
    /// against next-event estimation of the same point from the last vertex (after a delta bounce or from the camera: 1).
    /// (An emitting object's calls are made on its own sealed class, which the JIT inlines: an AggressiveOptimization
    /// method gets no profile-guided devirtualisation.)
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    void Seen<TSink>(ref TSink sink, int e, scoped in SurfaceHit hit, Vector3 direction, PathMaterial material, bool deltaBounce,
        float bsdfPdf, Vector3 previous, Vector3 previousFront, Span<float> beta, Span<float> scratch)
        where TSink : IPathSink, allows ref struct
    {
        var emitter = _emitters[e];
        var wo = -direction;
        if (!((emitter is ShapeEmitter shape ? shape.Emitted(hit.GeometricNormal, wo) : emitter.Emitted(hit.GeometricNormal, wo)) > 0))
            return;
        float w = 1;
        if (!deltaBounce)
        {
            float pdf = emitter is ShapeEmitter surface
                ? surface.Pdf(previous, previousFront, direction, hit.Position, hit.GeometricNormal)
                : emitter.Pdf(previous, previousFront, direction, hit.Position, hit.GeometricNormal);
            w = PowerHeuristic(bsdfPdf, _emitters.SelectionPdf(e, previous, previousFront) * pdf);
        }
        var le = emitter.Radiance;
        sink.Emitted(beta, _textured ? EmittedAt(material, le, in hit, wo, scratch) : le, w);
    }

    /// <summary>
    /// The delta lobes of <paramref name="bsdf"/> at a vertex: the mirror's and the transmission's f into
    /// <paramref name="mirror"/> and <paramref name="transmit"/>, their directions, and their shares of the lobe choice (channel
    /// values; 0: none), at the index of <paramref name="band"/>'s output band (−1: every band, band 0's index, a
    /// non-dispersive material's).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    void DeltaLobes(Bsdf bsdf, Vector3 wo, Vector3 ns, int band, Span<float> mirror, Span<float> transmit, out float mirrorShare,
        out float transmitShare, out Vector3 wiMirror, out Vector3 wiTransmit)
    {
        mirrorShare = bsdf.SampleMirror(wo, ns, band, mirror, out wiMirror) ? _grid.Luminance(mirror) : 0;
        transmitShare = bsdf.SampleTransmission(wo, ns, band, transmit, out wiTransmit) ? _grid.Luminance(transmit) : 0;
    }

    /// <summary>
    /// L += β·f·L_e·|cos θ|·w/(P(k)·p) for one sample of emitter k of the set, chosen by <paramref name="uLight"/>, at
    /// <paramref name="vertex"/>: a delta light's (w = 1, p = 1, its d_k·c_spot on I_k), an emitting object's point, or a sky
    /// direction (an environment map's radiance looked up into <paramref name="sky"/>), each unshadowed.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    void NextEvent<TSink>(ref TSink sink, scoped in PathVertex vertex, float uLight, Vector2 u, float smoothProbability,
        Span<float> beta, Span<float> f, Span<float> sky, ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        var p = vertex.P;
        int k = _emitters.Choose(p, vertex.Front, uLight, out float pick);
        if (k < 0) return;
        var emitter = _emitters[k];
        EmitterSample sample;
        // An emitting object, the common emitter of a path scene, by its sealed class's call (inlined; see Walk).
        if (!(emitter is ShapeEmitter shape ? shape.Sample(p, vertex.Front, u, out sample)
            : emitter.Sample(p, vertex.Front, u, out sample))) return;
        var wi = sample.Direction;
        float distance = sample.Distance, factor = sample.Factor, pdf = sample.Pdf;
        if (!(pdf > 0) || !(factor > 0)) return;
        ReadOnlySpan<float> radiance = emitter.Texture is not null
            ? EmittedAt(emitter, sample.Face, sample.Point, sample.Normal, wi, distance, vertex.Texels.Emission)
            : _environment is not null && k == _emitters.Sky ? _environment.Lookup(wi, sky) : emitter.Radiance;
        var ns = vertex.Ns;
        var ng = vertex.Ng;
        var bsdf = vertex.Material.Bsdf;
        float cos = MathF.Abs(Vector3.Dot(ns, wi));
        Evaluate(bsdf, in vertex.Texels, vertex.Wo, wi, ns, f);
        counters.Shadow++;
        if (_media.Length == 0 ? _geometry.OccludedScattered(Visibility.ShadowRay(p, ng, wi, distance, _geometry.Epsilon))
            : !ShadowThrough(p, ng, wi, distance, MediumToward(in vertex, wi), f)) return;   // f ⊙= T along it (Media.cs)
        float w = sample.IsDelta ? 1 : PowerHeuristic(pick * pdf, smoothProbability * bsdf.Pdf(vertex.Wo, wi, ns));
        sink.NextEvent(emitter.SceneLight, beta, f, radiance, factor * cos * w / (pick * pdf));
        // A fluorescent surface's shifted lobe: light sources excite it through this sample alone, weight 1 (a shifted bounce
        // of the continuation gives the sources it reaches weight 0 and carries only light from further bounces:
        // PathIntegrator.Fluorescence.cs).
        if (vertex.Material.Shift is { } shift && FluorescentShift.Reflects(vertex.Wo, wi, ns))
            sink.Shifted(emitter.SceneLight, shift, beta, radiance, factor * cos / (pick * pdf));
    }

    /// <summary>Veach's power heuristic (β = 2) for the strategy of density a against one of density b.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float PowerHeuristic(float a, float b)
    {
        float a2 = a * a, b2 = b * b;
        return a2 + b2 > 0 && float.IsFinite(a2 + b2) ? a2 / (a2 + b2) : float.IsInfinity(a2) ? 1 : 0;
    }

    static Span<Vector<float>> V(Span<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);
    static ReadOnlySpan<Vector<float>> RV(ReadOnlySpan<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);

    /// <summary>The largest value of a sub-band spectrum (its padding is 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    float Max(Span<float> a)
    {
        var v = V(a);
        var m = Vector<float>.Zero;
        for (int i = 0; i < v.Length; i++) m = Vector.Max(m, v[i]);
        float r = 0;
        for (int i = 0; i < Vector<float>.Count; i++) r = MathF.Max(r, m[i]);
        return r;
    }

    /// <summary>dst += a ⊙ b · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void AddProduct(Span<float> dst, Span<float> a, ReadOnlySpan<float> b, float s)
    {
        var d = V(dst); var va = V(a); var vb = RV(b[..dst.Length]); var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vb[i] * vs;
    }

    /// <summary>dst += a ⊙ b ⊙ c · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void AddProduct3(Span<float> dst, Span<float> a, Span<float> b, ReadOnlySpan<float> c, float s)
    {
        var d = V(dst); var va = V(a); var vb = V(b); var vc = RV(c[..dst.Length]); var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vb[i] * vc[i] * vs;
    }

    /// <summary>dst += a ⊙ b · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void AddProduct2(Span<float> dst, Span<float> a, Span<float> b, float s)
    {
        var d = V(dst); var va = V(a); var vb = V(b); var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vb[i] * vs;
    }

    /// <summary>dst ⊙= a · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void Multiply(Span<float> dst, Span<float> a, float s)
    {
        var d = V(dst); var va = V(a); var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] *= va[i] * vs;
    }

    /// <summary>dst ·= s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void Scale(Span<float> dst, float s)
    {
        var d = V(dst); var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] *= vs;
    }
}
