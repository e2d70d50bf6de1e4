using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// Reads a re-radiation (Donaldson) matrix from CSV (docs/scene-format.md, "Fluorescence"): a header
/// <c>emission_nm,λ_1,…,λ_n</c> naming the excitation wavelengths, then one row per emission wavelength <c>λ_o,D[o,1],…,D[o,n]</c>,
/// the same evenly spaced ascending wavelengths on both axes. Values finite and non-negative; each excitation column may not
/// re-emit more photons than it absorbs (<see cref="ReradiationMatrix.PhotonExcess"/>). Errors are "file:line: what is wrong".
/// </summary>
public static class ReradiationCsvReader
{
    /// <summary>Relative slack of the photon balance, for values printed with few digits.</summary>
    public const double PhotonTolerance = 1e-6;

    public static ReradiationMatrix Read(string path) => Parse(InputFile.ReadAllText(path, "re-radiation matrix"), path);

    public static ReradiationMatrix Parse(string text, string path)
    {
        var inv = CultureInfo.InvariantCulture;
        var lines = text.Replace("\r\n", "\n").Split('\n');
        int count = lines.Length;
        while (count > 0 && lines[count - 1].Trim().Length == 0) count--;
        if (count == 0) throw new InputException($"{path}:1", "the file is empty",
            "expected a header emission_nm,λ1,…,λn and one row per emission wavelength");
        var header = lines[0].TrimStart('\uFEFF').Split(',');
        int n = header.Length - 1;
        if (n < 2) throw new InputException($"{path}:1", "the header names fewer than two excitation wavelengths",
            "expected emission_nm,300,305,…");
        var wl = new double[n];
        for (int j = 0; j < n; j++)
            if (!double.TryParse(header[j + 1].Trim(), NumberStyles.Float, inv, out wl[j]) || !double.IsFinite(wl[j]) || wl[j] <= 0)
                throw new InputException($"{path}:1",
                    $"header column {j + 2} {MessageText.Quote(header[j + 1].Trim(), 40)} is not a wavelength in nm",
                    "the header lists the excitation wavelengths after the first cell");
        double spacing = (wl[^1] - wl[0]) / (n - 1);
        for (int j = 1; j < n; j++)
            if (!(wl[j] > wl[j - 1]) || Math.Abs(wl[j] - wl[j - 1] - spacing) > 1e-6 * Math.Abs(spacing))
                throw new InputException($"{path}:1", $"excitation wavelengths must ascend evenly (at {header[j + 1].Trim()} nm)",
                    "give the matrix on one evenly spaced wavelength list");
        if (count - 1 != n)
            throw new InputException($"{path}:{count}", $"{count - 1} emission rows for {n} excitation columns",
                "the matrix is square: one row per wavelength of the header");
        var d = new double[n * n];
        for (int o = 0; o < n; o++)
        {
            int line = o + 2;
            var cells = lines[o + 1].Split(',');
            if (cells.Length != n + 1)
                throw new InputException($"{path}:{line}", $"{cells.Length} cells, expected {n + 1}",
                    "every row: its emission wavelength, then one value per excitation column");
            if (!double.TryParse(cells[0].Trim(), NumberStyles.Float, inv, out double l) || Math.Abs(l - wl[o]) > 1e-6 * spacing)
                throw new InputException($"{path}:{line}",
                    $"emission wavelength {MessageText.Quote(cells[0].Trim(), 40)} should be {wl[o].ToString(inv)}",
                    "rows list the same wavelengths as the header, ascending");
            for (int i = 0; i < n; i++)
            {
                if (!double.TryParse(cells[i + 1].Trim(), NumberStyles.Float, inv, out double v) || !double.IsFinite(v))
                    throw new InputException($"{path}:{line}",
                        $"column {i + 2} {MessageText.Quote(cells[i + 1].Trim(), 40)} is not a number", "write plain numbers with '.'");
                if (v < 0)
                    throw new InputException($"{path}:{line}", $"column {i + 2} is negative ({v.ToString("G4", inv)})",
                        "a re-radiation matrix is non-negative");
                d[o * n + i] = v;
            }
        }
        var m = new ReradiationMatrix(Path.GetFileName(path), wl, d);
        int bad = m.PhotonExcess(PhotonTolerance, out double emitted, out double absorbed);
        if (bad >= 0)
            throw new InputException($"{path}:1",
                $"excitation {wl[bad].ToString(inv)} nm re-emits {emitted / wl[bad]:G4} photons per incident photon " +
                $"but absorbs only {absorbed / wl[bad]:G4} (1 − D[i,i])",
                "a passive surface emits at most the photons it absorbs: Σ_o D[o,i]·λo ≤ (1 − D[i,i])·λi per excitation column");
        return m;
    }
}
