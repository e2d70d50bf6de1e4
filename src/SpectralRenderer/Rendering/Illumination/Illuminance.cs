using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Illumination;

/// <summary>
/// Photometric quantities at surface points (physical radiometry, CIE 015:2018 §4): the illuminance E_v (lx) arriving at
/// a point directly from the scene's emitters (the emitter set, <see cref="EmitterSet"/>, on the output bands): from each
/// scene light E_v = K_m ∫V·I_k dλ · c_spot,k · d_k · max(0, n·l_k) with the shadow ray to light k unblocked (I/r²·cos θ for
/// a point light, E⊥·cos θ for a directional one), from each emitting object and the sky E_v = ∫ L_v cos θ dω ≈
/// 1/N Σ L_v·cos θ_i/p_ω(ω_i) over N of the emitter's own samples, each shadow ray honoured (<see cref="Visibility"/>); and,
/// for a path-traced scene, what arrives from every direction but the scene lights' (area lights, the sky, interreflection)
/// by a gather E = ∫ L_v cos θ dω: next-event estimation of the emitting objects and the sky and cosine-weighted rays
/// combined by multiple importance sampling, each ray's reflected light the integrator's own (<see cref="Gather"/>), with
/// its standard error, in place of the emitting objects' and the sky's direct share (which it counts). Luminance of a radiance
/// spectrum: L_v = K_m ∫V·L dλ, from the exact colour's Y (κ folded out) when the observer's ȳ is V (CIE 1931),
/// else from the bands with V's band integrals.
/// </summary>
public sealed class Illuminance
{
    readonly Scene _scene;
    readonly SceneGeometry? _geometry;
    readonly double[] _luminous;
    readonly double[] _bandV;
    readonly bool _yIsV;
    readonly double _yToLuminance;
    readonly EmitterSet? _emitters;           // the scene's emitters on the output bands (with the geometry)
    readonly double[] _emitterLuminance = [];   // L_v = K_m ∫V·L dλ of each emitting object and the sky (0: a scene light)

    /// <param name="geometry">The scene's ray queries; null: luminance only (<see cref="Maps"/> gives illuminance 0).</param>
    public Illuminance(Scene scene, SceneGeometry? geometry)
    {
        if (scene.Radiometry != Radiometry.Physical)
            throw new Diagnostics.InputException($"{scene.SourcePath}: $.radiometry",
                "illuminance and luminance need physical radiometry (eq. 2's paper units are relative)",
                "add \"radiometry\": \"physical\" to the scene");
        _scene = scene;
        _geometry = geometry;
        var grid = scene.Grid;
        _bandV = new double[grid.Count];
        for (int b = 0; b < grid.Count; b++) _bandV[b] = Colorimeter.Km * Photometry.V.Integrate(grid.Lower(b), grid.Upper(b));
        // K_m ∫V·I_k dλ: lumens per steradian (point, spot, goniometric per its c_spot) or lux facing it (directional).
        _luminous = scene.Lights.Select(l => l.Spectrum is { } s ? Photometry.Luminous(s) * l.Scale : BandLuminance(l.Intensity)).ToArray();
        _yIsV = ReferenceEquals(scene.Observer, Observer.Cie1931);
        _yToLuminance = Colorimeter.Km / scene.Colorimeter.Kappa;
        if (geometry is null) return;
        // A sub-band grid of one sub-band per band is the output bands (exact band means of each spectrum).
        _emitters = new EmitterSet(scene, new SubBandGrid(scene, grid.Width), geometry.BoundingRadius);
        _emitterLuminance = _emitters.All.Select(e => e.SceneLight >= 0 ? 0 : BandLuminance(e.Radiance)).ToArray();
        // The gather's: each emitter's luminance on a 1-nm sub-band grid reduced as a path film is (K_m ∫V·L dλ to the grid's
        // precision, as the integrator's own radiance it adds to), not from band means (off by 1e-3 or more under a
        // narrow-band spectrum at 40-nm bands). The same emitters in the same order.
        var fine = new SubBandGrid(scene, 1);
        var reduced = new float[scene.PaddedBands + 64];
        _gatherLuminance = new EmitterSet(scene, fine, geometry.BoundingRadius).All.Select(e =>
        {
            if (e.SceneLight >= 0) return 0;
            fine.Reduce(e.Radiance, reduced);
            return Luminance(reduced.AsSpan(0, grid.Count), reduced[grid.Count + 1]);
        }).ToArray();
    }

