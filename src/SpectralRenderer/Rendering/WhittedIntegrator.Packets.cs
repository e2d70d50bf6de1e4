using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// Camera rays in packets: the closest hits of up to 16 camera rays found together, then, light by light, the
// shadow rays of all lanes towards that light traced as one packet, and eq. 2 evaluated per lane over the bands
// (SIMD over bands). Every lane adds its terms in the order the single-ray Radiance does, so each pixel gets the
// same bits. A lane whose surface reflects or transmits (a Whitted recursion) is traced again alone.
public sealed partial class WhittedIntegrator
{
    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    public void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks, Span<float> scratch, ref RayCounters counters)
    {
        Span<SurfaceHit> hits = stackalloc SurfaceHit[RayPacket.Size];
        Span<Vector3> normals = stackalloc Vector3[RayPacket.Size];
        Span<Vector3> above = stackalloc Vector3[RayPacket.Size];
        Span<Vector3> toViewer = stackalloc Vector3[RayPacket.Size];
        Span<Vector3> toLight = stackalloc Vector3[RayPacket.Size];
        Span<float> attenuation = stackalloc float[RayPacket.Size];
        Span<float> cosine = stackalloc float[RayPacket.Size];
        Span<float> spotFactor = stackalloc float[RayPacket.Size];
        Span<int> material = stackalloc int[RayPacket.Size];
        uint found = _geometry.Intersect(ref packet, hits);
        uint shaded = 0;
        for (uint all = packet.Active; all != 0; all &= all - 1)
        {
            int lane = BitOperations.TrailingZeroCount(all);
            var result = results.Slice(lane * _padded, _padded);
            infos[lane] = default;
            fallbacks[lane] = false;
            if ((found >> lane & 1) == 0)
            {
                result.Clear();
                _tables.Background.AsSpan().CopyTo(result);
                objects[lane] = -1;
                continue;
            }
            ref var hit = ref hits[lane];
            int mi = _objectMaterial[hit.Object];
            var m = _materials[mi];
            objects[lane] = hit.Object;
            if (_scene.MaxDepth > 0 && (m.HasMirror || m.HasTransmission))
            {
                // The recursion is traced ray by ray.
                long before = counters.Fallback;
                Radiance(packet.Ray(lane) with { TMax = float.PositiveInfinity }, 0, -1, 1f, result, scratch, ref counters, ref infos[lane]);
                fallbacks[lane] = counters.Fallback != before;
                continue;
            }
            result.Clear();
            var d = new Vector3(packet.DirectionX[lane], packet.DirectionY[lane], packet.DirectionZ[lane]);
            var v = -d;
            bool outside = Vector3.Dot(hit.GeometricNormal, v) >= 0;
            var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
            normals[lane] = outside ? hit.Normal : -hit.Normal;
            above[lane] = hit.Position + _geometry.Epsilon * ng;
            toViewer[lane] = v;
            material[lane] = mi;
            if (_scene.HasGlobalAmbient && m.HasAmbient) SpectralMath.AddScaled(result, _tables.GlobalAmbient[mi], 1f);
            shaded |= 1u << lane;
        }
        if (shaded == 0) return;

        Unsafe.SkipInit(out RayPacket shadows);   // 1.6 KB, not zeroed: Set fills each lane it uses
        float eps = _geometry.Epsilon;
        for (int k = 0; k < _lights.Length; k++)
        {
            var light = _lights[k];
            shadows.Clear();
            for (uint all = shaded; all != 0; all &= all - 1)
            {
                int lane = BitOperations.TrailingZeroCount(all);
                if (!light.Illuminate(hits[lane].Position, out var ls)) continue;
                var l = ls.Direction;
                float dist = ls.Distance, spot = ls.Spot;
                var m = _materials[material[lane]];
                int term = _tables.Index(k, material[lane]);
                if (light.HasAmbient && m.HasAmbient) SpectralMath.AddScaled(results.Slice(lane * _padded, _padded), _tables.Ambient[term], spot);
                float nl = Vector3.Dot(normals[lane], l);
                if (nl <= 0) continue;
                counters.Shadow++;
                shadows.Set(lane, new Ray(above[lane], l, float.IsInfinity(dist) ? float.PositiveInfinity : dist - 2 * eps));
                toLight[lane] = l; attenuation[lane] = ls.Attenuation; cosine[lane] = nl; spotFactor[lane] = spot;
            }
            if (shadows.Active == 0) continue;
            uint lit = shadows.Active & ~_geometry.Occluded(ref shadows);
            for (; lit != 0; lit &= lit - 1)
            {
                int lane = BitOperations.TrailingZeroCount(lit);
                int mi = material[lane];
                var m = _materials[mi];
                var n = normals[lane];
                var l = toLight[lane];
                var v = toViewer[lane];
                float nl = cosine[lane];
                float dk = attenuation[lane] * spotFactor[lane];
                float s = 0;
                var result = results.Slice(lane * _padded, _padded);
                int term = _tables.Index(k, mi);
                var diffuse = _tables.Diffuse[term];
                if (m.HasSpecular)
                {
                    // Physical: the lobe is a BRDF, weighted by cos θ_i like the diffuse one (as the single-ray Radiance).
                    s = m.SpecularFactor(n, l, v, nl) * (_physical ? nl : 1f);
                    SpectralMath.AddScaled2(result, diffuse, dk * nl, _tables.Specular[term], dk * s);
                }
                else SpectralMath.AddScaled(result, diffuse, dk * nl);
                ref var info = ref infos[lane];
                if (k < 32) info.LitMask |= 1u << k;
                int y = _scene.Bands + 1;   // the Y colour lane
                info.DiffuseY += dk * nl * diffuse[y];
                info.SpecularY += dk * s * _tables.Specular[term][y];
            }
        }
    }
}
