using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>max(0, n·h)^shininess with the half-vector h = (l + v)/|l + v| (Blinn 1977).</summary>
public sealed class BlinnPhongModel : SpecularModel
{
    public override string Name => "blinn-phong";

    /// <summary>(n + 8)/(8π): the normalised Blinn–Phong lobe (Akenine-Möller et al., Real-Time Rendering 4th ed. §9.8; Blinn
    /// 1977).</summary>
    public override double EnergyNormalisation(double shininess) => (shininess + 8) / (8 * Math.PI);

    /// <summary>The half-vector h drawn with density (s+1)/(2π)·(n·h)^s, l its mirror of v: p(l) = p(h)/(4 v·h).</summary>
    public override Vector3 SampleLobe(Vector3 n, Vector3 v, Vector2 u, float shininess)
    {
        var h = Bsdf.PowerCosine(n, u, shininess);
        return 2 * Vector3.Dot(v, h) * h - v;
    }

    public override float LobePdf(Vector3 n, Vector3 v, Vector3 l, float shininess)
    {
        if (!(Vector3.Dot(n, l) > 0)) return 0;
        var h = Vector3.Normalize(l + v);
        float vh = Vector3.Dot(v, h);
        return vh > 0 ? Bsdf.PowerCosinePdf(Vector3.Dot(n, h), shininess) / (4 * vh) : 0;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per specular hit
    public override float Evaluate(Vector3 n, Vector3 l, Vector3 v, float nl, float shininess)
    {
        var h = Vector3.Normalize(l + v);
        return MathF.Pow(MathF.Max(0, Vector3.Dot(n, h)), shininess);
    }
}
