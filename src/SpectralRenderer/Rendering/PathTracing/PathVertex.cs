using System.Numerics;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// A vertex of a path: the surface point a ray reached (position p, geometric normal n_g, shading normal n_s and the shading
/// normal facing the ray), the direction back along the ray ωo, the material there and its texels. What next-event
/// estimation, the lobe choice and a shifted bounce read of the point (PathIntegrator.cs, PathIntegrator.Fluorescence.cs);
/// and the media about it: the one its ray came through and the one its object bounds (PathIntegrator.Media.cs).
/// </summary>
readonly ref struct PathVertex(scoped in SurfaceHit hit, Vector3 wo, PathMaterial material, SurfaceTexels texels, int medium,
    int interior)
{
    public readonly Vector3 P = hit.Position, Ng = hit.GeometricNormal, Ns = hit.Normal, Wo = wo;
    /// <summary>The medium of the ray that reached the vertex, and its object's interior medium (−1: vacuum; none).</summary>
    public readonly int Medium = medium, Interior = interior;
    /// <summary>The shading normal on ωo's side.</summary>
    public readonly Vector3 Front = Vector3.Dot(hit.Normal, wo) >= 0 ? hit.Normal : -hit.Normal;
    public readonly PathMaterial Material = material;
    public readonly SurfaceTexels Texels = texels;
}

/// <summary>
/// A vertex's texels on the sub-band grid (an empty span: the material's own spectrum), and the scratch an emitter's texel
/// drawn by next-event estimation goes to (PathIntegrator.Textures.cs).
/// </summary>
readonly ref struct SurfaceTexels(Span<float> diffuse, Span<float> specular, Span<float> emission)
{
    public readonly Span<float> Diffuse = diffuse, Specular = specular, Emission = emission;
    /// <summary>Does the vertex's BSDF take texels?</summary>
    public bool Any => !Diffuse.IsEmpty || !Specular.IsEmpty;
}
