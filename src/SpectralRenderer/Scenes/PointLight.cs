using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>A point light at <see cref="Position"/>, shining equally in every direction (c_spot = 1).</summary>
public sealed class PointLight(LightEmission emission) : Light(emission)
{
    public Vector3 Position { get; init; }
    public DistanceFalloff Falloff { get; init; } = DistanceFalloff.None;

    public override LightDescription Describe(Radiometry radiometry) =>
        new(Type, LightDescription.UnitOf(radiometry, LightDescription.RadiantIntensity), LightDescription.Of(Position), null,
            LightDescription.Of(Falloff));

    public override LightExtent? Extent => new LightExtent(Position, Vector3.UnitY, -1);

    public override string Type => "point";

    public override LanePointLight? LaneForm => new LanePointLight(Position, Falloff);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per hit, compiled for this CPU at first call
    public override bool Illuminate(Vector3 p, out LightSample sample)
    {
        var toLight = Position - p;
        float dist = toLight.Length();
        if (dist == 0) { sample = default; return false; }
        sample = new LightSample(toLight / dist, dist, 1f, Falloff.At(dist));
        return true;
    }
}
