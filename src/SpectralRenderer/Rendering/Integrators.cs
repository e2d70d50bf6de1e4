using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>The integrators by name: the one place one is built, and the one registration point for a new one.</summary>
public static class Integrators
{
    public const string Default = "whitted";

    static readonly Dictionary<string, Func<Scene, SceneGeometry, IIntegrator>> Factories = new(StringComparer.Ordinal)
    {
        ["whitted"] = (scene, geometry) => new WhittedIntegrator(scene, geometry),
        ["path"] = (scene, geometry) => new PathIntegrator(scene, geometry),
    };

    /// <summary>The names a render request may give (<c>--integrator</c>), in registration order.</summary>
    public static IReadOnlyCollection<string> Names
    {
        get { lock (Factories) return [.. Factories.Keys]; }
    }

    /// <summary>
    /// Registers integrator <paramref name="name"/> (a new light-transport method: its own file, this one line, e.g. from a
    /// plug-in or a test assembly). A name taken already is refused, so a registration cannot replace the paper's model.
    /// </summary>
    public static void Register(string name, Func<Scene, SceneGeometry, IIntegrator> create)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(name);
        ArgumentNullException.ThrowIfNull(create);
        lock (Factories)
            if (!Factories.TryAdd(name, create)) throw new ArgumentException($"integrator '{name}' is registered already", nameof(name));
    }

    /// <summary>Is <paramref name="name"/> registered?</summary>
    public static bool Has(string name)
    {
        lock (Factories) return Factories.ContainsKey(name);
    }

    /// <summary>The integrator <paramref name="name"/> for a scene whose geometry is built.</summary>
    public static IIntegrator Create(Scene scene, SceneGeometry geometry, string name = Default)
    {
        Func<Scene, SceneGeometry, IIntegrator>? make;
        lock (Factories) Factories.TryGetValue(name, out make);
        return make is not null ? make(scene, geometry)
            : throw new ArgumentException($"unknown integrator '{name}' (known: {string.Join(", ", Names)})", nameof(name));
    }
}
