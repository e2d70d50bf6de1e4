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

    /// <summary>πR²: its irradiance through the disc of the scene's bounding sphere.</summary>
    public override double PowerPerIntensity(double sceneRadius) => Math.PI * sceneRadius * sceneRadius;

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per hit, compiled for this CPU at first call
    public override bool Illuminate(Vector3 p, out LightSample sample)
    {
        sample = new LightSample(-Direction, float.PositiveInfinity, 1f, 1f);
        return true;
    }
}
