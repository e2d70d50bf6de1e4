using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Terms;

/// <summary>
/// The shifted part of a fluorescent material's diffuse term (<see cref="ReradiationMatrix"/>), added to its
/// <see cref="TermTables"/> entry for each light: the light's spectrum is averaged over the matrix's excitation cells
/// (exactly, on its table, within the render's bands: light outside them is not carried), the matrix gives the emission
/// per cell, and the table gains that emission's exact band means and its colour κ Σ_o L_o ∫_cell_o x̄ dλ (the CMFs are
/// zero outside 360–830 nm, so bands in the UV carry excitation but no colour). The reflective diagonal is the material's
/// <see cref="Material.Diffuse"/>, already in the table; a matrix without a shift adds nothing.
/// </summary>
public static class FluorescentTerms
{
    /// <summary>Adds (light ⊗ shift)·<paramref name="factor"/> to the padded table (bands, then X, Y, Z).</summary>
    public static void AddShift(Scene scene, float[] table, float[] light, ReradiationMatrix matrix, double factor)
    {
        var grid = scene.Grid;
        var cm = scene.Colorimeter;
        int n = scene.Bands;
        if (!matrix.HasShift || !SpectralMath.Any(light)) return;
        Func<double, double, double> integral = scene.Spectra.TryGetValue(light, out var s)
            ? s.Integrate
            : (lo, hi) => BandIntegral(light, grid, lo, hi);
        var cells = matrix.ShiftedCells(integral, grid.Start, grid.End);
        var bands = matrix.CellsToBands(cells, grid);
        Xyz xyz;
        if (cm.Scheme == BandIntegration.Exact)
        {
            double x = 0, y = 0, z = 0;
            for (int o = 0; o < cells.Length; o++)
            {
                double lo = Math.Max(grid.Start, matrix.CellLower(o)), hi = Math.Min(grid.End, matrix.CellUpper(o));
                if (hi <= lo || cells[o] == 0) continue;
                x += cells[o] * cm.Observer.XBar.Integrate(lo, hi);
                y += cells[o] * cm.Observer.YBar.Integrate(lo, hi);
                z += cells[o] * cm.Observer.ZBar.Integrate(lo, hi);
            }
            xyz = new Xyz(cm.Kappa * x, cm.Kappa * y, cm.Kappa * z);
        }
        else xyz = cm.ToXyz(bands);
        for (int b = 0; b < n; b++) table[b] += (float)(bands[b] * factor);
        table[n] += (float)(xyz.X * factor); table[n + 1] += (float)(xyz.Y * factor); table[n + 2] += (float)(xyz.Z * factor);
    }

    /// <summary>∫ E dλ over [lo, hi] of a spectrum known only by its band values (constant within each band).</summary>
    static double BandIntegral(float[] bands, BandGrid grid, double lo, double hi)
    {
        double s = 0;
        for (int b = 0; b < grid.Count; b++) s += bands[b] * ReradiationMatrix.Overlap(lo, hi, grid.Lower(b), grid.Upper(b));
        return s;
    }
}
