namespace SpectralRenderer.Scenes.Loading;

/// <summary>A medium type of the scene file: the keys it takes (beyond "type") and how it builds its <see cref="Medium"/>.</summary>
public sealed record MediumType(string[] Keys, Func<SceneLoader.MediumSource, Medium> Make);

/// <summary>
/// The medium types a scene file can name (a <c>"medium"</c>'s "type", on an object for its interior or at the top for the
/// space around the objects; <see cref="Default"/> when it names none): the one registration point for a new kind of
/// participating medium (ARCHITECTURE.md, "Extending").
/// </summary>
public static class MediumTypes
{
    /// <summary>The type of a <c>"medium"</c> that names none.</summary>
    public const string Default = "homogeneous";

    static readonly Lock Gate = new();
    static Dictionary<string, MediumType> s_byName = new(StringComparer.Ordinal)
    {
        // σ_a and σ_s, or α and σ_t, per band and per scene length unit, and a phase function (Scenes/HomogeneousMedium.cs).
        [Default] = new(["sigma_a", "sigma_s", "albedo", "sigma_t", "phase"], Homogeneous),
    };

    public static IReadOnlyDictionary<string, MediumType> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a medium type under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, MediumType type) => Registry.Add(ref s_byName, Gate, name, type);

    static Medium Homogeneous(SceneLoader.MediumSource s)
    {
        bool albedoForm = s.Has("albedo") || s.Has("sigma_t");
        if (albedoForm && (s.Has("sigma_a") || s.Has("sigma_s")))
            throw s.Error(s.Has("sigma_a") ? "sigma_a" : "sigma_s", "a medium gives both σ_a/σ_s and albedo/σ_t",
                "give either \"sigma_a\" and \"sigma_s\", or \"albedo\" and \"sigma_t\"");
        if (!albedoForm && !s.Has("sigma_a") && !s.Has("sigma_s"))
            throw s.Error("sigma_a", "a medium has no coefficients",
                "give \"sigma_a\" and/or \"sigma_s\" (per scene length unit), or \"albedo\" and \"sigma_t\"");
        var (first, second) = albedoForm
            ? (s.Coefficient("albedo", required: true, max: 1), s.Coefficient("sigma_t", required: true))
            : (s.Coefficient("sigma_a", required: false), s.Coefficient("sigma_s", required: false));
        return new HomogeneousMedium(first, second, albedoForm, s.Phase(), s.Grid.Count);
    }
}
