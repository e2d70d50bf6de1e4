using System.Collections.Concurrent;
using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Which term of eq. 2 a component is: light k through the diffuse or specular lobe (these follow the light's spectrum),
/// light k's own ambient spectrum I_amb,k·m_amb, the global ambient a_glob·m_amb, or the background radiance.
/// </summary>
public enum TransferLobe { Diffuse, Specular, Ambient, GlobalAmbient, Background }

/// <summary>
/// One spectral component of a pixel's radiance: a term of eq. 2 (<see cref="Lobe"/>) of light <see cref="Light"/>
/// (−1 for the global ambient and the background) at material <see cref="Material"/> (−1 for the background), reached
/// from the camera through the mirror (k_r) and transmission (k_t) weights of the materials in <see cref="Chain"/>
/// (first bounce first). Its band values are P_b = E_b · m_b · Π k_chain,b with E the light's spectrum × intensity
/// (diffuse, specular), its ambient spectrum, or a_glob, and m the lobe's reflectance — the products eq. 2 and the
/// Whitted recursion form in every band. A component reached through a dispersive material carries one band only
/// (<see cref="Band"/> ≥ 0): there each band follows its own path, as the integrator traces it.
/// </summary>
public sealed record TransferComponent(int Light, TransferLobe Lobe, int Material, (int Material, bool Transmit)[] Chain)
{
    /// <summary>The one band (0-based) this component reaches, after a dispersive split; −1 for all bands.</summary>
    public int Band { get; init; } = -1;

    /// <summary>Does the component follow light k's spectrum and intensity (diffuse and specular terms)?</summary>
    public bool FollowsLight => Lobe is TransferLobe.Diffuse or TransferLobe.Specular;

    public static string LobeName(TransferLobe l) => l switch
    {
        TransferLobe.Diffuse => "diffuse",
        TransferLobe.Specular => "specular",
        TransferLobe.Ambient => "ambient",
        TransferLobe.GlobalAmbient => "global-ambient",
        _ => "background",
    };

    public static TransferLobe ParseLobe(string s) => s switch
    {
        "diffuse" => TransferLobe.Diffuse,
        "specular" => TransferLobe.Specular,
        "ambient" => TransferLobe.Ambient,
        "global-ambient" => TransferLobe.GlobalAmbient,
        "background" => TransferLobe.Background,
        _ => throw new InputException("lights.json", $"unknown component lobe '{s}'", "the light-transfer files are damaged: render the folder again"),
    };

    /// <summary>A stable text key such as <c>0:diffuse:2</c>, <c>1:specular:3&lt;mirror:1</c> or, for band 5 only, <c>0:diffuse:2&lt;transmit:0@5</c>.</summary>
    public string Key => $"{Light}:{LobeName(Lobe)}:{Material}" +
        string.Concat(Chain.Reverse().Select(c => $"<{(c.Transmit ? "transmit" : "mirror")}:{c.Material}")) + (Band >= 0 ? $"@{Band + 1}" : "");

    /// <summary>
    /// P into <paramref name="dst"/> (padded: the bands, then X, Y, Z in the colour lanes): the scene's term table of this
    /// component (<see cref="TermTables"/>: exact band means of E·m and κ∫x̄E·m dλ, with the radiometry's constants) times
    /// the mirror and transmission weights along the chain, as the integrator multiplies them.
    /// </summary>
    public void BandValues(TermTables tables, Span<float> dst)
    {
        ReadOnlySpan<float> t = Lobe switch
        {
            TransferLobe.Diffuse => tables.Diffuse[tables.Index(Light, Material)],
            TransferLobe.Specular => tables.Specular[tables.Index(Light, Material)],
            TransferLobe.Ambient => tables.Ambient[tables.Index(Light, Material)],
            TransferLobe.GlobalAmbient => tables.GlobalAmbient[Material],
            _ => tables.Background,
        };
        t.CopyTo(dst);
        foreach (var (cm, tr) in Chain)
        {
            var w = tr ? tables.Transmit[cm] : tables.Mirror[cm];
            for (int b = 0; b < dst.Length; b++) dst[b] *= w[b];
        }
        if (Band >= 0)
        {   // One band only; its colour is eq. 3 on the band values (such pixels take the renderer's colour fallback).
            float v = dst[Band];
            dst.Clear();
            dst[Band] = v;
        }
    }

    /// <summary>Does the chain pass a mirror or transmittance that varies over the bands, or a dispersive split (so the colour lanes cannot be exact)?</summary>
    public bool Coloured(TermTables tables) => Band >= 0 || Chain.Any(c => c.Transmit ? tables.TransmitColoured[c.Material] : tables.MirrorColoured[c.Material]);

}

/// <summary>
/// Per-light transfer of a render: light transport in eq. 2 and the Whitted recursion is linear in each light's
/// spectrum, so a pixel's band values are L_b = Σ_c F_c · P_c,b over the spectral components c the pixel's rays
/// meet (<see cref="TransferComponent"/>: each light's diffuse and specular terms, each light's own ambient, the
/// global ambient and the background, per material and mirror/glass chain), with F_c the per-pixel geometric
/// factor (c_spot · d_k · max(0, n·l) for diffuse, c_spot · d_k · (n·h)^shininess for specular, c_spot for a light's
/// ambient, 1 for the global ambient and the background, times the Fresnel weights along the path, averaged over
/// the pixel's samples). Changing a light's spectrum or
/// intensity changes only P: <see cref="Relight"/> recomputes the image exactly as a render with those lights
/// computes it (the band values of this band scheme are products of band means, so P carries them exactly).
/// The tracer follows <see cref="WhittedIntegrator"/> ray for ray (same camera rays, jitter, shadow rays,
/// epsilons, Fresnel and total internal reflection, and a dispersive material's per-band paths: each band's refracted
/// ray, and for its per-band Fresnel reflectance the reflected ray once per band, recorded as one-band components).
/// </summary>
public sealed class LightTransfer
{
    public required int Width { get; init; }
    public required int Height { get; init; }
    public required int Bands { get; init; }
    /// <summary>Components in a fixed order (sorted by light, then key), whatever the thread count.</summary>
    public required TransferComponent[] Components { get; init; }
    /// <summary>Per component, the pixels (y·W + x, ascending) where its factor is not zero …</summary>
    public required int[][] Pixels { get; init; }
    /// <summary>… and the factors there.</summary>
    public required float[][] Factors { get; init; }
    /// <summary>Per component, how many traced components (chains with the same weights) were merged into it.</summary>
    public required int[] Merged { get; init; }
    public required Spectra.BandGrid Grid { get; init; }
    /// <summary>Per light, the centre ray's diffuse factor d·c_spot·(n·l) at its first hit (for the highlight mask), W × H.</summary>
    public required float[][] CentreDiffuse { get; init; }
    public required float[][] CentreSpecular { get; init; }
    public required int[] ObjectIds { get; init; }
    public required uint[] LitMasks { get; init; }
    /// <summary>Per pixel: did a path meet a coloured mirror or transmittance (the renderer's colour fallback to eq. 3)?</summary>
    public required bool[] Fallback { get; init; }
    public required RayCounters Rays { get; init; }
    /// <summary>
    /// The render folder whose lights/*.npy this transfer was read from when they are byte for byte what writing it
    /// gives (LightTransferFiles): a relit render copies them instead of encoding them again. Null for a traced transfer.
    /// </summary>
    public string? StoredIn { get; init; }

    public const int MaxChain = 6;

    /// <summary>Traces the scene's camera rays and records S, the factors and the centre-ray data.</summary>
    public static LightTransfer Trace(Scene scene, SceneGeometry geometry, int threads = 0, CancellationToken cancel = default)
    {
        if (scene.MaxDepth > MaxChain)
            throw new InputException("max_depth", $"the 'lights' output supports max_depth ≤ {MaxChain}, the scene has {scene.MaxDepth}", $"set max_depth to {MaxChain} or less");
        if (scene.Lights.Count > 254 || scene.Materials.Count > 4094)
            throw new InputException("lights", "the 'lights' output supports at most 255 lights and 4095 materials", "render fewer lights or materials with the 'lights' output");
        var t = new Tracer(scene, geometry);
        return t.Run(threads, cancel);
    }

    /// <summary>
    /// The image of <paramref name="scene"/> (the render's scene with its lights changed): Σ_c F_c · P_c with the
    /// scene's light band values (spectrum × intensity), on all cores.
    /// </summary>
    public (SpectralImage Image, float[] Xyz, long FallbackPixels) Relight(Scene scene)
    {
        int n = Width * Height, bands = Bands, padded = scene.PaddedBands;
        var tables = new TermTables(scene);
        var p = new float[Components.Length][];
        for (int c = 0; c < p.Length; c++)
        {
            p[c] = new float[padded];
            Components[c].BandValues(tables, p[c]);
        }
        var image = new SpectralImage(Width, Height, Grid);
        var data = image.Data;
        var xyz = new float[3 * n];
        // Pixel ranges in parallel: each component's run inside a range is found by binary search (pixels ascend).
        const int Chunk = 8192;
        Parallel.For(0, (n + Chunk - 1) / Chunk, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (chunk) =>
        {
            int i0 = chunk * Chunk, i1 = Math.Min(n, i0 + Chunk);
            for (int c = 0; c < p.Length; c++)
            {
                var pix = Pixels[c];
                var f = Factors[c];
                var pc = p[c];
                float cx = pc[bands], cy = pc[bands + 1], cz = pc[bands + 2];
                int j = Array.BinarySearch(pix, i0);
                if (j < 0) j = ~j;
                for (; j < pix.Length && pix[j] < i1; j++)
                {
                    float fi = f[j];
                    int i = pix[j];
                    var px = data.AsSpan(i * bands, bands);
                    // px[b] + fi·pc[b] per band, a vector of bands at a time (the same multiply and add per lane, no fused multiply-add).
                    int b = 0;
                    if (Vector.IsHardwareAccelerated)
                    {
                        var vf = new Vector<float>(fi);
                        for (; b + Vector<float>.Count <= bands; b += Vector<float>.Count)
                            (new Vector<float>(px[b..]) + vf * new Vector<float>(pc, b)).CopyTo(px[b..]);
                    }
                    for (; b < bands; b++) px[b] += fi * pc[b];
                    xyz[3 * i] += fi * cx; xyz[3 * i + 1] += fi * cy; xyz[3 * i + 2] += fi * cz;
                }
            }
        });
        // Where a path met a coloured weight the renderer takes eq. 3 on the band values; so does the relit render.
        long fallback = 0;
        for (int i = 0; i < n; i++)
        {
            if (!Fallback[i]) continue;
            var c = scene.Colorimeter.ToXyz((ReadOnlySpan<float>)data.AsSpan(i * bands, bands));
            xyz[3 * i] = (float)c.X; xyz[3 * i + 1] = (float)c.Y; xyz[3 * i + 2] = (float)c.Z;
            fallback++;
        }
        return (image, xyz, fallback);
    }

    /// <summary>The highlight mask (<see cref="PixelInfo.Highlight"/>) from the luminances of eq. 2's terms at the centre rays, under new light band values.</summary>
    public byte[] CentreHighlights(Scene scene)
    {
        var tables = new TermTables(scene);
        int n = Width * Height, lights = scene.Lights.Count, y = scene.Bands + 1;   // the Y colour lane
        var diffuse = new float[n]; var specular = new float[n];
        for (int i = 0; i < n; i++)
        {
            int o = ObjectIds[i];
            if (o < 0) continue;
            int m = scene.Objects[o].Material;
            for (int k = 0; k < lights; k++)
            {
                int term = tables.Index(k, m);
                diffuse[i] += CentreDiffuse[k][i] * tables.Diffuse[term][y];
                specular[i] += CentreSpecular[k][i] * tables.Specular[term][y];
            }
        }
        var mask = new byte[n];
        float fraction = (float)scene.Output.HighlightFraction;
        for (int i = 0; i < n; i++) mask[i] = PixelInfo.Highlight(specular[i], diffuse[i], fraction);
        return mask;
    }

    readonly record struct Key(ulong A, ulong B, int Band);

    sealed class Tracer
    {
        readonly Scene _scene;
        readonly SceneGeometry _geometry;
        readonly Material[] _materials;
        readonly Light[] _lights;
        readonly int[] _objectMaterial;
        readonly int _padded, _width, _height;
        readonly ConcurrentDictionary<Key, int> _index = new();
        readonly List<TransferComponent> _registered = [];
        // Per tile, its terms in pixel order: (component, pixel, factor).
        readonly ConcurrentBag<(int[] Comp, int[] Pixel, float[] Factor, int Count)> _tiles = [];
        readonly float[][] _centreDiffuse, _centreSpecular;
        readonly TermTables _tables;
        readonly bool _physical;
        readonly bool[] _fallback;

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
            _tables = new TermTables(scene);
            _physical = scene.Radiometry == Radiometry.Physical;
            _fallback = new bool[_width * _height];
        }

        sealed class Worker
        {
            public readonly int[] Chain = new int[MaxChain + 1];
            public int ChainLength;
            // The band the current path carries after a dispersive split (−1: all bands), as the integrator's band argument.
            public int Band = -1;
            public readonly Dictionary<Key, int> Index = new();
            // The current pixel's terms: component and accumulated factor (few distinct ones per pixel).
            public int[] TermComps = new int[64];
            public float[] TermFactors = new float[64];
            public int Terms;
            public bool Fallback;
            // The current tile's terms.
            public int[] TileComp = new int[4096], TilePixel = new int[4096];
            public float[] TileFactor = new float[4096];
            public int TileCount;
            public RayCounters Counters;

            public void Emit(int pixel)
            {
                if (TileCount + Terms > TileComp.Length)
                {
                    int size = Math.Max(TileComp.Length * 2, TileCount + Terms);
                    Array.Resize(ref TileComp, size); Array.Resize(ref TilePixel, size); Array.Resize(ref TileFactor, size);
                }
                for (int t = 0; t < Terms; t++)
                {
                    if (TermFactors[t] == 0) continue;
                    TileComp[TileCount] = TermComps[t]; TilePixel[TileCount] = pixel; TileFactor[TileCount++] = TermFactors[t];
                }
            }
        }

        public LightTransfer Run(int threads, CancellationToken cancel)
        {
            var cam = _scene.Camera;
            int width = _width, height = _height, bands = _scene.Bands, padded = _padded;
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
                var w = new Worker();
                int tile;
                while ((tile = Interlocked.Increment(ref next)) < tiles)
                {
                    cancel.ThrowIfCancellationRequested();
                    w.TileCount = 0;
                    int x0 = tile % tilesX * Renderer.TileSize, y0 = tile / tilesX * Renderer.TileSize;
                    int x1 = Math.Min(width, x0 + Renderer.TileSize), y1 = Math.Min(height, y0 + Renderer.TileSize);
                    for (int y = y0; y < y1; y++)
                        for (int x = x0; x < x1; x++)
                        {
                            int i = y * width + x;
                            w.Terms = 0;
                            w.Fallback = false;
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
                                // The centre ray for the analysis data, traced as the renderer traces it (its radiance weighs 0).
                                w.Counters.Primary++;
                                id = Primary(cam.Generate(x + 0.5f, y + 0.5f), w, 0f, i, ref mask, centre: true);
                            }
                            w.Emit(i);
                            _fallback[i] = w.Fallback;
                            ids[i] = id;
                            lit[i] = mask;
                        }
                    _tiles.Add((w.TileComp[..w.TileCount], w.TilePixel[..w.TileCount], w.TileFactor[..w.TileCount], w.TileCount));
                }
                lock (gate) total.Add(w.Counters);
            }
            var workers = new Task[Math.Min(threads, tiles)];
            for (int k = 0; k < workers.Length; k++) workers[k] = Task.Factory.StartNew(Work, cancel, TaskCreationOptions.None, TaskScheduler.Default);
            try { Task.WaitAll(workers); }
            catch (AggregateException e) when (e.InnerExceptions.All(x => x is OperationCanceledException)) { throw new OperationCanceledException(cancel); }

            var (components, pixels, factors, merged) = Assemble(width * height);
            return new LightTransfer
            {
                Width = width,
                Height = height,
                Bands = bands,
                Grid = _scene.Grid,
                Components = components,
                Pixels = pixels,
                Factors = factors,
                Merged = merged,
                CentreDiffuse = _centreDiffuse,
                CentreSpecular = _centreSpecular,
                Fallback = _fallback,
                ObjectIds = ids,
                LitMasks = lit,
                Rays = total,
            };
        }

        /// <summary>
        /// The tiles' terms gathered per component (pixels ascending), components that the renderer cannot tell apart
        /// merged (same light, term and material, and the same band values of the chain's weights: glass paths that
        /// differ only in which of two unit weights they took), in a fixed order whatever the thread count.
        /// </summary>
        (TransferComponent[], int[][], float[][], int[]) Assemble(int n)
        {
            int registered = _registered.Count;
            var groupKey = new string[registered];
            var weights = new float[_padded];
            for (int c = 0; c < registered; c++)
            {
                var comp = _registered[c];
                Array.Fill(weights, 1f);
                foreach (var (m, t) in comp.Chain)
                    for (int b = 0; b < _scene.Bands; b++) weights[b] *= t ? _materials[m].Transmit[b] : _materials[m].Mirror[b];
                if (comp.Band >= 0) for (int b = 0; b < _scene.Bands; b++) if (b != comp.Band) weights[b] = 0;
                groupKey[c] = $"{comp.Light}:{(int)comp.Lobe}:{comp.Material}@{comp.Band}:{Convert.ToHexString(System.Runtime.InteropServices.MemoryMarshal.AsBytes(weights.AsSpan(0, _scene.Bands)))}";
            }
            // One representative per group: the component with the smallest key (shortest chains first).
            var groups = Enumerable.Range(0, registered).GroupBy(c => groupKey[c])
                .Select(g => g.OrderBy(c => _registered[c].Chain.Length).ThenBy(c => _registered[c].Key, StringComparer.Ordinal).ToArray())
                .OrderBy(g => _registered[g[0]].Light).ThenBy(g => _registered[g[0]].Key, StringComparer.Ordinal).ToArray();
            var groupOf = new int[registered];
            for (int g = 0; g < groups.Length; g++) foreach (int c in groups[g]) groupOf[c] = g;
            // Count, then fill per group its (pixel, factor) pairs, sort by pixel and sum the terms a merge brought together.
            var counts = new int[groups.Length];
            foreach (var t in _tiles) for (int j = 0; j < t.Count; j++) counts[groupOf[t.Comp[j]]]++;
            var pix = counts.Select(c => new int[c]).ToArray();
            var fac = counts.Select(c => new float[c]).ToArray();
            var fill = new int[groups.Length];
            foreach (var t in _tiles.OrderBy(t => t.Count == 0 ? -1 : t.Pixel[0]))
                for (int j = 0; j < t.Count; j++)
                {
                    int g = groupOf[t.Comp[j]], at = fill[g]++;
                    pix[g][at] = t.Pixel[j]; fac[g][at] = t.Factor[j];
                }
            Parallel.For(0, groups.Length, g =>
            {
                // Stable: within a pixel the terms keep their trace order, so the sum is the same for any thread count.
                var order = Enumerable.Range(0, pix[g].Length).OrderBy(j => pix[g][j]).ToArray();
                var p2 = new List<int>(order.Length); var f2 = new List<float>(order.Length);
                foreach (int j in order)
                {
                    if (p2.Count > 0 && p2[^1] == pix[g][j]) f2[^1] += fac[g][j];
                    else { p2.Add(pix[g][j]); f2.Add(fac[g][j]); }
                }
                pix[g] = p2.ToArray(); fac[g] = f2.ToArray();
            });
            _ = n;
            return (groups.Select(g => _registered[g[0]]).ToArray(), pix, fac, groups.Select(g => g.Length).ToArray());
        }

        /// <summary>A camera sample of weight <paramref name="weight"/> (1/spp): radiance terms into the worker.</summary>
        int Primary(Ray ray, Worker w, float weight, int pixel, ref uint mask, bool centre)
        {
            w.ChainLength = 0;
            w.Band = -1;
            return Radiance(ray, 0, w, weight, pixel, ref mask, centre);
        }

        void Local(in Ray ray, in SurfaceHit hit, Material m, out Vector3 n, out Vector3 v, out Vector3 pAbove, out bool outside)
        {
            v = -ray.Direction;
            outside = Vector3.Dot(hit.GeometricNormal, v) >= 0;
            var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
            n = outside ? hit.Normal : -hit.Normal;
            pAbove = hit.Position + _geometry.Epsilon * ng;
        }

        /// <summary>Is the lit side facing the light (n·l &gt; 0) and the shadow ray unblocked? n·l, as the integrator tests it.</summary>
        bool Lit(in LightSample ls, Vector3 pAbove, Vector3 n, ref RayCounters counters, out float nl)
        {
            nl = Vector3.Dot(n, ls.Direction);
            if (nl <= 0) return false;
            counters.Shadow++;
            var shadowRay = new Ray(pAbove, ls.Direction, float.IsInfinity(ls.Distance) ? float.PositiveInfinity : ls.Distance - 2 * _geometry.Epsilon);
            return !_geometry.Occluded(shadowRay);
        }

        /// <summary>
        /// Eq. 2 at the hit, as <see cref="WhittedIntegrator.Radiance(Ray, int, int, float, Span{float}, Span{float}, ref RayCounters, ref PixelInfo)"/>
        /// computes it, each term recorded as its component's factor times the path's scalar weight <paramref name="weight"/>
        /// (1/spp times the Fresnel factors along it).
        /// </summary>
        int Radiance(Ray ray, int depth, Worker w, float weight, int pixel, ref uint mask, bool centre)
        {
            if (!_geometry.Intersect(ref ray, out var hit))
            {
                if (SpectralMath.Any(_scene.Background)) AddTerm(w, -1, TransferLobe.Background, -1, weight);
                return -1;
            }
            int mi = _objectMaterial[hit.Object];
            var m = _materials[mi];
            Local(ray, hit, m, out var n, out var v, out var pAbove, out bool outside);
            var p = hit.Position;
            if (_scene.HasGlobalAmbient && m.HasAmbient) AddTerm(w, -1, TransferLobe.GlobalAmbient, mi, weight);

            for (int k = 0; k < _lights.Length; k++)
            {
                var light = _lights[k];
                if (!light.Illuminate(p, out var ls)) continue;
                // The light's own ambient spectrum enters wherever the light reaches the point (before n·l and shadows).
                if (light.HasAmbient && m.HasAmbient) AddTerm(w, k, TransferLobe.Ambient, mi, weight * ls.Spot);
                if (!Lit(ls, pAbove, n, ref w.Counters, out float nl)) continue;
                float d = ls.Attenuation * ls.Spot;
                // Physical: the specular lobe is a BRDF, weighted by cos θ_i like the diffuse one (as the integrator does).
                float s = m.HasSpecular ? m.SpecularFactor(n, ls.Direction, v, nl) * (_physical ? nl : 1f) : 0;
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
            float cosI = Vector3.Dot(n, v);
            if (m.HasMirror)
            {
                var dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
                w.Counters.Secondary++;
                if (m.Fresnel && m.Dispersive && w.Band < 0)
                {
                    // F from each band's own index: the integrator traces the reflected ray once and weights band b by F_b;
                    // here its terms are recorded once per band, as one-band components (the ray counts as one).
                    w.Fallback = true;
                    var counted = w.Counters;
                    for (int b = 0; b < _scene.Bands; b++)
                    {
                        w.Band = b;
                        Follow(new Ray(pAbove, dir), depth, w, weight, m.MirrorFactor(cosI, outside, b), mi, transmit: false, pixel);
                        if (b == 0) counted = w.Counters;
                    }
                    w.Band = -1;
                    w.Counters = counted;
                }
                else Follow(new Ray(pAbove, dir), depth, w, weight, m.MirrorFactor(cosI, outside, w.Band), mi, transmit: false, pixel);
            }
            if (m.HasTransmission)
            {
                if (!m.Dispersive || w.Band >= 0) Refract(ray, hit, m, mi, n, cosI, outside, depth, w, weight, pixel);
                else
                {
                    // Dispersion: every band bends by its own index, so each gets its own refracted ray (one-band components).
                    w.Fallback = true;
                    for (int b = 0; b < _scene.Bands; b++)
                    {
                        w.Band = b;
                        Refract(ray, hit, m, mi, n, cosI, outside, depth, w, weight, pixel);
                    }
                    w.Band = -1;
                }
            }
            return hit.Object;
        }

        /// <summary>k_t·L(refracted) for the band the path carries (all when −1), as the integrator's Refract.</summary>
        void Refract(in Ray ray, in SurfaceHit hit, Material m, int mi, Vector3 n, float cosI, bool outside, int depth, Worker w, float weight, int pixel)
        {
            var p = hit.Position;
            float eta = m.Eta(outside, w.Band);
            float sin2T = eta * eta * (1 - cosI * cosI);
            var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
            Vector3 dir, origin;
            float f = 1;
            if (sin2T >= 1)
            {
                // Total internal reflection: with Fresnel nothing is transmitted (F = 1 on the mirror lobe).
                if (m.Fresnel) return;
                dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
                origin = p + _geometry.Epsilon * ng;
            }
            else
            {
                float cosT = MathF.Sqrt(1 - sin2T);
                dir = Vector3.Normalize(eta * ray.Direction + (eta * cosI - cosT) * n);
                origin = p - _geometry.Epsilon * ng;
                f = m.TransmitFactor(cosI, eta);
            }
            w.Counters.Secondary++;
            Follow(new Ray(origin, dir), depth, w, weight, f, mi, transmit: true, pixel);
        }

        void Follow(Ray ray, int depth, Worker w, float weight, float f, int mi, bool transmit, int pixel)
        {
            if (transmit ? _tables.TransmitColoured[mi] : _tables.MirrorColoured[mi]) w.Fallback = true;
            w.Chain[w.ChainLength++] = mi << 1 | (transmit ? 1 : 0);
            uint unused = 0;
            Radiance(ray, depth + 1, w, weight * f, pixel, ref unused, centre: false);
            w.ChainLength--;
        }

        void AddTerm(Worker w, int light, TransferLobe lobe, int material, float factor)
        {
            if (factor == 0) return;
            // light + 1 (8 bits), lobe (3), material + 1 (12), chain length (3), then 16 bits per chain element.
            ulong a = (uint)(light + 1) | (ulong)(uint)lobe << 8 | (ulong)(uint)(material + 1) << 11 | (ulong)(uint)w.ChainLength << 23;
            ulong b = 0;
            for (int c = 0; c < w.ChainLength; c++)
            {
                ulong e = (ulong)(w.Chain[c] + 1);   // 13 bits: material << 1 | transmit, + 1
                if (c < 2) a |= e << (26 + 16 * c); else b |= e << (16 * (c - 2));
            }
            var key = new Key(a, b, w.Band);
            if (!w.Index.TryGetValue(key, out int index))
            {
                var chain = new (int, bool)[w.ChainLength];
                for (int c = 0; c < chain.Length; c++) chain[c] = (w.Chain[c] >> 1, (w.Chain[c] & 1) == 1);
                lock (_registered)
                {
                    if (!_index.TryGetValue(key, out index))
                    {
                        index = _registered.Count;
                        _registered.Add(new TransferComponent(light, lobe, material, chain) { Band = w.Band });
                        _index[key] = index;
                    }
                }
                w.Index[key] = index;
            }
            for (int t = 0; t < w.Terms; t++)
                if (w.TermComps[t] == index) { w.TermFactors[t] += factor; return; }
            if (w.Terms == w.TermComps.Length)
            {
                Array.Resize(ref w.TermComps, w.Terms * 2);
                Array.Resize(ref w.TermFactors, w.Terms * 2);
            }
            w.TermComps[w.Terms] = index;
            w.TermFactors[w.Terms++] = factor;
        }
    }
}
