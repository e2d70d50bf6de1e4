using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// Reads spectral CSV files (data/README.md): one header line of named columns, the first
/// column the wavelength in nm, rows in strictly ascending wavelength, values finite and
/// non-negative (reflectances, powers and colour-matching functions are never negative).
/// Every defect is reported as "file:row:column: what is wrong" (row = line of the file, column = 1-based cell).
/// </summary>
public static class CsvSpectrumReader
{
    public static SpectralTable Read(string path)
    {
        return Parse(InputFile.ReadAllText(path), path);
    }

    /// <summary>A table of basis functions that may go negative (the CIE daylight components S₁, S₂).</summary>
    public static SpectralTable ReadSigned(string path) => Parse(InputFile.ReadAllText(path), path, allowNegative: true);

    public static SpectralTable Parse(string text, string path, bool allowNegative = false)
    {
        var lines = text.Replace("\r\n", "\n").Split('\n');
        int n = lines.Length;
        while (n > 0 && lines[n - 1].Trim().Length == 0) n--;
        if (n == 0)
            throw new InputException($"{path}:1:1", "the file is empty", "a spectral CSV needs a header line and data rows");

        var header = lines[0].TrimStart('\uFEFF').Split(',').Select(h => h.Trim()).ToArray();
        if (header.Length < 2)
            throw new InputException($"{path}:1:{header.Length + 1}", "the header names fewer than two columns",
                "expected e.g. wavelength_nm,value");
        for (int c = 0; c < header.Length; c++)
        {
            if (header[c].Length == 0)
                throw new InputException($"{path}:1:{c + 1}", $"column {c + 1} has no name", "every column needs a name in the header");
            for (int d = 0; d < c; d++)
                if (header[d] == header[c])
                    throw new InputException($"{path}:1:{c + 1}", $"column name '{header[c]}' appears twice",
                        "give every column its own name");
        }
        if (n == 1)
            throw new InputException($"{path}:2:1", "the file has a header but no data rows", "add rows of wavelength_nm,value");

        var wl = new List<double>(n);
        var cols = new List<double>[header.Length - 1];
        for (int c = 0; c < cols.Length; c++) cols[c] = new List<double>(n);

        for (int i = 1; i < n; i++)
        {
            int lineNo = i + 1;
            string line = lines[i];
            if (line.Trim().Length == 0)
                throw new InputException($"{path}:{lineNo}:1", "empty line inside the data", "remove it");
            var cells = line.Split(',');
            if (cells.Length != header.Length)
                throw new InputException($"{path}:{lineNo}:{Math.Min(cells.Length, header.Length) + 1}",
                    cells.Length < header.Length
                        ? $"missing column: {cells.Length} cells, the header names {header.Length} (first "
                            + $"missing: '{header[cells.Length]}')"
                        : $"{cells.Length} cells, the header names only {header.Length}", "every row needs one cell per header column");
            for (int c = 0; c < cells.Length; c++)
            {
                var cell = cells[c].Trim();
                if (!double.TryParse(cell, NumberStyles.Float, CultureInfo.InvariantCulture, out double v))
                    throw new InputException($"{path}:{lineNo}:{c + 1}",
                        $"{MessageText.Quote(cell)} in column {MessageText.Quote(header[c])} is not a number",
                        "cells are plain numbers with a '.' decimal point, e.g. 0.25");
                if (!double.IsFinite(v) || Math.Abs(v) > float.MaxValue)
                    throw new InputException($"{path}:{lineNo}:{c + 1}", $"{cell} in column '{header[c]}' is not finite",
                        "spectral values must be finite numbers");
                if (c == 0)
                {
                    if (v <= 0)
                        throw new InputException($"{path}:{lineNo}:{c + 1}", $"wavelength {cell} nm is not positive",
                            "wavelengths are in nm and positive");
                    if (wl.Count > 0 && v == wl[^1])
                        throw new InputException($"{path}:{lineNo}:{c + 1}", $"wavelength {cell} nm appears twice",
                            "each wavelength needs exactly one row");
                    if (wl.Count > 0 && v < wl[^1])
                        throw new InputException($"{path}:{lineNo}:{c + 1}",
                            $"wavelength {cell} nm follows {wl[^1].ToString(CultureInfo.InvariantCulture)} nm: not ascending",
                            "sort the rows by wavelength");
                    wl.Add(v);
                }
                else
                {
                    if (v < 0 && !allowNegative)
                        throw new InputException($"{path}:{lineNo}:{c + 1}", $"negative value {cell} in column '{header[c]}'",
                            "reflectances, powers and sensitivities cannot be negative");
                    cols[c - 1].Add(v);
                }
            }
        }

        var wavelengths = wl.ToArray();
        var spectra = new Dictionary<string, TabulatedSpectrum>(StringComparer.Ordinal);
        for (int c = 0; c < cols.Length; c++)
            spectra[header[c + 1]] = new TabulatedSpectrum(header[c + 1], wavelengths, cols[c].ToArray());
        return new SpectralTable(path, header.Skip(1).ToArray(), spectra);
    }
}
