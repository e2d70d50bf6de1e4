using System.Collections.Concurrent;
using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>The lobe of eq. 2 a light term goes through: L_diff,k or L_spec,k.</summary>
public enum TransferLobe { Diffuse, Specular }

/// <summary>
/// One spectral component of a light's contribution: light k's spectrum through material <see cref="Material"/>'s
/// diffuse or specular reflectance, reached from the camera through the mirror (k_r) and transmission (k_t)
/// weights of the materials in <see cref="Chain"/> (first bounce first). Its band values are
/// P_b = I_k,b · m_lobe,b · Π k_chain,b, the products eq. 2 and the Whitted recursion form in every band.
/// </summary>
public sealed record TransferComponent(int Light, TransferLobe Lobe, int Material, (int Material, bool Transmit)[] Chain)
{
    /// <summary>A stable text key such as <c>0:diffuse:2</c> or <c>1:specular:3&lt;mirror:1</c>.</summary>
    public string Key => $"{Light}:{(Lobe == TransferLobe.Diffuse ? "diffuse" : "specular")}:{Material}" +
        string.Concat(Chain.Reverse().Select(c => $"<{(c.Transmit ? "transmit" : "mirror")}:{c.Material}"));

    /// <summary>P_b into <paramref name="dst"/> for the light's band values <paramref name="light"/> (spectrum × intensity).</summary>
    public void BandValues(IReadOnlyList<Material> materials, ReadOnlySpan<float> light, Span<float> dst)
    {
        var m = materials[Material];
        var lobe = Lobe == TransferLobe.Diffuse ? m.Diffuse : m.Specular;
        for (int b = 0; b < dst.Length; b++)
        {
            float v = light[b] * lobe[b];
            foreach (var (cm, t) in Chain) v *= t ? materials[cm].Transmit[b] : materials[cm].Mirror[b];
            dst[b] = v;
        }
    }
}

/// <summary>
/// Per-light transfer of a render: light transport in eq. 2 and the Whitted recursion is linear in each light's
/// spectrum, so a pixel's band values are L_b = S_b + Σ_c F_c · P_c,b, where S is the part no light's spectrum
/// enters (global ambient, each light's own ambient spectrum, the background, all carried along mirror and
/// glass paths), F_c the per-pixel geometric factor of component c (c_spot · d_k · max(0, n·l) for diffuse,
/// c_spot · d_k · (n·h)^shininess for specular, times the Fresnel weights along the path, averaged over the
/// pixel's samples) and P_c its band values (<see cref="TransferComponent"/>). Changing a light's spectrum or
/// intensity changes only P: <see cref="Relight"/> recomputes the image exactly as a render with those lights
/// computes it (the band values of this band scheme are products of band means, so P carries them exactly).
/// The tracer follows <see cref="WhittedIntegrator"/> ray for ray (same camera rays, jitter, shadow rays,
/// epsilons, Fresnel and total internal reflection). Dispersive materials are not supported (their paths
/// split per band).
/// </summary>
public sealed class LightTransfer
{
    public required int Width { get; init; }
    public required int Height { get; init; }
    public required int Bands { get; init; }
    /// <summary>Components in a fixed order (sorted by light, then key), whatever the thread count.</summary>
    public required TransferComponent[] Components { get; init; }
    /// <summary>Per component, its W × H factor plane (row-major, row 0 at the top).</summary>
    public required float[][] Factors { get; init; }
    /// <summary>S: the light-independent radiance, H × W × N.</summary>
    public required SpectralImage Static { get; init; }
    /// <summary>Per light, the centre ray's diffuse factor d·c_spot·(n·l) at its first hit (for the highlight mask), W × H.</summary>
    public required float[][] CentreDiffuse { get; init; }
    public required float[][] CentreSpecular { get; init; }
    public required int[] ObjectIds { get; init; }
    public required uint[] LitMasks { get; init; }
    public required RayCounters Rays { get; init; }

    public const int MaxChain = 6;

    /// <summary>Traces the scene's camera rays and records S, the factors and the centre-ray data.</summary>
    public static LightTransfer Trace(Scene scene, SceneGeometry geometry, int threads = 0, CancellationToken cancel = default)
    {
        if (scene.Materials.Any(m => m.Dispersive && m.HasTransmission))
            throw new InputException("output.formats", "the 'lights' output does not support dispersive materials (their paths split per band)", "render those scenes without 'lights'");
        if (scene.MaxDepth > MaxChain)
            throw new InputException("max_depth", $"the 'lights' output supports max_depth ≤ {MaxChain}, the scene has {scene.MaxDepth}", $"set max_depth to {MaxChain} or less");
        if (scene.Lights.Count > 255 || scene.Materials.Count > 4095)
            throw new InputException("lights", "the 'lights' output supports at most 255 lights and 4095 materials");
        var t = new Tracer(scene, geometry);
        return t.Run(threads, cancel);
    }

