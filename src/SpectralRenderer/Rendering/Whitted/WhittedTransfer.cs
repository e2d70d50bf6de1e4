using System.Collections.Concurrent;
using System.Diagnostics;
using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Whitted;

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
/// A textured term (issue 26) has a texel per pixel, not one P: it is recorded per entry as V = Σ F × the filtered texel
/// samples (the walker's taps on the texture's own sample levels) and relit as Σ_i V_i · P_i (+ F × a fluorescent shift),
/// P_i the new light's product with sample i's tent function (<see cref="TransferComponent.TexelColumns"/>).
/// </summary>
[CompiledAtFirstCall]
internal sealed partial class WhittedTransfer
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
    /// Per component, for a textured one (<see cref="TransferComponent.Texture"/>), the texel samples of each of its entries
    /// (S floats per entry, in the order of <see cref="Pixels"/>): Σ over the pixel's terms of the factor × the filtered
    /// texel samples (trilinear taps of the texture's sample levels, <see cref="TexturedTerms.SamplesOf"/>); null entries
    /// (or a null array) for components of spectra.
    /// </summary>
    public float[]?[]? Texels { get; init; }
    /// <summary>Per pixel <see cref="CentreWidth"/> floats: the centre ray's filtered texel samples at its first hit, its
    /// material's diffuse texture's then its specular texture's (the highlight mask's Y of a textured lobe); null without
    /// textures.</summary>
    public float[]? CentreTexels { get; init; }
    public int CentreWidth { get; init; }
    /// <summary>
    /// The render folder whose lights/*.npy this transfer was read from when they are byte for byte what writing it
    /// gives (WhittedTransferFiles): a relit render copies them instead of encoding them again. Null for a traced transfer.
    /// </summary>
    public string? StoredIn { get; init; }

    public const int MaxChain = 6;

    /// <summary>Floats per pixel of the centre texels: the most any material's diffuse and specular textures' samples take.</summary>
    public static int CentreWidthOf(Scene scene) =>
        scene.Materials.Select(m => (m.DiffuseTexture?.Texture.Samples ?? 0) + (m.SpecularTexture?.Texture.Samples ?? 0))
            .DefaultIfEmpty(0).Max();

    /// <summary>
    /// Bytes the texel samples of a traced transfer hold at most for a first hit (the memory check; a mirror or glass adds
    /// its own): per pixel every light's textured diffuse, ambient and specular terms' samples and the centre ray's, twice
    /// (the tiles' and the assembled arrays), and the textures' sample levels. 0 without textures.
    /// </summary>
    public static long TexelBytes(Scene scene)
    {
        int lights = scene.Lights.Count;
        long perPixel = 0, levels = 0;
        foreach (var m in scene.Materials)
        {
            int d = m.DiffuseTexture?.Texture.Samples ?? 0, sp = m.SpecularTexture?.Texture.Samples ?? 0;
            bool ambient = TextureTables.AmbientIsTexture(m);
            perPixel = Math.Max(perPixel, (long)lights * (d * (ambient ? 2 : 1) + sp) + (ambient ? d : 0));
            foreach (var b in new[] { m.DiffuseTexture, m.SpecularTexture })
                if (b is not null) levels += TexelLevels.TexelsWithMips(b.Texture.Width, b.Texture.Height) * b.Texture.Samples;
        }
        if (perPixel == 0) return 0;
        long pixels = (long)scene.Camera.Width * scene.Camera.Height;
        return sizeof(float) * (pixels * (2 * perPixel + CentreWidthOf(scene)) + levels);
    }

    /// <summary>Traces the scene's camera rays and records S, the factors and the centre-ray data.</summary>
    public static WhittedTransfer Trace(Scene scene, SceneGeometry geometry, int threads = 0, CancellationToken cancel = default)
    {
        if (scene.MaxDepth > MaxChain)
            throw new InputException("max_depth", $"the 'lights' output supports max_depth ≤ {MaxChain}, the scene has {scene.MaxDepth}",
                $"set max_depth to {MaxChain} or less");
        if (scene.Lights.Count > 254 || scene.Materials.Count > 4094)
            throw new InputException("lights", "the 'lights' output supports at most 255 lights and 4095 materials",
                "render fewer lights or materials with the 'lights' output");
        if (scene.Media.Count > 0)   // a factor per term and light is a scalar: Beer–Lambert per band does not fit in it
            throw new InputException($"{scene.SourcePath}: $.medium",
                "the whitted integrator's 'lights' output does not carry participating media",
                "drop 'lights' from --formats, or render with \"integrator\": \"path\" (whose 'lights' output does)");
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
        var tables = new TermTables(scene, TexelContent.None);
        var p = new float[Components.Length][];
        var columns = new double[Components.Length][];
        var constants = new double[Components.Length][];
        for (int c = 0; c < p.Length; c++)
        {
            p[c] = new float[padded];
            Components[c].BandValues(tables, p[c]);
            if (Texels?[c] is not null)
                columns[c] = Components[c].TexelColumns(scene, tables, out constants[c])
                    ?? throw new InvalidOperationException($"component {Components[c].Key} has texels but its term is not textured");
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
                if (columns[c] is { } cols)
                {
                    AddTextured(c, cols, constants[c], i0, i1, data, xyz, bands, padded);
                    continue;
                }
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

    /// <summary>
    /// Textured component <paramref name="c"/>'s entries in pixels [i0, i1): per entry Σ_i V_i · column_i + F · constant in
    /// doubles (the bands, then X, Y, Z), added to the pixel as the untextured components' F · P are.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void AddTextured(int c, double[] columns, double[] constant, int i0, int i1, float[] data, float[] xyz, int bands, int padded)
    {
        var pix = Pixels[c];
        var f = Factors[c];
        var texels = Texels![c]!;
        int samples = columns.Length / padded;
        int j = Array.BinarySearch(pix, i0);
        if (j < 0) j = ~j;
        for (; j < pix.Length && pix[j] < i1; j++)
        {
            int i = pix[j];
            var v = texels.AsSpan(j * samples, samples);
            for (int r = 0; r < bands + SpectralMath.ColourLanes; r++)
            {
                double sum = f[j] * constant[r];
                for (int s = 0; s < samples; s++) sum += v[s] * columns[s * padded + r];
                if (r < bands) data[i * bands + r] += (float)sum;
                else xyz[3 * i + r - bands] += (float)sum;
            }
        }
    }

    /// <summary>The highlight mask (<see cref="PixelInfo.Highlight"/>) from the luminances of eq. 2's terms at the centre rays, under new
    /// light band values.</summary>
    public byte[] CentreHighlights(Scene scene)
    {
        var tables = new TermTables(scene, TexelContent.None);
        int n = Width * Height, lights = scene.Lights.Count, y = scene.Bands + 1;   // the Y colour lane
        var diffuse = new float[n]; var specular = new float[n];
        // A textured lobe's Y per light and material: the Y row of its texel columns (with the texel-independent part).
        var texturedY = new (double[] Row, double Constant)?[2, lights * scene.Materials.Count];
        if (CentreTexels is not null)
            for (int k = 0; k < lights; k++)
                for (int m = 0; m < scene.Materials.Count; m++)
                    for (int lobe = 0; lobe < 2; lobe++)
                    {
                        var comp = new TransferComponent(k, lobe == 0 ? TransferLobe.Diffuse : TransferLobe.Specular, m, []);
                        if (comp.TexelColumns(scene, tables, out var constant) is not { } cols) continue;
                        int samples = cols.Length / scene.PaddedBands;
                        var row = Enumerable.Range(0, samples).Select(s => cols[s * scene.PaddedBands + y]).ToArray();
                        texturedY[lobe, tables.Index(k, m)] = (row, constant[y]);
                    }
        for (int i = 0; i < n; i++)
        {
            int o = ObjectIds[i];
            if (o < 0) continue;
            int m = scene.Objects[o].Material;
            for (int k = 0; k < lights; k++)
            {
                int term = tables.Index(k, m);
                float dy = tables.Diffuse[term][y], sy = tables.Specular[term][y];
                if (texturedY[0, term] is { } td) dy = CentreY(td, i, 0);
                if (texturedY[1, term] is { } ts) sy = CentreY(ts, i, scene.Materials[m].DiffuseTexture?.Texture.Samples ?? 0);
                diffuse[i] += CentreDiffuse[k][i] * dy;
                specular[i] += CentreSpecular[k][i] * sy;
            }
        }
        var mask = new byte[n];
        float fraction = (float)scene.Output.HighlightFraction;
        for (int i = 0; i < n; i++) mask[i] = PixelInfo.Highlight(specular[i], diffuse[i], fraction);
        return mask;
    }

    /// <summary>Y of a textured lobe at pixel <paramref name="i"/>'s centre hit: its Y row times the centre's texel samples
    /// (from <paramref name="at"/> in the pixel's centre texels), plus the texel-independent part.</summary>
    float CentreY((double[] Row, double Constant) t, int i, int at)
    {
        var v = CentreTexels.AsSpan(i * CentreWidth + at, t.Row.Length);
        double y = t.Constant;
        for (int s = 0; s < v.Length; s++) y += v[s] * t.Row[s];
        return (float)y;
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
        // Per tile, its terms in pixel order: (component, pixel, factor, where its texel samples start or −1), and the samples.
        readonly ConcurrentBag<(int[] Comp, int[] Pixel, float[] Factor, int Count, int[] TexelAt, float[] Texels)> _tiles = [];
        readonly float[]? _centreTexels;
        readonly int _centreWidth;
        readonly float[][] _centreDiffuse, _centreSpecular;
        readonly TermTables _tables;
        readonly Eq2Walker _walker;
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
            // Textured lobes: the walker's taps index each texture's own samples (the same levels as its tables), recorded per term.
            _tables = new TermTables(scene, TexelContent.Samples);
            _centreWidth = CentreWidthOf(scene);
            if (_centreWidth > 0) _centreTexels = new float[(long)_width * _height * _centreWidth];
            _walker = new Eq2Walker(scene, geometry, _tables);
            _fallback = new bool[_width * _height];
        }

        sealed class Worker
        {
            public readonly int[] Chain = new int[MaxChain + 1];
            public int ChainLength;
            // Per depth, the path's scalar weight and the band its parent carried.
            public readonly float[] Weights = new float[MaxChain + 2];
            public readonly int[] Bands = new int[MaxChain + 1];
            // The camera sample's pixel; for the centre ray, the lights that reach its first hit.
            public int Pixel;
            public bool Centre;
            public uint Mask;
            // The band the current path carries after a dispersive split (−1: all bands), as the integrator's band argument.
            public int Band = -1;
            public readonly Dictionary<Key, int> Index = new();
            // The current pixel's terms: component and accumulated factor (few distinct ones per pixel), and for a textured
            // term where its samples (Σ factor × filtered texel) start in TermTexels and how many (−1, 0: a spectrum's term).
            public int[] TermComps = new int[64];
            public float[] TermFactors = new float[64];
            public int[] TermTexelAt = new int[64], TermTexelCount = new int[64];
            public float[] TermTexels = new float[256];
            public int Terms, TermTexelsUsed;
            public bool Fallback;
            // The hit's textured lobes and their taps (set by Texels after the walker's Begin, until the next Begin).
            public bool Textured;
            public TexturedTerms? Diffuse, Specular;
            public TexelTaps DiffuseTaps, SpecularTaps;
            // The current tile's terms.
            public int[] TileComp = new int[4096], TilePixel = new int[4096], TileTexelAt = new int[4096];
            public float[] TileFactor = new float[4096];
            public float[] TileTexels = new float[256];
            public int TileCount, TileTexelsUsed;

            public void Emit(int pixel)
            {
                if (TileCount + Terms > TileComp.Length)
                {
                    int size = Math.Max(TileComp.Length * 2, TileCount + Terms);
                    Array.Resize(ref TileComp, size); Array.Resize(ref TilePixel, size); Array.Resize(ref TileFactor, size);
                    Array.Resize(ref TileTexelAt, size);
                }
                if (TileTexelsUsed + TermTexelsUsed > TileTexels.Length)
                    Array.Resize(ref TileTexels, Math.Max(TileTexels.Length * 2, TileTexelsUsed + TermTexelsUsed));
                for (int t = 0; t < Terms; t++)
                {
                    if (TermFactors[t] == 0) continue;
                    TileComp[TileCount] = TermComps[t]; TilePixel[TileCount] = pixel; TileFactor[TileCount] = TermFactors[t];
                    int at = -1;
                    if (TermTexelAt[t] >= 0)
                    {
                        at = TileTexelsUsed;
                        TermTexels.AsSpan(TermTexelAt[t], TermTexelCount[t]).CopyTo(TileTexels.AsSpan(at));
                        TileTexelsUsed += TermTexelCount[t];
                    }
                    TileTexelAt[TileCount++] = at;
                }
            }

            /// <summary>The taps of the lobe a term of <paramref name="lobe"/> takes at this hit, or null (its spectrum).</summary>
            public TexturedTerms? TexelsOf(TransferLobe lobe, out TexelTaps taps)
            {
                taps = default;
                if (!Textured) return null;
                switch (lobe)
                {
                    case TransferLobe.Diffuse:
                        taps = DiffuseTaps; return Diffuse;
                    case TransferLobe.Specular:
                        taps = SpecularTaps; return Specular;
                    case TransferLobe.Ambient or TransferLobe.GlobalAmbient when Diffuse is { Ambient: true }:
                        taps = DiffuseTaps; return Diffuse;
                    default:
                        return null;
                }
            }
        }

        public WhittedTransfer Run(int threads, CancellationToken cancel)
        {
            int width = _width, height = _height, bands = _scene.Bands;
            var ids = new int[width * height];
            var lit = new uint[width * height];
            // The renderer's own loop (tiles, threads, jitter, weights 1/spp, the centre ray of weight 0) over the whole film.
            var sampling = new PixelSampling(_scene.Camera, _scene.RayBudget, analysis: true);
            var (total, _, _) = Renderer.RunTiles(PixelRect.Whole(width, height), threads, null, Stopwatch.StartNew(), cancel,
                () => new TileWork(this, sampling, ids, lit, cancel));

            var (components, pixels, factors, merged, texels) = Assemble(width * height);
            return new WhittedTransfer
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
                Texels = texels,
                CentreTexels = _centreTexels,
                CentreWidth = _centreWidth,
            };
        }

        /// <summary>
        /// The tiles' terms gathered per component (pixels ascending), components that the renderer cannot tell apart
        /// merged (same light, term and material, and the same band values of the chain's weights: glass paths that
        /// differ only in which of two unit weights they took), in a fixed order whatever the thread count.
        /// </summary>
        (TransferComponent[], int[][], float[][], int[], float[]?[]?) Assemble(int n)
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
                var weightBytes = System.Runtime.InteropServices.MemoryMarshal.AsBytes(weights.AsSpan(0, _scene.Bands));
                groupKey[c] = $"{comp.Light}:{(int)comp.Lobe}:{comp.Material}@{comp.Band}:{Convert.ToHexString(weightBytes)}";
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
            // A textured group's samples per entry (its chains are one material's: one texture, S samples).
            var samples = groups.Select(g => _registered[g[0]].Texture(_scene)?.Samples ?? 0).ToArray();
            var tex = counts.Select((c, g) => samples[g] > 0 ? new float[(long)c * samples[g]] : null).ToArray();
            var fill = new int[groups.Length];
            foreach (var t in _tiles.OrderBy(t => t.Count == 0 ? -1 : t.Pixel[0]))
                for (int j = 0; j < t.Count; j++)
                {
                    int g = groupOf[t.Comp[j]], at = fill[g]++;
                    pix[g][at] = t.Pixel[j]; fac[g][at] = t.Factor[j];
                    if (tex[g] is { } v) t.Texels.AsSpan(t.TexelAt[j], samples[g]).CopyTo(v.AsSpan(at * samples[g]));
                }
            Parallel.For(0, groups.Length, g =>
            {
                // Stable: within a pixel the terms keep their trace order, so the sum is the same for any thread count.
                var order = Enumerable.Range(0, pix[g].Length).OrderBy(j => pix[g][j]).ToArray();
                var p2 = new List<int>(order.Length); var f2 = new List<float>(order.Length);
                int s = samples[g];
                var v = tex[g];
                var v2 = v is null ? null : new float[v.Length];
                foreach (int j in order)
                {
                    bool same = p2.Count > 0 && p2[^1] == pix[g][j];
                    if (same) f2[^1] += fac[g][j];
                    else { p2.Add(pix[g][j]); f2.Add(fac[g][j]); }
                    if (v is null) continue;
                    var into = v2.AsSpan((p2.Count - 1) * s, s);
                    var from = v.AsSpan(j * s, s);
                    if (same) for (int i = 0; i < s; i++) into[i] += from[i];
                    else from.CopyTo(into);
                }
                pix[g] = p2.ToArray(); fac[g] = f2.ToArray();
                if (v2 is not null) tex[g] = v2.AsSpan(0, p2.Count * s).ToArray();
            });
            _ = n;
            return (groups.Select(g => _registered[g[0]]).ToArray(), pix, fac, groups.Select(g => g.Length).ToArray(),
                tex.Any(v => v is not null) ? tex : null);
        }

        /// <summary>A worker's tiles: each pixel's camera samples (<see cref="Renderer.SampleTile"/>) traced into its terms.</summary>
        sealed class TileWork(Tracer t, PixelSampling sampling, int[] ids, uint[] lit, CancellationToken cancel) : ITileWork
        {
            readonly Worker _w = new();

            public void Tile(int x0, int y0, int x1, int y1, ref RayCounters counters)
            {
                _w.TileCount = 0;
                _w.TileTexelsUsed = 0;
                var sink = new TransferSamples(t, _w, ids, lit);
                Renderer.SampleTile(ref sink, in sampling, x0, y0, x1, y1, cancel, ref counters);
                t._tiles.Add((_w.TileComp[.._w.TileCount], _w.TilePixel[.._w.TileCount], _w.TileFactor[.._w.TileCount], _w.TileCount,
                    _w.TileTexelAt[.._w.TileCount], _w.TileTexels[.._w.TileTexelsUsed]));
            }
        }

        /// <summary>A pixel's camera samples as terms with weight 1/spp (the centre ray's weigh 0: only its centre-ray data
        /// is kept).</summary>
        struct TransferSamples(Tracer t, Worker w, int[] ids, uint[] lit) : ISampleSink
        {
            uint _mask;

            public void BeginPixel(int x, int y, ref RayCounters counters)
            {
                w.Terms = 0;
                w.TermTexelsUsed = 0;
                w.Fallback = false;
                _mask = 0;
            }

            public int Sample(in CameraSample sample, float weight, bool centre, ref RayCounters counters) =>
                t.Primary(sample.Ray, w, weight, sample.Y * t._width + sample.X, ref _mask, centre, ref counters);

            public readonly void EndPixel(int x, int y, int id, ref RayCounters counters)
            {
                int i = y * t._width + x;
                w.Emit(i);
                t._fallback[i] = w.Fallback;
                ids[i] = id;
                lit[i] = _mask;
            }
        }

        /// <summary>A camera sample of weight <paramref name="weight"/> (1/spp): radiance terms into the worker.</summary>
        int Primary(Ray ray, Worker w, float weight, int pixel, ref uint mask, bool centre, ref RayCounters counters)
        {
            w.ChainLength = 0;
            w.Band = -1;
            w.Weights[0] = weight;
            w.Pixel = pixel;
            w.Centre = centre;
            w.Mask = 0;
            var sink = new TransferSink(this, w);
            int id = _walker.Trace(ref sink, ray, 0, -1, 1f, ref counters);
            if (centre) mask = w.Mask;
            return id;
        }

        /// <summary>
        /// Eq. 2's terms as the walker visits them (<see cref="Eq2Walker"/>), each recorded as its component's factor times the
        /// path's scalar weight (1/spp times the Fresnel factors along it); the chain of mirror and transmission weights is
        /// pushed on entering a branch and popped on leaving it. Nothing is pruned or cut by a budget; a dispersive Fresnel
        /// mirror's reflected ray is followed once per band as one-band components (counted as one ray).
        /// </summary>
        readonly struct TransferSink(Tracer t, Worker w) : IWalkSink
        {
            public static bool Prunes => false;
            public static bool Budgeted => false;
            public static bool ReflectPerBand => true;

            float Weight => w.Weights[w.ChainLength];

            public void Begin() => w.Textured = false;

            /// <summary>A textured lobe's taps (into the texture's sample levels) for the terms that follow; the centre ray's
            /// first hit keeps its filtered samples (the highlight mask's Y under new lights).</summary>
            public void Texels(TexturedTerms terms, in TexelTaps taps)
            {
                if (!w.Textured) { w.Diffuse = null; w.Specular = null; w.Textured = true; }
                int at = 0;
                if (terms.Lobe == TexturedLobe.Diffuse) { w.Diffuse = terms; w.DiffuseTaps = taps; }
                else { at = w.Diffuse?.Stride ?? 0; w.Specular = terms; w.SpecularTaps = taps; }
                if (w.ChainLength == 0 && w.Centre && t._centreTexels is { } centre)
                {
                    var into = centre.AsSpan(w.Pixel * t._centreWidth + at, terms.Stride);
                    into.Clear();
                    Filter(terms, in taps, 1f, into);
                }
            }

            public void Background()
            {
                if (SpectralMath.Any(t._scene.Background)) t.AddTerm(w, -1, TransferLobe.Background, -1, Weight);
            }

            public void GlobalAmbient(int material) => t.AddTerm(w, -1, TransferLobe.GlobalAmbient, material, Weight);
            public void Ambient(int light, int material, int term, float spot) =>
                t.AddTerm(w, light, TransferLobe.Ambient, material, Weight * spot);

            public void Direct(int light, int material, int term, float d, float nl, float s, bool specular)
            {
                float weight = Weight;
                t.AddTerm(w, light, TransferLobe.Diffuse, material, weight * d * nl);
                if (specular) t.AddTerm(w, light, TransferLobe.Specular, material, weight * d * s);
                if (w.ChainLength == 0 && w.Centre)
                {
                    if (light < 32) w.Mask |= 1u << light;
                    t._centreDiffuse[light][w.Pixel] = d * nl;
                    t._centreSpecular[light][w.Pixel] = d * s;
                }
            }

            public void Split(ref RayCounters counters) => w.Fallback = true;

            // Never asked: a scene with media has no Whitted transfer (Trace refuses it).
            public Span<float> Transmittance => default;
            public void DirectThrough(int light, int material, int term, float d, float nl, float s, bool specular,
                ReadOnlySpan<float> transmittance) => throw new InvalidOperationException("no transfer through media");
            public void Attenuate(Medium medium, Vector3 origin, Vector3 direction, float distance, ref RayCounters counters) =>
                throw new InvalidOperationException("no transfer through media");

            public void Enter(int material, bool transmit, int band, float factor)
            {
                if (transmit ? t._tables.TransmitColoured[material] : t._tables.MirrorColoured[material]) w.Fallback = true;
                w.Bands[w.ChainLength] = w.Band;
                w.Band = band;
                w.Weights[w.ChainLength + 1] = Weight * factor;
                w.Chain[w.ChainLength++] = material << 1 | (transmit ? 1 : 0);
            }

            public void Leave(int material, bool transmit, int band, float factor, ref RayCounters counters) =>
                w.Band = w.Bands[--w.ChainLength];

            public void LeavePerBand(Material m, int material, float cosI, bool outside, ref RayCounters counters) =>
                throw new UnreachableException("the transfer follows a per-band mirror once per band");
        }

        /// <summary>Σ over the taps of weight × <paramref name="factor"/> × the texel's samples, added into
        /// <paramref name="into"/>.</summary>
        static void Filter(TexturedTerms terms, in TexelTaps taps, float factor, Span<float> into)
        {
            for (int i = 0; i < taps.Count; i++)
            {
                float wgt = factor * taps.Weight[i];
                var texel = terms.Tap(in taps, i)[..into.Length];
                for (int j = 0; j < into.Length; j++) into[j] += wgt * texel[j];
            }
        }

        void AddTerm(Worker w, int light, TransferLobe lobe, int material, float factor)
        {
            if (factor == 0) return;
            var texels = w.TexelsOf(lobe, out var taps);
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
                if (w.TermComps[t] == index)
                {
                    w.TermFactors[t] += factor;
                    if (texels is not null) Filter(texels, in taps, factor, w.TermTexels.AsSpan(w.TermTexelAt[t], w.TermTexelCount[t]));
                    return;
                }
            if (w.Terms == w.TermComps.Length)
            {
                Array.Resize(ref w.TermComps, w.Terms * 2);
                Array.Resize(ref w.TermFactors, w.Terms * 2);
                Array.Resize(ref w.TermTexelAt, w.Terms * 2);
                Array.Resize(ref w.TermTexelCount, w.Terms * 2);
            }
            w.TermComps[w.Terms] = index;
            w.TermFactors[w.Terms] = factor;
            w.TermTexelAt[w.Terms] = -1;
            w.TermTexelCount[w.Terms] = 0;
            if (texels is not null)
            {
                int s = texels.Stride;
                if (w.TermTexelsUsed + s > w.TermTexels.Length)
                    Array.Resize(ref w.TermTexels, Math.Max(w.TermTexels.Length * 2, w.TermTexelsUsed + s));
                var into = w.TermTexels.AsSpan(w.TermTexelsUsed, s);
                into.Clear();
                Filter(texels, in taps, factor, into);
                w.TermTexelAt[w.Terms] = w.TermTexelsUsed;
                w.TermTexelCount[w.Terms] = s;
                w.TermTexelsUsed += s;
            }
            w.Terms++;
        }
    }
}