    readonly double[] _gatherLuminance = [];

    /// <summary>K_m/κ when luminance is the exact colour's Y times it (the observer's ȳ is V), else null (bands:
    /// <see cref="BandV"/>).</summary>
    public double? YToLuminance => _yIsV ? _yToLuminance : null;

    /// <summary>K_m ∫_b V dλ per band: a band mean's luminance weight (cd/m² per W·m⁻²·sr⁻¹·nm⁻¹).</summary>
    public IReadOnlyList<double> BandV => _bandV;

    /// <summary>K_m ∫V·L dλ of light k's spectral intensity: what its c_spot·d_k·cos θ multiply into lux.</summary>
    public double LuminousOf(int light) => _luminous[light];

    /// <summary>Σ_b L_b · K_m ∫_b V dλ: the luminance of band values (band means of a radiance).</summary>
    public double BandLuminance(ReadOnlySpan<float> bands)
    {
        double sum = 0;
        for (int b = 0; b < _bandV.Length; b++) sum += bands[b] * _bandV[b];
        return sum;
    }

    /// <summary>
    /// Luminance (cd/m²) of a pixel or a radiance buffer: bands, then X, Y, Z in the colour lanes (κ included).
    /// </summary>
    public double Luminance(ReadOnlySpan<float> bands, float y) => _yIsV ? y * _yToLuminance : BandLuminance(bands);

    /// <summary>
    /// Direct illuminance (lx) at point <paramref name="p"/> on the side of normal <paramref name="n"/> (unit) from the
    /// emitter set: every scene light (point, spot, directional, goniometric: their own falloff and spot factor) and, unless
    /// <paramref name="gathered"/> (an integrator's gather counts them), every emitting object and the sky by
    /// <see cref="GatherRays"/> samples each, drawn from (<paramref name="x"/>, <paramref name="y"/>) and the sample index;
    /// each shadow ray honoured. <paramref name="ng"/> is the geometric normal the shadow rays leave from (the surface's, or n
    /// for a free point).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public double Direct(int x, int y, Vector3 p, Vector3 n, Vector3 ng, bool gathered, ref RayCounters counters)
    {
        var set = _emitters ?? throw new InvalidOperationException("illuminance needs the scene's geometry");
        double e = 0;
        bool sampled = false;
        for (int k = 0; k < set.Count; k++)
        {
            if (set[k].SceneLight is int light and >= 0)
            {
                if (Lit(light, p, n, ng, ref counters, out var s, out float cos)) e += _luminous[light] * s.Spot * s.Attenuation * cos;
            }
            else sampled |= !gathered && _emitterLuminance[k] > 0;
        }
        return sampled ? e + FromEmitters(set, x, y, p, n, ng, ref counters) : e;
    }

    /// <summary>Σ over the emitting objects and the sky of 1/N Σ_i L_v·cos θ_i/p_ω(ω_i), ω_i the emitter's own draw.</summary>
    double FromEmitters(EmitterSet set, int x, int y, Vector3 p, Vector3 n, Vector3 ng, ref RayCounters counters)
    {
        var geometry = _geometry!;
        int rays = GatherRays(_scene);
        Span<float> sky = set.Environment is null ? default : stackalloc float[_scene.PaddedBands];
        double sum = 0;
        for (int i = 0; i < rays; i++)
        {
            // The gather's sample indices (beyond any camera sample's); each emitter takes the next 2D draw.
            var sampler = new Sampler(x, y, int.MaxValue - rays + i);
            for (int k = 0; k < set.Count; k++)
            {
                if (set[k].SceneLight >= 0 || !(_emitterLuminance[k] > 0)) continue;
                var (u, v) = sampler.Next2D();
                if (!set[k].Sample(p, n, new Vector2(u, v), out var s) || !(s.Pdf > 0)) continue;
                float cos = Vector3.Dot(n, s.Direction);
                if (!(cos > 0)) continue;
                counters.Shadow++;
                if (geometry.Occluded(Visibility.ShadowRay(p, ng, s.Direction, s.Distance, geometry.Epsilon))) continue;
                // an environment map's luminance is its direction's (EnvironmentEmitter.Lookup), else the emitter's own
                double lv = set.Environment is { } map && k == set.Sky ? BandLuminance(map.Lookup(s.Direction, sky))
                    : _emitterLuminance[k];
                sum += lv * s.Factor * cos / s.Pdf;
            }
        }
        return sum / rays;
    }