    /// <summary>
    /// The image under new light band values (spectrum × intensity per light, padded): S + Σ_c F_c · P_c, on all cores.
    /// </summary>
    public SpectralImage Relight(IReadOnlyList<Material> materials, IReadOnlyList<float[]> lightBands)
    {
        int n = Width * Height, bands = Bands;
        var p = new float[Components.Length][];
        for (int c = 0; c < p.Length; c++)
        {
            p[c] = new float[bands];
            Components[c].BandValues(materials, lightBands[Components[c].Light], p[c]);
        }
        var image = new SpectralImage(Width, Height, Static.Grid, (float[])Static.Data.Clone());
        var data = image.Data;
        Parallel.For(0, (n + 4095) / 4096, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (chunk) =>
        {
            int i0 = chunk * 4096, i1 = Math.Min(n, i0 + 4096);
            for (int c = 0; c < p.Length; c++)
            {
                var f = Factors[c];
                var pc = p[c];
                for (int i = i0; i < i1; i++)
                {
                    float fi = f[i];
                    if (fi == 0) continue;
                    var px = data.AsSpan(i * bands, bands);
                    for (int b = 0; b < bands; b++) px[b] += fi * pc[b];
                }
            }
        });
        return image;
    }

    /// <summary>The highlight-mask luminances of eq. 2's terms at the centre rays, under new light band values.</summary>
    public (float[] DiffuseY, float[] SpecularY) CentreLuminance(Scene scene, IReadOnlyList<float[]> lightBands)
    {
        int n = Width * Height, lights = lightBands.Count, mats = scene.Materials.Count;
        var wy = scene.Colorimeter.Wy;
        var dy = new float[lights * mats]; var sy = new float[lights * mats];
        for (int k = 0; k < lights; k++)
        for (int m = 0; m < mats; m++)
        {
            double d = 0, s = 0;
            for (int b = 0; b < scene.Bands; b++)
            {
                d += wy[b] * lightBands[k][b] * scene.Materials[m].Diffuse[b];
                s += wy[b] * lightBands[k][b] * scene.Materials[m].Specular[b];
            }
            dy[k * mats + m] = (float)d; sy[k * mats + m] = (float)s;
        }
        var diffuse = new float[n]; var specular = new float[n];
        for (int i = 0; i < n; i++)
        {
            int o = ObjectIds[i];
            if (o < 0) continue;
            int m = scene.Objects[o].Material;
            for (int k = 0; k < lights; k++)
            {
                diffuse[i] += CentreDiffuse[k][i] * dy[k * mats + m];
                specular[i] += CentreSpecular[k][i] * sy[k * mats + m];
            }
        }
        return (diffuse, specular);
    }

    readonly record struct Key(ulong A, ulong B);

    sealed class Tracer
    {
        readonly Scene _scene;
        readonly SceneGeometry _geometry;
        readonly Material[] _materials;
        readonly Light[] _lights;
        readonly int[] _objectMaterial;
        readonly int _padded, _width, _height;
        readonly ConcurrentDictionary<Key, TransferComponent> _components = new();
        readonly ConcurrentDictionary<Key, float[]> _planes = new();
        readonly float[][] _centreDiffuse, _centreSpecular;

        public Tracer(Scene scene, SceneGeometry geometry)
        {
            _scene = scene; _geometry = geometry;
            _materials = scene.Materials.ToArray();
            _lights = scene.Lights.ToArray();
            _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
            _padded = scene.PaddedBands;
            _width = scene.Camera.Width; _height = scene.Camera.Height;
            _centreDiffuse = _lights.Select(_ => new float[_width * _height]).ToArray();
            _centreSpecular = _lights.Select(_ => new float[_width * _height]).ToArray();
        }

        sealed class Worker(int padded, int depth)
        {
            public readonly float[] Static = new float[padded];
            /// <summary>Spectral throughput Π k·weight per recursion level.</summary>
            public readonly float[] Throughput = new float[(depth + 2) * padded];
            public readonly int[] Chain = new int[MaxChain + 1];
            public int ChainLength;
            public readonly Dictionary<Key, float[]> Planes = new();
            // The current pixel's terms: plane and accumulated factor (few distinct ones per pixel).
            public float[]?[] TermPlanes = new float[]?[64];
            public float[] TermFactors = new float[64];
            public int Terms;
            public RayCounters Counters;
        }

