using System.Text.Json.Nodes;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

// What an integrator can do beyond a picture, asked by capability, never by name: the render job, the output products,
// relighting, the camera's exact route, the memory check, the shard merge and the C ABI hold "the integrator's
// transfer" or "an integrator that gathers" and do not know its class. A new integrator implements the ones it can
// (ARCHITECTURE.md, "Extending: an integrator"); what is known before its geometry is built rides on its registration
// (IntegratorEntry in Registry/Integrators.cs: its settings keys, its transfer's format, its tables' memory).

/// <summary>
/// An integrator that records a per-light transfer (the lights product; relight; the C ABI's relight and exact route):
/// its camera samples traced again with each scene light's contribution kept apart.
/// </summary>
public interface ITransferIntegrator : IIntegrator
{
    /// <summary>The format of the transfer it records (its files' kind, memory, what a render with it may not ask for).</summary>
    TransferFormat TransferFormat { get; }

    /// <summary>
    /// The transfer of <paramref name="crop"/> (null: the whole film; a crop only when <see cref="TransferFormat.Shards"/>),
    /// the render's camera samples bit for bit.
    /// </summary>
    ILightTransfer TraceTransfer(Scene scene, int threads, CancellationToken cancel, PixelRect? crop);
}

/// <summary>
/// A per-light transfer: a render's film as a sum over the scene's lights of what each one's light did, so the film can be
/// recombined under other light spectra and intensities without tracing a ray (relight).
/// </summary>
public interface ILightTransfer
{
    TransferFormat Format { get; }
    /// <summary>The film's size and the pixels the transfer holds (a whole render's, or a shard's strip).</summary>
    int FilmWidth { get; }
    int FilmHeight { get; }
    PixelRect Region { get; }
    /// <summary>Per pixel of the region, the object its centre ray hit (−1: none).</summary>
    int[] ObjectIds { get; }

    /// <summary>
    /// Why <paramref name="scene"/> (the render's scene with its lights changed) cannot be recombined from it (its film or
    /// bands differ: the scene file changed since the render), or null.
    /// </summary>
    string? Mismatch(Scene scene);

    /// <summary>The film of <paramref name="scene"/>: the transfer recombined under its lights, the geometry's images as traced.</summary>
    RenderResult Relight(Scene scene);

    /// <summary>How <see cref="Relight"/> forms the film, as a relit render.json's relit.method says.</summary>
    string RelightMethod { get; }

    /// <summary>Files under lights/ a relit render copies from the folder it was read from (byte for byte what it writes).</summary>
    IEnumerable<string> StoredFiles { get; }

    /// <summary>Writes lights/ into <paramref name="outDir"/>, calling <paramref name="done"/> with each file's relative name.</summary>
    void Write(Scene scene, string outDir, Action<string> done);
}

/// <summary>Which exact camera route a render's transfer gives the camera (<c>spectral camera --signals exact</c>).</summary>
public enum CameraRoute
{
    /// <summary>None: the camera integrates the band cube.</summary>
    None,
    /// <summary>Eq. 2's terms per light (the term route, <c>ITermRoute</c>): each term's spectrum integrated at full resolution.</summary>
    Terms,
    /// <summary>The film on a sub-band grid (<see cref="ISubBandFilmRoute"/>, <see cref="ISubBandFilmIntegrator"/>).</summary>
    SubBandFilm,
}

/// <summary>
/// What an integrator's per-light transfer is before one is traced or read: the kind lights.json names, the memory a
/// render's transfer takes, whether shards may write it, how it is read back, how its shards' arrays merge, and the camera
/// route it gives. One instance per integrator, on its registration (<c>IntegratorEntry.Transfer</c>).
/// </summary>
public abstract class TransferFormat
{
    /// <summary>The folder of a render that holds its transfer, and the file there that says which format it is (every format's).
    /// </summary>
    public const string Folder = "lights", Description = "lights.json";

    /// <summary>lights.json's entry of scene light k (every format's): its index, name, kind, spectrum name and band values
    /// I_k,b (spectrum × intensity, unpadded).</summary>
    internal static JsonObject LightEntry(Scene scene, int k)
    {
        var l = scene.Lights[k];
        return new JsonObject
        {
            ["index"] = k,
            ["name"] = l.Name,
            ["kind"] = l.Type,
            ["spectrum"] = l.Spectrum?.Name,
            ["band_values"] = Values(l.Intensity.AsSpan(0, scene.Bands)),
        };
    }

