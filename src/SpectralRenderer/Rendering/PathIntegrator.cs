using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Unidirectional path tracing of the rendering equation (Kajiya 1986) in physical radiometry, every band on every path:
/// the throughput β and the radiance L are spectra on a fine internal grid (<see cref="FineGrid"/>, 5 nm by default),
/// multiplied band by band in SIMD lanes and reduced to the output bands (exact band means) and to XYZ only at the film.
/// At each vertex one light, chosen uniformly, is sampled (next-event estimation) and the BSDF is sampled to continue; both
/// estimates of light that arrives from surfaces that emit, and from the sky, are combined by multiple importance
/// sampling with the power heuristic w_a = p_a²/(p_a² + p_b²) (Veach &amp; Guibas 1995). Delta lights (point, spot,
/// directional) are reached by next-event estimation only, delta lobes (mirror, Fresnel dielectric) by the BSDF only; at
/// its first dispersive glass a path splits into one sub-path per output band (PathIntegrator.Dispersion.cs).
/// A lobe is chosen by a luminance-like channel (<see cref="FineGrid.Luminance"/>), and Russian roulette ends a path from
/// depth <see cref="IntegratorSettings.RrDepth"/> on with survival probability min(0.95, max_λ β) (the largest band, so
/// no band's light is starved); each band keeps its own f·cos/pdf, so no wavelength is ever sampled. The sky is the scene's <c>background</c>: the radiance of every escaping
/// ray, sampled cosine-weighted about the shading normal. Depth is unbounded unless <c>max_depth</c> is given (1: direct
/// light only). Every random number comes from the camera sample's <see cref="Sampler"/>, so the picture is the same on
/// any thread count, tile order or shard; nothing is allocated per path.
/// </summary>
[CompiledAtFirstCall]
[SkipLocalsInit]   // the walk's locals are all written before read: no 0.7 KB of stack cleared per camera sample
internal sealed partial class PathIntegrator : IAnalysisIntegrator
{
    readonly SceneGeometry _geometry;
    readonly FineGrid _grid;
    readonly int _maxDepth, _rrDepth, _padded;
    readonly int[] _objectMaterial, _emitterOf;
    readonly Bsdf[] _bsdf;
    readonly float[]?[] _emission;
    readonly FluorescentShift?[] _shift;   // a fluorescent material's shifted diffuse lobe (FluorescentShift.cs)
    readonly float[]?[] _albedoDiffuse, _albedoSpecular;   // a fluorescent material's m_diff and m_spec (its lobe choice)
    readonly bool[] _twoSided, _smooth, _delta;
    readonly float[] _smoothChannel;
    readonly Light[] _lights;
    readonly float[][] _lightRadiance;
    readonly AreaEmitter[] _emitters;
    readonly float[]? _sky;
    readonly float[] _background;
    readonly int _lightCount;

