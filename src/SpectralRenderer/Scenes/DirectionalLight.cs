using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>A light at infinity shining towards <see cref="Direction"/>: no attenuation (d = 1), c_spot = 1.</summary>
public sealed class DirectionalLight(LightEmission emission) : Light(emission)
{
    /// <summary>Unit direction the light shines towards.</summary>
    public Vector3 Direction { get; init; }

    public override LightDescription Describe(Radiometry radiometry) =>
        new(Type, LightDescription.UnitOf(radiometry, LightDescription.Irradiance), null, LightDescription.Of(Direction));

    public override string Type => "directional";

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per hit, compiled for this CPU at first call
    public override bool Illuminate(Vector3 p, out LightSample sample)
    {
        sample = new LightSample(-Direction, float.PositiveInfinity, 1f, 1f);
        return true;
    }
}