    /// <summary>Scene light <paramref name="k"/> at p: its sample, n·l > 0, c_spot > 0 and the shadow ray unblocked.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    bool Lit(int k, Vector3 p, Vector3 n, Vector3 ng, ref RayCounters counters, out LightSample s, out float cos)
    {
        var geometry = _geometry ?? throw new InvalidOperationException("illuminance needs the scene's geometry");
        cos = 0;
        if (!_scene.Lights[k].Illuminate(p, out s)) return false;
        cos = Vector3.Dot(n, s.Direction);
        if (!(cos > 0) || !(s.Spot > 0)) return false;
        counters.Shadow++;
        return !geometry.Occluded(Visibility.ShadowRay(p, ng, s.Direction, s.Distance, geometry.Epsilon));
    }

    /// <summary>
    /// Light <paramref name="k"/>'s share of <see cref="Direct"/> per unit of its luminous value: c_spot·d_k·max(0, n·l)
    /// with the shadow ray unblocked, else 0 (lx per cd for a point light, lx per lx facing it for a directional one).
    /// </summary>
    public double LightFactor(int k, Vector3 p, Vector3 n, Vector3 ng, ref RayCounters counters) =>
        Lit(k, p, n, ng, ref counters, out var s, out float cos) ? (double)s.Spot * s.Attenuation * cos : 0;

    /// <summary>
    /// Per light, per pixel of the whole film, <see cref="LightFactor"/> at the surface the pixel-centre ray meets (as
    /// <see cref="Maps"/> finds it; 0 where it meets nothing): the illuminance is linear in each light's luminous value, so
    /// Σ_k K_m∫V·I_k dλ · G_k is the direct illuminance under any spectra and intensities of the same lights (the viewer's
    /// relighting). The same on any thread count.
    /// </summary>
    public float[][] LightFactorMaps(int threads, CancellationToken cancel = default)
    {
        var geometry = _geometry ?? throw new InvalidOperationException("illuminance needs the scene's geometry");
        var camera = _scene.Camera;
        int w = camera.Width, h = camera.Height, lights = _scene.Lights.Count;
        var maps = new float[lights][];
        for (int k = 0; k < lights; k++) maps[k] = new float[w * h];
        var options = new ParallelOptions { MaxDegreeOfParallelism = threads > 0 ? threads : -1, CancellationToken = cancel };
        Parallel.For(0, h, options, y =>
        {
            var counters = new RayCounters();
            for (int x = 0; x < w; x++)
            {
                var ray = camera.Generate(x + 0.5f, y + 0.5f);
                if (!geometry.Intersect(ref ray, out var hit)) continue;
                var wo = -ray.Direction;
                var ng = Vector3.Dot(hit.GeometricNormal, wo) >= 0 ? hit.GeometricNormal : -hit.GeometricNormal;
                var n = Vector3.Dot(hit.Normal, wo) >= 0 ? hit.Normal : -hit.Normal;
                for (int k = 0; k < lights; k++) maps[k][y * w + x] = (float)LightFactor(k, hit.Position, n, ng, ref counters);
            }
        });
        return maps;
    }

    /// <summary>The gather rays a pixel's illuminance takes under an integrator that gathers: the camera's spp, at least 64.</summary>
    public static int GatherRays(Scene scene) => Math.Max(64, scene.Camera.SamplesPerPixel);