    public PathIntegrator(Scene scene, SceneGeometry geometry)
    {
        string where = scene.SourcePath;
        if (scene.Radiometry != Radiometry.Physical)
            throw new InputException($"{where}: $.radiometry", "the path integrator needs physical radiometry (eq. 2's paper units are not radiance)",
                "add \"radiometry\": \"physical\" to the scene, or render it with the whitted integrator");
        var settings = scene.Integrator is { Name: "path" } s ? s : new IntegratorSettings("path");
        _geometry = geometry;
        _grid = new FineGrid(scene, settings.SpectralGrid);
        _padded = _grid.Padded;
        _maxDepth = settings.MaxDepth;
        Sampler = new SamplerSettings(settings.Sampler ?? SamplerKind.Sobol, settings.Seed);
        _rrDepth = settings.RrDepth;
        int materials = scene.Materials.Count;
        _bsdf = new Bsdf[materials];
        _emission = new float[]?[materials];
        _shift = new FluorescentShift?[materials];
        _albedoDiffuse = new float[]?[materials];
        _albedoSpecular = new float[]?[materials];
        _twoSided = new bool[materials];
        _smooth = new bool[materials];
        _delta = new bool[materials];
        _smoothChannel = new float[materials];
        _dispersive = new bool[materials];
        for (int m = 0; m < materials; m++)
        {
            var material = scene.Materials[m];
            _dispersive[m] = material.Dispersive && material.HasTransmission;   // its paths split per band (PathIntegrator.Dispersion.cs)
            _bsdf[m] = material.Bsdf.Resampled(_grid.Resample)
                ?? throw new InputException($"{where}: $.materials.{material.Name}",
                    $"material '{material.Name}' ({material.Bsdf.GetType().Name}) cannot be carried to the path integrator's spectral grid",
                    "use a material type the path integrator knows (eq2, lambertian), or the whitted integrator");
            _smooth[m] = (_bsdf[m].Lobes & (BsdfFlags.Diffuse | BsdfFlags.Glossy)) != 0;
            _delta[m] = (_bsdf[m].Lobes & BsdfFlags.Delta) != 0;
            if (_smooth[m])
            {   // the smooth lobes' share in the lobe choice: the channel value of m_diff + m_spec (their albedo at most)
                var albedo = _grid.Resample(material.Diffuse);
                var spec = _grid.Resample(material.Specular);
                for (int i = 0; i < albedo.Length; i++) albedo[i] += spec[i];
                _smoothChannel[m] = Math.Max(_grid.Luminance(albedo), 1e-6f);
            }
            if (material.Fluorescence is { HasShift: true } fl)
            {
                _shift[m] = new FluorescentShift(fl, _grid);
                _albedoDiffuse[m] = _grid.Resample(material.Diffuse);
                _albedoSpecular[m] = _grid.Resample(material.Specular);
            }
            if (material.Emission is { } e) { _emission[m] = _grid.Resample(e.Radiance); _twoSided[m] = e.TwoSided; }
            TakeTextures(scene, m);   // PathIntegrator.Textures.cs
        }
        // A band's sub-path after a dispersive split (PathIntegrator.Dispersion.cs) walks the plain lobes only.
        if (Array.IndexOf(_dispersive, true) is int glass and >= 0 && Array.FindIndex(_shift, x => x is not null) is int paper and >= 0)
            throw new InputException($"{where}: $.materials.{scene.Materials[paper].Name}.fluorescence",
                $"material '{scene.Materials[paper].Name}' fluoresces and material '{scene.Materials[glass].Name}' is dispersive: the path integrator does not follow a shifted bounce after a dispersive split yet",
                "give the glass a constant \"ior\", or render the scene with the whitted integrator");
        if (Array.IndexOf(_dispersive, true) is int prism and >= 0 && _textured)
            throw new InputException($"{where}: $.materials.{scene.Materials[prism].Name}.ior",
                $"material '{scene.Materials[prism].Name}' is dispersive and the scene has textures: the path integrator does not look textures up after a dispersive split yet",
                "give the glass a constant \"ior\", or the textured materials spectra");
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _emitterOf = new int[scene.Objects.Count];
        var emitters = new List<AreaEmitter>();
        for (int i = 0; i < scene.Objects.Count; i++)
        {
            _emitterOf[i] = -1;
            var o = scene.Objects[i];
            if (_emission[o.Material] is { } radiance)
            {
                _emitterOf[i] = emitters.Count;
                emitters.Add(new AreaEmitter(o, radiance, _twoSided[o.Material], $"{where}: $.objects", EmissionTexture(o.Material)));
            }
        }
        _emitters = [.. emitters];
        _lights = [.. scene.Lights];
        _lightRadiance = _lights.Select(l => _grid.Resample(l.Intensity)).ToArray();
        _background = _grid.Resample(scene.Background);
        _sky = Spectra.SpectralMath.Any(scene.Background) ? _background : null;
        _lightCount = _lights.Length + _emitters.Length + (_sky is null ? 0 : 1);
        foreach (var shift in _shift) shift?.Prepare([.. _lightRadiance, .. _emitters.Select(e => e.Radiance), .. _sky is null ? [] : new[] { _sky }]);
    }

