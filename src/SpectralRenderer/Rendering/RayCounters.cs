namespace SpectralRenderer.Rendering;

/// <summary>Rays traced, by kind (counted per tile, summed at the end).</summary>
public struct RayCounters
{
    public long Primary;
    public long Shadow;
    public long Secondary;
    public readonly long Total => Primary + Shadow + Secondary;

    public void Add(in RayCounters o) { Primary += o.Primary; Shadow += o.Shadow; Secondary += o.Secondary; }
}
