using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Whitted;

// Camera rays in packets: the closest hits of up to 16 camera rays found together, then, light by light, the
// light's direction, distance and falloff, n·l and the shadow rays of all lanes (SIMD over rays for a light with a
// lane form, LaneGeometry), the shadow rays traced as one packet; then each lane's eq. 2 by the one walker's local step
// (Eq2Walker.Shade) fed from those lane results, its terms listed and summed over the bands in one pass (SIMD over
// bands). Every lane adds its terms in the order the single-ray walk does, so each pixel gets the same bits. A lane
// whose surface reflects or transmits (a Whitted recursion) is walked alone.
internal sealed partial class WhittedIntegrator
{
    /// <inheritdoc/>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    [SkipLocalsInit]
    public void Radiance(ref RayPacket packet, Span<float> results, Span<int> objects, Span<PixelInfo> infos, Span<bool> fallbacks,
        Span<float> scratch, ref RayCounters counters)
    {
        Span<int> material = stackalloc int[RayPacket.Size];
        // The lane structures on cache-line boundaries (LaneMemory), not zeroed: the lanes found are filled.
        Span<byte> laneMemory = stackalloc byte[LaneMemory.Bytes<PacketLanesWork>()];
        ref var work = ref LaneMemory.At<PacketLanesWork>(laneMemory);
        ref var hits = ref work.Hits;
        ref var at = ref work.At;
        ref var shadows = ref work.Shadows;   // 1.6 KB: each lane used is filled
        // Each shaded lane's terms of eq. 2, in the single-ray order, summed over the bands in one pass at the end; with more
        // lights than the lists hold, added to the lane's spectrum at once (the same bits either way).
        bool listed = 1 + 2 * _lights.Length <= TermsPerLane;
        // Constant sizes: a stackalloc of a size known only at run time is a probing loop on every packet.
        Span<SpectralTerm> terms = stackalloc SpectralTerm[RayPacket.Size * TermsPerLane];
        uint found = _geometry.Intersect(ref packet, ref hits);
        float eps = _geometry.Epsilon;
        if (found != 0)
            switch (PacketLanes.Width)
            {
                case 16: LaneGeometry.Shading<Lanes512>(ref packet, in hits, ref at); break;
                case 8: LaneGeometry.Shading<Lanes256>(ref packet, in hits, ref at); break;
                case 4: LaneGeometry.Shading<Lanes128>(ref packet, in hits, ref at); break;
                default: LaneGeometry.Shading<Lanes1>(ref packet, in hits, ref at); break;
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
                // The recursion is walked ray by ray.
                long before = counters.Fallback;
                var sink = new Sink(_tables, _scene.Bands, result, scratch, FramesEnd, ref infos[lane]);
                _walker.Trace(ref sink, packet.Ray(lane) with { TMax = float.PositiveInfinity }, 0, -1, 1f, ref counters);
                fallbacks[lane] = counters.Fallback != before;
                continue;
            }
            if (!listed) result.Clear();
            material[lane] = mi;
            shaded |= 1u << lane;
        }
        if (shaded == 0) return;