        public LightTransfer Run(int threads, CancellationToken cancel)
        {
            var cam = _scene.Camera;
            int width = _width, height = _height, bands = _scene.Bands, padded = _padded;
            var image = new SpectralImage(width, height, _scene.Grid);
            var ids = new int[width * height];
            var lit = new uint[width * height];
            int tilesX = (width + Renderer.TileSize - 1) / Renderer.TileSize, tilesY = (height + Renderer.TileSize - 1) / Renderer.TileSize;
            int tiles = tilesX * tilesY;
            if (threads <= 0) threads = Environment.ProcessorCount;
            int spp = cam.SamplesPerPixel;
            int strataX = 1;
            for (int m = (int)Math.Sqrt(spp); m >= 1; m--) if (spp % m == 0) { strataX = m; break; }
            int strataY = spp / strataX;
            float inv = 1f / spp;
            var total = new RayCounters();
            var gate = new object();
            int next = -1;

            void Work()
            {
                var w = new Worker(padded, _scene.MaxDepth);
                int tile;
                while ((tile = Interlocked.Increment(ref next)) < tiles)
                {
                    cancel.ThrowIfCancellationRequested();
                    int x0 = tile % tilesX * Renderer.TileSize, y0 = tile / tilesX * Renderer.TileSize;
                    int x1 = Math.Min(width, x0 + Renderer.TileSize), y1 = Math.Min(height, y0 + Renderer.TileSize);
                    for (int y = y0; y < y1; y++)
                    for (int x = x0; x < x1; x++)
                    {
                        int i = y * width + x;
                        Array.Clear(w.Static);
                        w.Terms = 0;
                        uint mask = 0;
                        int id;
                        if (spp == 1)
                        {
                            w.Counters.Primary++;
                            id = Primary(cam.Generate(x + 0.5f, y + 0.5f), w, 1f, i, ref mask, centre: true);
                        }
                        else
                        {
                            for (int s = 0; s < spp; s++)
                            {
                                uint h = Renderer.Hash((uint)x, (uint)y, (uint)s);
                                float jx = ((s % strataX) + (h & 0xFFFF) / 65536f) / strataX;
                                float jy = ((s / strataX) + (h >> 16) / 65536f) / strataY;
                                w.Counters.Primary++;
                                uint unused = 0;
                                Primary(cam.Generate(x + jx, y + jy), w, inv, i, ref unused, centre: false);
                            }
                            // The centre ray only for the analysis data (no radiance).
                            w.Counters.Primary++;
                            id = Centre(cam.Generate(x + 0.5f, y + 0.5f), i, ref mask, ref w.Counters);
                        }
                        w.Static.AsSpan(0, bands).CopyTo(image.Data.AsSpan(image.Offset(x, y), bands));
                        for (int t = 0; t < w.Terms; t++) w.TermPlanes[t]![i] = w.TermFactors[t];
                        ids[i] = id;
                        lit[i] = mask;
                    }
                }
                lock (gate) total.Add(w.Counters);
            }
            var workers = new Task[Math.Min(threads, tiles)];
            for (int k = 0; k < workers.Length; k++) workers[k] = Task.Factory.StartNew(Work, cancel, TaskCreationOptions.None, TaskScheduler.Default);
            try { Task.WaitAll(workers); }
            catch (AggregateException e) when (e.InnerExceptions.All(x => x is OperationCanceledException)) { throw new OperationCanceledException(cancel); }

            var order = _components.OrderBy(c => c.Value.Light).ThenBy(c => c.Value.Key, StringComparer.Ordinal).ToArray();
            return new LightTransfer
            {
                Width = width, Height = height, Bands = bands,
                Components = order.Select(c => c.Value).ToArray(),
                Factors = order.Select(c => _planes[c.Key]).ToArray(),
                Static = image, CentreDiffuse = _centreDiffuse, CentreSpecular = _centreSpecular,
                ObjectIds = ids, LitMasks = lit, Rays = total,
            };
        }

        /// <summary>A camera sample of weight <paramref name="weight"/> (1/spp): radiance terms into the worker.</summary>
        int Primary(Ray ray, Worker w, float weight, int pixel, ref uint mask, bool centre)
        {
            var tp = w.Throughput.AsSpan(0, _padded);
            tp.Fill(weight);
            w.ChainLength = 0;
            return Radiance(ray, 0, w, weight, pixel, ref mask, centre);
        }

