using System.Runtime.CompilerServices;
using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Whitted ray tracing with the paper's local model, eq. 2, in every band at once:
///   L(b) = a_glob(b)·m_amb(b) + Σ_k c_spot,k · { I_amb,k(b)·m_amb(b) + d_k·[L_diff,k(b) + L_spec,k(b)] }
/// with L_diff = I_k·m_diff·max(0, n·l), L_spec = I_k·m_spec·max(0, n·h)^shininess (Blinn–Phong) or
/// (r·v)^shininess (Phong), hard shadows, then k_r·L(reflected) and k_t·L(refracted) to the maximum
/// depth. One ray carries all bands; a wavelength-dependent index of refraction splits it per band.
/// </summary>
public sealed class WhittedIntegrator
{
    readonly Scene _scene;
    readonly SceneGeometry _geometry;
    readonly Material[] _materials;
    readonly Light[] _lights;
    readonly int[] _objectMaterial;
    readonly int _padded;
    // Luminance (eq. 3's Y weights) of I_k ⊙ m_diff and I_k ⊙ m_spec per (light, material), for the highlight mask.
    readonly float[] _diffuseY, _specularY;

    public WhittedIntegrator(Scene scene, SceneGeometry geometry)
    {
        _scene = scene;
        _geometry = geometry;
        _materials = scene.Materials.ToArray();
        _lights = scene.Lights.ToArray();
        _objectMaterial = scene.Objects.Select(o => o.Material).ToArray();
        _padded = scene.PaddedBands;
        _diffuseY = new float[_lights.Length * _materials.Length];
        _specularY = new float[_diffuseY.Length];
        var wy = scene.Colorimeter.Wy;
        for (int k = 0; k < _lights.Length; k++)
        for (int m = 0; m < _materials.Length; m++)
        {
            double d = 0, sp = 0;
            for (int b = 0; b < scene.Bands; b++)
            {
                d += wy[b] * _lights[k].Intensity[b] * _materials[m].Diffuse[b];
                sp += wy[b] * _lights[k].Intensity[b] * _materials[m].Specular[b];
            }
            _diffuseY[k * _materials.Length + m] = (float)d;
            _specularY[k * _materials.Length + m] = (float)sp;
        }
    }

    public SceneGeometry Geometry => _geometry;
    public int PaddedBands => _padded;

    /// <summary>Scratch floats a thread needs: two spectra per recursion level.</summary>
    public int ScratchLength => (_scene.MaxDepth + 2) * 2 * _padded;

    /// <summary>
    /// The radiance along <paramref name="ray"/> into <paramref name="result"/> (padded band values).
    /// <paramref name="band"/> ≥ 0 marks a ray that carries only that band (after dispersion).
    /// Returns the object hit, or −1.
    /// </summary>
    public int Radiance(Ray ray, int depth, int band, Span<float> result, Span<float> scratch, ref RayCounters counters)
    {
        PixelInfo unused = default;
        return Radiance(ray, depth, band, result, scratch, ref counters, ref unused);
    }

