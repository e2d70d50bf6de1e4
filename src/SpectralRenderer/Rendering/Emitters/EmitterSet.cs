using System.Runtime.CompilerServices;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// Every emitter of a scene in one index space (Mitsuba 3's <c>scene.emitters()</c>, SeeSharp's one emitter list): the
/// scene lights in their order (index k is <c>Scene.Lights[k]</c>), then the emitting objects in object order, then the
/// sky if the background is not black. Next-event estimation chooses one by <see cref="Choose"/> with probability
/// <see cref="SelectionPdf"/>, and a surface hit finds its emitter by its object (<see cref="OfObject"/>), an escaping ray the
/// sky's (<see cref="Sky"/>). The choice is uniform, P(k) = 1/N (N the emitters' count). A new kind of emitter plugs in
/// as one file (a subclass of <see cref="Emitter"/>) and one line here; a new scene light kind or emissive shape kind
/// needs not even that (a <see cref="Light"/> subclass, a registered shape).
/// </summary>
internal sealed class EmitterSet
{
    readonly Emitter[] _emitters;
    readonly int[] _ofObject;
    readonly float _pick;

    /// <summary>The set of <paramref name="scene"/> on the sub-band grid <paramref name="grid"/>, an emitting object's radiance,
    /// sidedness and texture from its material's <paramref name="emission"/> (per material, null: none).</summary>
    public EmitterSet(Scene scene, SubBandGrid grid, IReadOnlyList<SurfaceEmission?> emission)
    {
        var emitters = new List<Emitter>();
        for (int k = 0; k < scene.Lights.Count; k++)
            emitters.Add(new SceneLightEmitter(scene.Lights[k], k, grid.Resample(scene.Lights[k].Intensity)));
        _ofObject = new int[scene.Objects.Count];
        for (int i = 0; i < scene.Objects.Count; i++)
        {
            _ofObject[i] = -1;
            var o = scene.Objects[i];
            if (emission[o.Material] is not { } e) continue;
            _ofObject[i] = emitters.Count;
            var area = new AreaEmitter(o, e.Radiance, e.TwoSided, $"{scene.SourcePath}: $.objects", e.Texture);
            emitters.Add(new ShapeEmitter(area, o.Name));
        }
        Background = grid.Resample(scene.Background);
        Sky = -1;
        if (Spectra.SpectralMath.Any(scene.Background))
        {
            Sky = emitters.Count;
            emitters.Add(new SkyEmitter(Background));
        }
        _emitters = [.. emitters];
        _pick = _emitters.Length > 0 ? 1f / _emitters.Length : 0;
    }

    /// <summary>The number of emitters N.</summary>
    public int Count => _emitters.Length;

    /// <summary>Emitter <paramref name="k"/> of the set.</summary>
    public Emitter this[int k] => _emitters[k];

    /// <summary>The emitters, in index order.</summary>
    public IReadOnlyList<Emitter> All => _emitters;

    /// <summary>The sky's index, or −1 when the background is black.</summary>
    public int Sky { get; }

    /// <summary>The background radiance on the sub-band grid (what a camera ray that escapes sees; black without a sky).</summary>
    public float[] Background { get; }

    /// <summary>The emitter of scene object <paramref name="obj"/> (its index), or −1 when it emits nothing.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int OfObject(int obj) => _ofObject[obj];

    /// <summary>The emitter that next-event estimation takes for <paramref name="u"/> ∈ [0, 1): uniform over the set.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int Choose(float u) => Math.Min((int)(u * _emitters.Length), _emitters.Length - 1);

    /// <summary>P(k), the probability that <see cref="Choose"/> takes emitter <paramref name="k"/>: 1/N (0 for an empty set).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float SelectionPdf(int k) => _pick;
}
