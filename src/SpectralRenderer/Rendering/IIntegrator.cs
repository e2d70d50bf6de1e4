using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A light-transport method: the spectral radiance a camera sample brings back. The <see cref="Renderer"/>
/// owns pixels, samples and threads and hands each camera sample (pixel, sample index, camera ray and a
/// <see cref="Sampler"/> for further random numbers); an integrator owns physics. Implementations must not allocate
/// per call (each thread hands in its own scratch) and must give the same result for the same sample on any thread.
/// </summary>
public interface IIntegrator
{
    /// <summary>Floats of scratch a thread needs for one <see cref="Radiance"/> call.</summary>
    int ScratchLength { get; }

    /// <summary>
    /// The radiance of camera sample <paramref name="sample"/> into <paramref name="result"/> (padded band values: the
    /// bands, then X, Y, Z in the colour lanes). Returns the object the camera ray hits first, or −1.
    /// </summary>
    int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters);

    /// <summary>The sampler its camera samples carry (<see cref="SamplerKind.Independent"/> unless it asks for another).</summary>
    SamplerSettings Sampler => SamplerSettings.Independent;
}

/// <summary>
/// An integrator that can also record what a camera ray saw for the analysis images (<see cref="PixelInfo"/>: lights
/// reaching the point, luminance of eq. 2's diffuse and specular terms). The renderer asks it for the centre rays only;
/// without it the analysis images hold the object hit and nothing else.
/// </summary>
public interface IAnalysisIntegrator : IIntegrator
{
    /// <summary>As <see cref="IIntegrator.Radiance"/>, recording in <paramref name="info"/> what the ray saw.</summary>
    int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info);
}
