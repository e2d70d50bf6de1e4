using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Whitted;

/// <summary>
/// What receives the terms of eq. 2's local step (<see cref="Eq2Walker.Shade"/>) as the walker visits them: summed into a
/// pixel's spectrum (Whitted), listed per packet lane, or recorded as geometric factors (the light transfer). A sink is a
/// struct, so each walk is compiled for its sink and its policy members fold to constants.
/// </summary>
internal interface ITermSink
{
    /// <summary>a_glob·m_amb of material <paramref name="material"/>.</summary>
    void GlobalAmbient(int material);
    /// <summary>c_spot·I_amb,k·m_amb; <paramref name="term"/> = <see cref="TermTables.Index"/>(k, material).</summary>
    void Ambient(int light, int material, int term, float spot);
    /// <summary>A light that reaches the point unshadowed with n·l &gt; 0: d·(n·l)·I_k·m_diff and, when
    /// <paramref name="specular"/>, d·s·I_k·m_spec, with d = c_spot·d_k and s the lobe's factor.</summary>
    void Direct(int light, int material, int term, float d, float nl, float s, bool specular);
    /// <summary><see cref="Direct"/> with its shadow ray through a participating medium: the pair ⊙ the transmittance
    /// <paramref name="transmittance"/> per band (a sink whose rays meet no medium is never asked).</summary>
    void DirectThrough(int light, int material, int term, float d, float nl, float s, bool specular, ReadOnlySpan<float> transmittance);
}

/// <summary>
/// A sink that also follows the Whitted recursion (<see cref="Eq2Walker.Trace"/>): rays that leave the scene, the mirror and
/// transmission branches and dispersive splits. A packet lane's sink takes the local step only (such lanes are walked alone).
/// </summary>
internal interface IWalkSink : ITermSink
{
    /// <summary>Is a branch whose weight falls below <see cref="Scene.MinRayWeight"/> left untraced (adaptive depth)?</summary>
    static abstract bool Prunes { get; }
    /// <summary>Does a camera ray's tree end where its ray budget is spent (<see cref="RayCounters.BudgetSpent"/>)?</summary>
    static abstract bool Budgeted { get; }
    /// <summary>A dispersive Fresnel mirror on an all-band path: trace the reflected ray once per band as a one-band path
    /// (counted once), rather than once with F per band on the way back (<see cref="LeavePerBand"/>)?</summary>
    static abstract bool ReflectPerBand { get; }

    /// <summary>A ray's radiance starts (its own spectrum is empty).</summary>
    void Begin();
    /// <summary>A lobe of the hit's material is textured: that lobe's terms (<see cref="TexturedTerms"/>, its
    /// <see cref="TexturedTerms.Lobe"/>) come from these texels in the local step that follows (until the next
    /// <see cref="Begin"/>); called once per textured lobe (diffuse first), each with its own taps.</summary>
    void Texels(TexturedTerms terms, in TexelTaps taps);
    /// <summary>The ray left the scene: the background radiance.</summary>
    void Background();
    /// <summary>A dispersive split (each band its own path): the colour lanes cannot follow.</summary>
    void Split(ref RayCounters counters);
    /// <summary>Before the reflected (k_r) or transmitted (k_t) ray of <paramref name="material"/> with scalar weight
    /// <paramref name="factor"/> (Fresnel) carrying <paramref name="band"/> (−1: all bands).</summary>
    void Enter(int material, bool transmit, int band, float factor);
    /// <summary>After it: the child's radiance enters the parent's through the material's weight.</summary>
    void Leave(int material, bool transmit, int band, float factor, ref RayCounters counters);
    /// <summary>After a reflected ray of a dispersive Fresnel mirror traced once: band b enters weighted by F_b.</summary>
    void LeavePerBand(Material m, int material, float cosI, bool outside, ref RayCounters counters);
    /// <summary>The ray's radiance so far (its terms and branches) ⊙= T of <paramref name="medium"/> along the ray for
    /// <paramref name="distance"/> (+∞: it left the scene): Beer–Lambert per band.</summary>
    void Attenuate(Medium medium, Vector3 origin, Vector3 direction, float distance, ref RayCounters counters);
    /// <summary>Where a shadow ray's transmittance goes (a padded spectrum; empty for a sink whose rays meet no medium).</summary>
    Span<float> Transmittance { get; }
}