    /// <summary>The sampler of its camera samples: Owen-scrambled Sobol unless the scene's "sampler" says otherwise.</summary>
    public SamplerSettings Sampler { get; }

    /// <summary>The internal grid's sub-bands per output band.</summary>
    public int SubBands => _grid.PerBand;

    /// <summary>
    /// Scratch: L, β, f and the two delta lobes' weights, each a fine spectrum; then either a band's β after a dispersive
    /// split or a fluorescent scene's shifted paths' (<see cref="ShiftScratch"/>): a scene has not both (the constructor);
    /// then a textured vertex's texels (<see cref="TextureBase"/>).
    /// </summary>
    public int ScratchLength => TextureBase + TextureScratch;

    /// <summary>Where a textured vertex's texels start in the scratch: after the dispersive split's or the shifted paths' part.</summary>
    int TextureBase => 5 * _padded + Math.Max(_padded, ShiftScratch);

    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters)
    {
        var l = scratch[.._padded];
        l.Clear();
        var sink = new FilmSink(l);
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
            if (!_lights[k].Sample(p, new Vector2(0.5f, 0.5f), out var inc) || !(inc.Factor > 0) || Vector3.Dot(front, inc.Direction) <= 0) continue;
            var origin = p + (Vector3.Dot(ng, inc.Direction) >= 0 ? 1 : -1) * _geometry.Epsilon * ng;
            var shadow = new Ray(origin, inc.Direction);
            if (!float.IsInfinity(inc.Distance))
            {
                var towards = p + inc.Distance * inc.Direction - origin;
                float length = towards.Length();
                shadow = new Ray(origin, towards / length, length - 2 * _geometry.Epsilon);
            }
            if (!_geometry.Occluded(shadow)) mask |= 1u << k;
        }
        return mask;
    }

    /// <summary>Scene lights whose spectra a relight may change (their transfer is kept apart): the scene's lights, in order.</summary>
    public int TransferLights => _lights.Length;

    /// <summary>The fine grid's sub-bands (the transfer's spectral resolution).</summary>
    internal FineGrid Grid => _grid;

    /// <summary>What a path does with the light it finds: a film sums it; the per-light transfer keeps each scene light's apart.</summary>
    interface IPathSink
    {
        /// <summary>β ⊙ L_e · w: an emitter or the sky reached by the path.</summary>
        void Emitted(Span<float> beta, ReadOnlySpan<float> le, float w);
        /// <summary>β ⊙ f ⊙ E · s: next-event estimation of light <paramref name="light"/> (−1: an emitter or the sky).</summary>
        void NextEvent(int light, Span<float> beta, Span<float> f, ReadOnlySpan<float> radiance, float s);
        /// <summary>β ⊙ (S·E) · s: a fluorescent surface's shifted lobe S excited by next-event light <paramref name="light"/>.</summary>
        void Shifted(int light, FluorescentShift shift, Span<float> beta, ReadOnlySpan<float> radiance, float s);
        /// <summary>Where emitters and the sky go: a path continued through a shifted lobe remaps it (PathIntegrator.Fluorescence.cs).</summary>
        Span<float> Fixed { get; }
        /// <summary>
        /// A shifted bounce through <paramref name="shift"/> with factor g = β·<paramref name="w"/>: what the path finds from
        /// here on reaches the film through A = diag(g)·f_s more (PathIntegrator.Fluorescence.cs; the fixed slot is carried by
        /// the walk itself).
        /// </summary>
        void Shift(FluorescentShift shift, Span<float> beta, float w);
        /// <summary>The end of a path that took a shifted bounce.</summary>
        void End();
    }

    ref struct FilmSink(Span<float> l) : IPathSink
    {
        readonly Span<float> _l = l;
        public readonly void Emitted(Span<float> beta, ReadOnlySpan<float> le, float w) => AddProduct(_l, beta, le, w);
        public readonly void NextEvent(int light, Span<float> beta, Span<float> f, ReadOnlySpan<float> radiance, float s) =>
            AddProduct3(_l, beta, f, radiance, s);
        public readonly void Shifted(int light, FluorescentShift shift, Span<float> beta, ReadOnlySpan<float> radiance, float s) =>
            shift.AddEmitted(_l, beta, radiance, s);
        public readonly Span<float> Fixed => _l;
        public readonly void Shift(FluorescentShift shift, Span<float> beta, float w) { }   // the walk carries the film
        public readonly void End() { }
    }

    /// <summary>The path of one camera sample; the light it finds goes to <paramref name="sink"/>. Returns the first object hit.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int Walk<TSink>(ref TSink sink, in CameraSample sample, Span<float> scratch, ref RayCounters counters)
        where TSink : IPathSink, allows ref struct
    {
        int n = _padded;
        var beta = scratch.Slice(n, n);
        var f = scratch.Slice(2 * n, n);
        var mirror = scratch.Slice(3 * n, n);
        var transmit = scratch.Slice(4 * n, n);
        beta.Clear();
        beta[.._grid.Count].Fill(1);   // the padding stays 0
        var sampler = sample.Sampler;
        var ray = sample.Ray;
        float pick = _lightCount > 0 ? 1f / _lightCount : 0;
        bool deltaBounce = true;     // the last bounce was a delta lobe (or the camera): emitters seen count in full
        float bsdfPdf = 0;           // the last bounce's solid-angle density (lobe choice included), for MIS
        Vector3 previous = default, previousFront = default;
        int first = -1, shifted = 0;   // shifted: the path's shifted bounces so far (PathIntegrator.Fluorescence.cs)
        float gain = 1;   // a bound of the shifted bounces' amplification towards the film (1 without them)
        for (int depth = 0; ; depth++)
        {
            var traced = ray;
            if (!_geometry.IntersectScattered(ref traced, out var hit))
            {
                // The ray escapes: the sky (background) radiance, MIS-weighted against its own sampling.
                if (depth == 0) sink.Emitted(beta, _background, 1);
                else if (_sky is not null)
                {
                    float w = deltaBounce ? 1 : PowerHeuristic(bsdfPdf, pick * SkyPdf(previousFront, ray.Direction));
                    sink.Emitted(beta, _sky, w);
                }
                break;
            }
            if (depth == 0) first = hit.Object;
            var wo = -ray.Direction;
            var p = hit.Position;
            var ng = hit.GeometricNormal;
            int m = _objectMaterial[hit.Object];

            // Light the surface emits towards the ray (Le), MIS-weighted against next-event estimation of the same point.
            if (_emission[m] is { } le && (_twoSided[m] || Vector3.Dot(ng, wo) > 0))
            {
                float w = 1;
                if (!deltaBounce)
                {
                    int e = _emitterOf[hit.Object];
                    w = PowerHeuristic(bsdfPdf, e >= 0 ? pick * _emitters[e].Pdf(previous, p, ng) : 0);
                }
                sink.Emitted(beta, _textured ? EmittedAt(m, le, in hit, wo, scratch) : le, w);
            }
            if (_maxDepth >= 0 && depth >= _maxDepth) break;
            if (counters.BudgetSpent) { counters.OverBudget = true; break; }
            if (_dispersive[m]) { Disperse(ref sink, in hit, ray, depth, beta, sampler, scratch, ref counters); break; }

            var bsdf = _bsdf[m];
            var ns = hit.Normal;
            var front = Vector3.Dot(ns, wo) >= 0 ? ns : -ns;
            // The lobes' shares of the continuation, by the channel: smooth (m_diff + m_spec), mirror, transmission.
            float smoothShare = _smooth[m] ? _smoothChannel[m] : 0;
            var texels = _textured ? Texels(m, in hit, wo, scratch, ref smoothShare) : default;
            // (a BSDF without a delta lobe is not asked for one: both answers would be "none")
            float mirrorShare = 0, transmitShare = 0;
            Vector3 wiMirror = default, wiTransmit = default;
            if (_delta[m])
            {
                mirrorShare = bsdf.SampleMirror(wo, ns, -1, mirror, out wiMirror) ? _grid.Luminance(mirror) : 0;
                transmitShare = bsdf.SampleTransmission(wo, ns, -1, transmit, out wiTransmit) ? _grid.Luminance(transmit) : 0;
            }
            // A fluorescent vertex weighs the smooth and the shifted lobe by their albedos under β (PathIntegrator.Fluorescence.cs).
            float shiftShare = _shift[m] is not null ? LobeShares(m, in texels, beta, ref smoothShare) : 0;
            float total = smoothShare + mirrorShare + transmitShare + shiftShare;
            float smoothProbability = total > 0 ? smoothShare / total : 0;

            // Each vertex takes the same five dimensions (light, point on it, lobe, direction, roulette); a number is drawn
            // only where it is used (Sampler.Reserve1D), so skipping one changes no other.
            int dLight = sampler.Reserve1D(), dPoint = sampler.Reserve2D(), dLobe = sampler.Reserve1D(), dDirection = sampler.Reserve2D();
            int dRoulette = sampler.Reserve1D();

            // Next-event estimation: one light chosen uniformly, one point on it.
            if ((_smooth[m] || shiftShare > 0) && _lightCount > 0)
            {
                float uLight = _lightCount > 1 ? sampler.At1D(dLight) : 0;   // one light: no choice
                var uPoint = sampler.At2D(dPoint);
                NextEvent(ref sink, bsdf, in texels, _shift[m], p, ng, ns, front, wo, uLight, new Vector2(uPoint.U, uPoint.V), pick, smoothProbability, beta, f, ref counters);
            }

            // Continue: choose a lobe, then a direction from it; β gains f·|cos θ|/pdf per band.
            if (!(total > 0)) break;
            Vector3 wi;
            float x = smoothShare == total ? 0 : sampler.At1D(dLobe) * total;   // the smooth lobes alone: no choice
            if (x < smoothShare)
            {
                var u = sampler.At2D(dDirection);
                if (!bsdf.Sample(wo, ns, new Vector2(u.U, u.V), f, out var bs)) break;
                if (texels.Any) Evaluate(bsdf, in texels, wo, bs.Wi, ns, f);
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
                if (!ShiftedBounce(ref sink, m, shiftShare / total, wo, ns, front, new Vector2(u.U, u.V), beta, scratch, ref shifted,
                    ref gain, out wi, out bsdfPdf)) break;
                deltaBounce = false;
            }
            else
            {
                wi = wiTransmit;
                Multiply(beta, transmit, total / transmitShare);
                deltaBounce = true;
            }
            previous = p;
            previousFront = front;

            // Russian roulette on the throughput's channel value.
            if (depth + 1 >= _rrDepth)
            {
                float q = MathF.Min(Survival, Max(beta) * gain);
                if (!(q > 0) || sampler.At1D(dRoulette) >= q) break;
                Scale(beta, 1 / q);
            }
            float side = Vector3.Dot(ng, wi) >= 0 ? 1 : -1;
            ray = new Ray(p + side * _geometry.Epsilon * ng, wi);
            counters.Secondary++;
        }
        if (shifted > 0)
        {
            FinishShifted(sink.Fixed, scratch, shifted);
            sink.End();
        }
        return first;
    }

    /// <summary>
    /// L += β·f·L_e·|cos θ|·w/(P(light)·p) for one light sample: a delta light's (w = 1, p = 1, its d_k·c_spot on I_k), an
    /// emitter's point, or a sky direction, each unshadowed.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void NextEvent<TSink>(ref TSink sink, Bsdf bsdf, in SurfaceTexels texels, FluorescentShift? shift, Vector3 p, Vector3 ng, Vector3 ns, Vector3 front, Vector3 wo, float uLight, Vector2 u,
        float pick, float smoothProbability, Span<float> beta, Span<float> f, ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        int k = Math.Min((int)(uLight * _lightCount), _lightCount - 1);
        Vector3 wi;
        float distance, factor, pdf;
        bool delta;
        ReadOnlySpan<float> radiance;
        if (k < _lights.Length)
        {
            if (!_lights[k].Sample(p, u, out var inc)) return;
            wi = inc.Direction; distance = inc.Distance; factor = inc.Factor; pdf = inc.Pdf; delta = inc.IsDelta;
            radiance = _lightRadiance[k];
        }
        else if (k < _lights.Length + _emitters.Length)
        {
            var emitter = _emitters[k - _lights.Length];
            if (!emitter.Sample(p, u, out var x, out var nx, out pdf, out int face)) return;
            var d = x - p;
            distance = d.Length();
            if (!(distance > 0)) return;
            wi = d / distance;
            if (!emitter.Emits(nx, -wi)) return;
            factor = 1; delta = false;
            radiance = emitter.Texture is null ? emitter.Radiance : EmittedAt(emitter, face, x, nx, wi, distance, texels.Emission);
        }
        else
        {
            wi = Bsdf.CosineHemisphere(front, u);
            pdf = SkyPdf(front, wi);
            distance = float.PositiveInfinity; factor = 1; delta = false;
            radiance = _sky!;
        }
        if (!(pdf > 0) || !(factor > 0)) return;
        float cos = MathF.Abs(Vector3.Dot(ns, wi));
        Evaluate(bsdf, in texels, wo, wi, ns, f);
        float side = Vector3.Dot(ng, wi) >= 0 ? 1 : -1;
        var origin = p + side * _geometry.Epsilon * ng;
        var shadow = new Ray(origin, wi);
        if (!float.IsInfinity(distance))
        {   // aimed from the offset origin at the light's point itself: a ray grazing a sphere light would otherwise meet it early
            var towards = p + distance * wi - origin;
            float length = towards.Length();
            shadow = new Ray(origin, towards / length, length - 2 * _geometry.Epsilon);
        }
        counters.Shadow++;
        if (_geometry.OccludedScattered(shadow)) return;
        float w = delta ? 1 : PowerHeuristic(pick * pdf, smoothProbability * bsdf.Pdf(wo, wi, ns));
        sink.NextEvent(k < _lights.Length ? k : -1, beta, f, radiance, factor * cos * w / (pick * pdf));
        // A fluorescent surface's shifted lobe: light sources excite it through this sample alone, weight 1 (a shifted bounce
        // of the continuation gives the sources it reaches weight 0 and carries only light from further bounces:
        // PathIntegrator.Fluorescence.cs).
        if (shift is not null && FluorescentShift.Reflects(wo, wi, ns)) sink.Shifted(k < _lights.Length ? k : -1, shift, beta, radiance, factor * cos / (pick * pdf));
    }

    /// <summary>The sky's sampling density: cosine-weighted about the front shading normal.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float SkyPdf(Vector3 front, Vector3 wi) => MathF.Max(0, Vector3.Dot(front, wi)) / MathF.PI;

    /// <summary>Veach's power heuristic (β = 2) for the strategy of density a against one of density b.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float PowerHeuristic(float a, float b)
    {
        float a2 = a * a, b2 = b * b;
        return a2 + b2 > 0 && float.IsFinite(a2 + b2) ? a2 / (a2 + b2) : float.IsInfinity(a2) ? 1 : 0;
    }

    static Span<Vector<float>> V(Span<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);
    static ReadOnlySpan<Vector<float>> RV(ReadOnlySpan<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);

    /// <summary>The largest value of a fine spectrum (its padding is 0).</summary>
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
