using System.Numerics;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>A light type of the scene file: the keys it takes beyond the common ones, and how it is built.</summary>
public sealed record LightType(string[] Keys, Func<SceneLoader.LightSource, Light> Make);

/// <summary>
/// The light types a scene file can name ("type"): the one registration point for a new kind of light.
/// Each entry lists its own keys and builds its <see cref="Light"/> subclass (one file each in Scenes/) from what every
/// light emits (<see cref="SceneLoader.LightSource.Emission"/>) and its own keys.
/// </summary>
public static class LightTypes
{
    /// <summary>Keys every light takes; the loader parses them into <see cref="SceneLoader.LightSource"/>.</summary>
    public static readonly string[] CommonKeys = ["type", "name", "spectrum", "intensity", "ambient", "attenuation"];

    static readonly Lock Gate = new();
    static Dictionary<string, LightType> s_byName = new(StringComparer.Ordinal)
    {
        ["point"] = new(["position"], s => new PointLight(s.Emission) { Position = s.Point("position"), Falloff = s.Falloff }),
        ["spot"] = new(["position", "direction", "look_at", "cutoff", "exponent"], Spot),
        ["directional"] = new(["direction"], s => new DirectionalLight(s.Emission) { Direction = s.Direction("direction") }),
    };

    public static IReadOnlyDictionary<string, LightType> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a light type under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, LightType type) => Registry.Add(ref s_byName, Gate, name, type);

    static SpotLight Spot(SceneLoader.LightSource s)
    {
        var position = s.Point("position");
        Vector3 direction;
        if (s.Has("direction")) direction = s.Direction("direction");
        else if (s.Has("look_at"))
        {
            var towards = s.Point("look_at") - position;
            if (towards.LengthSquared() == 0) throw s.Error("look_at", "look_at equals position", "a spot light needs a direction to shine in");
            direction = Vector3.Normalize(towards);
        }
        else throw s.Error("direction", "a spot light needs a direction or look_at", "e.g. \"direction\": [0, -1, 0] or \"look_at\": [0, 0, 0]");
        return new SpotLight(s.Emission)
        {
            Position = position,
            Direction = direction,
            Falloff = s.Falloff,
            CosCutoff = MathF.Cos((float)s.Number("cutoff", 30, 0, 180) * MathF.PI / 180),
            Exponent = (float)s.Number("exponent", 0, 0, 1e6),
        };
    }
}
