using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// The white diffuser's radiance in a render, per unit of the scene light's band values, read off the ColorChecker in the
/// picture as a photographer white-balances on a chart: the least-squares scale s of the patches' band values L_p,b against
/// E_b·ρ_p,b (the light's and the patch's band means), s = Σ L·Eρ / Σ (Eρ)². For a path render, whose light at the chart
/// is every bounce and not eq. 2's terms, this is the white the camera's colour correction is fitted to.
/// </summary>
public static class ChartWhite
{
    /// <summary>The scale, or null when the render shows no ColorChecker patch (or no light on it).</summary>
    public static double? Scale(CameraScene cs)
    {
        if (cs.Patches.Count == 0) return null;
        var e = BandProjection.Means(cs.Light, cs.Grid);
        var data = cs.Folder.Image.Data;
        int bands = cs.Grid.Count;
        double num = 0, den = 0;
        foreach (var p in cs.Patches)
        {
            var r = BandProjection.Means(ColorChecker.Patch(p.Number), cs.Grid);
            foreach (int i in p.Pixels)
                for (int b = 0; b < bands; b++)
                {
                    double m = e[b] * r[b];
                    num += data[i * bands + b] * m;
                    den += m * m;
                }
        }
        return num > 0 && den > 0 ? num / den : null;
    }
}
