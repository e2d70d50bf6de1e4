using System.Numerics;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// A light type of the scene file: the keys it takes beyond the common ones, how it is built, and the photometric keys
/// it accepts instead of "intensity" (physical radiometry only).
/// </summary>
public sealed record LightType(string[] Keys, Func<SceneLoader.LightSource, Light> Make,
    IReadOnlyDictionary<string, PhotometricKey>? Photometric = null);

/// <summary>
/// A photometric alternative to "intensity": its unit and the geometric factor G (sr, or 1) with which the photometric
/// value X_v = K_m ∫V·S dλ · intensity · G (<see cref="Color.Photometry.Luminous"/>), read from the light's own keys —
/// so intensity = X_v / (K_m ∫V·S dλ · G).
/// </summary>
public sealed record PhotometricKey(string Unit, Func<SceneLoader.LightSource, double> Geometry);

/// <summary>
/// The light types a scene file can name ("type"): the one registration point for a new kind of light.
/// Each entry lists its own keys and builds its <see cref="Light"/> subclass (one file each in Scenes/) from what every
/// light emits (<see cref="SceneLoader.LightSource.Emission"/>) and its own keys.
/// </summary>
public static class LightTypes
{
    /// <summary>Keys every light takes; the loader parses them into <see cref="SceneLoader.LightSource"/>.</summary>
    public static readonly string[] CommonKeys = ["type", "name", "spectrum", "intensity", "ambient", "attenuation", SceneLoader.FilterKey];

    /// <summary>The photometric keys of every light type, each an alternative to "intensity".</summary>
    public static readonly string[] PhotometricKeys = ["luminous_flux", "luminous_intensity", "illuminance", "luminance"];

    // Point: I_v in cd is the radiant intensity's photometric value; Φ_v = 4π·I_v (isotropic).
    static readonly Dictionary<string, PhotometricKey> PointPhotometry = new(StringComparer.Ordinal)
    {
        ["luminous_intensity"] = new("cd", _ => 1),
        ["luminous_flux"] = new("lm", _ => 4 * Math.PI),
    };

    // Spot: I_v on the axis; Φ_v = I_v ∫ c_spot dΩ = I_v · 2π ∫_{cos θc}^1 μ^e dμ (c_spot = max(μ, 0)^e inside the cone).
    static readonly Dictionary<string, PhotometricKey> SpotPhotometry = new(StringComparer.Ordinal)
    {
        ["luminous_intensity"] = new("cd", _ => 1),
        ["luminous_flux"] =
            new("lm", s => SpotLight.SolidAngle(Math.Cos(s.Number("cutoff", 30, 0, 180) * Math.PI / 180), s.Number("exponent", 0, 0, 1e6))),
    };

    // Directional: E_v in lx on a surface facing the light.
    static readonly Dictionary<string, PhotometricKey> DirectionalPhotometry = new(StringComparer.Ordinal)
    {
        ["illuminance"] = new("lx", _ => 1),
    };

    // Goniometric: Φ_v = intensity × lamp factor × ∫ I_file dΩ; G = that integral (per unit intensity) / (K_m ∫V·S).
    static readonly Dictionary<string, PhotometricKey> GoniometricPhotometry = new(StringComparer.Ordinal)
    {
        ["luminous_flux"] = new("lm", s => File(s).Table.Flux() * LampFactor(s) / Color.Photometry.Luminous(s.Spectrum)),
    };

    static PhotometricFile File(SceneLoader.LightSource s) => s.Memo("photometric-file", () =>
    {
        var (path, text) = s.ReadText("file", "photometric file");
        return Path.GetExtension(path).Equals(".ldt", StringComparison.OrdinalIgnoreCase)
            ? EulumdatReader.Parse(text, path) : IesReader.Parse(text, path);
    });

    /// <summary>"lamp_lumens" over the file's rated lamp lumens (relative photometry), else 1.</summary>
    static double LampFactor(SceneLoader.LightSource s)
    {
        if (!s.Has("lamp_lumens")) return 1;
        double lumens = s.Number("lamp_lumens", 1, 0, 1e9);
        return File(s).LampLumens is { } rated ? lumens / rated
            : throw s.Error("lamp_lumens", "the file has absolute photometry (lumens per lamp −1)",
                "its candela are the luminaire's: drop lamp_lumens, or scale with luminous_flux");
    }

    static GoniometricLight Goniometric(SceneLoader.LightSource s)
    {
        if (s.Radiometry != Radiometry.Physical)
            throw s.Error("type", "a goniometric light needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene: its file gives candela");
        var file = File(s);
        var orientation = Matrix4x4.Identity;
        if (s.Has("rotate"))
        {
            var deg = s.Point("rotate") * (MathF.PI / 180);
            orientation = Matrix4x4.CreateRotationX(deg.X) * Matrix4x4.CreateRotationY(deg.Y) * Matrix4x4.CreateRotationZ(deg.Z);
        }
        return new GoniometricLight(s.Emission, file.Table, Color.Photometry.Luminous(s.Spectrum) / LampFactor(s))
        {
            Position = s.Point("position"),
            Orientation = orientation,
            Falloff = s.Falloff,
        };
    }

    static readonly Lock Gate = new();
    static Dictionary<string, LightType> s_byName = new(StringComparer.Ordinal)
    {
        ["point"] = new(["position"], s => new PointLight(s.Emission) { Position = s.Point("position"), Falloff = s.Falloff },
            PointPhotometry),
        ["spot"] = new(["position", "direction", "look_at", "cutoff", "exponent"], Spot, SpotPhotometry),
        ["directional"] = new(["direction"], s => new DirectionalLight(s.Emission) { Direction = s.Direction("direction") },
            DirectionalPhotometry),
        ["goniometric"] = new(["position", "file", "rotate", "lamp_lumens"], Goniometric, GoniometricPhotometry),
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
            if (towards.LengthSquared() == 0)
                throw s.Error("look_at", "look_at equals position", "a spot light needs a direction to shine in");
            direction = Vector3.Normalize(towards);
        }
        else
            throw s.Error("direction", "a spot light needs a direction or look_at",
                "e.g. \"direction\": [0, -1, 0] or \"look_at\": [0, 0, 0]");
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
