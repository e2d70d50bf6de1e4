using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// Camera rays in packets: the closest hits of up to 16 camera rays found together, then, light by light, the
// light's direction, distance and falloff, n·l and the shadow rays of all lanes (SIMD over rays for a point light,
// LaneGeometry), the shadow rays traced as one packet, and eq. 2's band sums per lane (SIMD over bands). Every
// lane adds its terms in the order the single-ray Radiance does, so each pixel gets the same bits. A lane whose surface reflects or transmits (a Whitted recursion) is traced again alone.
public sealed partial class WhittedIntegrator
{
    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    public void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks, Span<float> scratch, ref RayCounters counters)
    {
        Span<SurfaceHit> hits = stackalloc SurfaceHit[RayPacket.Size];
        Span<Vector3> toViewer = stackalloc Vector3[RayPacket.Size];
        Span<int> material = stackalloc int[RayPacket.Size];
        Unsafe.SkipInit(out ShadingLanes at);                 // filled for the shaded lanes below
        Unsafe.SkipInit(out PacketFloats attenuation);
        Unsafe.SkipInit(out PacketFloats cosine);
        Unsafe.SkipInit(out PacketFloats spotFactor);
        uint found = _geometry.Intersect(ref packet, hits);
        uint shaded = 0;
        float eps = _geometry.Epsilon;
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
            at.Set(lane, hit.Position, outside ? hit.Normal : -hit.Normal, hit.Position + eps * ng);
            toViewer[lane] = v;
            material[lane] = mi;
            if (_scene.HasGlobalAmbient && m.HasAmbient) SpectralMath.AddScaled(result, _tables.GlobalAmbient[mi], 1f);
            shaded |= 1u << lane;
        }
        if (shaded == 0) return;

        Unsafe.SkipInit(out RayPacket shadows);   // 1.6 KB, not zeroed: each lane used is filled
        for (int k = 0; k < _lights.Length; k++)
        {
            var light = _lights[k];
            uint reached;
            if (light is PointLight point)
            {
                // Direction, distance, falloff, n·l and the shadow rays of all lanes at once (c_spot = 1).
                switch (PacketLanes.Width)
                {
                    case 16: LaneGeometry.PointLight<Lanes512>(point, eps, shaded, in at, ref shadows, ref attenuation, ref cosine, out reached); break;
                    case 8: LaneGeometry.PointLight<Lanes256>(point, eps, shaded, in at, ref shadows, ref attenuation, ref cosine, out reached); break;
                    case 4: LaneGeometry.PointLight<Lanes128>(point, eps, shaded, in at, ref shadows, ref attenuation, ref cosine, out reached); break;
                    default: LaneGeometry.PointLight<Lanes1>(point, eps, shaded, in at, ref shadows, ref attenuation, ref cosine, out reached); break;
                }
                ((Span<float>)spotFactor).Fill(1f);
            }
            else reached = IlluminateLanes(light, shaded, in at, ref shadows, ref attenuation, ref cosine, ref spotFactor);
            if (light.HasAmbient)
                for (uint all = reached; all != 0; all &= all - 1)
                {
                    int lane = BitOperations.TrailingZeroCount(all);
                    if (_materials[material[lane]].HasAmbient)
                        SpectralMath.AddScaled(results.Slice(lane * _padded, _padded), _tables.Ambient[_tables.Index(k, material[lane])], spotFactor[lane]);
                }
            if (shadows.Active == 0) continue;
            counters.Shadow += BitOperations.PopCount(shadows.Active);
            uint lit = shadows.Active & ~_geometry.Occluded(ref shadows);
            for (; lit != 0; lit &= lit - 1)
            {
                int lane = BitOperations.TrailingZeroCount(lit);
                int mi = material[lane];
                var m = _materials[mi];
                float nl = cosine[lane];
                float dk = attenuation[lane] * spotFactor[lane];
                float s = 0;
                var result = results.Slice(lane * _padded, _padded);
                int term = _tables.Index(k, mi);
                var diffuse = _tables.Diffuse[term];
                if (m.HasSpecular)
                {
                    // Physical: the lobe is a BRDF, weighted by cos θ_i like the diffuse one (as the single-ray Radiance).
                    var l = new Vector3(shadows.DirectionX[lane], shadows.DirectionY[lane], shadows.DirectionZ[lane]);
                    s = m.SpecularFactor(at.Normal(lane), l, toViewer[lane], nl) * (_physical ? nl : 1f);
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

    /// <summary>
    /// Any light, lane by lane (<see cref="Light.Illuminate"/>): the lanes it reaches, their attenuation, c_spot and n·l, and
    /// for those facing it (not n·l ≤ 0) the shadow ray in <paramref name="shadows"/>, whose active lanes they become.
    /// </summary>
    uint IlluminateLanes(Light light, uint lanes, in ShadingLanes at, ref RayPacket shadows, ref PacketFloats attenuation, ref PacketFloats cosine, ref PacketFloats spot)
    {
        float eps = _geometry.Epsilon;
        uint reached = 0;
        shadows.Clear();
        for (; lanes != 0; lanes &= lanes - 1)
        {
            int lane = BitOperations.TrailingZeroCount(lanes);
            if (!light.Illuminate(new Vector3(at.PX[lane], at.PY[lane], at.PZ[lane]), out var ls)) continue;
            reached |= 1u << lane;
            float nl = Vector3.Dot(at.Normal(lane), ls.Direction);
            attenuation[lane] = ls.Attenuation; cosine[lane] = nl; spot[lane] = ls.Spot;
            if (nl <= 0) continue;
            float dist = ls.Distance;
            shadows.Set(lane, new Ray(new Vector3(at.AX[lane], at.AY[lane], at.AZ[lane]), ls.Direction, float.IsInfinity(dist) ? float.PositiveInfinity : dist - 2 * eps));
        }
        return reached;
    }
}
