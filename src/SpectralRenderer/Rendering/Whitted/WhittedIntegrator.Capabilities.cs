using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Whitted;

// What the Whitted integrator can do beyond a picture (IntegratorCapabilities.cs): its per-light transfer of eq. 2's terms
// (WhittedTransfer.cs, files in WhittedTransferFiles.cs) and camera-ray packets for the scenes the packet path takes.
internal sealed partial class WhittedIntegrator : ITransferIntegrator
{
    public TransferFormat TransferFormat => WhittedTransferFiles.Format;

    /// <summary>The whole film's transfer (a Whitted transfer is not written for a crop or shard).</summary>
    public ILightTransfer TraceTransfer(Scene scene, int threads, CancellationToken cancel, PixelRect? crop) =>
        WhittedTransfer.Trace(scene, _geometry, threads, cancel);

    /// <summary>
    /// A scene with mirrors or glass is traced ray by ray, where each camera ray's tree has its ray budget and a stop request
    /// is seen at every pixel (bounded work, prompt SIGINT). Textured materials (a diffuse or specular texture) are looked up
    /// on the single-ray path (Eq2Walker); the packet path takes spectra only, and no participating media.
    /// </summary>
    public bool PrefersPackets(Scene scene)
    {
        bool recursive = scene.MaxDepth > 0 && scene.Materials.Any(m => m.HasMirror || m.HasTransmission);
        bool textured = scene.Materials.Any(m => m.DiffuseTexture is not null || m.SpecularTexture is not null);
        return !recursive && !textured && scene.Media.Count == 0;
    }
}
