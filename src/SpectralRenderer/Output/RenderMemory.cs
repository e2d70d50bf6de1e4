using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output;

/// <summary>
/// What a render and its writers hold at once, in bytes, by part — the framebuffer and the renderer's per-pixel
/// arrays, then everything <see cref="RenderOutputWriter"/> keeps while its writers run side by side (band planes,
/// XYZ, each PNG's rows and deflate stream, each EXR's chunks, the ground-truth cube) — checked before rendering
/// against what this process may use: the GC's view of available memory, which is the GC heap hard limit when one
/// is set (DOTNET_GCHeapHardLimit) and the container's memory limit (cgroup) otherwise, less what is already in use.
/// </summary>
public static class RenderMemory
{
    /// <summary>The parts of the estimate, largest first, in bytes, for a render by <paramref name="integrator"/> (null: the
    /// scene's).</summary>
    public static List<(string Part, long Bytes)> Estimate(Scene scene, int threads, IReadOnlyList<OutputProduct>? named = null,
        string? integrator = null)
    {
        long n = (long)scene.Camera.Width * scene.Camera.Height, bands = scene.Bands;
        var p = scene.Output.Products;
        if (threads <= 0) threads = Environment.ProcessorCount;
        var parts = new List<(string, long)>
        {
            ("framebuffer", 4 * n * bands),
            ("per-pixel arrays", 16 * n),
        };
        int triangles = scene.TriangleCount;
        if (triangles > 0) parts.Add(("BVH", 160L * triangles));
        // The integrator's tables shared by the threads (textures: the Whitted route's tables per texel, mip level and light;
        // the path tracer's texel spectra on its sub-band grid), as its registration says.
        var entry = Rendering.Registry.Integrators.Entry(integrator ?? scene.Integrator?.Name ?? Rendering.Registry.Integrators.Default);
        if (entry?.Tables is { } tables) parts.AddRange(tables(scene));
        // The inputs the products share, once; then what each product's writers hold.
        var products = OutputProductTable.For(p, named);
        var needs = ProductInputs.None;
        foreach (var product in products) needs |= product.Needs;
        if (needs.HasFlag(ProductInputs.BandPlanes)) parts.Add(("band planes", 4 * n * bands));
        if (needs.HasFlag(ProductInputs.Xyz)) parts.Add(("XYZ planes", 24 * n));
        foreach (var product in products) parts.AddRange(product.Memory(scene, threads));
        // The per-light transfer the integrator records for the lights product: its format's estimate (of the integrator the
        // render uses, which a request's --integrator may set beside the scene's).
        if (products.Any(x => x is LightsProduct) && entry?.Transfer is { } transfer) parts.AddRange(transfer.Memory(scene));
        parts.Sort((a, b) => b.Item2.CompareTo(a.Item2));
        return parts;
    }

    /// <summary>Throws bad input (the camera's size) when the estimate exceeds what the process may still use.</summary>
    public static void Check(Scene scene, int threads, IReadOnlyList<OutputProduct>? named = null, string? integrator = null)
    {
        var parts = Estimate(scene, threads, named, integrator);   // never empty: the framebuffer comes first
        long need = parts.Sum(x => x.Bytes);
        var info = GC.GetGCMemoryInfo();
        long available = info.TotalAvailableMemoryBytes;
        long inUse = GC.GetTotalMemory(false);
        // Keep a tenth for the runtime, the JIT, buffers and fragmentation.
        long usable = (long)(0.9 * available) - inUse;
        if (need <= usable) return;
        string top = $"{parts[0].Part} {InputFile.Size(parts[0].Bytes)}";
        throw new InputException($"{scene.SourcePath}: $.camera",
            $"a {scene.Camera.Width}×{scene.Camera.Height}×{scene.Bands} render needs about {InputFile.Size(need)} ({top}, …), more than "
                + $"the {InputFile.Size(Math.Max(0, usable))} left of {LimitName()} {InputFile.Size(available)}",
            "lower the width, height or band count, or write fewer --formats");
    }

    static string LimitName()
    {
        if (AppContext.GetData("GCHeapHardLimit") is not null
            || Environment.GetEnvironmentVariable("DOTNET_GCHeapHardLimit") is { Length: > 0 }
            || Environment.GetEnvironmentVariable("DOTNET_GCHeapHardLimitPercent") is { Length: > 0 })
            return "the GC heap limit of";
        try
        {
            foreach (var f in new[] { "/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes" })
                if (File.Exists(f) && long.TryParse(File.ReadAllText(f).Trim(), out long limit) && limit < (1L << 50))
                    return "the container's memory limit of";
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException) { }
        return "the machine's memory of";
    }
}