    /// <summary>
    /// Per pixel of the render's crop, the luminance (cd/m²) of what the camera sees, from the rendered pixels, and the
    /// illuminance (lx) arriving at the surface the pixel-centre ray meets first (on the side facing the camera; 0 where
    /// it meets nothing): the direct share (<see cref="Direct"/>: the lights, and without a gather the emitting objects and
    /// the sky), plus, when <paramref name="gather"/> is given (an integrator that gathers), π/N Σ L_v of N cosine-weighted
    /// rays it traces (area lights, sky and interreflection; delta lights it cannot hit).
    /// The same on any thread count: a pixel's rays depend on (x, y, ray index) only. <paramref name="progress"/> hears (rows
    /// done, rows) after each row of pixels.
    /// </summary>
    public (float[] Luminance, float[] Illuminance) Maps(RenderResult result, IGatherIntegrator? gather, int threads,
        CancellationToken cancel = default, Action<int, int>? progress = null)
    {
        var crop = result.Crop;
        var image = result.Image;
        int w = crop.Width, h = crop.Height;
        var luminance = new float[w * h];
        var illuminance = new float[w * h];
        var xyz = result.Xyz;
        for (int i = 0; i < w * h; i++)
            luminance[i] = (float)(xyz is not null && _yIsV ? xyz[3 * i + 1] * _yToLuminance : BandLuminance(image.Pixel(i % w, i / w)));
        if (_geometry is not { } geometry) return (luminance, illuminance);
        var camera = _scene.Camera;
        int rays = GatherRays(_scene), done = 0;
        var options = new ParallelOptions { MaxDegreeOfParallelism = threads > 0 ? threads : -1, CancellationToken = cancel };
        Parallel.For(0, h, options, () => (new float[_scene.PaddedBands + 64], new float[gather?.ScratchLength ?? 0]), (row, _, buffers) =>
        {
            var (radiance, scratch) = buffers;
            var counters = new RayCounters();
            int y = crop.Y0 + row;
            for (int col = 0; col < w; col++)
            {
                int x = crop.X0 + col;
                var ray = camera.Generate(x + 0.5f, y + 0.5f);
                if (!geometry.Intersect(ref ray, out var hit)) continue;
                var wo = -ray.Direction;
                var ng = Vector3.Dot(hit.GeometricNormal, wo) >= 0 ? hit.GeometricNormal : -hit.GeometricNormal;
                var n = Vector3.Dot(hit.Normal, wo) >= 0 ? hit.Normal : -hit.Normal;
                double e = Direct(x, y, hit.Position, n, ng, gather is not null, ref counters);
                if (gather is not null)
                    e += Gather(gather, GatherSampler(gather, 0), x, y, hit.Position, n, ng, rays, 0, e, radiance, scratch,
                        ref counters).Lux;
                illuminance[row * w + col] = (float)e;
            }
            progress?.Invoke(Interlocked.Increment(ref done), h);
            return buffers;
        }, _ => { });
        return (luminance, illuminance);
    }

    /// <summary>
    /// The illuminance (lx) at each point of a calculation grid (i fastest), on the side of its normal: its direct share
    /// (<see cref="Direct"/>: the lights, and without a gather the emitting objects and the sky), plus, when
    /// <paramref name="gather"/> is given (one that gathers: path), the gather of the emitting objects, the sky and
    /// interreflection (<see cref="Gather"/>), drawn from the point's (i, j). The same on any thread count.
    /// </summary>
    public double[] OnGrid(CalculationGrid grid, IGatherIntegrator? gather, int threads, CancellationToken cancel = default) =>
        OnGridWithError(grid, gather, threads, 0, 0, null, cancel).Lux;