        int Centre(Ray ray, int pixel, ref uint mask, ref RayCounters counters)
        {
            if (!_geometry.Intersect(ref ray, out var hit)) return -1;
            var m = _materials[_objectMaterial[hit.Object]];
            Local(ray, hit, m, out var n, out var v, out var pAbove, out _);
            for (int k = 0; k < _lights.Length; k++)
            {
                if (!Reaches(k, hit.Position, pAbove, n, ref counters, out float d, out float nl, out var l)) continue;
                if (k < 32) mask |= 1u << k;
                _centreDiffuse[k][pixel] = d * nl;
                _centreSpecular[k][pixel] = d * Specular(m, n, l, v, nl);
            }
            return hit.Object;
        }

        void Local(in Ray ray, in SurfaceHit hit, Material m, out Vector3 n, out Vector3 v, out Vector3 pAbove, out bool outside)
        {
            v = -ray.Direction;
            outside = Vector3.Dot(hit.GeometricNormal, v) >= 0;
            var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
            n = outside ? hit.Normal : -hit.Normal;
            pAbove = hit.Position + _geometry.Epsilon * ng;
        }

        /// <summary>Does light k reach the point (spot cone, n·l &gt; 0, shadow ray)? Its d·c_spot and n·l.</summary>
        bool Reaches(int k, Vector3 p, Vector3 pAbove, Vector3 n, ref RayCounters counters, out float d, out float nl, out Vector3 l)
        {
            var light = _lights[k];
            float dist;
            d = 0; nl = 0;
            if (light.Kind == LightKind.Directional) { l = -light.Direction; dist = float.PositiveInfinity; }
            else
            {
                var toLight = light.Position - p;
                dist = toLight.Length();
                l = default;
                if (dist == 0) return false;
                l = toLight / dist;
            }
            float spot = light.SpotFactor(-l);
            if (spot == 0) return false;
            nl = Vector3.Dot(n, l);
            if (nl <= 0) return false;
            counters.Shadow++;
            var shadowRay = new Ray(pAbove, l, float.IsInfinity(dist) ? float.PositiveInfinity : dist - 2 * _geometry.Epsilon);
            if (_geometry.Occluded(shadowRay)) return false;
            d = light.Attenuation(dist) * spot;
            return true;
        }

        static float Specular(Material m, Vector3 n, Vector3 l, Vector3 v, float nl)
        {
            if (!m.HasSpecular) return 0;
            if (m.Model == SpecularModel.BlinnPhong)
            {
                var h = Vector3.Normalize(l + v);
                return MathF.Pow(MathF.Max(0, Vector3.Dot(n, h)), m.Shininess);
            }
            var r = 2 * nl * n - l;
            return MathF.Pow(MathF.Max(0, Vector3.Dot(r, v)), m.Shininess);
        }

