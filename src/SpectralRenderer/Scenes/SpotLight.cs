using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A spot light at <see cref="Position"/> shining towards <see cref="Direction"/>: c_spot = (cos θ)^e inside
/// the cone of half-angle θ_c and 0 outside, θ the angle between the axis and the direction to the point.
/// </summary>
public sealed class SpotLight(LightEmission emission) : Light(emission)
{
    public Vector3 Position { get; init; }
    /// <summary>Unit direction the light shines towards.</summary>
    public Vector3 Direction { get; init; }
    public DistanceFalloff Falloff { get; init; } = DistanceFalloff.None;
    /// <summary>cos of the cutoff half-angle θ_c.</summary>
    public float CosCutoff { get; init; } = -1;
    public float Exponent { get; init; }

    public override LightDescription Describe(Radiometry radiometry) =>
        new(Type, LightDescription.UnitOf(radiometry, LightDescription.RadiantIntensity), LightDescription.Of(Position),
            LightDescription.Of(Direction), LightDescription.Of(Falloff));

    public override LightExtent? Extent => new LightExtent(Position, Direction, CosCutoff);

    public override string Type => "spot";

    /// <summary>∫c_spot dω (<see cref="SolidAngle"/>).</summary>
    public override double PowerPerIntensity(double sceneRadius) => SolidAngle(CosCutoff, Exponent);

    /// <summary>
    /// ∫c_spot dω = 2π ∫ max(0, μ)^e dμ over μ = cos θ from cos θ_c to 1: 2π(1 − max(0, cos θ_c)^(e+1))/(e + 1), and
    /// 2π(1 − cos θ_c) for e = 0 (c_spot is then 1 down to the cutoff, behind the light too).
    /// </summary>
    public static double SolidAngle(double cosCutoff, double exponent) => exponent == 0
        ? 2 * Math.PI * (1 - cosCutoff)
        : 2 * Math.PI * (1 - Math.Pow(Math.Max(cosCutoff, 0), exponent + 1)) / (exponent + 1);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per hit, compiled for this CPU at first call
    public override bool Illuminate(Vector3 p, out LightSample sample)
    {
        var toLight = Position - p;
        float dist = toLight.Length();
        if (dist == 0) { sample = default; return false; }
        var l = toLight / dist;
        float c = Vector3.Dot(-l, Direction);
        float spot = c < CosCutoff ? 0f : MathF.Pow(Math.Max(c, 0f), Exponent);
        if (spot == 0) { sample = default; return false; }
        sample = new LightSample(l, dist, spot, Falloff.At(dist));
        return true;
    }
}
