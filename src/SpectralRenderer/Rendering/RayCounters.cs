namespace SpectralRenderer.Rendering;

/// <summary>Rays traced, by kind (counted per tile, summed at the end).</summary>
public struct RayCounters
{
    public long Primary;
    public long Shadow;
    public long Secondary;
    /// <summary>Terms whose colour lanes could not be exact (a coloured mirror or transmittance, dispersion, per-band Fresnel): see <see cref="RenderResult.FallbackPixels"/>.</summary>
    public long Fallback;
    public readonly long Total => Primary + Shadow + Secondary;

    public void Add(in RayCounters o) { Primary += o.Primary; Shadow += o.Shadow; Secondary += o.Secondary; Fallback += o.Fallback; }
}
