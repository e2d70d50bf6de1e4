namespace SpectralRenderer.Scenes.Loading;

/// <summary>A medium type of the scene file: the keys it takes (beyond "type") and how it builds its <see cref="Medium"/>.</summary>
public sealed record MediumType(string[] Keys, Func<SceneLoader.MediumSource, Medium> Make);

/// <summary>
/// The medium types a scene file can name (a <c>"medium"</c>'s "type", on an object for its interior or at the top for the
/// space around the objects): the one registration point for a new kind of participating medium. The engine registers
/// none yet, so no scene of today has a medium (issue 41 adds the homogeneous and grid media); a test registers an
/// absorbing one (ARCHITECTURE.md, "Extending").
/// </summary>
public static class MediumTypes
{
    static readonly Lock Gate = new();
    static Dictionary<string, MediumType> s_byName = new(StringComparer.Ordinal);

    public static IReadOnlyDictionary<string, MediumType> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a medium type under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, MediumType type) => Registry.Add(ref s_byName, Gate, name, type);
}
