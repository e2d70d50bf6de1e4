using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// Every emitter of a scene in one index space (Mitsuba 3's <c>scene.emitters()</c>, SeeSharp's one emitter list): the
/// scene lights in their order (index k is <c>Scene.Lights[k]</c>), then the emitting objects in object order, then the
/// sky if the background is not black. Next-event estimation chooses one by <see cref="Choose"/> with probability
/// <see cref="SelectionPdf"/>, and a surface hit finds its emitter by its object (<see cref="OfObject"/>), an escaping ray the
/// sky's (<see cref="Sky"/>: a uniform <see cref="SkyEmitter"/>, a CIE overcast <see cref="OvercastSkyEmitter"/> — whose
/// escaping rays see the factor <see cref="Emitter.Emitted"/> of their direction on its radiance —, or an
/// <see cref="EnvironmentEmitter"/> for an image sky; any of them seen through the scene's window portals, a
/// <see cref="PortalSkyEmitter"/>). A new kind of
/// emitter plugs in as one file (a subclass of <see cref="Emitter"/>) and one line here; a new scene light kind or emissive shape kind
/// needs not even that (a <see cref="Light"/> subclass, a registered shape).
/// <para>
/// The choice is by power (pbrt-v4's <c>PowerLightSampler</c>), the emitter's radiant power over the grid's range,
/// Φ_k = <see cref="Emitter.PowerPerRadiance"/> · Σ_f L_f·Δλ_f in W (<see cref="Power"/>): radiant rather than luminous, because
/// the film keeps every band, invisible ones included (a UV lamp that excites a fluorescent surface must be drawn), and the
/// estimator's noise is in each band alike. The emitters fall in two groups, each given its share of the choice by its count
/// (N_g/N, N all emitters): the scene lights, whose spectra and intensities a relight may change (a choice by their power
/// would make a relit render differ in its noise from a render of the changed lights, which the per-light transfer promises
/// to equal: <c>PathRelightTests</c>), are chosen uniformly in theirs, P(k) = 1/N; the emitting objects and the sky, which a
/// relight keeps, by power in theirs, P(k) = (N_e/N)·Φ_k/Σ_e Φ_e (uniform in the group when it has no power at all). A scene
/// with emitting objects and a sky only is therefore chosen wholly by power, one with lights only uniformly. The choice is a
/// table lookup in the cumulative probabilities (no allocation).
/// </para>
/// <para>
/// Many lights: when a group holds at least <see cref="TreeThreshold"/> emitters with extent (emitting objects; scene lights
/// at a point), their summed P(k) becomes one entry of the table, redistributed among them by a <see cref="LightTree"/>
/// according to the shading point and normal — the emitting objects by their power, the scene lights by a power of 1 each
/// (so a relight still never changes the choice). Emitters at infinity (the sky, directional lights) keep their P(k)
/// (pbrt-v4's <c>BVHLightSampler</c> also draws its infinite lights apart). The probability of an emitter then depends
/// on the point (<see cref="SelectionPdf"/>), the same for the draw and for the MIS weight of a ray that hits it.
/// </para>
/// </summary>
internal sealed class EmitterSet
{
    readonly Emitter[] _emitters;
    readonly int[] _ofObject;
    readonly float[] _probability;        // P(k) of an emitter chosen by its fixed probability
    readonly int[] _entryEmitter;         // the table's entries: an emitter k, or ~t for light tree t
    readonly float[] _entryProbability;   // an entry's probability: P(k), or the sum over a tree's members
    readonly float[] _cumulative;         // Σ of the entries' probabilities up to each, the last 1
    readonly LightTree[] _trees;
    readonly int[]? _treeOf;              // by emitter: its light tree, −1 for none; null without trees
    readonly float[] _treeShare;          // by tree: its entry's probability
    readonly double _sceneRadius;

