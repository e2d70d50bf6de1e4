using System.Globalization;
using SpectralRenderer.Color;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Spectra;
using static SpectralRenderer.Validation.CaseScenes;

namespace SpectralRenderer.Validation;

/// <summary>
/// Colour: the rendered ColorChecker (Ohta's reflectances) under D65, A, FL11 and a phosphor-white LED against the CIE 015
/// 1 nm summation written here (<see cref="Summation"/>), and that summation itself against colour-science's published
/// values under D65 (data/reference/colorchecker-ohta-d65-2deg.csv).
/// </summary>
internal static class ColourCases
{
    internal static IEnumerable<ValidationCase> All =>
        [SummationCheck, Chart("D65", "CIE D65"), Chart("A", "CIE A"), Chart("FL11", "CIE FL11"),
            Chart("led-yag", "a phosphor-white LED (NIST)")];

    /// <summary>
    /// CIE 015:2018 §7.1's summation at 1 nm: X = Σ_λ x̄·E·R / Σ_λ ȳ·E_white over λ = 380, 381, …, 780 nm, each table
    /// at λ by linear interpolation (its end value beyond it) — the yardstick, independent of the engine's band
    /// integration. The test hook's CMF shift reads the three CMFs that many nanometres off here.
    /// </summary>
    internal static Xyz Summation(TabulatedSpectrum? reflectance, TabulatedSpectrum light)
    {
        var o = Observer.Cie1931;
        double shift = Perturbation.CmfShiftNm, x = 0, y = 0, z = 0, yw = 0;
        for (int l = 380; l <= 780; l++)
        {
            double e = At(light, l), r = reflectance is null ? 1 : At(reflectance, l), ybar = At(o.YBar, l + shift);
            x += At(o.XBar, l + shift) * e * r;
            y += ybar * e * r;
            z += At(o.ZBar, l + shift) * e * r;
            yw += ybar * e;
        }
        return new Xyz(x / yw, y / yw, z / yw);
    }

    static double At(TabulatedSpectrum s, double l)
    {
        var w = s.Wavelengths;
        var v = s.Values;
        if (l <= w[0]) return v[0];
        if (l >= w[^1]) return v[^1];
        int i = 0;
        while (w[i + 1] < l) i++;
        return v[i] + (l - w[i]) / (w[i + 1] - w[i]) * (v[i + 1] - v[i]);
    }

    const double ChartTolerance = 0.02;

    static ValidationCase Chart(string light, string what) => new()
    {
        Name = $"colorchecker-{light.ToLowerInvariant()}",
        Group = "colour",
        Title = $"the 24-patch ColorChecker rendered under {what} (white: the same light): each patch's colour",
        Reference = "CIELAB of X = Σ x̄·E·R / Σ ȳ·E at 1 nm, 380–780 nm (linear interpolation of each table), ΔE00 to the "
            + "rendered patch's mean XYZ",
        Source = "CIE 015:2018 §7.1 (tristimulus values by summation), CIE 1931 2° CMFs; Ohta's ColorChecker reflectances; "
            + "CIEDE2000 (CIE 142-2001)",
        Tolerance = ChartTolerance,
        ToleranceWhy = "the renderer integrates each band exactly (light × reflectance × CMF of linear tables); the 1 nm sum "
            + "differs from that integral by ≤ 0.02 ΔE00 for a narrow-band light",
        ErrorKind = ErrorKind.Absolute,
        AbsoluteUnit = "ΔE00",
        XLabel = "patch",
        Quantity = "L* (expected and measured)",
        Measure = context =>
        {
            var scene = Load($$"""
                { "bands": "380:780:20", "white": "{{light}}", "radiometry": "physical",
                  "camera": { "position": [0, 0, 20], "look_at": [0, 0, 0], "fov": 16, "width": 72, "height": 48 },
                  "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "{{light}}", "intensity": {{Light(1)}} } ],
                  "objects": [ { "type": "colorchecker", "name": "patch", "frame": true } ] }
                """);
            var result = Integrators.Render(scene, context.Threads);
            var spd = SpectrumLibrary.Resolve(light);
            var white = Summation(null, spd);
            var points = new List<ValidationPoint>();
            for (int p = 1; p <= ColorChecker.PatchCount; p++)
            {
                int obj = scene.Objects.FindIndex(o => o.Name == $"patch-{p:00}");
                double x = 0, y = 0, z = 0;
                int count = 0;
                for (int i = 0; i < result.ObjectIds.Length; i++)
                    if (result.ObjectIds[i] == obj)
                    {
                        x += result.Xyz![3 * i];
                        y += result.Xyz[3 * i + 1];
                        z += result.Xyz[3 * i + 2];
                        count++;
                    }
                if (count == 0) throw new InvalidOperationException($"patch {p} is not in the picture");
                var rendered = Lab.FromXyz(new Xyz(x / count, y / count, z / count), white);
                var reference = Lab.FromXyz(Summation(ColorChecker.Patch(p), spd), white);
                points.Add(ValidationPoint.Absolute(p, $"{p:00} {ColorChecker.Name(p)}", reference.L, rendered.L,
                    DeltaE2000.Between(rendered, reference)));
            }
            return points;
        },
    };

    static ValidationCase SummationCheck => new()
    {
        Name = "cie-summation",
        Group = "colour",
        Title = "the colour cases' 1 nm summation (ColorChecker under D65) against colour-science 0.4.7's published XYZ",
        Reference = "XYZ of data/reference/colorchecker-ohta-d65-2deg.csv (colour-science 0.4.7, 1 nm, white-normalised), "
            + "compared in CIELAB",
        Source = "CIE 015:2018 §7.1; the values as computed by colour-science (data/reference/README.md)",
        Tolerance = 1e-3,
        ToleranceWhy = "two implementations of one summation: only rounding and the tables' interpolation order differ",
        ErrorKind = ErrorKind.Absolute,
        AbsoluteUnit = "ΔE00",
        XLabel = "patch",
        Quantity = "L* (expected and measured)",
        Measure = _ =>
        {
            var table = File.ReadAllLines(DataDirectory.File_(Path.Combine("reference", "colorchecker-ohta-d65-2deg.csv")));
            var d65 = SpectrumLibrary.Resolve("D65");
            var white = Summation(null, d65);
            var referenceWhite = new Xyz(0.950423, 1, 1.088610);   // the README's white (1 nm)
            var points = new List<ValidationPoint>();
            foreach (var line in table.Skip(1).Where(l => l.Length > 0))
            {
                var f = line.Split(',');
                int p = int.Parse(f[0], CultureInfo.InvariantCulture);
                var published = new Xyz(double.Parse(f[2], CultureInfo.InvariantCulture), double.Parse(f[3], CultureInfo.InvariantCulture),
                    double.Parse(f[4], CultureInfo.InvariantCulture));
                var mine = Lab.FromXyz(Summation(ColorChecker.Patch(p), d65), white);
                var theirs = Lab.FromXyz(published, referenceWhite);
                points.Add(ValidationPoint.Absolute(p, $"{p:00} {f[1]}", theirs.L, mine.L, DeltaE2000.Between(mine, theirs)));
            }
            return points;
        },
    };
}