    /// <summary>
    /// <see cref="OnGrid"/> with each point's standard error (lx; null without a gather: the lights' share is exact) and
    /// the gather's rays per point: <see cref="GatherRays"/>, or with <paramref name="target"/> &gt; 0 as many more, in rounds
    /// of <see cref="Sampler.Randomisations"/>, up to <see cref="TargetCap"/> × that, until the point's relative standard error
    /// (by the conservative rule of the pixels' adaptive stop) is at most the target. <paramref name="stream"/> gives each grid
    /// its own random numbers; <paramref name="progress"/> hears (rows done, rows) after each row of points.
    /// </summary>
    public GridIlluminance OnGridWithError(CalculationGrid grid, IGatherIntegrator? gather, int threads, double target, int stream,
        Action<int, int>? progress, CancellationToken cancel = default)
    {
        int nu = grid.PointsU, nv = grid.PointsV;
        var lux = new double[nu * nv];
        var errors = gather is null ? null : new double[nu * nv];
        var used = new int[nu * nv];
        var n = grid.Normal;
        int rays = GatherRays(_scene), done = 0;
        var settings = gather is null ? default : GatherSampler(gather, stream);
        var options = new ParallelOptions { MaxDegreeOfParallelism = threads > 0 ? threads : -1, CancellationToken = cancel };
        Parallel.For(0, nv, options, () => (new float[_scene.PaddedBands + 64], new float[gather?.ScratchLength ?? 0]), (j, _, buffers) =>
        {
            var (radiance, scratch) = buffers;
            var counters = new RayCounters();
            for (int i = 0; i < nu; i++)
            {
                var p = grid.Point(i, j);
                double e = Direct(i, j, p, n, n, gather is not null, ref counters);
                if (gather is not null)
                {
                    var g = Gather(gather, settings, i, j, p, n, n, rays, target, e, radiance, scratch, ref counters);
                    e += g.Lux;
                    errors![j * nu + i] = g.StandardError;
                    used[j * nu + i] = g.Rays;
                }
                lux[j * nu + i] = e;
            }
            progress?.Invoke(Interlocked.Increment(ref done), nv);
            return buffers;
        }, _ => { });
        return new GridIlluminance(lux, errors, used);
    }

    /// <summary>The most gather rays a point takes towards a target error, as a multiple of <see cref="GatherRays"/>.</summary>
    public const int TargetCap = 64;

    /// <summary>The gather's sampler: the integrator's kind and seed, on a stream of its own (not the camera samples').</summary>
    static SamplerSettings GatherSampler(IGatherIntegrator gather, int stream) =>
        new(gather.Sampler.Kind, gather.Sampler.Seed ^ 0x5BD1E995u ^ (uint)stream * 0x27D4EB2Fu);

    /// <summary>The dimension the gather's next-event draws start at, beyond any path's own (5 per vertex).</summary>
    const int NextEventDimension = 1 << 16;

    /// <summary>
    /// What arrives at p from every direction but the scene lights' (which <see cref="Direct"/> counts exactly), E = ∫ L_v
    /// cos θ dω, by two strategies combined by multiple importance sampling (Veach 1997, §9.2, power heuristic): per gather
    /// ray i, (1) a sample of each emitting object and of the sky (<see cref="Emitter.Sample"/>, density p_e, the shadow ray
    /// honoured), L_v·cos θ/p_e · p_e²/(p_e² + p_c²), and (2) a cosine-weighted direction (p_c = cos θ/π): the emitter or
    /// sky it meets first, π·L_v · p_c²/(p_c² + p_e²), plus π·L_v of the light its first vertex reflects (the integrator's
    /// <see cref="IGatherIntegrator.Reflected"/>: interreflection, with next-event estimation of its own). The rays' numbers
    /// come from the integrator's sampler at (x, y) (a point of its own), so a Sobol gather is <see
    /// cref="Sampler.Randomisations"/> independent randomisations whose spread gives the standard error, as the pixels'
    /// (Renderer.Statistics.cs); independent rays give s/√n. <paramref name="direct"/> is the point's exact share, for the
    /// relative target.
    /// </summary>
    GatherEstimate Gather(IGatherIntegrator integrator, SamplerSettings settings, int x, int y, Vector3 p, Vector3 n, Vector3 ng,
        int rays, double target, double direct, float[] radiance, float[] scratch, ref RayCounters counters)
    {
        var set = _emitters!;
        var geometry = _geometry!;
        int bands = _scene.Bands, cap = target > 0 ? TargetCap * rays : rays;
        bool sobol = settings.Kind == SamplerKind.Sobol;
        const int R = Sampler.Randomisations;
        Span<double> groups = stackalloc double[R];
        groups.Clear();
        double s1 = 0, s2 = 0;
        int count = 0;
        for (; count < cap; count++)
        {
            if (count >= rays && count % R == 0 && Converged(s1, s2, count, direct, target)) break;
            var (u, v) = new Sampler(x, y, count, 0, settings).Next2D();
            var wi = Bsdf.CosineHemisphere(n, new Vector2(u, v));
            double pc = Math.Max(0, Vector3.Dot(n, wi)) / Math.PI, value = 0;
            // (1) next-event estimation of each emitting object and the sky
            var nee = new Sampler(x, y, count, NextEventDimension, settings);
            for (int k = 0; k < set.Count; k++)
            {
                if (set[k].SceneLight >= 0 || !(_gatherLuminance[k] > 0)) continue;
                var (a, b) = nee.Next2D();
                if (!set[k].Sample(p, n, new Vector2(a, b), out var s) || !(s.Pdf > 0) || !(s.Factor > 0)) continue;
                float cos = Vector3.Dot(n, s.Direction);
                if (!(cos > 0)) continue;
                counters.Shadow++;
                if (geometry.Occluded(Visibility.ShadowRay(p, ng, s.Direction, s.Distance, geometry.Epsilon))) continue;
                double pe = s.Pdf, pn = cos / Math.PI;
                value += _gatherLuminance[k] * s.Factor * cos / pe * (pe * pe / (pe * pe + pn * pn));
            }
            // (2) the cosine-weighted ray: the emitter or sky it sees, then what its first vertex reflects
            var ray = Visibility.Leaving(p, ng, wi, geometry.Epsilon);
            var traced = ray;
            counters.Secondary++;
            if (geometry.Intersect(ref traced, out var hit))
            {
                if (set.OfObject(hit.Object) is int k and >= 0 && _gatherLuminance[k] > 0
                    && set[k].Emitted(hit.GeometricNormal, -wi) is var seen and > 0)
                {
                    double pe = set[k].Pdf(p, n, wi, hit.Position, hit.GeometricNormal);
                    value += Math.PI * _gatherLuminance[k] * seen * (pc * pc / (pc * pc + pe * pe));
                }
            }
            else if (set.Sky is int sky and >= 0 && _gatherLuminance[sky] > 0 && set.SkySeen(wi) is var seen and > 0)
            {
                double pe = set[sky].Pdf(p, n, wi, default, default);
                value += Math.PI * _gatherLuminance[sky] * seen * (pc * pc / (pc * pc + pe * pe));
            }
            integrator.Reflected(new CameraSample(x, y, count, ray, settings), radiance.AsSpan(0, _scene.PaddedBands), scratch,
                ref counters);
            value += Math.PI * Luminance(radiance.AsSpan(0, bands), radiance[bands + 1]);
            s1 += value;
            s2 += value * value;
            groups[count % R] += value;
        }
        double mean = s1 / count;
        return new GatherEstimate(mean, sobol ? RandomisationError(groups, s1, count) : IndependentError(s1, s2, count), count);
    }

