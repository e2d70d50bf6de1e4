using System.Runtime.CompilerServices;

namespace SpectralRenderer.Rendering.PathTracing;

internal sealed partial class PathIntegrator
{
    /// <summary>
    /// One camera sample's radiance on the sub-band grid (<see cref="Grid"/>), before the film reduces it to output bands and
    /// XYZ: the film's walk (the same random numbers, the same decisions), its L_f copied into <paramref name="fine"/>
    /// (<see cref="SubBandGrid.Padded"/> floats). What <see cref="SubBandFilm"/> sums for the camera's exact signals.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal int SubBandRadiance(in CameraSample sample, Span<float> fine, Span<float> scratch, ref RayCounters counters)
    {
        var l = scratch[.._padded];
        l.Clear();
        var sink = new FilmSink(l, firstEmission: true);
        int first = Walk(ref sink, in sample, scratch, ref counters);
        l.CopyTo(fine);
        return first;
    }
}
