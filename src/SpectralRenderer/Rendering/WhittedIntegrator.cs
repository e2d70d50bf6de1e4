using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

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
public sealed partial class WhittedIntegrator : IPacketIntegrator
{
    readonly Scene _scene;
    readonly SceneGeometry _geometry;
    readonly Material[] _materials;
    readonly Light[] _lights;
    readonly int[] _objectMaterial;
    readonly int _padded;
    readonly TermTables _tables;
    readonly bool _physical;
    // Per material, the largest mirror and transmit factor over the bands: a branch's weight grows by at most these.
    readonly float[] _mirrorMax, _transmitMax;
    readonly float _minWeight;

    public WhittedIntegrator(Scene scene, SceneGeometry geometry)
    {
        _scene = scene;
        _geometry = geometry;
        _materials = scene.Materials.ToArray();
        _lights = scene.Lights.ToArray();
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _padded = scene.PaddedBands;
        _tables = new TermTables(scene);
        _physical = scene.Radiometry == Radiometry.Physical;
        _mirrorMax = _tables.Mirror.Select(t => t.AsSpan(0, scene.Bands).ToArray().DefaultIfEmpty(0).Max()).ToArray();
        _transmitMax = _tables.Transmit.Select(t => t.AsSpan(0, scene.Bands).ToArray().DefaultIfEmpty(0).Max()).ToArray();
        _minWeight = scene.MinRayWeight;
        // The term tables side by side for the packet path's one-pass band sums: the global ambient of each material, then per
        // (light, material) the ambient, diffuse and specular tables, at the offsets below.
        int materials = _materials.Length, pairs = _tables.Diffuse.Length;
        _flat = new float[(materials + 3 * pairs) * _padded];
        _globalAmbientAt = new int[materials];
        _ambientAt = new int[pairs]; _diffuseAt = new int[pairs]; _specularAt = new int[pairs];
        int at = 0;
        int Put(float[] table) { table.AsSpan().CopyTo(_flat.AsSpan(at)); at += _padded; return at - _padded; }
        for (int m = 0; m < materials; m++) _globalAmbientAt[m] = Put(_tables.GlobalAmbient[m]);
        for (int t = 0; t < pairs; t++) { _ambientAt[t] = Put(_tables.Ambient[t]); _diffuseAt[t] = Put(_tables.Diffuse[t]); _specularAt[t] = Put(_tables.Specular[t]); }
    }

    readonly float[] _flat;
    readonly int[] _globalAmbientAt, _ambientAt, _diffuseAt, _specularAt;

    /// <summary>Scratch floats a thread needs: two spectra per recursion level.</summary>
    public int ScratchLength => (_scene.MaxDepth + 2) * 2 * _padded;

    /// <inheritdoc/>
    public int Radiance(Ray ray, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info) =>
        Radiance(ray, 0, -1, 1f, result, scratch, ref counters, ref info);

    /// <summary>
    /// The radiance along <paramref name="ray"/> into <paramref name="result"/> (padded band values).
    /// <paramref name="band"/> ≥ 0 marks a ray that carries only that band (after dispersion).
    /// Returns the object hit, or −1. <paramref name="weight"/> is the largest factor by which this ray's radiance
    /// enters the pixel (1 for a camera ray): below <see cref="Scene.MinRayWeight"/> a branch is not traced further.
    /// </summary>
    public int Radiance(Ray ray, int depth, int band, float weight, Span<float> result, Span<float> scratch, ref RayCounters counters)
    {
        PixelInfo unused = default;
        return Radiance(ray, depth, band, weight, result, scratch, ref counters, ref unused);
    }

