using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

// Spectral textures in the path tracer (issue 26): a material's diffuse reflectance (and specular weight) given as a
// texture is projected onto the fine grid once (FineTexture, shared by the threads) and looked up at every path vertex
// with the Whitted route's uv, bilinear and mip-map filtering; the filtered texel replaces the BSDF's spectrum in f for
// next-event estimation and BSDF sampling alike, and in the lobe choice's channel share. The texel goes into the
// thread's scratch: nothing is allocated per path.
public sealed partial class PathIntegrator
{
    FineTexture?[] _diffuseTexture = [], _specularTexture = [];
    float[] _diffuseChannel = [], _specularChannel = [];   // a textured material's plain m_diff, m_spec channel values
    bool _textured;
    float _pixelAngle;

    /// <summary>A vertex's texels on the fine grid (an empty span: the material's own spectrum).</summary>
    readonly ref struct SurfaceTexels(Span<float> diffuse, Span<float> specular)
    {
        public readonly Span<float> Diffuse = diffuse, Specular = specular;
        public bool Any => !Diffuse.IsEmpty || !Specular.IsEmpty;
    }

    /// <summary>Scratch the textures take after the walk's own five spectra: a diffuse and a specular texel.</summary>
    int TextureScratch => _textured ? 2 * _padded : 0;

    /// <summary>Material <paramref name="m"/>'s textures onto the fine grid, or bad input naming what cannot be textured.</summary>
    void TakeTextures(Scene scene, int m)
    {
        var material = scene.Materials[m];
        if (material.DiffuseTexture is null) return;
        string where = $"{scene.SourcePath}: $.materials.{material.Name}.diffuse";
        if (!_bsdf[m].TakesTextures)
            throw new InputException(where, $"material '{material.Name}' ({material.Bsdf.GetType().Name}) is textured: the path integrator textures eq. 2 and lambertian materials only",
                "give this material a spectrum, or use an eq2 or lambertian material for the texture");
        if (material.Fluorescence is not null)
            throw new InputException(where, $"material '{material.Name}' is textured and fluorescent: a texture with a re-radiation matrix is not supported yet",
                "give the fluorescent material a spectrum, or drop its \"fluorescence\"");
        if (_diffuseTexture.Length == 0)
        {
            _diffuseTexture = new FineTexture?[scene.Materials.Count];
            _specularTexture = new FineTexture?[scene.Materials.Count];
            _diffuseChannel = new float[scene.Materials.Count];
            _specularChannel = new float[scene.Materials.Count];
            // A camera pixel's angular width at the image centre: a hit's footprint t·angle/|cos θ| picks the mip level,
            // as the Whitted route's (Eq2Walker): a secondary ray's cone starts at its own origin.
            _pixelAngle = 2 * MathF.Tan(scene.Camera.Fov * MathF.PI / 360) / Math.Max(1, scene.Camera.Height);
            _textured = true;
        }
        _diffuseTexture[m] = new FineTexture(material.DiffuseTexture, _grid);
        _diffuseChannel[m] = _grid.Luminance(_grid.Resample(material.Diffuse));
        _specularChannel[m] = _grid.Luminance(_grid.Resample(material.Specular));
    }

    /// <summary>
    /// The texels of material <paramref name="m"/> at <paramref name="hit"/> into scratch (after the walk's five spectra),
    /// and the smooth lobes' channel share from them; none when the material has no texture.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    SurfaceTexels Texels(int m, scoped in SurfaceHit hit, Vector3 wo, Span<float> scratch, scoped ref float smoothShare)
    {
        var diffuse = _diffuseTexture[m];
        var specular = _specularTexture[m];
        if (diffuse is null && specular is null) return default;
        var uv = _geometry.TexCoord(in hit, out float density);
        float width = hit.T * _pixelAngle / MathF.Max(MathF.Abs(Vector3.Dot(hit.GeometricNormal, wo)), 0.25f) * density;
        Span<float> d = default, s = default;
        if (diffuse is not null) diffuse.Filter(uv, width, d = scratch.Slice(5 * _padded, _padded));
        if (specular is not null) specular.Filter(uv, width, s = scratch.Slice(6 * _padded, _padded));
        if (_smooth[m])
        {   // the channel value of m_diff + m_spec, as for a plain material (Σ c_f·v_f is linear)
            float share = diffuse is not null ? _grid.Luminance(d) : _diffuseChannel[m];
            share += specular is not null ? _grid.Luminance(s) : _specularChannel[m];
            smoothShare = MathF.Max(share, 1e-6f);
        }
        return new SurfaceTexels(d, s);
    }

    /// <summary>f of the smooth lobes, with the vertex's texels when it has any.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static void Evaluate(Bsdf bsdf, in SurfaceTexels texels, Vector3 wo, Vector3 wi, Vector3 ns, Span<float> f)
    {
        if (texels.Any) bsdf.Evaluate(wo, wi, ns, texels.Diffuse, texels.Specular, f);
        else bsdf.Evaluate(wo, wi, ns, f);
    }
}
