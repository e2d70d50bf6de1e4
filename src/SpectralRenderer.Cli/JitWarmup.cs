using System.Diagnostics.CodeAnalysis;
using System.Reflection;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Cli;

/// <summary>
/// Compiles the engine's hot loops on a background thread while the main thread reads the scene and its meshes.
/// Methods marked <see cref="MethodImplOptions.AggressiveOptimization"/> are kept out of the ReadyToRun image (they are
/// compiled for the machine's SIMD width at first call); in a 2-core render of the bunny at 512² their compilation is
/// ~0.2 s of processor time, and made at first call it stalls the render's threads (BENCHMARKS.md). Compiled here
/// first, the same code is ready when they get there; what the warm-up has not reached yet is compiled at first call as
/// before. Generic methods are compiled for this machine's packet lanes (<see cref="Acceleration.PacketLanes"/>) and
/// every engine value type their interface constraints admit (the triangle and analytic-shape intersectors).
/// </summary>
static class JitWarmup
{
    /// <summary>Rendering's namespaces: the film, then its wings (Whitted's first, the default integrator's).</summary>
    static readonly string[] RenderingWings =
    [
        "SpectralRenderer.Rendering", "SpectralRenderer.Rendering.Whitted", "SpectralRenderer.Rendering.Terms",
        "SpectralRenderer.Rendering.Emitters", "SpectralRenderer.Rendering.PathTracing", "SpectralRenderer.Rendering.Illumination",
        "SpectralRenderer.Rendering.Registry",
    ];

    /// <summary>The namespaces whose hot loops a render runs, in the order it reaches them: the BVH build, the render, the
    /// writers.</summary>
    public static readonly string[] Render =
    [
        "SpectralRenderer.Acceleration", .. RenderingWings, "SpectralRenderer.Scenes", "SpectralRenderer.Imaging",
        "SpectralRenderer.Output", "SpectralRenderer.Spectra", "SpectralRenderer.Color",
    ];

    /// <summary>What a relight runs: the recombination of the transfer (in Rendering), then the writers.</summary>
    public static readonly string[] Relight = ["SpectralRenderer.Imaging", "SpectralRenderer.Output", .. RenderingWings];

    static int _started;
    static volatile bool _stopped;

    /// <summary>
    /// Ends the warm-up after the method it is compiling: for a render whose integrator is not the default one (the path
    /// tracer, <see cref="Rendering.CompiledAtFirstCallAttribute"/>), the Whitted loops it compiles would only take the
    /// second core from the render's own threads.
    /// </summary>
    public static void Stop() => _stopped = true;

    /// <summary>Starts the warm-up of the hot loops in <paramref name="stages"/> (namespaces, in order), once per process (a test host runs
    /// many commands).</summary>
    public static void Start(string[] stages)
    {
        // The native build (Native AOT) has nothing to compile: its hot loops are machine code already.
        if (!RuntimeFeature.IsDynamicCodeCompiled) return;
        if (Interlocked.Exchange(ref _started, 1) == 0) ThreadPool.UnsafeQueueUserWorkItem(static s => Run(s), stages, preferLocal: false);
    }

    [UnconditionalSuppressMessage("Trimming", "IL2026", Justification = "Runs only under the JIT (Start), where nothing is trimmed.")]
    [UnconditionalSuppressMessage("Trimming", "IL2060", Justification = "Runs only under the JIT (Start), where nothing is trimmed.")]
    [UnconditionalSuppressMessage("Trimming", "IL2065", Justification = "Runs only under the JIT (Start), where nothing is trimmed.")]
    [UnconditionalSuppressMessage("Trimming", "IL2070", Justification = "Runs only under the JIT (Start), where nothing is trimmed.")]
    [UnconditionalSuppressMessage("Trimming", "IL2075", Justification = "Runs only under the JIT (Start), where nothing is trimmed.")]
    [UnconditionalSuppressMessage("AOT", "IL3050",
        Justification = "Runs only under the JIT (Start: RuntimeFeature.IsDynamicCodeCompiled).")]
    static void Run(string[] stages)
    {
        try
        {
            const BindingFlags all =
                BindingFlags.Public | BindingFlags.NonPublic | BindingFlags.Instance | BindingFlags.Static | BindingFlags.DeclaredOnly;
            var types = typeof(Rendering.Renderer).Assembly.GetTypes();
            var values = types.Where(t => t.IsValueType && !t.ContainsGenericParameters && !LeftToFirstCall(t)).ToArray();
            var lanes = values.FirstOrDefault(t => t.Name.StartsWith("Lanes", StringComparison.Ordinal)
                && t.GetProperty("Count", BindingFlags.Public | BindingFlags.Static)?.GetValue(null) is int n
                    && n == Acceleration.PacketLanes.Width);
            foreach (var stage in stages)
                foreach (var type in types)
                {
                    if (type.Namespace != stage || type.ContainsGenericParameters || LeftToFirstCall(type)) continue;
                    foreach (var method in type.GetMethods(all))
                    {
                        if (_stopped) return;
                        if ((method.MethodImplementationFlags & MethodImplAttributes.AggressiveOptimization) == 0 || method.IsAbstract)
                            continue;
                        if (!method.ContainsGenericParameters) { Prepare(method); continue; }
                        foreach (var args in Instantiations(method.GetGenericArguments(), values, lanes))
                        {
                            MethodInfo made;
                            try { made = method.MakeGenericMethod(args); }
                            catch (ArgumentException) { continue; }   // the arguments break a constraint
                            Prepare(made);
                        }
                    }
                }
        }
        catch (Exception)
        {
            // A warm-up that fails leaves the methods to be compiled at first call: nothing is lost but time.
        }
    }

    /// <summary>Is <paramref name="type"/>, or a type it is nested in, hot code a default render does not run
    /// (<see cref="Rendering.CompiledAtFirstCallAttribute"/>)? Its methods and instantiations over it are left to their first
    /// call.</summary>
    static bool LeftToFirstCall(Type type)
    {
        for (Type? t = type; t is not null; t = t.DeclaringType)
            if (t.IsDefined(typeof(Rendering.CompiledAtFirstCallAttribute), inherit: false)) return true;
        return false;
    }

    static void Prepare(MethodInfo method)
    {
        try { RuntimeHelpers.PrepareMethod(method.MethodHandle); }
        catch (Exception) { }   // this one is compiled at first call
    }

    /// <summary>Every choice of type arguments: a lanes parameter (constrained to ILanes) takes this machine's lanes; any other, each
    /// engine value type its interface constraints admit — none when it has no plain interface constraint (an intersector's), so a
    /// loosely constrained method is left to its first call rather than compiled for every struct.</summary>
    static IEnumerable<Type[]> Instantiations(Type[] parameters, Type[] values, Type? lanes)
    {
        IEnumerable<Type[]> choices = [[]];
        foreach (var p in parameters)
        {
            var constraints = p.GetGenericParameterConstraints();
            Type[] candidates = constraints.Any(c => c.Name == "ILanes`1")
                ? lanes is null ? [] : [lanes]
                : !constraints.Any(c => c.IsInterface && !c.ContainsGenericParameters) ? []
                : values.Where(v => constraints.All(c => c == typeof(ValueType) || (!c.ContainsGenericParameters && c.IsAssignableFrom(v))))
                    .ToArray();
            choices = choices.SelectMany(prefix => candidates.Select(c => (Type[])[.. prefix, c])).ToArray();
        }
        return choices;
    }
}
