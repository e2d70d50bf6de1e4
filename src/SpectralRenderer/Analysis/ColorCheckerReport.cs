using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>One ColorChecker patch as rendered, against its 1 nm reference.</summary>
public sealed record PatchReport(int Patch, string Object, int Pixels, Xyz Rendered, Lab RenderedLab, Xyz Reference, Lab ReferenceLab,
    (byte R, byte G, byte B) Srgb8, double DeltaE00);

/// <summary>
/// The paper's §3.1 check: each ColorChecker patch's pixels (found by object id) averaged, turned into
/// XYZ with the render's own eq. 3 weights, and compared by CIEDE2000 with the patch's reflectance
/// under the reference white integrated at 1 nm (CIELAB relative to the 1 nm white).
/// </summary>
public static class ColorCheckerReport
{
    public static List<PatchReport> Compute(RenderFolder folder)
    {
        var observer = folder.ObserverDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931;
        var grid = folder.Image.Grid;
        var reference = new ReferenceColorimeter(observer, folder.ReferenceWhite, grid.Start, grid.End);
        var rows = new List<PatchReport>();
        for (int i = 0; i < folder.ObjectNames.Length; i++)
        {
            var r = folder.ObjectReflectances[i];
            if (r is null || !r.StartsWith("colorchecker:", StringComparison.Ordinal)) continue;
            int patch = int.Parse(r["colorchecker:".Length..]);
            var (mean, pixels) = folder.MeanSpectrum(i);
            if (pixels == 0) continue;
            var xyz = folder.ToXyz(mean);
            var refXyz = reference.OfReflectance(ColorChecker.Patch(patch));
            var lab = Lab.FromXyz(xyz, reference.White);
            var refLab = Lab.FromXyz(refXyz, reference.White);
            rows.Add(new PatchReport(patch, folder.ObjectNames[i], pixels, xyz, lab, refXyz, refLab, RgbSpace.Srgb.Encode8(xyz), DeltaE2000.Between(lab, refLab)));
        }
        rows.Sort((a, b) => a.Patch.CompareTo(b.Patch));
        return rows;
    }
}
