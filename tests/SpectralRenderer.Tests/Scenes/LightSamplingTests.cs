using System.Numerics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>Delta lights sampled: the direction, distance and d·c_spot of <see cref="Light.Illuminate"/>; the inverse-square law.</summary>
public class LightSamplingTests
{
    static readonly LightEmission Emission = new("l", [1f], [0f], false);

    static Light[] Lights() =>
    [
        new PointLight(Emission) { Position = new(1, 4, -2), Falloff = new(1, 0.3f, 0.05f) },
        new SpotLight(Emission)
        {
            Position = new(0, 5, 0), Direction = -Vector3.UnitY, Falloff = new(0, 0, 1), CosCutoff = MathF.Cos(0.6f), Exponent = 3,
        },
        new DirectionalLight(Emission) { Direction = Vector3.Normalize(new Vector3(1, -2, 0.5f)) },
    ];

    [Fact]
    public void A_delta_lights_sample_is_what_Illuminate_gives_whatever_the_random_numbers()
    {
        var points = new[] { new Vector3(0, 0, 0), new Vector3(0.5f, 0, 0.2f), new Vector3(3, 0, 0), new Vector3(-1, 1, 2) };
        foreach (var light in Lights())
            foreach (var p in points)
                foreach (var u in new[] { new Vector2(0, 0), new Vector2(0.3f, 0.9f), new Vector2(0.999f, 0.5f) })
                {
                    bool reached = light.Illuminate(p, out var ls);
                    Assert.Equal(reached, light.Sample(p, u, out var s));
                    if (!reached) continue;
                    Assert.Equal(ls.Direction, s.Direction);
                    Assert.Equal(ls.Distance, s.Distance);
                    Assert.Equal(ls.Attenuation * ls.Spot, s.Factor);
                    Assert.True(s.IsDelta && light.IsDelta, light.Type);
                    Assert.Equal(1f, s.Pdf);
                }
    }

    [Theory]
    [InlineData(2.0)]
    [InlineData(0.25)]
    [InlineData(7.5)]
    public void A_point_light_of_unit_intensity_falls_off_as_the_inverse_square(double r)
    {
        // Physical radiometry: I = 1 W/sr/nm at distance r gives irradiance 1/r² facing it.
        var light = new PointLight(Emission) { Position = new(0, 3, 0), Falloff = new(0, 0, 1) };
        var p = new Vector3(0, 3 - (float)r, 0);
        Assert.True(light.Sample(p, new Vector2(0.5f, 0.5f), out var s));
        Assert.Equal(1 / (r * r), s.Factor, 1e-6 / (r * r));
        Assert.Equal((float)r, s.Distance, 1e-5f);
        Assert.Equal(Vector3.UnitY, s.Direction);
    }

    [Fact]
    public void A_spot_light_gives_nothing_outside_its_cone()
    {
        var spot = (SpotLight)Lights()[1];
        // 45° off the axis, outside a 0.6 rad ≈ 34° cone.
        Assert.False(spot.Sample(new Vector3(5, 0, 0), new Vector2(0.5f, 0.5f), out _));
        Assert.True(spot.Sample(new Vector3(0.5f, 0, 0), new Vector2(0.5f, 0.5f), out var inside));
        float cos = 5 / MathF.Sqrt(25.25f);
        Assert.Equal(MathF.Pow(cos, 3) / 25.25f, inside.Factor, 1e-6f);
    }

    [Fact]
    public void Describe_gives_the_manifest_parameters_of_each_kind()
    {
        var lights = Lights();
        var point = lights[0].Describe(Radiometry.Physical);
        Assert.Equal(("point", LightDescription.RadiantIntensity), (point.Type, point.Unit));
        Assert.Equal([1.0, 4.0, -2.0], point.Position!);
        Assert.Null(point.Direction);
        Assert.Equal([1.0, 0.3f, 0.05f], point.Attenuation!);
        var spot = lights[1].Describe(Radiometry.Paper);
        Assert.Equal(("spot", LightDescription.Relative), (spot.Type, spot.Unit));
        Assert.Equal([0.0, -1.0, 0.0], spot.Direction!);
        var directional = lights[2].Describe(Radiometry.Physical);
        Assert.Equal(("directional", LightDescription.Irradiance), (directional.Type, directional.Unit));
        Assert.Null(directional.Position);
        Assert.Null(directional.Attenuation);
        Assert.NotNull(directional.Direction);
    }
}