    /// <summary>Float values as a JSON array of numbers (lights.json's band values).</summary>
    internal static JsonArray Values(ReadOnlySpan<float> v)
    {
        var a = new JsonArray();
        foreach (float x in v) a.Add((JsonNode)JsonValue.Create((double)x));
        return a;
    }

    /// <summary>lights.json's "kind", or null for the format whose lights.json names none (the first one, Whitted's).</summary>
    public abstract string? Kind { get; }

    /// <summary>The integrator it belongs to (its registered name).</summary>
    public abstract string Integrator { get; }

    /// <summary>The exact camera route its transfer (and its integrator) gives.</summary>
    public virtual CameraRoute Route => CameraRoute.None;

    /// <summary>Whether a shard writes its strip of the transfer (<c>spectral merge</c> joins them by <see cref="RowShape"/>).</summary>
    public virtual bool Shards => false;

    /// <summary>Why a render of <paramref name="scene"/> cannot record it (e.g. adaptive sampling), and a hint; null if it can.</summary>
    public virtual (string Option, string What, string Hint)? Refuses(Scene scene) => null;

    /// <summary>Why a relight cannot give scene light <paramref name="light"/> a new spectrum with it, or null.</summary>
    public virtual string? RefusesNewSpectrum(Light light) => null;

    /// <summary>What a render's transfer of <paramref name="scene"/> holds, by part (the memory check).</summary>
    public abstract IEnumerable<(string Part, long Bytes)> Memory(Scene scene);

    /// <summary>The transfer in <paramref name="outDir"/>/lights/ for <paramref name="scene"/>; bad input when damaged.</summary>
    public abstract ILightTransfer Read(string outDir, Scene scene);

    /// <summary>
    /// A shard's lights/<paramref name="file"/> as an H × W × … float32 array: the per-pixel shape (from the shard's
    /// lights.json in <paramref name="lightsDir"/>), or null when the file is not joined by rows.
    /// </summary>
    public virtual int[]? RowShape(string file, string lightsDir) => null;
}

/// <summary>The exact camera route of a film on a sub-band grid, recombined from a transfer without rays.</summary>
public interface ISubBandFilmRoute : ILightTransfer
{
    /// <summary>The sub-band film of <paramref name="scene"/> (the render's lights).</summary>
    SubBandFilm Film(Scene scene);

    /// <summary>How the film is formed from the transfer, for the camera's route text.</summary>
    string FilmMethod { get; }
}

/// <summary>An integrator whose radiance lives on a sub-band grid: its film traced again for the camera's exact route.</summary>
public interface ISubBandFilmIntegrator : IIntegrator
{
    /// <summary>The sub-bands of the grid its radiance lives on (the film's size is 4 bytes per pixel and sub-band).</summary>
    int FilmSubBands { get; }

    /// <summary>The render's camera samples traced again (the same paths) onto the sub-band grid.</summary>
    SubBandFilm TraceSubBandFilm(Scene scene, int threads, CancellationToken cancel = default);
}

/// <summary>
/// An integrator whose <see cref="IIntegrator.Radiance"/> along any ray is all the light arriving back along it (emitters,
/// sky, interreflection), so a cosine-weighted gather of it from a surface point gives the illuminance the lights' shadow
/// rays miss (<c>Illuminance.Maps</c>, <c>Illuminance.OnGrid</c>: photometry and calculation grids).
/// </summary>
public interface IGatherIntegrator : IIntegrator
{
    /// <summary>
    /// The radiance arriving back along the sample's ray without the light its first vertex emits — a surface of the
    /// emitter set it meets, or the sky it escapes to: what the gather adds to its own next-event estimation and MIS of
    /// the emitters (<c>Illuminance</c>), which count that light. The default, <see cref="IIntegrator.Radiance"/>, is
    /// right for an integrator whose rays see no emitter of the set directly (none in the scene); one that does overrides it.
    /// </summary>
    int Reflected(in CameraSample sample, Span<float> result, Span<float> scratch, ref RayCounters counters) =>
        Radiance(in sample, result, scratch, ref counters);
}
