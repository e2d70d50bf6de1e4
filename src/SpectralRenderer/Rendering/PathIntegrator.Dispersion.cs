using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Dispersion in the path tracer: a refracting material whose index varies over the bands (Cauchy or Sellmeier,
/// <see cref="Scenes.RefractiveIndex"/>) bends every wavelength its own way, so one direction cannot serve all bands. At
/// the first vertex of such a material the path splits deterministically into one sub-path per output band: sub-path b
/// carries β on band b's sub-bands only (the others 0) and from there on follows its own Fresnel reflection and refraction
/// with band b's index at its centre wavelength (the index the scene gives that band, as the Whitted integrator uses it),
/// at this and at every later vertex. The bands together are the whole path's estimate (β is their sum), each band
/// weighted by its own Fresnel factors, so there is no wavelength sampling and no chromatic noise.
/// Per output band, not per sub-band of the fine grid: the output keeps one index per band (docs/scene-format.md), and a
/// sub-path costs a whole path's spectral work, so splitting per sub-band would cost <see cref="FineGrid.PerBand"/> times
/// as much after the split for a refraction resolved finer than the film's bands.
/// Random numbers: every sub-path starts from a copy of the path's <see cref="Sampler"/> at the split, so all bands draw the
/// same dimensions (common random numbers: their noise is correlated, hence colourless) and the picture depends on the
/// camera sample only — the same for any thread count or shard. A path that meets no dispersive vertex draws exactly as
/// before. A dispersive material without transmission (a Fresnel mirror) needs no split: its direction is the same in
/// every band and <see cref="Scenes.Bsdf.SampleMirror"/> weights each band by its own F.
/// </summary>
internal sealed partial class PathIntegrator
{
    readonly bool[] _dispersive;   // per material: a transmitting material with a dispersive index

    /// <summary>
    /// Splits the path at <paramref name="hit"/> (reached along <paramref name="ray"/> at <paramref name="depth"/>, its
    /// emission already counted) into one sub-path per output band that β reaches, each walked by <see cref="WalkBand"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Disperse<TSink>(ref TSink sink, in SurfaceHit hit, Ray ray, int depth, Span<float> beta, Sampler sampler, Span<float> scratch,
        ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        int n = _padded, width = _grid.PerBand;
        var bandBeta = scratch.Slice(5 * n, n);
        for (int lo = 0; lo < _grid.Count; lo += width)
        {
            var part = beta.Slice(lo, width);
            if (!part.ContainsAnyExcept(0f)) continue;   // nothing of this band left to carry
            bandBeta.Clear();
            part.CopyTo(bandBeta.Slice(lo, width));
            WalkBand(ref sink, lo, hit, ray, depth, bandBeta, sampler, scratch, ref counters);
        }
    }

    /// <summary>
    /// One band's sub-path from the vertex <paramref name="hit"/> on: the walk of <see cref="Walk"/> (next-event estimation,
    /// lobe choice, MIS, Russian roulette, the same draws) with the delta lobes at sub-band <paramref name="band"/>'s index
    /// (any sub-band of the output band: they share its index).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void WalkBand<TSink>(ref TSink sink, int band, SurfaceHit hit, Ray ray, int depth, Span<float> beta, Sampler sampler, Span<float> scratch,
        ref RayCounters counters) where TSink : IPathSink, allows ref struct
    {
        int n = _padded;
        var f = scratch.Slice(2 * n, n);
        var mirror = scratch.Slice(3 * n, n);
        var transmit = scratch.Slice(4 * n, n);
        float pick = _lightCount > 0 ? 1f / _lightCount : 0;
        for (; ; )
        {
            var wo = -ray.Direction;
            var p = hit.Position;
            var ng = hit.GeometricNormal;
            int m = _objectMaterial[hit.Object];
            var bsdf = _bsdf[m];
            var ns = hit.Normal;
            var front = Vector3.Dot(ns, wo) >= 0 ? ns : -ns;
            float smoothShare = _smooth[m] ? _smoothChannel[m] : 0;
            float mirrorShare = 0, transmitShare = 0;
            Vector3 wiMirror = default, wiTransmit = default;
            if (_delta[m])
            {
                mirrorShare = bsdf.SampleMirror(wo, ns, band, mirror, out wiMirror) ? _grid.Luminance(mirror) : 0;
                transmitShare = bsdf.SampleTransmission(wo, ns, band, transmit, out wiTransmit) ? _grid.Luminance(transmit) : 0;
            }
            float total = smoothShare + mirrorShare + transmitShare;
            float smoothProbability = total > 0 ? smoothShare / total : 0;

            // The five dimensions of a vertex, as Walk reserves them.
            int dLight = sampler.Reserve1D(), dPoint = sampler.Reserve2D(), dLobe = sampler.Reserve1D(), dDirection = sampler.Reserve2D();
            int dRoulette = sampler.Reserve1D();
            if (_smooth[m] && _lightCount > 0)
            {
                float uLight = _lightCount > 1 ? sampler.At1D(dLight) : 0;
                var uPoint = sampler.At2D(dPoint);
                NextEvent(ref sink, bsdf, default, _shift[m], p, ng, ns, front, wo, uLight, new Vector2(uPoint.U, uPoint.V), pick, smoothProbability, beta, f, ref counters);
            }

            if (!(total > 0)) return;
            Vector3 wi;
            bool deltaBounce;
            float bsdfPdf = 0;
            float x = smoothShare == total ? 0 : sampler.At1D(dLobe) * total;
            if (x < smoothShare)
            {
                var u = sampler.At2D(dDirection);
                if (!bsdf.Sample(wo, ns, new Vector2(u.U, u.V), f, out var bs)) return;
                wi = bs.Wi;
                bsdfPdf = bs.Pdf * smoothProbability;
                Multiply(beta, f, MathF.Abs(Vector3.Dot(ns, wi)) / bsdfPdf);
                deltaBounce = false;
            }
            else if (x < smoothShare + mirrorShare)
            {
                wi = wiMirror;
                Multiply(beta, mirror, total / mirrorShare);
                deltaBounce = true;
            }
            else
            {
                wi = wiTransmit;
                Multiply(beta, transmit, total / transmitShare);
                deltaBounce = true;
            }

            if (depth + 1 >= _rrDepth)
            {
                float q = MathF.Min(0.95f, Max(beta));
                if (!(q > 0) || sampler.At1D(dRoulette) >= q) return;
                Scale(beta, 1 / q);
            }
            float side = Vector3.Dot(ng, wi) >= 0 ? 1 : -1;
            ray = new Ray(p + side * _geometry.Epsilon * ng, wi);
            counters.Secondary++;
            depth++;

            var traced = ray;
            if (!_geometry.IntersectScattered(ref traced, out hit))
            {
                if (_sky is not null) sink.Emitted(beta, _sky, deltaBounce ? 1 : PowerHeuristic(bsdfPdf, pick * SkyPdf(front, ray.Direction)));
                return;
            }
            int mh = _objectMaterial[hit.Object];
            var ngh = hit.GeometricNormal;
            if (_emission[mh] is { } le && (_twoSided[mh] || Vector3.Dot(ngh, -ray.Direction) > 0))
            {
                float w = 1;
                if (!deltaBounce)
                {
                    int e = _emitterOf[hit.Object];
                    w = PowerHeuristic(bsdfPdf, e >= 0 ? pick * _emitters[e].Pdf(p, hit.Position, ngh) : 0);
                }
                sink.Emitted(beta, le, w);
            }
            if (_maxDepth >= 0 && depth >= _maxDepth) return;
            if (counters.BudgetSpent) { counters.OverBudget = true; return; }
        }
    }
}
