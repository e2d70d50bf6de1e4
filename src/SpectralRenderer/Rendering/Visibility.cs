using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

/// <summary>
/// The one rule for whether a light sample is seen from a surface point, with its epsilon policy — used by Whitted's walk
/// (<c>Eq2Walker</c>) and its packets (<c>LaneGeometry.PointLight</c>, the same operations in SIMD lanes), the path tracer's
/// next-event estimation and the illuminance gather; the path tracer's and the gather's other rays leave a surface the same
/// way (Whitted's mirror and refracted rays leave on the viewer's and the far side, <c>Eq2Walker</c>). A ray leaves point p
/// from p offset by ε (the scene's <see cref="SceneGeometry.Epsilon"/>) along ±n_g, on the side of the surface its direction
/// ω goes to (so light through a transmitting surface is tested from its far side). A shadow ray towards a sample at distance
/// d is aimed from there at the sample's point p + d·ω_i itself (an offset ray parallel to ω_i meets a curved emitter, a
/// sphere grazed, before the point) and ends 2ε short of it; towards a sample at infinity it goes along ω_i, unbounded.
/// </summary>
internal static class Visibility
{
    /// <summary>The ray from surface point <paramref name="p"/> (geometric normal <paramref name="ng"/>, either way round)
    /// along <paramref name="direction"/>: its origin offset by ε along ±n_g on the direction's side.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Ray Leaving(Vector3 p, Vector3 ng, Vector3 direction, float epsilon) =>
        new(Origin(p, ng, direction, epsilon), direction);

    /// <summary>
    /// The shadow ray from surface point <paramref name="p"/> (geometric normal <paramref name="ng"/>) to a light sample along
    /// <paramref name="wi"/> at <paramref name="distance"/> (∞: a direction): the sample is seen when it meets nothing.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Ray ShadowRay(Vector3 p, Vector3 ng, Vector3 wi, float distance, float epsilon)
    {
        var origin = Origin(p, ng, wi, epsilon);
        if (float.IsInfinity(distance)) return new Ray(origin, wi);
        var towards = p + distance * wi - origin;
        float length = towards.Length();
        return new Ray(origin, towards / length, length - 2 * epsilon);
    }

    /// <summary>p + s·ε·n_g, s = 1 where n_g·ω ≥ 0, else −1.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static Vector3 Origin(Vector3 p, Vector3 ng, Vector3 direction, float epsilon)
    {
        float side = Vector3.Dot(ng, direction) >= 0 ? 1 : -1;
        return p + side * epsilon * ng;
    }
}
