using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Whitted;

/// <summary>
/// Whitted ray tracing with the paper's local model, eq. 2, in every band at once:
///   L(b) = a_glob(b)·m_amb(b) + Σ_k c_spot,k · { I_amb,k(b)·m_amb(b) + d_k·[L_diff,k(b) + L_spec,k(b)] }
/// with L_diff = I_k·m_diff·max(0, n·l), L_spec = I_k·m_spec·max(0, n·h)^shininess (Blinn–Phong) or
/// (r·v)^shininess (Phong), hard shadows, then k_r·L(reflected) and k_t·L(refracted) to the maximum
/// depth. One ray carries all bands; a wavelength-dependent index of refraction splits it per band.
/// Each term adds a precomputed table (<see cref="TermTables"/>: the exact band means of I_k·m and their XYZ in the
/// colour lanes) times its scalar. Physical radiometry reads the same terms in units: the tables carry 1/π and the
/// specular normalisation, the specular term gains the cos θ_i of a BRDF, and point lights fall off as 1/r².
/// With Fresnel, k_r·F and k_t·(1 − F), F = 1 under total internal reflection (nothing is transmitted), F per band
/// for a dispersive material.
/// </summary>
internal sealed partial class WhittedIntegrator : IPacketIntegrator, IAnalysisIntegrator
{
    readonly Scene _scene;
    readonly SceneGeometry _geometry;
    readonly Material[] _materials;
    readonly Light[] _lights;
    /// <summary>Each light's lane form (<see cref="Light.LaneForm"/>), asked once: the packet path's SIMD point lights.</summary>
    readonly LanePointLight?[] _laneForms;
    readonly int[] _objectMaterial;
    readonly int _padded;
    readonly TermTables _tables;
    readonly Eq2Walker _walker;

    public WhittedIntegrator(Scene scene, SceneGeometry geometry)
    {
        // Eq. 2 has no sky term: Whitted's escaping rays see a uniform background, which a sky that varies with direction is not.
        if (scene.SkyDistribution != SkyDistribution.Uniform && SpectralMath.Any(scene.Background))
            throw new InputException($"{scene.SourcePath}: $.sky.distribution",
                "the whitted integrator sees the sky as one uniform background and cannot render a CIE overcast sky",
                "render it with \"integrator\": \"path\" in the scene, or --integrator path");
        _scene = scene;
        _geometry = geometry;
        _materials = scene.Materials.ToArray();
        _lights = scene.Lights.ToArray();
        _laneForms = _lights.Select(l => l.LaneForm).ToArray();
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _padded = scene.PaddedBands;
        _tables = new TermTables(scene);
        _walker = new Eq2Walker(scene, geometry, _tables);
        // The term tables side by side for the packet path's one-pass band sums: the global ambient of each material, then per
        // (light, material) the ambient, diffuse and specular tables, at the offsets below.
        int materials = _materials.Length, pairs = _tables.Diffuse.Length;
        _tablesFlat = new LineFloats((materials + 3 * pairs) * _padded);
        _globalAmbientAt = new int[materials];
        _ambientAt = new int[pairs]; _diffuseAt = new int[pairs]; _specularAt = new int[pairs];
        int at = 0;
        int Put(float[] table) { table.AsSpan().CopyTo(Flat[at..]); at += _padded; return at - _padded; }
        for (int m = 0; m < materials; m++) _globalAmbientAt[m] = Put(_tables.GlobalAmbient[m]);
        for (int t = 0; t < pairs; t++)
        {
            _ambientAt[t] = Put(_tables.Ambient[t]);
            _diffuseAt[t] = Put(_tables.Diffuse[t]);
            _specularAt[t] = Put(_tables.Specular[t]);
        }
        // Per (light, material), the direct pair's offsets and its Y colour lane, in one place for a lane's Direct term.
        int y = scene.Bands + 1;
        _direct = new DirectPair[pairs];
        for (int t = 0; t < pairs; t++)
            _direct[t] = new DirectPair(_diffuseAt[t], _specularAt[t], _tables.Diffuse[t][y], _tables.Specular[t][y]);
    }

    /// <summary>A (light, material) pair's diffuse and specular tables in <see cref="Flat"/> and their Y colour lane (the
    /// values <see cref="TermTables"/> holds, gathered so a packet lane's direct term reads one entry).</summary>
    readonly record struct DirectPair(int DiffuseAt, int SpecularAt, float DiffuseY, float SpecularY);

    readonly DirectPair[] _direct;

    // On a cache-line boundary (LineFloats): each table starts on one, as the one-pass band sums' SIMD loads do.
    readonly LineFloats _tablesFlat;
    Span<float> Flat => _tablesFlat.Span;
    readonly int[] _globalAmbientAt, _ambientAt, _diffuseAt, _specularAt;