        /// <summary>
        /// Eq. 2 at the hit, as <see cref="WhittedIntegrator.Radiance(Ray, int, int, Span{float}, Span{float}, ref RayCounters, ref PixelInfo)"/>
        /// computes it: light-independent terms into S (times the path's spectral throughput), light terms as factors
        /// (times the path's scalar Fresnel weight <paramref name="weight"/>).
        /// </summary>
        int Radiance(Ray ray, int depth, Worker w, float weight, int pixel, ref uint mask, bool centre)
        {
            var tp = w.Throughput.AsSpan(depth * _padded, _padded);
            if (!_geometry.Intersect(ref ray, out var hit))
            {
                SpectralMath.AddProduct(w.Static, tp, _scene.Background);
                return -1;
            }
            int mi = _objectMaterial[hit.Object];
            var m = _materials[mi];
            Local(ray, hit, m, out var n, out var v, out var pAbove, out bool outside);
            var p = hit.Position;
            if (_scene.HasGlobalAmbient && m.HasAmbient) AddStatic(w.Static, tp, _scene.GlobalAmbient, m.Ambient, 1);

            for (int k = 0; k < _lights.Length; k++)
            {
                var light = _lights[k];
                // The light's own ambient spectrum enters wherever the spot cone admits the point (before n·l and shadows).
                if (light.HasAmbient && m.HasAmbient)
                {
                    Vector3 l0;
                    float dist0 = 1;
                    if (light.Kind == LightKind.Directional) l0 = -light.Direction;
                    else { var toLight = light.Position - p; dist0 = toLight.Length(); l0 = toLight / dist0; }
                    float spot = dist0 == 0 ? 0 : light.SpotFactor(-l0);
                    if (spot != 0) AddStatic(w.Static, tp, light.Ambient, m.Ambient, spot);
                }
                if (!Reaches(k, p, pAbove, n, ref w.Counters, out float d, out float nl, out var l)) continue;
                float s = Specular(m, n, l, v, nl);
                AddTerm(w, k, TransferLobe.Diffuse, mi, weight * d * nl);
                if (m.HasSpecular) AddTerm(w, k, TransferLobe.Specular, mi, weight * d * s);
                if (depth == 0 && centre)
                {
                    if (k < 32) mask |= 1u << k;
                    _centreDiffuse[k][pixel] = d * nl;
                    _centreSpecular[k][pixel] = d * s;
                }
            }

            if (depth >= _scene.MaxDepth || !(m.HasMirror || m.HasTransmission)) return hit.Object;
            var next = w.Throughput.AsSpan((depth + 1) * _padded, _padded);
            float cosI = Vector3.Dot(n, v);
            if (m.HasMirror)
            {
                var dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
                w.Counters.Secondary++;
                float f = m.Fresnel ? WhittedIntegrator.FresnelDielectric(cosI, outside ? 1 / m.Ior[0] : m.Ior[0]) : 1f;
                Follow(new Ray(pAbove, dir), depth, w, weight, f, m.Mirror, mi, transmit: false, pixel);
            }
            if (m.HasTransmission)
            {
                float eta = outside ? 1f / m.Ior[0] : m.Ior[0];
                float sin2T = eta * eta * (1 - cosI * cosI);
                var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
                Vector3 dir, origin;
                float f = 1;
                if (sin2T >= 1)
                {
                    dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
                    origin = p + _geometry.Epsilon * ng;
                }
                else
                {
                    float cosT = MathF.Sqrt(1 - sin2T);
                    dir = Vector3.Normalize(eta * ray.Direction + (eta * cosI - cosT) * n);
                    origin = p - _geometry.Epsilon * ng;
                    if (m.Fresnel) f = 1 - WhittedIntegrator.FresnelDielectric(cosI, eta);
                }
                w.Counters.Secondary++;
                Follow(new Ray(origin, dir), depth, w, weight, f, m.Transmit, mi, transmit: true, pixel);
            }
            return hit.Object;
        }

        void Follow(Ray ray, int depth, Worker w, float weight, float f, float[] k, int mi, bool transmit, int pixel)
        {
            var tp = w.Throughput.AsSpan(depth * _padded, _padded);
            var next = w.Throughput.AsSpan((depth + 1) * _padded, _padded);
            for (int b = 0; b < _padded; b++) next[b] = tp[b] * k[b] * f;
            w.Chain[w.ChainLength++] = mi << 1 | (transmit ? 1 : 0);
            uint unused = 0;
            Radiance(ray, depth + 1, w, weight * f, pixel, ref unused, centre: false);
            w.ChainLength--;
        }

        static void AddStatic(Span<float> dst, ReadOnlySpan<float> tp, ReadOnlySpan<float> a, ReadOnlySpan<float> b, float s)
        {
            for (int i = 0; i < dst.Length; i++) dst[i] += tp[i] * (a[i] * b[i] * s);
        }

        void AddTerm(Worker w, int light, TransferLobe lobe, int material, float factor)
        {
            ulong a = (ulong)light | (ulong)lobe << 8 | (ulong)material << 10 | (ulong)w.ChainLength << 22;
            ulong b = 0;
            for (int c = 0; c < w.ChainLength; c++)
            {
                ulong e = (ulong)(w.Chain[c] + 1);   // 13 bits: material << 1 | transmit, + 1
                if (c < 2) a |= e << (26 + 16 * c); else b |= e << (16 * (c - 2));
            }
            var key = new Key(a, b);
            if (!w.Planes.TryGetValue(key, out var plane))
            {
                var chain = new (int, bool)[w.ChainLength];
                for (int c = 0; c < chain.Length; c++) chain[c] = (w.Chain[c] >> 1, (w.Chain[c] & 1) == 1);
                _components.TryAdd(key, new TransferComponent(light, lobe, material, chain));
                plane = _planes.GetOrAdd(key, _ => new float[_width * _height]);
                w.Planes[key] = plane;
            }
            for (int t = 0; t < w.Terms; t++)
                if (ReferenceEquals(w.TermPlanes[t], plane)) { w.TermFactors[t] += factor; return; }
            if (w.Terms == w.TermPlanes.Length)
            {
                Array.Resize(ref w.TermPlanes, w.Terms * 2);
                Array.Resize(ref w.TermFactors, w.Terms * 2);
            }
            w.TermPlanes[w.Terms] = plane;
            w.TermFactors[w.Terms++] = factor;
        }
    }
}
