using System.Numerics;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>One ColorChecker patch as rendered, against its 1 nm reference.</summary>
public sealed record PatchReport(int Patch, string Object, int Pixels, Xyz Rendered, Lab RenderedLab, Xyz Reference, Lab ReferenceLab,
    (byte R, byte G, byte B) Srgb8, double DeltaE00);

/// <summary>
/// The paper's §3.1 check: each ColorChecker patch's pixels (found by object id) averaged — the render's own pixel
/// colours (spectral.exr X, Y, Z), else eq. 3 on the mean spectrum — and compared by CIEDE2000 with the patch's
/// reflectance under the scene's lights integrated at 1 nm (CIE 015 summation, normalised by the reference white;
/// CIELAB relative to the 1 nm white). Only meaningful for a flat chart lit uniformly and head-on:
/// <see cref="Compute"/> refuses anything else with the reason.
/// </summary>
public static class ColorCheckerReport
{
    /// <summary>Largest relative spread of a patch's pixel luminance that still counts as uniformly lit.</summary>
    public const double UniformityTolerance = 1e-3;
    /// <summary>cos of the largest angle between a light and the chart normal that still counts as head-on (0.5°).</summary>
    public static readonly double HeadOnCos = Math.Cos(0.5 * Math.PI / 180);

    public static List<PatchReport> Compute(RenderFolder folder)
    {
        var observer = folder.ObserverDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931;
        var grid = folder.Image.Grid;
        var patches = new List<(int Index, int Patch)>();
        for (int i = 0; i < folder.ObjectNames.Length; i++)
        {
            var r = folder.ObjectReflectances[i];
            if (r is null || !r.StartsWith("colorchecker:", StringComparison.Ordinal)) continue;
            if (folder.MeanSpectrum(i).Pixels == 0) continue;
            patches.Add((i, int.Parse(r["colorchecker:".Length..])));
        }
        if (patches.Count == 0) return [];
        var illuminant = HeadOnIlluminant(folder, patches);
        var reference = new ReferenceColorimeter(observer, folder.ReferenceWhite, grid.Start, grid.End);
        var rows = new List<PatchReport>();
        foreach (var (i, patch) in patches)
        {
            int pixels = folder.MeanSpectrum(i).Pixels;
            var xyz = folder.MeanXyz(i);
            var refXyz = reference.OfReflectance(ColorChecker.Patch(patch), illuminant);
            var lab = Lab.FromXyz(xyz, reference.White);
            var refLab = Lab.FromXyz(refXyz, reference.White);
            rows.Add(new PatchReport(patch, folder.ObjectNames[i], pixels, xyz, lab, refXyz, refLab, RgbSpace.Srgb.Encode8(xyz),
                DeltaE2000.Between(lab, refLab)));
        }
        rows.Sort((a, b) => a.Patch.CompareTo(b.Patch));
        return rows;
    }

    /// <summary>
    /// The irradiance on the chart, Σ_k intensity_k · S_k(λ) over its lights, when the render is a flat chart lit
    /// uniformly and head-on by directional lights and nothing else; otherwise an <see cref="InputException"/> saying why.
    /// </summary>
    static TabulatedSpectrum HeadOnIlluminant(RenderFolder folder, List<(int Index, int Patch)> patches)
    {
        string where = folder.Path;
        const string hint = "colorcheck compares with the 1 nm colour of each patch under the scene's lights; render a flat chart lit "
            + "head-on by directional lights, e.g. scenes/paper-3.1-colorchecker-d65.json";
        var objects = folder.Manifest.Objects;
        Vector3? normal = null;
        foreach (var (i, patch) in patches)
        {
            if (objects[i].FlatNormal is not { Length: 3 } n)
                throw new InputException(where, $"is not a flat chart: patch {patch} ('{folder.ObjectNames[i]}') is not a quad or plane",
                    hint);
            var v = new Vector3((float)n[0], (float)n[1], (float)n[2]);
            if (normal is { } first && Vector3.Dot(first, v) < HeadOnCos)
                throw new InputException(where, $"is not a flat chart: patch {patch} faces another way than the first patch", hint);
            normal ??= v;
            var (lo, hi, mean) = LuminanceSpread(folder, i);
            if (mean > 0 && (hi - lo) / mean > UniformityTolerance)
                throw new InputException(where,
                    $"is not uniformly lit: the luminance of patch {patch} ('{folder.ObjectNames[i]}') varies by {(hi - lo) / mean:P1} "
                        + $"across its pixels (shading, shadow or a highlight)",
                    hint);
        }
        if (folder.Manifest.GlobalAmbient)
            throw new InputException(where, "has global ambient light, which the head-on 1 nm reference does not include", hint);
        var lights = folder.Manifest.Lights;
        if (lights.Count == 0) throw new InputException(where, "has no light", hint);
        var grid = folder.Image.Grid;
        TabulatedSpectrum? sum = null;
        foreach (var l in lights)
        {
            if (l.Kind != "directional")
                throw new InputException(where,
                    $"is not lit uniformly: light '{l.Name}' is a {l.Kind} light, whose irradiance varies over the chart", hint);
            if (l.HasAmbient)
                throw new InputException(where, $"light '{l.Name}' has an ambient term, which the head-on 1 nm reference does not include",
                    hint);
            if (l.Direction is not { Length: 3 } d || l.Spd is null)
                throw new InputException(where, $"render.json does not record light '{l.Name}''s direction and spectrum",
                    "re-render the scene with this version");
            var dir = new Vector3((float)d[0], (float)d[1], (float)d[2]);
            double cos = -Vector3.Dot(dir, normal!.Value);
            if (cos < HeadOnCos)
                throw new InputException(where,
                    $"is not lit head-on: light '{l.Name}' meets the chart at "
                        + $"{Math.Acos(Math.Clamp(cos, -1, 1)) * 180 / Math.PI:0.#}° from its normal",
                    hint);
            var s = l.Spd.Scaled(l.Intensity);
            sum = sum is null ? s : Sum(sum, s, grid);
        }
        return sum!;
    }

    /// <summary>The sum of two tables on the union of their knots inside the band range (exact for piecewise-linear tables).</summary>
    static TabulatedSpectrum Sum(TabulatedSpectrum a, TabulatedSpectrum b, BandGrid grid)
    {
        var knots = new SortedSet<double>(a.Wavelengths.ToArray().Concat(b.Wavelengths.ToArray())
            .Where(w => w >= grid.Start && w <= grid.End)) { grid.Start,
            grid.End };
        var wl = knots.ToArray();
        return new TabulatedSpectrum($"{a.Name}+{b.Name}", wl, wl.Select(w => a.Evaluate(w) + b.Evaluate(w)).ToArray(),
            Extrapolation.Clamp);
    }

    static (double Lo, double Hi, double Mean) LuminanceSpread(RenderFolder folder, int index)
    {
        double lo = double.PositiveInfinity, hi = double.NegativeInfinity, sum = 0;
        int count = 0;
        int bands = folder.Image.Bands;
        for (int p = 0; p < folder.ObjectIds.Length; p++)
        {
            if (folder.ObjectIds[p] != index) continue;
            double y = folder.PixelXyz is { } xyz
                ? xyz.Y[p]
                : folder.ToXyz(Array.ConvertAll(folder.Image.Data.AsSpan(p * bands, bands).ToArray(), v => (double)v)).Y;
            lo = Math.Min(lo, y); hi = Math.Max(hi, y); sum += y; count++;
        }
        return (lo, hi, count > 0 ? sum / count : 0);
    }
}