/// <summary>A shading point as eq. 2's local step sees it: its normal and view direction (on the viewer's side) and where
/// the lights stand from it; a ray's own query, or a packet lane's precomputed results.</summary>
internal interface ILightQuery
{
    /// <summary>The shading normal n (asked only where a specular lobe needs it).</summary>
    Vector3 Normal { get; }
    /// <summary>The direction v towards the viewer (asked only where a specular lobe needs it).</summary>
    Vector3 View { get; }
    /// <summary>Light k's direction, distance, c_spot and d_k, and n·l; false when it cannot reach the point at all.</summary>
    bool Reach(int k, out LightSample sample, out float nl);
    /// <summary>Is light k unshadowed (asked only where n·l &gt; 0)?</summary>
    bool Visible(int k, in LightSample sample, ref RayCounters counters);
    /// <summary>The transmittance per band along the shadow ray last found <see cref="Visible"/> (empty: it crosses no medium).</summary>
    ReadOnlySpan<float> Transmittance { get; }
}

/// <summary>
/// The one walk of the paper's local model, eq. 2, and the Whitted recursion:
///   L(b) = a_glob(b)·m_amb(b) + Σ_k c_spot,k · { I_amb,k(b)·m_amb(b) + d_k·[L_diff,k(b) + L_spec,k(b)] } + k_r·L_r + k_t·L_t,
/// terms visited in a fixed order (global ambient; per light its ambient, then, facing and unshadowed, its diffuse and
/// specular pair; then the mirror and the transmission branch with Fresnel, total internal reflection and dispersion per
/// band, to the maximum depth). What a term does is the sink's (<see cref="ITermSink"/>); the walk is written once.
/// Participating media absorb along its rays (it scatters nothing): every ray travels in one medium — a camera ray in the
/// scene's, a refracted ray into an object with an interior medium in that one and out of it in the scene's, any other in
/// the medium it came in — and its radiance, terms and branches together, is multiplied by Beer–Lambert's
/// T = exp(−σ_t·t) per band over its length (exact: a homogeneous medium's <see cref="Medium.Attenuate"/>), each direct
/// term by T along its shadow ray, which leaves on the viewer's side and so travels in the ray's medium.
/// </summary>
internal sealed class Eq2Walker
{
    readonly SceneGeometry _geometry;
    readonly Material[] _materials;
    readonly Light[] _lights;
    readonly int[] _objectMaterial;
    readonly TermTables _tables;
    readonly bool _physical, _globalAmbient;
    readonly int _bands, _maxDepth;
    // Per material, the largest mirror and transmit factor over the bands: a branch's weight grows by at most these.
    readonly float[] _mirrorMax, _transmitMax;
    readonly float _minWeight;
    readonly TextureTables? _textures;
    readonly float _pixelAngle;
    // Participating media: the scene's, each object's interior (−1: none) and the camera's medium (−1: vacuum).
    readonly Medium[] _media;
    readonly int[] _interiorOf;
    readonly int _sceneMedium;

    public Eq2Walker(Scene scene, SceneGeometry geometry, TermTables tables)
    {
        _geometry = geometry;
        _materials = scene.Materials.ToArray();
        _lights = scene.Lights.ToArray();
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _tables = tables;
        _physical = scene.Radiometry == Radiometry.Physical;
        _globalAmbient = scene.HasGlobalAmbient;
        _bands = scene.Bands;
        _maxDepth = scene.MaxDepth;
        _mirrorMax = tables.Mirror.Select(t => t.AsSpan(0, scene.Bands).ToArray().DefaultIfEmpty(0).Max()).ToArray();
        _transmitMax = tables.Transmit.Select(t => t.AsSpan(0, scene.Bands).ToArray().DefaultIfEmpty(0).Max()).ToArray();
        _minWeight = scene.MinRayWeight;
        _textures = tables.Textures;
        // A camera pixel's angular width at the image centre: a hit's footprint t·angle/|cos θ| picks the mip level (a ray
        // cone from the camera; a secondary ray's cone starts at its own origin).
        _pixelAngle = 2 * MathF.Tan(scene.Camera.Fov * MathF.PI / 360) / Math.Max(1, scene.Camera.Height);
        _media = [.. scene.Media];
        _interiorOf = scene.Objects.Select(o => o.Medium).ToArray();
        _sceneMedium = scene.Medium;
    }

