using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Illumination;

/// <summary>
/// Photometric quantities at surface points (physical radiometry, CIE 015:2018 §4): the illuminance E_v (lx) arriving at
/// a point from the scene's lights, E_v = Σ_k K_m ∫V·I_k dλ · c_spot,k · d_k · max(0, n·l_k) with the shadow ray to light
/// k unblocked (I/r²·cos θ for a point light, E⊥·cos θ for a directional one), and, for a path-traced scene, what arrives
/// from every other direction (area lights, the sky, interreflection) by a cosine-weighted gather
/// E = ∫ L_v cos θ dω ≈ π/N Σ L_v(ω_i), each L_v(ω_i) the integrator's own radiance along ω_i. Luminance of a radiance
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
    }

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
    /// Illuminance (lx) at point <paramref name="p"/> on the side of normal <paramref name="n"/> (unit) from the scene's
    /// lights (point, spot, directional, goniometric: their own falloff and spot factor), each shadow ray honoured;
    /// <paramref name="ng"/> is the geometric normal the shadow rays leave from (the surface's, or n for a free point).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public double FromLights(Vector3 p, Vector3 n, Vector3 ng, ref RayCounters counters)
    {
        double e = 0;
        var geometry = _geometry ?? throw new InvalidOperationException("illuminance needs the scene's geometry");
        float eps = geometry.Epsilon;
        var lights = _scene.Lights;
        for (int k = 0; k < lights.Count; k++)
        {
            if (!lights[k].Illuminate(p, out var s)) continue;
            float cos = Vector3.Dot(n, s.Direction);
            if (!(cos > 0) || !(s.Spot > 0)) continue;
            float side = Vector3.Dot(ng, s.Direction) >= 0 ? 1 : -1;
            var origin = p + side * eps * ng;
            var shadow = float.IsInfinity(s.Distance) ? new Ray(origin, s.Direction)
                : new Ray(origin, s.Direction, MathF.Max(0, s.Distance - 2 * eps));
            counters.Shadow++;
            if (geometry.Occluded(shadow)) continue;
            e += _luminous[k] * s.Spot * s.Attenuation * cos;
        }
        return e;
    }

    /// <summary>
    /// Light <paramref name="k"/>'s share of <see cref="FromLights"/> per unit of its luminous value: c_spot·d_k·max(0, n·l)
    /// with the shadow ray unblocked, else 0 (lx per cd for a point light, lx per lx facing it for a directional one).
    /// </summary>
    public double LightFactor(int k, Vector3 p, Vector3 n, Vector3 ng, ref RayCounters counters)
    {
        var geometry = _geometry ?? throw new InvalidOperationException("illuminance needs the scene's geometry");
        if (!_scene.Lights[k].Illuminate(p, out var s)) return 0;
        float cos = Vector3.Dot(n, s.Direction);
        if (!(cos > 0) || !(s.Spot > 0)) return 0;
        float eps = geometry.Epsilon;
        float side = Vector3.Dot(ng, s.Direction) >= 0 ? 1 : -1;
        var origin = p + side * eps * ng;
        var shadow = float.IsInfinity(s.Distance) ? new Ray(origin, s.Direction)
            : new Ray(origin, s.Direction, MathF.Max(0, s.Distance - 2 * eps));
        counters.Shadow++;
        return geometry.Occluded(shadow) ? 0 : (double)s.Spot * s.Attenuation * cos;
    }

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
    /// it meets nothing): from the lights with shadows, plus, when <paramref name="gather"/> is given (an integrator that gathers),
    /// π/N Σ L_v of N cosine-weighted rays it traces (area lights, sky and interreflection; delta lights it cannot hit).
    /// The same on any thread count: a pixel's rays depend on (x, y, ray index) only.
    /// </summary>
    public (float[] Luminance, float[] Illuminance) Maps(RenderResult result, IGatherIntegrator? gather, int threads,
        CancellationToken cancel = default)
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
        int rays = GatherRays(_scene);
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
                double e = FromLights(hit.Position, n, ng, ref counters);
                if (gather is not null) e += Gather(gather, x, y, hit.Position, n, ng, rays, radiance, scratch, ref counters);
                illuminance[row * w + col] = (float)e;
            }
            return buffers;
        }, _ => { });
        return (luminance, illuminance);
    }

    /// <summary>
    /// The illuminance (lx) at each point of a calculation grid (i fastest), on the side of its normal: from the lights with
    /// shadows (<see cref="FromLights"/>), plus, when <paramref name="gather"/> is given (one that gathers: path), π/N Σ L_v of
    /// <see cref="GatherRays"/> cosine-weighted rays from the point (area lights, sky and interreflection), drawn from the
    /// point's (i, j). The same on any thread count.
    /// </summary>
    public double[] OnGrid(CalculationGrid grid, IGatherIntegrator? gather, int threads, CancellationToken cancel = default)
    {
        int nu = grid.PointsU, nv = grid.PointsV;
        var lux = new double[nu * nv];
        var n = grid.Normal;
        int rays = GatherRays(_scene);
        var options = new ParallelOptions { MaxDegreeOfParallelism = threads > 0 ? threads : -1, CancellationToken = cancel };
        Parallel.For(0, nv, options, () => (new float[_scene.PaddedBands + 64], new float[gather?.ScratchLength ?? 0]), (j, _, buffers) =>
        {
            var (radiance, scratch) = buffers;
            var counters = new RayCounters();
            for (int i = 0; i < nu; i++)
            {
                var p = grid.Point(i, j);
                double e = FromLights(p, n, n, ref counters);
                if (gather is not null) e += Gather(gather, i, j, p, n, n, rays, radiance, scratch, ref counters);
                lux[j * nu + i] = e;
            }
            return buffers;
        }, _ => { });
        return lux;
    }

    /// <summary>π/N Σ L_v(ω_i) over N cosine-weighted directions about n (E = ∫ L cos θ dω, pdf cos θ/π).</summary>
    double Gather(IIntegrator integrator, int x, int y, Vector3 p, Vector3 n, Vector3 ng, int rays, float[] radiance, float[] scratch,
        ref RayCounters counters)
    {
        double sum = 0;
        int bands = _scene.Bands;
        for (int i = 0; i < rays; i++)
        {
            // Sample indices beyond any camera sample's (the film jitter draw of (x, y, index) picks the direction).
            int index = int.MaxValue - rays + i;
            var (u, v) = new Sampler(x, y, index).Next2D();
            var wi = Bsdf.CosineHemisphere(n, new Vector2(u, v));
            float side = Vector3.Dot(ng, wi) >= 0 ? 1 : -1;
            var ray = new Ray(p + side * _geometry!.Epsilon * ng, wi);
            counters.Secondary++;
            integrator.Radiance(new CameraSample(x, y, index, ray), radiance.AsSpan(0, _scene.PaddedBands), scratch, ref counters);
            sum += Luminance(radiance.AsSpan(0, bands), radiance[bands + 1]);
        }
        return Math.PI * sum / rays;
    }
}
