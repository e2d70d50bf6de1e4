using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>max(0, n·h)^shininess with the half-vector h = (l + v)/|l + v| (Blinn 1977).</summary>
public sealed class BlinnPhongModel : SpecularModel
{
    public override string Name => "blinn-phong";

    /// <summary>(n + 8)/(8π): the normalised Blinn–Phong lobe (Akenine-Möller et al., Real-Time Rendering 4th ed. §9.8; Blinn 1977).</summary>
    public override double EnergyNormalisation(double shininess) => (shininess + 8) / (8 * Math.PI);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per specular hit
    public override float Evaluate(Vector3 n, Vector3 l, Vector3 v, float nl, float shininess)
    {
        var h = Vector3.Normalize(l + v);
        return MathF.Pow(MathF.Max(0, Vector3.Dot(n, h)), shininess);
    }
}