    /// <summary>The set of <paramref name="scene"/> on the sub-band grid <paramref name="grid"/>: an emitting object's radiance and
    /// sidedness from its material's emission (on the grid), its texture from <paramref name="emissionTexture"/> (by material;
    /// none when null), a light at infinity's power through the sphere of radius <paramref name="sceneRadius"/> about the
    /// scene's finite geometry (<see cref="SceneGeometry.BoundingRadius"/>; 1 when there is none); a group of at least
    /// <paramref name="treeThreshold"/> emitters with extent chosen by a light tree (the class summary).</summary>
    public EmitterSet(Scene scene, SubBandGrid grid, double sceneRadius, Func<int, SubBandTexture?>? emissionTexture = null,
        int treeThreshold = TreeThreshold)
    {
        _sceneRadius = sceneRadius > 0 ? sceneRadius : 1;
        var emitters = new List<Emitter>();
        for (int k = 0; k < scene.Lights.Count; k++)
            emitters.Add(new SceneLightEmitter(scene.Lights[k], k, grid.Resample(scene.Lights[k].Intensity)));
        _ofObject = new int[scene.Objects.Count];
        for (int i = 0; i < scene.Objects.Count; i++)
        {
            _ofObject[i] = -1;
            var o = scene.Objects[i];
            if (scene.Materials[o.Material].Emission is not { } emission) continue;
            _ofObject[i] = emitters.Count;
            var area = new AreaEmitter(o, grid.Resample(emission.Radiance), emission.TwoSided, $"{scene.SourcePath}: $.objects",
                emissionTexture?.Invoke(o.Material));
            emitters.Add(new ShapeEmitter(area, o.Name));
        }
        Background = grid.Resample(scene.Background);
        Sky = -1;
        if (Spectra.SpectralMath.Any(scene.Background))
        {
            Sky = emitters.Count;
            Emitter sky = scene.Environment is { } map ? Environment = new EnvironmentEmitter(map, grid)
                : scene.SkyDistribution == SkyDistribution.CieOvercast ? new OvercastSkyEmitter(Background, scene.Zenith)
                : new SkyEmitter(Background);
            // window portals: the sky drawn through them too (an environment map's radiance still looked up by direction)
            emitters.Add(scene.Portals.Count > 0 ? new PortalSkyEmitter(sky, scene.Portals) : sky);
        }
        _emitters = [.. emitters];
        Widths = new double[grid.Count];
        for (int f = 0; f < grid.Count; f++) Widths[f] = grid.Upper[f] - grid.Lower[f];
        Selection(treeThreshold, out _probability, out _entryEmitter, out _entryProbability, out _cumulative, out _trees, out _treeOf);
        _treeShare = [.. _trees.Select((_, t) => _entryProbability[Array.IndexOf(_entryEmitter, ~t)])];
    }

    /// <summary>
    /// P(k) of each emitter (the groups and shares of the class summary), then the table <see cref="Choose"/> searches: one
    /// entry per emitter, but one per light tree for the members of a tree (the group's emitters with extent, when there are
    /// at least <see cref="TreeThreshold"/>), whose share is the sum of its members' P(k), redistributed by the tree.
    /// </summary>
    void Selection(int treeThreshold, out float[] probability, out int[] entryEmitter, out float[] entryProbability, out float[] cumulative,
        out LightTree[] trees, out int[]? treeOf)
    {
        int n = _emitters.Length, lights = _emitters.Count(e => e.SceneLight >= 0), others = n - lights;
        var p = new double[n];
        double power = 0;
        for (int k = 0; k < n; k++) if (_emitters[k].SceneLight < 0) power += Power(k);
        for (int k = 0; k < n; k++)
            p[k] = _emitters[k].SceneLight >= 0 ? 1.0 / n
                : (double)others / n * (power > 0 ? Power(k) / power : 1.0 / others);
        probability = new float[n];
        for (int k = 0; k < n; k++) probability[k] = (float)p[k];
        // The light trees: the scene lights at a point by a power of 1 each (a relight changes their spectra and intensities,
        // never the choice), the emitting objects by their power.
        var treeList = new List<LightTree>();
        treeOf = null;
        foreach (bool sceneLights in (ReadOnlySpan<bool>)[true, false])
        {
            var members = new List<(int, EmitterBounds, double)>();
            double share = 0;
            for (int k = 0; k < n; k++)
                if ((_emitters[k].SceneLight >= 0) == sceneLights && _emitters[k].Bounds is { } b && p[k] > 0)
                {
                    members.Add((k, b, sceneLights ? 1 : Power(k)));
                    share += p[k];
                }
            if (members.Count < treeThreshold || !(share > 0)) continue;
            treeOf ??= Enumerable.Repeat(-1, n).ToArray();
            foreach (var (k, _, _) in members) treeOf[k] = treeList.Count;
            treeList.Add(new LightTree(members));
        }
        trees = [.. treeList];
        var entries = new List<(int Emitter, double P)>();
        var treeShare = new double[trees.Length];
        for (int k = 0; k < n; k++) if (treeOf is not null && treeOf[k] >= 0) treeShare[treeOf[k]] += p[k];
        var placed = new bool[trees.Length];
        for (int k = 0; k < n; k++)
        {
            int t = treeOf is null ? -1 : treeOf[k];
            if (t < 0) entries.Add((k, p[k]));
            else if (!placed[t]) { placed[t] = true; entries.Add((~t, treeShare[t])); }
        }
        int m = entries.Count;
        entryEmitter = new int[m];
        entryProbability = new float[m];
        cumulative = new float[m];
        double sum = 0;
        for (int e = 0; e < m; e++)
        {
            entryEmitter[e] = entries[e].Emitter;
            entryProbability[e] = (float)entries[e].P;
            sum += entries[e].P;
            cumulative[e] = (float)sum;
        }
        // The sums end at 1 from the last entry that can be chosen on, so a rounding gap never reaches one of P = 0.
        for (int e = m - 1; e >= 0; e--)
        {
            cumulative[e] = 1;
            if (entryProbability[e] > 0) break;
        }
    }

