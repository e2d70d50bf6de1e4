using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>The integrators by name: the one place one is built, and the one registration point for a new one.</summary>
public static class Integrators
{
    public const string Default = "whitted";

    static readonly Dictionary<string, Func<Scene, SceneGeometry, IIntegrator>> Factories = new(StringComparer.Ordinal)
    {
        ["whitted"] = (scene, geometry) => new WhittedIntegrator(scene, geometry),
    };

    /// <summary>The integrator <paramref name="name"/> for a scene whose geometry is built.</summary>
    public static IIntegrator Create(Scene scene, SceneGeometry geometry, string name = Default) =>
        Factories.TryGetValue(name, out var make) ? make(scene, geometry)
            : throw new ArgumentException($"unknown integrator '{name}' (known: {string.Join(", ", Factories.Keys)})", nameof(name));
}