    /// <summary>Scratch floats a thread needs: a spectrum per recursion level (two per level, as before), and for packets
    /// each light's lane results (<see cref="LightLanes"/>).</summary>
    public int ScratchLength => (_scene.MaxDepth + 2) * 2 * _padded + _lights.Length * LightLanes.Floats;

    /// <summary>Where the scratch's frames (one per recursion level below the camera ray's) end: the sink's two spectra
    /// for a shadow ray through a medium follow.</summary>
    int FramesEnd => (_scene.MaxDepth + 1) * _padded;

    /// <inheritdoc/>
    public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters) =>
        Radiance(in sample, result, scratch, ref counters, ref Unsafe.NullRef<PixelInfo>());

    /// <inheritdoc/>
    public int Radiance(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info)
    {
        var sink = new Sink(_tables, _scene.Bands, result, scratch, FramesEnd, ref info);
        return _walker.Trace(ref sink, sample.Ray, 0, -1, 1f, ref counters);
    }

    /// <summary>
    /// Eq. 2's terms summed into the ray's spectrum, each a precomputed table times its scalar
    /// (<see cref="SpectralMath.AddScaled"/>, <see cref="SpectralMath.AddScaled2"/>), a mirror or transmitted ray's spectrum
    /// (its own frame in the scratch) added through k_r or k_t
    /// (<see cref="SpectralMath.AddProduct(Span{float}, ReadOnlySpan{float}, ReadOnlySpan{float}, float)"/>).
    /// At the camera ray's hit it records, when asked, which lights reach the point and the Y of its diffuse and specular terms.
    /// </summary>
    ref struct Sink : IWalkSink
    {
        readonly TermTables _tables;
        readonly int _padded, _bands;
        readonly Span<float> _result, _scratch;
        readonly ref PixelInfo _info;   // null: no analysis
        Span<float> _frame;
        int _depth;
        // The current hit's textured lobes and their texels: valid while _textured (set by Texels, cleared by Begin).
        bool _textured;
        TexturedTerms? _diffuse, _specular;
        TexelTaps _diffuseTaps, _specularTaps;

        // Past the frames (one per recursion level): a shadow ray's transmittance, and a direct pair before it is applied.
        readonly Span<float> _transmittance, _pair;

        public Sink(TermTables tables, int bands, Span<float> result, Span<float> scratch, int frames, ref PixelInfo info)
        {
            _tables = tables; _bands = bands; _padded = result.Length;
            _result = result; _scratch = scratch; _frame = result;
            _info = ref info;
            _transmittance = scratch.Slice(frames, _padded);
            _pair = scratch.Slice(frames + _padded, _padded);
        }

        public readonly Span<float> Transmittance => _transmittance;

        /// <summary>The pair as <see cref="Direct"/> adds it, into a frame of its own, then ⊙ T per band into the ray's frame.</summary>
        public void DirectThrough(int light, int material, int term, float d, float nl, float s, bool specular,
            ReadOnlySpan<float> transmittance)
        {
            var frame = _frame;
            _frame = _pair;
            _pair.Clear();
            Direct(light, material, term, d, nl, s, specular);
            _frame = frame;
            for (int b = 0; b < _bands; b++) frame[b] += _pair[b] * transmittance[b];   // (colour: eq. 3 on the bands, Attenuate)
        }

        /// <summary>The ray's frame ⊙= T per band; its colour lanes no longer follow, so the pixel's colour is eq. 3 on its
        /// bands.</summary>
        public readonly void Attenuate(Medium medium, Vector3 origin, Vector3 direction, float distance, ref RayCounters counters)
        {
            medium.Attenuate(origin, direction, distance, _frame[.._bands]);
            counters.Fallback++;
        }

        public static bool Prunes => true;
        public static bool Budgeted => true;
        public static bool ReflectPerBand => false;

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        readonly Span<float> Frame(int depth) => depth == 0 ? _result : _scratch.Slice((depth - 1) * _padded, _padded);

        public void Begin() { _frame.Clear(); _textured = false; }

        public void Texels(TexturedTerms terms, in TexelTaps taps)
        {
            if (!_textured) { _diffuse = null; _specular = null; _textured = true; }
            if (terms.Lobe == TexturedLobe.Diffuse) { _diffuse = terms; _diffuseTaps = taps; }
            else { _specular = terms; _specularTaps = taps; }
        }
        public readonly void Background() => _tables.Background.AsSpan().CopyTo(_frame);

        public readonly void GlobalAmbient(int material)
        {
            if (_textured && _diffuse is { Ambient: true } t) AddTexels(t, in _diffuseTaps, 0, 1f);
            else SpectralMath.AddScaled(_frame, _tables.GlobalAmbient[material], 1f);
        }

        public readonly void Ambient(int light, int material, int term, float spot)
        {
            if (_textured && _diffuse is { Ambient: true } t) AddTexels(t, in _diffuseTaps, 1 + light, spot);
            else SpectralMath.AddScaled(_frame, _tables.Ambient[term], spot);
        }

        /// <summary>The tables of <paramref name="slot"/> of the texels <paramref name="taps"/>, each by its weight, times
        /// <paramref name="scale"/>.</summary>
        readonly void AddTexels(TexturedTerms t, in TexelTaps taps, int slot, float scale)
        {
            int offset = t.SlotOffset(slot);
            for (int i = 0; i < taps.Count; i++)
                SpectralMath.AddScaled(_frame, t.Tap(in taps, i).Slice(offset, _padded), scale * taps.Weight[i]);
        }

        /// <summary>A light's direct pair at a textured hit: each textured lobe's term from its texels (the light's slot), the
        /// other from its plain table.</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]   // textured hits only: kept out of the walk's code
        readonly void TexturedDirect(int light, int term, float d, float nl, float s, bool specular)
        {
            if (_diffuse is { } dt) AddTexels(dt, in _diffuseTaps, dt.LightSlot(light), d * nl);
            else SpectralMath.AddScaled(_frame, _tables.Diffuse[term], d * nl);
            if (specular)
            {
                if (_specular is { } st) AddTexels(st, in _specularTaps, st.LightSlot(light), d * s);
                else SpectralMath.AddScaled(_frame, _tables.Specular[term], d * s);
            }
            if (_depth == 0 && !Unsafe.IsNullRef(ref _info))
            {
                if (light < 32) _info.LitMask |= 1u << light;
                int yLane = _bands + 1;
                _info.DiffuseY += d * nl * (_diffuse is { } dy ? TexelsY(dy, in _diffuseTaps, light) : _tables.Diffuse[term][yLane]);
                _info.SpecularY += d * s * (_specular is { } sy ? TexelsY(sy, in _specularTaps, light) : _tables.Specular[term][yLane]);
            }
        }

        /// <summary>The Y colour lane of light <paramref name="light"/>'s slot of the texels <paramref name="taps"/>, weighted.</summary>
        readonly float TexelsY(TexturedTerms t, in TexelTaps taps, int light)
        {
            int at = t.SlotOffset(t.LightSlot(light)) + _bands + 1;
            float y = 0;
            for (int i = 0; i < taps.Count; i++) y += taps.Weight[i] * t.Tap(in taps, i)[at];
            return y;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public readonly void Direct(int light, int material, int term, float d, float nl, float s, bool specular)
        {
            if (_textured)
            {
                TexturedDirect(light, term, d, nl, s, specular);
                return;
            }
            var diffuse = _tables.Diffuse[term];
            if (specular) SpectralMath.AddScaled2(_frame, diffuse, d * nl, _tables.Specular[term], d * s);
            else SpectralMath.AddScaled(_frame, diffuse, d * nl);
            if (_depth == 0 && !Unsafe.IsNullRef(ref _info))
            {
                if (light < 32) _info.LitMask |= 1u << light;
                int y = _bands + 1;   // the Y colour lane
                _info.DiffuseY += d * nl * diffuse[y];
                _info.SpecularY += d * s * _tables.Specular[term][y];
            }
        }

        // Per-band paths: the colour comes from the band values.
        public readonly void Split(ref RayCounters counters) => counters.Fallback++;

        public void Enter(int material, bool transmit, int band, float factor) => _frame = Frame(++_depth);

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Leave(int material, bool transmit, int band, float factor, ref RayCounters counters)
        {
            var incoming = _frame;
            _frame = Frame(--_depth);
            if (!transmit)
            {
                SpectralMath.AddProduct(_frame, _tables.Mirror[material], incoming, factor);
                if (_tables.MirrorColoured[material]) counters.Fallback++;
            }
            else if (band < 0)
            {
                SpectralMath.AddProduct(_frame, _tables.Transmit[material], incoming, factor);
                if (_tables.TransmitColoured[material]) counters.Fallback++;
            }
            else _frame[band] += _tables.Transmit[material][band] * incoming[band] * factor;
        }

        public void LeavePerBand(Material m, int material, float cosI, bool outside, ref RayCounters counters)
        {
            var incoming = _frame;
            _frame = Frame(--_depth);
            var mirror = _tables.Mirror[material];
            for (int b = 0; b < _bands; b++) _frame[b] += mirror[b] * incoming[b] * m.MirrorFactor(cosI, outside, b);
            counters.Fallback++;
        }
    }
}