        // Per light, the lanes it reaches and their d_k, c_spot, n·l; the lanes that face it get a shadow ray, traced as one packet.
        int lightCount = _lights.Length;
        // Their lane results on the stack for a few lights (1.8 KB: in cache, aligned), else in the worker's scratch.
        var lanes = lightCount <= 4 ? LaneMemory.Span<LightLanes>(stackalloc byte[LaneMemory.Bytes<LightLanes>(4)], lightCount)
            : MemoryMarshal.Cast<float, LightLanes>(scratch[((_scene.MaxDepth + 2) * 2 * _padded)..])[..lightCount];
        for (int k = 0; k < lightCount; k++)
        {
            var light = _lights[k];
            ref var lk = ref lanes[k];
            if (_laneForms[k] is LanePointLight point)
            {
                // Direction, distance, falloff, n·l and the shadow rays of all lanes at once (c_spot = 1).
                ref var d = ref lk.Attenuation;
                ref var nl = ref lk.Cosine;
                switch (PacketLanes.Width)
                {
                    case 16:
                        LaneGeometry.PointLight<Lanes512>(in point, eps, shaded, in at, ref shadows, ref d, ref nl, ref lk.Direction,
                            out lk.Reached);
                        break;
                    case 8:
                        LaneGeometry.PointLight<Lanes256>(in point, eps, shaded, in at, ref shadows, ref d, ref nl, ref lk.Direction,
                            out lk.Reached);
                        break;
                    case 4:
                        LaneGeometry.PointLight<Lanes128>(in point, eps, shaded, in at, ref shadows, ref d, ref nl, ref lk.Direction,
                            out lk.Reached);
                        break;
                    default:
                        LaneGeometry.PointLight<Lanes1>(in point, eps, shaded, in at, ref shadows, ref d, ref nl, ref lk.Direction,
                            out lk.Reached);
                        break;
                }
                ((Span<float>)lk.Spot).Fill(1f);
            }
            else
                lk.Reached = IlluminateLanes(light, shaded, in at, ref shadows, ref lk.Attenuation, ref lk.Cosine, ref lk.Spot,
                    ref lk.Direction);
            lk.Lit = 0;
            if (shadows.Active == 0) continue;
            counters.Shadow += BitOperations.PopCount(shadows.Active);
            lk.Lit = shadows.Active & ~_geometry.Occluded(ref shadows);
        }
        ShadeLanes(ref packet, in at, shaded, material, lanes, listed, terms, results, infos, ref counters);
    }

    /// <summary>Each shaded lane's eq. 2 by the walker's local step from the lights' lane results, then its listed terms summed
    /// over the bands. A method of its own: inlined into the packet's <see cref="Radiance(ref RayPacket, Span{float}, Span{int},
    /// Span{PixelInfo}, Span{bool}, Span{float}, ref RayCounters)"/>, the walker's step spent the JIT's inlining budget there and
    /// left span conversions as calls in the lane loop.</summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    void ShadeLanes(ref RayPacket packet, in ShadingLanes at, uint shaded, ReadOnlySpan<int> material, ReadOnlySpan<LightLanes> lanes,
        bool listed, Span<SpectralTerm> terms, Span<float> results, Span<PixelInfo> infos, ref RayCounters counters)
    {
        // One sink and one light query for the packet, moved from lane to lane (scoped: both hold this call's lane data, so the
        // walker may be handed the two together).
        scoped var laneSink = new LaneSink(this, listed, terms, results, infos);
        scoped var laneLights = new LaneLights(lanes, ref packet, in at);
        ReadOnlySpan<float> flat = Flat;
        for (uint all = shaded; all != 0; all &= all - 1)
        {
            int lane = BitOperations.TrailingZeroCount(all);
            int mi = material[lane];
            laneSink.Start(lane);
            laneLights.Lane = lane;
            _walker.Shade(ref laneSink, ref laneLights, mi, _materials[mi], ref counters);
            if (listed)
                SpectralMath.SumTerms(results.Slice(lane * _padded, _padded), flat, terms.Slice(lane * TermsPerLane, laneSink.Count));
        }
    }

    /// <summary>A packet's hit records, shading frames and shadow rays, laid out to sit on cache-line boundaries (the packet last:
    /// its lane arrays come first).</summary>
    struct PacketLanesWork
    {
        public HitLanes Hits;
        public ShadingLanes At;
        public RayPacket Shadows;
    }

    /// <summary>Most terms a lane lists: the global ambient and, per light, its ambient and its diffuse (+ specular) term, for 8
    /// lights.</summary>
    const int TermsPerLane = 17;

    /// <summary>One light's results for the lanes of a packet: d_k, c_spot, n·l and (lanes lit) the direction l; the lanes it
    /// reaches and those its shadow rays found lit. Seven cache lines, so that each light's lanes start on one.</summary>
    [StructLayout(LayoutKind.Sequential, Size = Floats * sizeof(float))]
    struct LightLanes
    {
        public const int Floats = 7 * RayPacket.Size;
        public PacketFloats Attenuation, Cosine, Spot;
        public LaneVectors Direction;   // l of the lanes that face the light
        public uint Reached, Lit;
    }

    /// <summary>A packet lane's shading point for the walker's local step: its normal and view direction read from the packet's
    /// lanes when asked, its lights from their precomputed lane results (shadow rays already traced).</summary>
    ref struct LaneLights(ReadOnlySpan<LightLanes> lanes, ref RayPacket packet, in ShadingLanes at) : ILightQuery
    {
        readonly ReadOnlySpan<LightLanes> _lanes = lanes;
        readonly ref RayPacket _packet = ref packet;
        readonly ref readonly ShadingLanes _at = ref at;
        /// <summary>The lane asked about.</summary>
        public int Lane;

        public readonly Vector3 Normal => _at.Normal(Lane);
        public readonly Vector3 View => -new Vector3(_packet.DirectionX[Lane], _packet.DirectionY[Lane], _packet.DirectionZ[Lane]);

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public readonly bool Reach(int k, out LightSample sample, out float nl)
        {
            int lane = Lane;
            ref readonly var r = ref _lanes[k];
            if ((r.Reached >> lane & 1) == 0) { sample = default; nl = 0; return false; }
            nl = r.Cosine[lane];
            var l = new Vector3(r.Direction.X[lane], r.Direction.Y[lane], r.Direction.Z[lane]);
            sample = new LightSample(l, 0, r.Spot[lane], r.Attenuation[lane]);
            return true;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public readonly bool Visible(int k, in LightSample sample, ref RayCounters counters) => (_lanes[k].Lit >> Lane & 1) != 0;

        /// <summary>None: a scene with media is traced ray by ray (<see cref="PrefersPackets"/>).</summary>
        public readonly ReadOnlySpan<float> Transmittance => default;
    }

    /// <summary>A packet lane's terms: listed as <see cref="SpectralTerm"/>s for the one-pass band sum (or added at once), and what the
    /// camera ray saw for the analysis images: the local step only (<see cref="ITermSink"/>; lanes that recurse are walked
    /// alone).</summary>
    ref struct LaneSink : ITermSink
    {
        readonly WhittedIntegrator _owner;
        readonly bool _listed;
        readonly Span<SpectralTerm> _terms;
        readonly Span<float> _results;
        readonly Span<PixelInfo> _infos;
        // The lane's own list and analysis record, found once per lane (Start).
        ref SpectralTerm _list;
        ref PixelInfo _info;
        int _lane;
        /// <summary>The terms listed for the lane so far.</summary>
        public int Count;

        public LaneSink(WhittedIntegrator owner, bool listed, Span<SpectralTerm> terms, Span<float> results, Span<PixelInfo> infos)
        {
            _owner = owner; _listed = listed; _terms = terms; _results = results; _infos = infos;
            _list = ref Unsafe.NullRef<SpectralTerm>();
            _info = ref Unsafe.NullRef<PixelInfo>();
        }

        /// <summary>The terms that follow are lane <paramref name="lane"/>'s.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Start(int lane)
        {
            _lane = lane;
            Count = 0;
            _info = ref _infos[lane];
            if (_listed) _list = ref _terms.Slice(lane * TermsPerLane, TermsPerLane)[0];
        }

        public void GlobalAmbient(int material) => Add(new SpectralTerm(_owner._globalAmbientAt[material], 1f));
        public void Ambient(int light, int material, int term, float spot) => Add(new SpectralTerm(_owner._ambientAt[term], spot));

        /// <summary>Never asked: a scene with media is traced ray by ray (<see cref="PrefersPackets"/>).</summary>
        public readonly void DirectThrough(int light, int material, int term, float d, float nl, float s, bool specular,
            ReadOnlySpan<float> transmittance) => throw new InvalidOperationException("packets carry no participating media");

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Direct(int light, int material, int term, float d, float nl, float s, bool specular)
        {
            ref readonly var pair = ref _owner._direct[term];
            if (specular) Add(new SpectralTerm(pair.DiffuseAt, d * nl, pair.SpecularAt, d * s));
            else Add(new SpectralTerm(pair.DiffuseAt, d * nl));
            ref var info = ref _info;
            if (light < 32) info.LitMask |= 1u << light;
            info.DiffuseY += d * nl * pair.DiffuseY;   // the Y colour lane
            info.SpecularY += d * s * pair.SpecularY;
        }

        /// <summary>A term of eq. 2 for the lane: listed for the one-pass sum, or added to the lane's spectrum now.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        void Add(SpectralTerm term)
        {
            if (_listed)
            {
                // At most 1 + 2 × lights ≤ TermsPerLane terms (listed only then); checked, as the write below is not.
                if ((uint)Count >= TermsPerLane) throw new InvalidOperationException("more eq. 2 terms than a lane's list holds");
                Unsafe.Add(ref _list, Count++) = term;
                return;
            }
            int padded = _owner._padded;
            var result = _results.Slice(_lane * padded, padded);
            var a = _owner.Flat.Slice(term.A, padded);
            if (term.B < 0) SpectralMath.AddScaled(result, a, term.S);
            else SpectralMath.AddScaled2(result, a, term.S, _owner.Flat.Slice(term.B, padded), term.T);
        }
    }

    /// <summary>
    /// Any light, lane by lane (<see cref="Light.Illuminate"/>): the lanes it reaches, their attenuation, c_spot and n·l, and
    /// for those facing it (not n·l ≤ 0) l in <paramref name="direction"/> and the shadow ray
    /// (<see cref="Visibility.ShadowRay"/>) in <paramref name="shadows"/>, whose active lanes they become.
    /// </summary>
    uint IlluminateLanes(Light light, uint lanes, in ShadingLanes at, ref RayPacket shadows, ref PacketFloats attenuation,
        ref PacketFloats cosine, ref PacketFloats spot, ref LaneVectors direction)
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
            direction.X[lane] = ls.Direction.X; direction.Y[lane] = ls.Direction.Y; direction.Z[lane] = ls.Direction.Z;
            shadows.Set(lane, Visibility.ShadowRay(new Vector3(at.PX[lane], at.PY[lane], at.PZ[lane]), at.Face(lane), ls.Direction,
                ls.Distance, eps));
        }
        return reached;
    }
}