    /// <summary>As above; at depth 0 also records which lights reach the point and the Y of its diffuse and specular terms.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public int Radiance(Ray ray, int depth, int band, Span<float> result, Span<float> scratch, ref RayCounters counters, ref PixelInfo info)
    {
        result.Clear();
        if (!_geometry.Intersect(ref ray, out var hit))
        {
            _scene.Background.AsSpan().CopyTo(result);
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

        if (_scene.HasGlobalAmbient && m.HasAmbient) SpectralMath.AddProduct(result, _scene.GlobalAmbient, m.Ambient);

        for (int k = 0; k < _lights.Length; k++)
        {
            var light = _lights[k];
            Vector3 l;
            float dist;
            if (light.Kind == LightKind.Directional) { l = -light.Direction; dist = float.PositiveInfinity; }
            else
            {
                var toLight = light.Position - p;
                dist = toLight.Length();
                if (dist == 0) continue;
                l = toLight / dist;
            }
            float spot = light.SpotFactor(-l);
            if (spot == 0) continue;
            if (light.HasAmbient && m.HasAmbient) SpectralMath.AddProduct(result, light.Ambient, m.Ambient, spot);

            float nl = Vector3.Dot(n, l);
            if (nl <= 0) continue;
            counters.Shadow++;
            var shadowRay = new Ray(pAbove, l, float.IsInfinity(dist) ? float.PositiveInfinity : dist - 2 * eps);
            if (_geometry.Occluded(shadowRay)) continue;

            float d = light.Attenuation(dist) * spot;
            float s = 0;
            if (m.HasSpecular)
            {
                if (m.Model == SpecularModel.BlinnPhong)
                {
                    var h = Vector3.Normalize(l + v);
                    s = MathF.Pow(MathF.Max(0, Vector3.Dot(n, h)), m.Shininess);
                }
                else
                {
                    var r = 2 * nl * n - l;
                    s = MathF.Pow(MathF.Max(0, Vector3.Dot(r, v)), m.Shininess);
                }
                SpectralMath.AddProduct2(result, light.Intensity, m.Diffuse, d * nl, m.Specular, d * s);
            }
            else SpectralMath.AddProduct(result, light.Intensity, m.Diffuse, d * nl);
            if (depth == 0)
            {
                if (k < 32) info.LitMask |= 1u << k;
                info.DiffuseY += d * nl * _diffuseY[k * _materials.Length + mi];
                info.SpecularY += d * s * _specularY[k * _materials.Length + mi];
            }
        }

        if (depth >= _scene.MaxDepth || !(m.HasMirror || m.HasTransmission)) return hit.Object;

        var incoming = scratch[.._padded];
        var rest = scratch[(2 * _padded)..];
        float cosI = Vector3.Dot(n, v);
        if (m.HasMirror)
        {
            var dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
            counters.Secondary++;
            Radiance(new Ray(pAbove, dir), depth + 1, band, incoming, rest, ref counters);
            float f = m.Fresnel ? FresnelDielectric(cosI, outside ? 1 / IorOf(m, band) : IorOf(m, band)) : 1f;
            SpectralMath.AddProduct(result, m.Mirror, incoming, f);
        }
        if (m.HasTransmission)
        {
            if (!m.Dispersive || band >= 0)
                Refract(m, band < 0 ? 0 : band, band, ray, n, ng, v, cosI, outside, p, depth, result, incoming, rest, ref counters, allBands: band < 0);
            else
            {
                // Dispersion: every band bends by its own index, so each gets its own refracted ray.
                var one = scratch.Slice(_padded, _padded);
                for (int b = 0; b < _scene.Bands; b++)
                {
                    one.Clear();
                    Refract(m, b, b, ray, n, ng, v, cosI, outside, p, depth, one, incoming, rest, ref counters, allBands: false);
                    result[b] += one[b];
                }
            }
        }
        return hit.Object;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Refract(Material m, int iorBand, int band, in Ray ray, Vector3 n, Vector3 ng, Vector3 v, float cosI, bool outside, Vector3 p, int depth,
        Span<float> result, Span<float> incoming, Span<float> rest, ref RayCounters counters, bool allBands)
    {
        float eta = outside ? 1f / m.Ior[iorBand] : m.Ior[iorBand];   // n_i / n_t
        float sin2T = eta * eta * (1 - cosI * cosI);
        Vector3 dir;
        Vector3 origin;
        float weight = 1;
        if (sin2T >= 1)
        {   // total internal reflection: the transmitted share goes into the mirror direction
            dir = Vector3.Normalize(ray.Direction + 2 * cosI * n);
            origin = p + _geometry.Epsilon * ng;
        }
        else
        {
            float cosT = MathF.Sqrt(1 - sin2T);
            dir = Vector3.Normalize(eta * ray.Direction + (eta * cosI - cosT) * n);
            origin = p - _geometry.Epsilon * ng;
            if (m.Fresnel) weight = 1 - FresnelDielectric(cosI, eta);
        }
        counters.Secondary++;
        Radiance(new Ray(origin, dir), depth + 1, allBands ? -1 : band, incoming, rest, ref counters);
        if (allBands) SpectralMath.AddProduct(result, m.Transmit, incoming, weight);
        else result[band] += m.Transmit[band] * incoming[band] * weight;
    }

    static float IorOf(Material m, int band) => m.Ior[band < 0 ? 0 : band];

    /// <summary>Unpolarised Fresnel reflectance of a dielectric interface, eta = n_i / n_t (Hecht, Optics §4.6).</summary>
    public static float FresnelDielectric(float cosI, float eta)
    {
        float sin2T = eta * eta * (1 - cosI * cosI);
        if (sin2T >= 1) return 1;
        float cosT = MathF.Sqrt(1 - sin2T);
        float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
        float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
        return 0.5f * (rs * rs + rp * rp);
    }
}
