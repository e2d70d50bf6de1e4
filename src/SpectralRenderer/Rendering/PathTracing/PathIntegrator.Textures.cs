using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Rendering.Emitters;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

// Spectral textures in the path tracer (issue 26): a material's diffuse reflectance, specular weight or emitted radiance
// given as a texture is projected onto the sub-band grid once (SubBandTexture, shared by the threads) and looked up with the
// Whitted route's uv, bilinear and mip-map filtering: at every path vertex, the filtered texel replaces the BSDF's
// spectrum in f for next-event estimation and BSDF sampling alike, and in the lobe choice's channel share; an emitter's
// texel is looked up where a path hits it and where next-event estimation draws a point on it. Texels go into the
// thread's scratch: nothing is allocated per path. A fluorescent material's diffuse texture is its reflective diagonal per
// texel (SceneLoader.Fluorescence.cs): the texel replaces the diagonal as above, and the matrix's shifted part — next-event
// excitation and the shifted lobe (PathIntegrator.Fluorescence.cs), with its share in the lobe choice — is the same at
// every texel, so a textured fluorescent vertex takes no other code than the two parts' own.
internal sealed partial class PathIntegrator
{
    bool _textured;   // has a material of the scene a texture (PathMaterial)?
    float _pixelAngle;

    /// <summary>Scratch the textures take at <see cref="TextureBase"/>: a diffuse, a specular and an emitted texel.</summary>
    int TextureScratch => _textured ? 3 * _padded : 0;

    /// <summary>Whether the scene's materials are textured, and the camera's pixel angle their lookups' footprint takes.</summary>
    void TakeTextures(Scene scene)
    {
        _textured = _materials.Any(m => m.Textured);
        // A camera pixel's angular width at the image centre: a hit's footprint t·angle/|cos θ| picks the mip level,
        // as the Whitted route's (Eq2Walker): a secondary ray's cone starts at its own origin.
        if (_textured) _pixelAngle = 2 * MathF.Tan(scene.Camera.Fov * MathF.PI / 360) / Math.Max(1, scene.Camera.Height);
    }

    /// <summary>The footprint (uv units) of a lookup at distance <paramref name="t"/>, cosine <paramref name="cos"/> and mapping density
    /// <paramref name="density"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    float Footprint(float t, float cos, float density) => t * _pixelAngle / MathF.Max(MathF.Abs(cos), 0.25f) * density;

    /// <summary>
    /// The texels of <paramref name="material"/> at <paramref name="hit"/> into scratch (at TextureBase),
    /// and the smooth lobes' channel share from them; no diffuse or specular texel when the material has no such texture.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // textured vertices only: kept out of the walk's code
    SurfaceTexels Texels(PathMaterial material, scoped in SurfaceHit hit, Vector3 wo, Span<float> scratch, scoped ref float smoothShare)
    {
        var emission = scratch.Slice(TextureBase + 2 * _padded, _padded);
        var diffuse = material.DiffuseTexture;
        var specular = material.SpecularTexture;
        if (diffuse is null && specular is null) return new SurfaceTexels(default, default, emission);
        var uv = _geometry.TexCoord(in hit, out float density);
        float width = Footprint(hit.T, Vector3.Dot(hit.GeometricNormal, wo), density);
        Span<float> d = default, s = default;
        if (diffuse is not null) diffuse.Filter(uv, width, d = scratch.Slice(TextureBase, _padded));
        if (specular is not null) specular.Filter(uv, width, s = scratch.Slice(TextureBase + _padded, _padded));
        if (material.Smooth)
        {   // the channel value of m_diff + m_spec, as for a plain material (Σ c_f·v_f is linear)
            float share = diffuse is not null ? _grid.Luminance(d) : material.DiffuseChannel;
            share += specular is not null ? _grid.Luminance(s) : material.SpecularChannel;
            smoothShare = MathF.Max(share, 1e-6f);
        }
        return new SurfaceTexels(d, s, emission);
    }

    /// <summary>
    /// The radiance <paramref name="material"/> emits at <paramref name="hit"/>: its texel when textured, else
    /// <paramref name="le"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // textured vertices only: kept out of the walk's code
    ReadOnlySpan<float> EmittedAt(PathMaterial material, float[] le, scoped in SurfaceHit hit, Vector3 wo, Span<float> scratch)
    {
        if (material.EmissionTexture is not { } texture) return le;
        var uv = _geometry.TexCoord(in hit, out float density);
        var texel = scratch.Slice(TextureBase + 2 * _padded, _padded);
        texture.Filter(uv, Footprint(hit.T, Vector3.Dot(hit.GeometricNormal, wo), density), texel);
        return texel;
    }

    /// <summary>The radiance a textured emitter sends from point <paramref name="x"/> (normal <paramref name="nx"/>) of
    /// <paramref name="face"/> along −<paramref name="wi"/>, seen from <paramref name="distance"/> away, into
    /// <paramref name="texel"/>.</summary>
    ReadOnlySpan<float> EmittedAt(Emitter emitter, int face, Vector3 x, Vector3 nx, Vector3 wi, float distance, Span<float> texel)
    {
        var uv = emitter.TexCoord(face, x, out float density);
        emitter.Texture!.Filter(uv, Footprint(distance, Vector3.Dot(nx, wi), density), texel);
        return texel;
    }

    /// <summary>f of the smooth lobes, with the vertex's texels when it has any.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]   // textured vertices only: kept out of the walk's code
    static void Evaluate(Bsdf bsdf, in SurfaceTexels texels, Vector3 wo, Vector3 wi, Vector3 ns, Span<float> f)
    {
        if (texels.Any) bsdf.Evaluate(wo, wi, ns, texels.Diffuse, texels.Specular, f);
        else bsdf.Evaluate(wo, wi, ns, f);
    }
}
