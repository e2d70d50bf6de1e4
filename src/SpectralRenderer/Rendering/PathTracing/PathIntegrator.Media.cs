using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// The medium slot of the walk (PathIntegrator.cs). Every ray segment travels in one medium (<see cref="Medium"/>; −1:
/// vacuum): a camera ray in the scene's "medium"; a ray that leaves a vertex of an object that names an interior medium
/// travels in that medium when it goes into the object (against its outward geometric normal) and in the scene's medium
/// when it goes out; any other vertex keeps the medium its ray came in (a surface that names no medium is no boundary,
/// as pbrt-v4's primitives without a MediumInterface). <see cref="PathVertex.Medium"/> is the medium of the ray that
/// reached a vertex and <see cref="PathVertex.Interior"/> its object's interior, so next-event estimation knows its
/// shadow ray's. The walk multiplies β by the segment's transmittance T per band (Medium.Attenuate: the segment from
/// one vertex to the next, measured between the vertices, not from the ray's ε-offset origin; +∞ for a ray that escapes)
/// before it uses β at the segment's end, and next-event estimation multiplies f by T along the shadow ray (a shadow ray
/// is blocked by any surface, so it crosses no boundary) — in f, not in the light's spectrum, so the per-light transfer
/// keeps T and a relight stays exact. Absorption only: both MIS strategies see the same deterministic T, so the weights
/// are unchanged. Without media (every scene of today) no medium is read and no number changes: the pictures are the
/// same bit for bit. Issue 41 adds, here and at the segment in the walk, free-flight sampling against a majorant (a
/// scattering vertex with a phase function instead of a surface), ratio-tracking transmittance on shadow rays and the
/// Whitted integrator's Beer–Lambert.
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
        _interiorOf = scene.Objects.Select(o => o.Medium).ToArray();
        _sceneMedium = scene.Medium;
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