    public TermTables Tables => _tables;
    public SceneGeometry Geometry => _geometry;

    /// <summary>
    /// The terms along <paramref name="ray"/> into <paramref name="sink"/>. <paramref name="band"/> ≥ 0 marks a ray that
    /// carries only that band (after dispersion); <paramref name="weight"/> is the largest factor by which this ray's
    /// radiance enters the pixel (1 for a camera ray), below <see cref="Scene.MinRayWeight"/> a pruning sink stops.
    /// Returns the object hit, or −1.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Trace<TSink>(ref TSink sink, Ray ray, int depth, int band, float weight, ref RayCounters counters)
        where TSink : IWalkSink, allows ref struct => TraceIn(ref sink, ray, _sceneMedium, depth, band, weight, ref counters);

    /// <summary><see cref="Trace{TSink}(ref TSink, Ray, int, int, float, ref RayCounters)"/> of a ray in
    /// <paramref name="medium"/> (−1: vacuum).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    int TraceIn<TSink>(ref TSink sink, Ray ray, int medium, int depth, int band, float weight, ref RayCounters counters)
        where TSink : IWalkSink, allows ref struct
    {
        sink.Begin();
        var origin = ray.Origin;
        if (!_geometry.Intersect(ref ray, out var hit))
        {
            sink.Background();
            if (medium >= 0) sink.Attenuate(_media[medium], origin, ray.Direction, float.PositiveInfinity, ref counters);
            return -1;
        }
        int id = Follow(ref sink, ray, in hit, medium, depth, band, weight, ref counters);
        if (medium >= 0) sink.Attenuate(_media[medium], origin, ray.Direction, hit.T, ref counters);
        return id;
    }