    /// <summary>
    /// The fewest emitters with extent of one group (scene lights at a point, or emitting objects) for which the group is
    /// chosen by a light tree rather than by its fixed probabilities alone, unless the scene's <c>"light_tree"</c> says
    /// otherwise. Measured (BENCHMARKS.md, "Many lights"): the tree already pays at 8 and 16 emitters (0.70× and 0.74× the
    /// error at equal time); 8 keeps every shipped scene (at most two emitters) as it was.
    /// </summary>
    public const int TreeThreshold = 8;

    /// <summary>The width Δλ_f (nm) of each sub-band of the grid.</summary>
    double[] Widths { get; }

    /// <summary>
    /// Φ_k, emitter <paramref name="k"/>'s radiant power (W) over the grid's range: its <see cref="Emitter.PowerPerRadiance"/>
    /// times Σ_f L_f·Δλ_f of its spectrum (a textured emitter's mean).
    /// </summary>
    public double Power(int k)
    {
        var radiance = _emitters[k].Radiance;
        double integral = 0;
        for (int f = 0; f < Widths.Length; f++) integral += radiance[f] * Widths[f];
        return _emitters[k].PowerPerRadiance(_sceneRadius) * integral;
    }

    /// <summary>The number of emitters N.</summary>
    public int Count => _emitters.Length;

    /// <summary>Emitter <paramref name="k"/> of the set.</summary>
    public Emitter this[int k] => _emitters[k];

    /// <summary>The emitters, in index order.</summary>
    public IReadOnlyList<Emitter> All => _emitters;

    /// <summary>The sky's index, or −1 when the background is black.</summary>
    public int Sky { get; }

    /// <summary>The sky's environment map (its radiance varies with direction: <see cref="EnvironmentEmitter.Lookup"/>), or null.</summary>
    public EnvironmentEmitter? Environment { get; }

    /// <summary>The background radiance on the sub-band grid (what a camera ray that escapes sees, × <see cref="SkySeen"/>; black
    /// without a sky).</summary>
    public float[] Background { get; }

    /// <summary>
    /// The factor on the sky's radiance of a ray that escapes in direction <paramref name="direction"/> (the sky's
    /// <see cref="Emitter.Emitted"/>: 1 for a uniform sky and an environment map, whose radiance is looked up instead).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float SkySeen(Vector3 direction) => Sky >= 0 ? _emitters[Sky].Emitted(default, -direction) : 1;

    /// <summary>The emitter of scene object <paramref name="obj"/> (its index), or −1 when it emits nothing.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int OfObject(int obj) => _ofObject[obj];

    /// <summary>
    /// The emitter that next-event estimation takes for <paramref name="u"/> ∈ [0, 1) at <paramref name="p"/> (normal
    /// <paramref name="n"/>, 0 in a medium), and its probability <paramref name="pick"/> (<see cref="SelectionPdf"/>): the
    /// first entry of the table whose running sum exceeds u (an entry of probability 0 is never taken) — an emitter, or a light
    /// tree walked with u rescaled within the entry —; −1 when a tree has no member that can shine towards p. The set must
    /// not be empty.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int Choose(Vector3 p, Vector3 n, float u, out float pick)
    {
        var c = _cumulative;
        int lo = 0, hi = c.Length - 1;
        while (lo < hi)
        {
            int mid = (lo + hi) >> 1;
            if (u < c[mid]) hi = mid;
            else lo = mid + 1;
        }
        int k = _entryEmitter[lo];
        pick = _entryProbability[lo];
        if (k >= 0) return k;
        float below = lo == 0 ? 0 : c[lo - 1];
        k = _trees[~k].Choose(p, n, MathF.Min((u - below) / pick, 0.99999994f), out float pmf);
        pick *= pmf;
        return k;
    }

    /// <summary>
    /// P(k | p, n), the probability that <see cref="Choose"/> at <paramref name="p"/> (normal <paramref name="n"/>) takes emitter
    /// <paramref name="k"/> (the class summary's P(k); a tree member's: its tree's share times the tree's probability at p).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float SelectionPdf(int k, Vector3 p, Vector3 n)
    {
        if (_treeOf is null || _treeOf[k] < 0) return _probability[k];
        int t = _treeOf[k];
        return _treeShare[t] * _trees[t].Pmf(p, n, k);
    }


    /// <summary>Is emitter <paramref name="k"/> chosen by a light tree (its probability varies with the point)?</summary>
    public bool InTree(int k) => _treeOf is not null && _treeOf[k] >= 0;
}
