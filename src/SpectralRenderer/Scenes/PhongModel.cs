using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>max(0, r·v)^shininess with the mirrored light direction r = 2(n·l)n − l (Phong 1975).</summary>
public sealed class PhongModel : SpecularModel
{
    public override string Name => "phong";

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per specular hit
    public override float Evaluate(Vector3 n, Vector3 l, Vector3 v, float nl, float shininess)
    {
        var r = 2 * nl * n - l;
        return MathF.Pow(MathF.Max(0, Vector3.Dot(r, v)), shininess);
    }
}
