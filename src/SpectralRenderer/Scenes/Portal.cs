using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A window portal (<c>"portal": true</c> on a quad): a rectangle in an opening through which the sky lights the inside,
/// the parallelogram <see cref="Corner"/> + a·<see cref="Edge1"/> + b·<see cref="Edge2"/> (a, b ∈ [0, 1]) with the unit
/// <see cref="Normal"/> pointing into the room. It is no object: rays pass through it; the path tracer draws sky directions
/// through it from points on its inner side (Rendering/Emitters/PortalSkyEmitter.cs).
/// </summary>
public sealed record Portal(string Name, Vector3 Corner, Vector3 Edge1, Vector3 Edge2, Vector3 Normal)
{
    /// <summary>The portal's area.</summary>
    public float Area { get; } = Vector3.Cross(Edge1, Edge2).Length();
}
