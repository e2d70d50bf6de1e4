using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

// Camera rays in packets: the closest hits of up to 16 camera rays found together, then, light by light, the
// light's direction, distance and falloff, n·l and the shadow rays of all lanes (SIMD over rays for a point light,
// LaneGeometry), the shadow rays traced as one packet, and eq. 2's band sums per lane (SIMD over bands), each lane's
// terms listed and summed in one pass over the bands. Every lane adds its terms in the order the single-ray Radiance
// does, so each pixel gets the same bits. A lane whose surface reflects or transmits (a Whitted recursion) is traced again alone.
public sealed partial class WhittedIntegrator
{
    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    public void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks, Span<float> scratch, ref RayCounters counters)
    {
        Span<int> material = stackalloc int[RayPacket.Size];
        Unsafe.SkipInit(out HitLanes hits);                   // the lanes found are filled
        Unsafe.SkipInit(out ShadingLanes at);
        Unsafe.SkipInit(out PacketFloats attenuation);
        Unsafe.SkipInit(out PacketFloats cosine);
        Unsafe.SkipInit(out PacketFloats spotFactor);
        // Each shaded lane's terms of eq. 2, in the single-ray order, summed over the bands in one pass at the end; with more
        // lights than the lists hold, added to the lane's spectrum at once (the same bits either way).
        bool listed = 1 + 2 * _lights.Length <= TermsPerLane;
        Span<SpectralTerm> terms = stackalloc SpectralTerm[listed ? RayPacket.Size * TermsPerLane : 0];
        Span<int> termCount = stackalloc int[RayPacket.Size];
        uint found = _geometry.Intersect(ref packet, ref hits);
        float eps = _geometry.Epsilon;
        if (found != 0)
            switch (PacketLanes.Width)
            {
                case 16: LaneGeometry.Shading<Lanes512>(ref packet, in hits, eps, ref at); break;
                case 8: LaneGeometry.Shading<Lanes256>(ref packet, in hits, eps, ref at); break;
                case 4: LaneGeometry.Shading<Lanes128>(ref packet, in hits, eps, ref at); break;
                default: LaneGeometry.Shading<Lanes1>(ref packet, in hits, eps, ref at); break;
            }
        uint shaded = 0;
        for (uint all = packet.Active; all != 0; all &= all - 1)
        {
            int lane = BitOperations.TrailingZeroCount(all);
            var result = results.Slice(lane * _padded, _padded);
            infos[lane] = default;
            fallbacks[lane] = false;
            if ((found >> lane & 1) == 0)
            {
                _tables.Background.AsSpan().CopyTo(result);
                objects[lane] = -1;
                continue;
            }
            int obj = hits.Object[lane];
            int mi = _objectMaterial[obj];
            var m = _materials[mi];
            objects[lane] = obj;
            if (_scene.MaxDepth > 0 && (m.HasMirror || m.HasTransmission))
            {
                // The recursion is traced ray by ray.
                long before = counters.Fallback;
                Radiance(packet.Ray(lane) with { TMax = float.PositiveInfinity }, 0, -1, 1f, result, scratch, ref counters, ref infos[lane]);
                fallbacks[lane] = counters.Fallback != before;
                continue;
            }
            if (!listed) result.Clear();
            termCount[lane] = 0;
            material[lane] = mi;
            if (_scene.HasGlobalAmbient && m.HasAmbient) AddTerm(lane, new SpectralTerm(_globalAmbientAt[mi], 1f), listed, terms, termCount, results);
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
                        AddTerm(lane, new SpectralTerm(_ambientAt[_tables.Index(k, material[lane])], spotFactor[lane]), listed, terms, termCount, results);
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
                int term = _tables.Index(k, mi);
                var diffuse = _tables.Diffuse[term];
                if (m.HasSpecular)
                {
                    // Physical: the lobe is a BRDF, weighted by cos θ_i like the diffuse one (as the single-ray Radiance).
                    var l = new Vector3(shadows.DirectionX[lane], shadows.DirectionY[lane], shadows.DirectionZ[lane]);
                    var v = -new Vector3(packet.DirectionX[lane], packet.DirectionY[lane], packet.DirectionZ[lane]);
                    s = m.SpecularFactor(at.Normal(lane), l, v, nl) * (_physical ? nl : 1f);
                    AddTerm(lane, new SpectralTerm(_diffuseAt[term], dk * nl, _specularAt[term], dk * s), listed, terms, termCount, results);
                }
                else AddTerm(lane, new SpectralTerm(_diffuseAt[term], dk * nl), listed, terms, termCount, results);
                ref var info = ref infos[lane];
                if (k < 32) info.LitMask |= 1u << k;
                int y = _scene.Bands + 1;   // the Y colour lane
                info.DiffuseY += dk * nl * diffuse[y];
                info.SpecularY += dk * s * _tables.Specular[term][y];
            }
        }
        if (listed)
            for (uint all = shaded; all != 0; all &= all - 1)
            {
                int lane = BitOperations.TrailingZeroCount(all);
                SpectralMath.SumTerms(results.Slice(lane * _padded, _padded), _flat, terms.Slice(lane * TermsPerLane, termCount[lane]));
            }
    }

    /// <summary>Most terms a lane lists: the global ambient and, per light, its ambient and its diffuse (+ specular) term, for 8 lights.</summary>
    const int TermsPerLane = 17;

    /// <summary>A term of eq. 2 for a lane: listed for the one-pass sum, or added to the lane's spectrum now.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void AddTerm(int lane, SpectralTerm term, bool listed, Span<SpectralTerm> terms, Span<int> termCount, Span<float> results)
    {
        if (listed) { terms[lane * TermsPerLane + termCount[lane]++] = term; return; }
        var result = results.Slice(lane * _padded, _padded);
        var a = _flat.AsSpan(term.A, _padded);
        if (term.B < 0) SpectralMath.AddScaled(result, a, term.S);
        else SpectralMath.AddScaled2(result, a, term.S, _flat.AsSpan(term.B, _padded), term.T);
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