    /// <summary>As above; at depth 0 also records which lights reach the point and the Y of its diffuse and specular terms.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Radiance(Ray ray, int depth, int band, float weight, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info)
    {
        result.Clear();
        if (!_geometry.Intersect(ref ray, out var hit))
        {
            _tables.Background.AsSpan().CopyTo(result);
            return -1;
        }
        int mi = _objectMaterial[hit.Object];
        var m = _materials[mi];
        var v = -ray.Direction;
        // The face normal decides which side the viewer is on; the shading normal follows it.
        bool outside = Vector3.Dot(hit.GeometricNormal, v) >= 0;
        var ng = outside ? hit.GeometricNormal : -hit.GeometricNormal;
        var n = outside ? hit.Normal : -hit.Normal;
        float eps = _geometry.Epsilon;
        var p = hit.Position;
        var pAbove = p + eps * ng;

        if (_scene.HasGlobalAmbient && m.HasAmbient) SpectralMath.AddScaled(result, _tables.GlobalAmbient[mi], 1f);

        for (int k = 0; k < _lights.Length; k++)
        {
            var light = _lights[k];
            if (!light.Illuminate(p, out var ls)) continue;
            var l = ls.Direction;
            float dist = ls.Distance, spot = ls.Spot;
            int term = _tables.Index(k, mi);
            if (light.HasAmbient && m.HasAmbient) SpectralMath.AddScaled(result, _tables.Ambient[term], spot);

            float nl = Vector3.Dot(n, l);
            if (nl <= 0) continue;
            counters.Shadow++;
            var shadowRay = new Ray(pAbove, l, float.IsInfinity(dist) ? float.PositiveInfinity : dist - 2 * eps);
            if (_geometry.Occluded(shadowRay)) continue;

            float d = ls.Attenuation * spot;
            float s = 0;
            var diffuse = _tables.Diffuse[term];
            if (m.HasSpecular)
            {
                // Physical: the lobe is a BRDF, so it is weighted by cos θ_i like the diffuse one (paper: eq. 2 as written).
                s = m.SpecularFactor(n, l, v, nl) * (_physical ? nl : 1f);
                SpectralMath.AddScaled2(result, diffuse, d * nl, _tables.Specular[term], d * s);
            }
            else SpectralMath.AddScaled(result, diffuse, d * nl);
            if (depth == 0)
            {
                if (k < 32) info.LitMask |= 1u << k;
                int y = _scene.Bands + 1;   // the Y colour lane
                info.DiffuseY += d * nl * diffuse[y];
                info.SpecularY += d * s * _tables.Specular[term][y];
            }
        }

        if (depth >= _scene.MaxDepth || !(m.HasMirror || m.HasTransmission)) return hit.Object;
        // Bounded work: a camera ray's tree ends where its budget is spent (the renderer counts those rays).
        if (counters.BudgetSpent) { counters.OverBudget = true; return hit.Object; }

        var incoming = scratch[.._padded];
        var rest = scratch[(2 * _padded)..];
        float cosI = Vector3.Dot(n, v);
        float mirrorWeight = m.HasMirror ? weight * _mirrorMax[mi] * m.MirrorFactor(cosI, outside, band) : 0;
        if (m.HasMirror && mirrorWeight < _minWeight) counters.PrunedRays++;   // adaptive depth (Hall & Greenberg 1983)
        else if (m.HasMirror)
        {
            var dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
            counters.Secondary++;
            Radiance(new Ray(pAbove, dir), depth + 1, band, mirrorWeight, incoming, rest, ref counters);
            if (m.Fresnel && m.Dispersive && band < 0)
            {   // F from each band's own index: reflection + transmission = 1 in every band; the colour lanes cannot follow.
                for (int b = 0; b < _scene.Bands; b++) result[b] += _tables.Mirror[mi][b] * incoming[b] * m.MirrorFactor(cosI, outside, b);
                counters.Fallback++;
            }
            else
            {
                SpectralMath.AddProduct(result, _tables.Mirror[mi], incoming, m.MirrorFactor(cosI, outside, band));
                if (_tables.MirrorColoured[mi]) counters.Fallback++;
            }
        }
        if (m.HasTransmission)
        {
            var at = new SurfacePoint(p, n, ng, ray.Direction, cosI, outside);
            float wt = weight * _transmitMax[mi];
            if (!m.Dispersive || band >= 0)
                Refract(m, mi, band, at, depth, wt, result, incoming, rest, ref counters);
            else
            {
                // Dispersion: every band bends by its own index, so each gets its own refracted ray.
                var one = scratch.Slice(_padded, _padded);
                for (int b = 0; b < _scene.Bands; b++)
                {
                    one.Clear();
                    Refract(m, mi, b, at, depth, wt, one, incoming, rest, ref counters);
                    result[b] += one[b];
                }
                counters.Fallback++;   // per-band paths: the colour comes from the band values
            }
        }
        return hit.Object;
    }

    /// <summary>A shading point: position, shading and face normals on the viewer's side, incident direction, cos θ_i = n·v.</summary>
    readonly struct SurfacePoint(Vector3 p, Vector3 n, Vector3 ng, Vector3 incident, float cosI, bool outside)
    {
        public readonly Vector3 P = p, N = n, Ng = ng, Incident = incident;
        public readonly float CosI = cosI;
        public readonly bool Outside = outside;
    }

    /// <summary>k_t·L(refracted) into <paramref name="result"/>: all bands when <paramref name="band"/> is −1, else that band only.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Refract(Material m, int mi, int band, in SurfacePoint at, int depth, float branch,
        Span<float> result, Span<float> incoming, Span<float> rest, ref RayCounters counters)
    {
        float eta = m.Eta(at.Outside, band);   // n_i / n_t
        float cosI = at.CosI;
        float sin2T = eta * eta * (1 - cosI * cosI);
        Vector3 dir;
        Vector3 origin;
        float weight = 1;
        if (sin2T >= 1)
        {
            // Total internal reflection. With Fresnel, F = 1: the mirror lobe already reflects everything (k_r·F) and
            // k_t·(1 − F) = 0 — nothing more to add. Without Fresnel the constant k_t share goes into the mirror direction.
            if (m.Fresnel) return;
            dir = Vector3.Normalize(at.Incident + 2 * cosI * at.N);
            origin = at.P + _geometry.Epsilon * at.Ng;
        }
        else
        {
            float cosT = MathF.Sqrt(1 - sin2T);
            dir = Vector3.Normalize(eta * at.Incident + (eta * cosI - cosT) * at.N);
            origin = at.P - _geometry.Epsilon * at.Ng;
            weight = m.TransmitFactor(cosI, eta);
        }
        if (branch * weight < _minWeight) { counters.PrunedRays++; return; }   // adaptive depth (Hall & Greenberg 1983)
        counters.Secondary++;
        Radiance(new Ray(origin, dir), depth + 1, band, branch * weight, incoming, rest, ref counters);
        if (band < 0)
        {
            SpectralMath.AddProduct(result, _tables.Transmit[mi], incoming, weight);
            if (_tables.TransmitColoured[mi]) counters.Fallback++;
        }
        else result[band] += m.Transmit[band] * incoming[band] * weight;
    }
}
