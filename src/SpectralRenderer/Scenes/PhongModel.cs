using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>max(0, r·v)^shininess with the mirrored light direction r = 2(n·l)n − l (Phong 1975).</summary>
public sealed class PhongModel : SpecularModel
{
    public override string Name => "phong";

    /// <summary>(n + 2)/(2π): the energy-conserving modified Phong lobe (Lafortune &amp; Willems 1994), albedo m_spec at normal
    /// incidence.</summary>
    public override double EnergyNormalisation(double shininess) => (shininess + 2) / (2 * Math.PI);

    /// <summary>l drawn about the mirror direction r of v with density (s+1)/(2π)·(r·l)^s (Lafortune &amp; Willems 1994).</summary>
    public override Vector3 SampleLobe(Vector3 n, Vector3 v, Vector2 u, float shininess) =>
        Bsdf.PowerCosine(2 * Vector3.Dot(n, v) * n - v, u, shininess);

    public override float LobePdf(Vector3 n, Vector3 v, Vector3 l, float shininess) =>
        Vector3.Dot(n, l) > 0 ? Bsdf.PowerCosinePdf(Vector3.Dot(2 * Vector3.Dot(n, v) * n - v, l), shininess) : 0;

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per specular hit
    public override float Evaluate(Vector3 n, Vector3 l, Vector3 v, float nl, float shininess)
    {
        var r = 2 * nl * n - l;
        return MathF.Pow(MathF.Max(0, Vector3.Dot(r, v)), shininess);
    }
}