    /// <summary>The terms and branches at <paramref name="hit"/>, reached by <paramref name="ray"/> in <paramref name="medium"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    int Follow<TSink>(ref TSink sink, Ray ray, scoped in SurfaceHit hit, int medium, int depth, int band, float weight,
        ref RayCounters counters) where TSink : IWalkSink, allows ref struct
    {
        int mi = _objectMaterial[hit.Object];
        var m = _materials[mi];
        var v = -ray.Direction;
        // The face normal decides which side the viewer is on; the shading normal follows it.
        bool outside = Vector3.Dot(hit.GeometricNormal, v) >= 0;
        var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
        var n = outside ? hit.Normal : -hit.Normal;
        var p = hit.Position;
        var pAbove = p + _geometry.Epsilon * ng;
        if (_textures is { } textures && textures.Textured[mi]) LookUpTexels(ref sink, textures, mi, in hit, ng, v);
        var lights = new RayLights(_lights, _geometry, p, ng, n, v, medium >= 0 ? _media[medium] : null,
            medium >= 0 ? sink.Transmittance : default);
        Shade(ref sink, ref lights, mi, m, ref counters);

        if (depth >= _maxDepth || !(m.HasMirror || m.HasTransmission)) return hit.Object;
        // Bounded work: a camera ray's tree ends where its budget is spent (the renderer counts those rays).
        if (TSink.Budgeted && counters.BudgetSpent) { counters.OverBudget = true; return hit.Object; }

        float cosI = Vector3.Dot(n, v);
        if (m.HasMirror) Reflect(ref sink, ray.Direction, pAbove, n, m, mi, cosI, outside, medium, depth, band, weight, ref counters);
        if (m.HasTransmission)
        {
            float wt = weight * _transmitMax[mi];
            // The medium beyond the surface: into the object's interior, out of it into the scene's, else unchanged.
            int beyond = _interiorOf[hit.Object] is int interior and >= 0 ? outside ? interior : _sceneMedium : medium;
            var across = new Media(medium, beyond);
            if (!m.Dispersive || band >= 0)
                Refract(ref sink, ray.Direction, p, n, ng, m, mi, cosI, outside, across, depth, band, wt, ref counters);
            else
            {
                // Dispersion: every band bends by its own index, so each gets its own refracted ray.
                sink.Split(ref counters);
                for (int b = 0; b < _bands; b++)
                    Refract(ref sink, ray.Direction, p, n, ng, m, mi, cosI, outside, across, depth, b, wt, ref counters);
            }
        }
        return hit.Object;
    }

    /// <summary>The texels of each textured lobe of material <paramref name="mi"/> at the hit, handed to the sink: one uv and
    /// footprint (t·pixel angle/|cos θ| from the ray's origin, times the mapping's density), each texture its own filtered taps.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // textured hits only: kept out of the walk's code
    void LookUpTexels<TSink>(ref TSink sink, TextureTables textures, int mi, in SurfaceHit hit, Vector3 ng, Vector3 v)
        where TSink : IWalkSink, allows ref struct
    {
        var uv = _geometry.TexCoord(in hit, out float density);
        float width = hit.T * _pixelAngle / MathF.Max(MathF.Abs(Vector3.Dot(ng, v)), 0.25f) * density;
        if (textures.Diffuse[mi] is { } diffuse)
        {
            diffuse.Lookup(uv, width, out var taps);
            sink.Texels(diffuse, in taps);
        }
        if (textures.Specular[mi] is { } specular)
        {
            specular.Lookup(uv, width, out var taps);
            sink.Texels(specular, in taps);
        }
    }

    /// <summary>Eq. 2's local terms at the shading point of <paramref name="lights"/> (its normal, view direction and lights).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Shade<TSink, TLights>(ref TSink sink, ref TLights lights, int mi, Material m, ref RayCounters counters)
        where TSink : ITermSink, allows ref struct
        where TLights : ILightQuery, allows ref struct
    {
        if (_globalAmbient && m.HasAmbient) sink.GlobalAmbient(mi);
        for (int k = 0; k < _lights.Length; k++)
        {
            if (!lights.Reach(k, out var ls, out float nl)) continue;
            int term = _tables.Index(k, mi);
            // The light's own ambient enters wherever the light reaches the point (before n·l and shadows).
            if (_lights[k].HasAmbient && m.HasAmbient) sink.Ambient(k, mi, term, ls.Spot);
            if (nl <= 0 || !lights.Visible(k, in ls, ref counters)) continue;
            float d = ls.Attenuation * ls.Spot;
            // Physical: the specular lobe is a BRDF, so it is weighted by cos θ_i like the diffuse one (paper: eq. 2 as written).
            float s = m.HasSpecular ? m.SpecularFactor(lights.Normal, ls.Direction, lights.View, nl) * (_physical ? nl : 1f) : 0;
            if (lights.Transmittance is { IsEmpty: false } t) sink.DirectThrough(k, mi, term, d, nl, s, m.HasSpecular, t);
            else sink.Direct(k, mi, term, d, nl, s, m.HasSpecular);
        }
    }

    /// <summary>k_r·L(reflected), with F per band for a dispersive Fresnel mirror.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Reflect<TSink>(ref TSink sink, Vector3 incident, Vector3 pAbove, Vector3 n, Material m, int mi, float cosI, bool outside,
        int medium, int depth, int band, float weight, ref RayCounters counters) where TSink : IWalkSink, allows ref struct
    {
        float f = m.MirrorFactor(cosI, outside, band);
        float branch = weight * _mirrorMax[mi] * f;
        if (TSink.Prunes && branch < _minWeight) { counters.PrunedRays++; return; }   // adaptive depth (Hall & Greenberg 1983)
        var ray = new Ray(pAbove, Vector3.Normalize(incident + 2 * cosI * n));
        counters.Secondary++;
        if (m.Fresnel && m.Dispersive && band < 0)
        {
            // F from each band's own index: reflection + transmission = 1 in every band; the colour lanes cannot follow.
            if (TSink.ReflectPerBand)
            {
                sink.Split(ref counters);
                var counted = counters;   // one ray, whatever the bands
                for (int b = 0; b < _bands; b++)
                {
                    float fb = m.MirrorFactor(cosI, outside, b);
                    sink.Enter(mi, false, b, fb);
                    TraceIn(ref sink, ray, medium, depth + 1, b, branch, ref counters);
                    sink.Leave(mi, false, b, fb, ref counters);
                    if (b == 0) counted = counters;
                }
                counters = counted;
                return;
            }
            sink.Enter(mi, false, band, f);
            TraceIn(ref sink, ray, medium, depth + 1, band, branch, ref counters);
            sink.LeavePerBand(m, mi, cosI, outside, ref counters);
            return;
        }
        sink.Enter(mi, false, band, f);
        TraceIn(ref sink, ray, medium, depth + 1, band, branch, ref counters);
        sink.Leave(mi, false, band, f, ref counters);
    }

    /// <summary>k_t·L(refracted) for <paramref name="band"/> (all bands when −1); under total internal reflection nothing with
    /// Fresnel (F = 1 on the mirror lobe), else the constant k_t share into the mirror direction.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Refract<TSink>(ref TSink sink, Vector3 incident, Vector3 p, Vector3 n, Vector3 ng, Material m, int mi, float cosI, bool outside,
        Media across, int depth, int band, float branch, ref RayCounters counters) where TSink : IWalkSink, allows ref struct
    {
        float eta = m.Eta(outside, band);   // n_i / n_t
        float sin2T = eta * eta * (1 - cosI * cosI);
        Vector3 dir, origin;
        float f = 1;
        int medium = across.Beyond;
        if (sin2T >= 1)
        {
            if (m.Fresnel) return;
            dir = Vector3.Normalize(incident + 2 * cosI * n);
            origin = p + _geometry.Epsilon * ng;
            medium = across.Here;   // reflected back: the ray stays on its side
        }
        else
        {
            float cosT = MathF.Sqrt(1 - sin2T);
            dir = Vector3.Normalize(eta * incident + (eta * cosI - cosT) * n);
            origin = p - _geometry.Epsilon * ng;
            f = m.TransmitFactor(cosI, eta);
        }
        if (TSink.Prunes && branch * f < _minWeight) { counters.PrunedRays++; return; }   // adaptive depth (Hall & Greenberg 1983)
        counters.Secondary++;
        sink.Enter(mi, true, band, f);
        TraceIn(ref sink, new Ray(origin, dir), medium, depth + 1, band, branch * f, ref counters);
        sink.Leave(mi, true, band, f, ref counters);
    }

    /// <summary>The media on the two sides of a surface a ray meets: where it came from and beyond it.</summary>
    readonly record struct Media(int Here, int Beyond);

    /// <summary>A ray's own lights: <see cref="Light.Illuminate"/> at P (face normal n_g), and the shadow ray of
    /// <see cref="Visibility.ShadowRay"/> (counted), with its transmittance through <paramref name="medium"/> (null: vacuum)
    /// into <paramref name="transmittance"/>.</summary>
    readonly ref struct RayLights(Light[] lights, SceneGeometry geometry, Vector3 p, Vector3 ng, Vector3 n, Vector3 v, Medium? medium,
        Span<float> transmittance) : ILightQuery
    {
        readonly Span<float> _transmittance = transmittance;

        public ReadOnlySpan<float> Transmittance => medium is null ? default : _transmittance;

        public Vector3 Normal => n;
        public Vector3 View => v;

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public bool Reach(int k, out LightSample sample, out float nl)
        {
            if (!lights[k].Illuminate(p, out sample)) { nl = 0; return false; }
            nl = Vector3.Dot(n, sample.Direction);
            return true;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public bool Visible(int k, in LightSample sample, ref RayCounters counters)
        {
            counters.Shadow++;
            if (geometry.Occluded(Visibility.ShadowRay(p, ng, sample.Direction, sample.Distance, geometry.Epsilon))) return false;
            if (medium is not null)
            {
                _transmittance.Fill(1);
                medium.Attenuate(p, sample.Direction, sample.Distance, _transmittance);
            }
            return true;
        }
    }
}
