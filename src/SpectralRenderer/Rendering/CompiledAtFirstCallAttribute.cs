namespace SpectralRenderer.Rendering;

/// <summary>
/// Marks hot code that a Whitted render (the default) does not run — the per-light transfer, the path integrator and its
/// helpers — so that a start-up warm-up of the hot loops (the CLI's, which compiles the AggressiveOptimization methods of a
/// render's namespaces on the second core while the scene loads) leaves it, and the types nested in it, to its first call.
/// Compiled at every start, it took that core from the default render's own loops (BENCHMARKS.md, issue 22).
/// </summary>
[AttributeUsage(AttributeTargets.Class | AttributeTargets.Struct, Inherited = false)]
public sealed class CompiledAtFirstCallAttribute : Attribute;
