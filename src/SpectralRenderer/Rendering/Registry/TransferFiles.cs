using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Registry;

/// <summary>
/// A render folder's lights/: the per-light transfer of whichever integrator rendered it, told by lights.json's "kind"
/// (a file-format tag owned by the transfer's <see cref="TransferFormat"/>; none: the first format, Whitted's) among the
/// registered integrators' formats. Relight, the camera, the viewer and the shard merge read it through here.
/// </summary>
public static class TransferFiles
{
    /// <summary>
    /// The format of <paramref name="outDir"/>'s lights/, or null when it has no lights.json. Unreadable JSON is the first
    /// format's (its reader says what is wrong); a kind no registered integrator writes is bad input.
    /// </summary>
    public static TransferFormat? FormatOf(string outDir)
    {
        var path = Path.Combine(outDir, TransferFormat.Folder, TransferFormat.Description);
        if (!File.Exists(path)) return null;
        string? kind = null;
        try { kind = JsonNode.Parse(File.ReadAllText(path))?["kind"] is JsonValue v && v.TryGetValue(out string? k) ? k : null; }
        catch (Exception e) when (e is JsonException or InvalidOperationException or FormatException or ArgumentException) { }
        return Integrators.TransferFormats.FirstOrDefault(f => f.Kind == kind)
            ?? throw new InputException(path, $"names kind {MessageText.Quote(kind ?? "")}, which no registered integrator writes",
                $"kinds: {string.Join(", ", Integrators.TransferFormats.Select(f => f.Kind ?? "(none)"))}");
    }

    /// <summary>The transfer in <paramref name="outDir"/>/lights/ checked against <paramref name="scene"/>; bad input if absent.</summary>
    public static ILightTransfer Read(string outDir, Scene scene)
    {
        var format = FormatOf(outDir)
            ?? throw new InputException(outDir, "has no per-light outputs (lights/lights.json)",
                "render with --formats …,lights or \"output\": { \"light_groups\": true }");
        return format.Read(outDir, scene);
    }
}
