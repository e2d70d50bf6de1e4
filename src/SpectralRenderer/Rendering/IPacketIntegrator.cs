using SpectralRenderer.Acceleration;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// An integrator that also takes camera rays a packet at a time (<see cref="RayPacket"/>: up to 16 rays as
/// SIMD lanes), which the <see cref="Renderer"/> then prefers for the scenes it says so (<see cref="PrefersPackets"/>).
/// Each lane must get exactly what
/// <see cref="IIntegrator.Radiance"/> gives its ray alone, so the picture does not depend on the path.
/// </summary>
public interface IPacketIntegrator : IIntegrator
{
    /// <summary>
    /// Whether <paramref name="scene"/>'s camera rays go in packets (the same picture either way: a scene the packet path
    /// does not take, e.g. one with mirrors or textures, is traced ray by ray).
    /// </summary>
    bool PrefersPackets(Scene scene) => true;

    /// <summary>
    /// The radiance of each active lane's camera ray into results[lane · padded bands …], the object hit (or −1)
    /// into objects[lane], what the ray saw into infos[lane], and into fallbacks[lane] whether one of its terms had to
    /// fall back to eq. 3 on the band values (<see cref="RayCounters.Fallback"/>). Allocates nothing.
    /// </summary>
    void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks,
        Span<float> scratch, ref RayCounters counters);
}
