using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A light-transport method: the spectral radiance a camera ray brings back. The <see cref="Renderer"/>
/// owns pixels, samples and threads; an integrator owns physics. Implementations must not allocate per call
/// (each thread hands in its own scratch) and must give the same result for the same ray on any thread.
/// </summary>
public interface IIntegrator
{
    /// <summary>Floats of scratch a thread needs for one <see cref="Radiance"/> call.</summary>
    int ScratchLength { get; }

    /// <summary>
    /// The radiance along camera ray <paramref name="ray"/> into <paramref name="result"/> (padded band values),
    /// recording in <paramref name="info"/> what the ray saw for the analysis images. Returns the object hit, or −1.
    /// </summary>
    int Radiance(Ray ray, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info);
}