    /// <summary>s/√n of n independent values (0 for n &lt; 2).</summary>
    static double IndependentError(double s1, double s2, int n) =>
        n < 2 ? 0 : Math.Sqrt(Math.Max(0, (s2 - s1 * s1 / n) / (n - 1)) / n);

    /// <summary>The standard error of the mean from the sums of its randomisations (Renderer.Statistics.cs, the same rule).</summary>
    static double RandomisationError(ReadOnlySpan<double> groups, double s1, int n)
    {
        if (n < 2) return 0;
        int r = Math.Min(Sampler.Randomisations, n);
        double mean = s1 / n, sum = 0;
        for (int g = 0; g < r; g++)
        {
            int size = n / Sampler.Randomisations + (g < n % Sampler.Randomisations ? 1 : 0);
            double deviation = groups[g] - size * mean;
            sum += deviation * deviation;
        }
        return Math.Sqrt(r / (r - 1.0) * sum) / n;
    }

    /// <summary>The adaptive stop's conservative rule (the pixels'): s/√n × (1 + 2/√(2(n − 1))) ≤ target × the point's lux.</summary>
    static bool Converged(double s1, double s2, int n, double direct, double target)
    {
        if (!(target > 0)) return true;
        double se = IndependentError(s1, s2, n) * (1 + 2 / Math.Sqrt(2.0 * (n - 1)));
        return se <= target * Math.Abs(direct + s1 / n);
    }
}

/// <summary>One point's gather: its mean (lx), standard error (lx) and rays.</summary>
public readonly record struct GatherEstimate(double Lux, double StandardError, int Rays);

/// <summary>A calculation grid's illuminance (lx, i fastest), each point's standard error (lx; null: exact, no gather) and the
/// gather's rays per point (0: none).</summary>
public sealed record GridIlluminance(double[] Lux, double[]? StandardError, int[] Rays);
