namespace SpectralRenderer.Rendering;

/// <summary>Rays traced, by kind (counted per tile, summed at the end).</summary>
public struct RayCounters
{
    public long Primary;
    public long Shadow;
    public long Secondary;
    /// <summary>Terms whose colour lanes could not be exact (a coloured mirror or transmittance, dispersion, per-band Fresnel): see
    /// <see cref="RenderResult.FallbackPixels"/>.</summary>
    public long Fallback;
    public readonly long Total => Primary + Shadow + Secondary;

    /// <summary>The <see cref="Total"/> at which the current camera ray's budget is spent (set by the renderer per camera ray; 0 =
    /// none).</summary>
    public long BudgetEnd;
    /// <summary>Set when the current camera ray's branches were cut short by the budget.</summary>
    public bool OverBudget;
    /// <summary>Camera rays cut short by the ray budget.</summary>
    public long OverBudgetRays;
    /// <summary>Reflected and refracted rays not traced because their weight fell below the threshold (adaptive depth).</summary>
    public long PrunedRays;

    public void Add(in RayCounters o)
    {
        Primary += o.Primary; Shadow += o.Shadow; Secondary += o.Secondary; Fallback += o.Fallback;
        OverBudgetRays += o.OverBudgetRays; PrunedRays += o.PrunedRays;
    }

    /// <summary>Starts the budget of one camera ray.</summary>
    public void StartCameraRay(int budget) { BudgetEnd = Total + budget; OverBudget = false; }

    /// <summary>Ends a camera ray, counting it when its budget ran out.</summary>
    public void EndCameraRay() { if (OverBudget) OverBudgetRays++; OverBudget = false; BudgetEnd = 0; }

    public readonly bool BudgetSpent => BudgetEnd != 0 && Total >= BudgetEnd;
}
