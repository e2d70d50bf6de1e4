using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Rendering.Whitted;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Registry;

/// <summary>
/// A registered integrator: how it is built, and what is known of it before a scene's geometry is: the keys its
/// "integrator" object may give beside "type" (the loader reads them, the render job refuses a key the integrator does not
/// take), the per-light transfer it records (<see cref="ITransferIntegrator"/>; null: none) and the memory its tables take.
/// </summary>
public sealed record IntegratorEntry(string Name, Func<Scene, SceneGeometry, IIntegrator> Create)
{
    /// <summary>Keys of <c>{ "type": name, … }</c> it takes beside "type" (IntegratorSettings' fields it reads).</summary>
    public IReadOnlyList<string> Keys { get; init; } = [];

    /// <summary>The format of the per-light transfer it records, or null when it records none.</summary>
    public TransferFormat? Transfer { get; init; }

    /// <summary>What its tables shared by the threads hold for a scene, by part (the memory check), e.g. texture spectra.</summary>
    public Func<Scene, IEnumerable<(string Part, long Bytes)>>? Tables { get; init; }

    /// <summary>Whether the CLI's JIT warm-up compiles its hot loops ahead (the paper's model's); else the warm-up stops.</summary>
    public bool WarmedUp { get; init; }
}

/// <summary>The integrators by name: the one place one is built, and the one registration point for a new one.</summary>
public static class Integrators
{
    public const string Default = "whitted";

    static readonly Dictionary<string, IntegratorEntry> Entries = new(StringComparer.Ordinal);

    static Integrators()
    {
        Register(new IntegratorEntry(Default, (scene, geometry) => new WhittedIntegrator(scene, geometry))
        {
            Transfer = WhittedTransferFiles.Format,
            Tables = scene => TextureTables.Bytes(scene) is > 0 and var b ? [("texture tables", b)] : [],
            WarmedUp = true,
        });
        Register(new IntegratorEntry("path", (scene, geometry) => new PathIntegrator(scene, geometry))
        {
            Keys = ["max_depth", "rr_depth", "spectral_grid", "sampler", "seed", "light_tree"],
            Transfer = PathTransferFiles.Format,
            Tables = scene => SubBandTexture.Bytes(scene, PathIntegrator.SettingsOf(scene).SpectralGrid) is > 0 and var b
                ? [("texture spectra (fine grid)", b)]
                : [],
        });
    }

    /// <summary>The names a render request may give (<c>--integrator</c>), in registration order.</summary>
    public static IReadOnlyCollection<string> Names
    {
        get { lock (Entries) return [.. Entries.Keys]; }
    }

    /// <summary>
    /// Registers integrator <paramref name="name"/> (a new light-transport method: its own file, this one line, e.g. from a
    /// plug-in or a test assembly). A name taken already is refused, so a registration cannot replace the paper's model.
    /// </summary>
    public static void Register(string name, Func<Scene, SceneGeometry, IIntegrator> create) =>
        Register(new IntegratorEntry(name, create));

    /// <summary>Registers an integrator with its settings keys, transfer format and tables' memory (an <see cref="IntegratorEntry"/>).
    /// </summary>
    public static void Register(IntegratorEntry entry)
    {
        ArgumentNullException.ThrowIfNull(entry);
        ArgumentException.ThrowIfNullOrWhiteSpace(entry.Name);
        ArgumentNullException.ThrowIfNull(entry.Create);
        lock (Entries)
        {
            if (entry.Transfer is { } f && (f.Integrator != entry.Name || Entries.Values.Any(e => e.Transfer?.Kind == f.Kind)))
                throw new ArgumentException($"integrator '{entry.Name}': its transfer format must name it and have a kind of its own",
                    nameof(entry));
            if (!Entries.TryAdd(entry.Name, entry))
                throw new ArgumentException($"integrator '{entry.Name}' is registered already", nameof(entry));
        }
    }

    /// <summary>Is <paramref name="name"/> registered?</summary>
    public static bool Has(string name)
    {
        lock (Entries) return Entries.ContainsKey(name);
    }

    /// <summary>The registration of <paramref name="name"/>, or null.</summary>
    public static IntegratorEntry? Entry(string name)
    {
        lock (Entries) return Entries.GetValueOrDefault(name);
    }

    /// <summary>The transfer formats of the registered integrators, in registration order.</summary>
    public static IReadOnlyList<TransferFormat> TransferFormats
    {
        get { lock (Entries) return [.. Entries.Values.Select(e => e.Transfer).OfType<TransferFormat>()]; }
    }

    /// <summary>Renders <paramref name="scene"/> with the default integrator (the <see cref="Renderer"/>'s loop).</summary>
    public static RenderResult Render(Scene scene, int threads = 0, Action<RenderProgress>? progress = null,
        CancellationToken cancel = default, PixelRect? crop = null)
    {
        var geometry = new SceneGeometry(scene);
        return Renderer.Render(scene, Create(scene, geometry), threads, progress, cancel, crop);
    }

    /// <summary>The integrator <paramref name="name"/> for a scene whose geometry is built.</summary>
    public static IIntegrator Create(Scene scene, SceneGeometry geometry, string name = Default) =>
        Entry(name) is { } entry ? entry.Create(scene, geometry)
            : throw new ArgumentException($"unknown integrator '{name}' (known: {string.Join(", ", Names)})", nameof(name));
}
