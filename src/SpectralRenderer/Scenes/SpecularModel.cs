using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// The shape of the specular lobe of eq. 2: the scalar factor that multiplies I_k·m_spec·d_k·c_spot,k.
/// A new model is one subclass (one file) plus one line in <see cref="SpecularModels.ByName"/>.
/// </summary>
public abstract class SpecularModel
{
    /// <summary>The name a scene file gives it (its "model" key) and render.json reports.</summary>
    public abstract string Name { get; }

    /// <summary>The factor for unit normal n, unit light direction l, unit view direction v, n·l > 0.</summary>
    public abstract float Evaluate(Vector3 n, Vector3 l, Vector3 v, float nl, float shininess);

    /// <summary>
    /// Physical radiometry: the constant that makes m_spec · factor · cos θ_i an energy-conserving BRDF lobe times cos θ_i
    /// (its directional albedo at most m_spec), e.g. (n + 8)/(8π) for Blinn–Phong, (n + 2)/(2π) for Phong.
    /// </summary>
    public abstract double EnergyNormalisation(double shininess);

    /// <summary>
    /// A light direction l drawn for unit normal n and view direction v (same side), for importance sampling the lobe as a
    /// BSDF; the density is <see cref="LobePdf"/>. By default cos θ/π over the hemisphere, right for any lobe shape.
    /// </summary>
    public virtual Vector3 SampleLobe(Vector3 n, Vector3 v, Vector2 u, float shininess) => Bsdf.CosineHemisphere(n, u);

    /// <summary>The solid-angle density of <see cref="SampleLobe"/> at l (0 below the surface).</summary>
    public virtual float LobePdf(Vector3 n, Vector3 v, Vector3 l, float shininess) => MathF.Max(0, Vector3.Dot(n, l)) / MathF.PI;
}

/// <summary>The specular models a scene file can name: the one registration point for a new model.</summary>
public static class SpecularModels
{
    public static readonly SpecularModel Default = new BlinnPhongModel();

    public static readonly IReadOnlyDictionary<string, SpecularModel> ByName = new Dictionary<string, SpecularModel>(StringComparer.Ordinal)
    {
        ["blinn-phong"] = Default,
        ["blinn"] = Default,
        ["phong"] = new PhongModel(),
    };
}
