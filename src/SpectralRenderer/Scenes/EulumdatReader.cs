using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// EULUMDAT (.ldt, Stockmar 1990) files: one field per line — identification (1), type Ityp (2), symmetry Isym (3), the
/// number Mc of C-planes and their spacing (4, 5), the number Ng of intensities per plane and their spacing (6, 7), texts
/// and dimensions (8–21), DFF, LORL (22, 23), the conversion factor CFLI (24), tilt (25), the number n of lamp sets (26)
/// and six lines per set (number of lamps, type, total flux in lm, colour, CRI, watts), ten direct ratios, the Mc C
/// angles, the Ng γ angles, and the intensities in cd/klm for the planes Isym needs: Isym 0 all Mc, 1 one, 2 C0–C180,
/// 3 C270–C90 (planes 3Mc/4 … 3Mc/4 + Mc/2, wrapping), 4 C0–C90. Candela = value × (first set's lumens) / 1000 × CFLI.
/// Decimal commas are read as points. Errors: file:line, a hint.
/// </summary>
public static class EulumdatReader
{
    public static PhotometricFile Parse(string text, string file)
    {
        var lines = text.Replace("\r\n", "\n").Replace('\r', '\n').TrimEnd('\n').Split('\n');
        int at = 0;
        string Line(string what)
        {
            if (at >= lines.Length)
                throw new InputException($"{file}:{lines.Length}", $"the file ends before {what} (line {at + 1})",
                    "an EULUMDAT file has a fixed sequence of lines: it is cut short");
            return lines[at++].Trim();
        }
        double Number(string what)
        {
            var t = Line(what);
            if (!double.TryParse(t.Replace(',', '.'), NumberStyles.Float, CultureInfo.InvariantCulture, out double v)
                || !double.IsFinite(v))
                throw new InputException($"{file}:{at}", $"{what} is {MessageText.Quote(t, 40)}, not a number",
                    "EULUMDAT has one number per line here");
            return v;
        }
        int Count(string what, int min, int max)
        {
            double v = Number(what);
            return v == Math.Floor(v) && v >= min && v <= max ? (int)v
                : throw new InputException($"{file}:{at}", $"{what} is {v:g}", $"a whole number from {min} to {max}");
        }

        Line("the identification");
        Count("the type indicator Ityp", 0, 3);
        int isym = Count("the symmetry indicator Isym", 0, 4);
        int mc = Count("the number of C-planes Mc", 1, 3600);
        Number("the C-plane spacing Dc");
        int ng = Count("the number of intensities per plane Ng", 1, 18000);
        Number("the γ spacing Dg");
        for (int i = 8; i <= 12; i++) Line($"text line {i}");
        for (int i = 13; i <= 23; i++) Number($"dimension or ratio (line {i})");
        double cfli = Number("the conversion factor CFLI");
        if (!(cfli > 0))
            throw new InputException($"{file}:{at}", $"the conversion factor CFLI is {cfli.ToString(CultureInfo.InvariantCulture)}",
                "intensities are multiplied by CFLI: give 1 when they need no conversion");
        Number("the tilt");
        int sets = Count("the number of lamp sets n", 1, 20);
        double flux = 0;
        for (int s = 0; s < sets; s++)
        {
            Number("the number of lamps");
            Line("the lamp type");
            double f = Number("the total luminous flux of the lamps (lm)");
            if (s == 0) flux = Math.Abs(f);
            Line("the colour appearance");
            Line("the colour rendering");
            Number("the wattage");
        }
        if (!(flux > 0))
            throw new InputException($"{file}:{at}", "the first lamp set's luminous flux is 0",
                "intensities are cd per 1000 lm of the lamps: give their flux");
        for (int i = 0; i < 10; i++) Number("a direct ratio");
        var c = new double[mc];
        for (int i = 0; i < mc; i++)
        {
            c[i] = Number($"C angle {i + 1} of {mc}");
            if (c[i] < 0 || c[i] >= 360 || (i > 0 && !(c[i] > c[i - 1])))
                throw new InputException($"{file}:{at}", $"C angle {c[i]:g} is not in 0–360° after {(i > 0 ? c[i - 1] : 0):g}",
                    "C angles ascend from 0 below 360°");
        }
        var g = new double[ng];
        for (int i = 0; i < ng; i++)
        {
            g[i] = Number($"γ angle {i + 1} of {ng}");
            if (g[i] < 0 || g[i] > 180 || (i > 0 && !(g[i] > g[i - 1])))
                throw new InputException($"{file}:{at}", $"γ angle {g[i]:g} is not in 0–180° after {(i > 0 ? g[i - 1] : 0):g}",
                    "γ angles ascend from 0 to at most 180°");
        }
        if (c[0] != 0 && isym != 1)
            throw new InputException($"{file}:{at - ng - mc + 1}", $"the first C angle is {c[0]:g}", "C angles start at 0");
        if ((isym is 2 or 3 && mc % 2 != 0) || (isym is 3 or 4 && mc % 4 != 0))
            throw new InputException($"{file}:4", $"Mc = {mc} does not split into the planes symmetry {isym} needs",
                "Mc must be a multiple of 4 for Isym 3 and 4, of 2 for Isym 2");
        // The planes present (EULUMDAT Mc1 … Mc2, 1-based; Isym 3 wraps past 360).
        var (first, count, symmetry) = isym switch
        {
            1 => (0, 1, CandelaSymmetry.Axial),
            2 => (0, mc / 2 + 1, CandelaSymmetry.BilateralC0),
            3 => (3 * mc / 4, mc / 2 + 1, CandelaSymmetry.BilateralC90),
            4 => (0, mc / 4 + 1, CandelaSymmetry.Quadrant),
            _ => (0, mc, CandelaSymmetry.Full),
        };
        double toCd = flux / 1000 * cfli;
        var horizontal = new double[count];
        var rows = new double[count][];
        for (int p = 0; p < count; p++)
        {
            int index = (first + p) % mc;
            horizontal[p] = isym == 1 ? 0 : c[index] + (first + p >= mc ? 360 : 0);
            rows[p] = new double[ng];
            for (int k = 0; k < ng; k++)
            {
                double v = Number($"intensity {k + 1} of C-plane {c[index]:g}");
                if (v < 0) throw new InputException($"{file}:{at}", $"intensity {v:g} is negative", "intensities are cd/klm ≥ 0");
                rows[p][k] = v * toCd;
            }
        }
        if (isym == 3)
            for (int p = 1; p < count; p++)
                if (!(horizontal[p] > horizontal[p - 1]))
                    throw new InputException($"{file}:{at}", "the C angles of Isym 3 do not run from 270° through 360° to 90°",
                        "Isym 3 needs C-planes evenly around the circle");
        if (isym == 2 && horizontal[^1] != 180 || isym == 4 && horizontal[^1] != 90
            || isym == 3 && (horizontal[0] != 270 || horizontal[^1] != 450))
            throw new InputException($"{file}:{at}", $"the planes symmetry {isym} needs end at C {horizontal[^1] % 360:g}",
                "Isym 2 needs C0–C180, 3 C270–C90, 4 C0–C90: evenly spaced C angles");
        while (at < lines.Length && string.IsNullOrWhiteSpace(lines[at])) at++;
        if (at < lines.Length)
            throw new InputException($"{file}:{at + 1}", "lines after the intensity table",
                "Mc, Ng and Isym say where the table ends: check them");
        return new PhotometricFile(new CandelaTable(g, horizontal, rows, symmetry, file), flux, "EULUMDAT");
    }
}
