using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// wavelengths.csv beside an .npy cube: header "band,start_nm,centre_nm,end_nm", one row per band in the
/// order of the array's last axis. Bands are numbered from 1 (<see cref="BandGrid.Number"/>), as in the band PNGs' names,
/// the probe and reconstruction tables: band b is index b − 1 of the cube's last axis.
/// </summary>
public static class WavelengthsCsv
{
    public const string Header = "band,start_nm,centre_nm,end_nm";

    public static string Format(BandGrid grid)
    {
        var sb = new StringBuilder(Header).Append('\n');
        for (int b = 0; b < grid.Count; b++) AppendRow(sb, grid, b).Append('\n');
        return sb.ToString();
    }

    /// <summary>Band <paramref name="b"/>'s columns of <see cref="Header"/> (number from 1, edges and centre in nm, round-trip exact), without a line end: the one writer of band rows.</summary>
    public static StringBuilder AppendRow(StringBuilder sb, BandGrid grid, int b)
    {
        var inv = CultureInfo.InvariantCulture;
        return sb.Append(inv, $"{BandGrid.Number(b)},{grid.Lower(b).ToString("R", inv)},{grid.Centre(b).ToString("R", inv)},{grid.Upper(b).ToString("R", inv)}");
    }

    public static void Write(string path, BandGrid grid) => AtomicFile.WriteAllText(path, Format(grid));

    /// <summary>Reads the grid back (evenly spaced bands).</summary>
    public static BandGrid Read(string path)
    {
        var lines = InputFile.ReadAllText(path, "wavelengths.csv").Split('\n').Select(l => l.TrimEnd('\r')).Where(l => l.Trim().Length > 0).ToArray();
        if (lines.Length < 2 || lines[0].Trim() != Header)
            throw new InputException(path, "not a wavelengths.csv", $"the first line must be {Header}");
        var rows = lines.Skip(1).Select((l, i) =>
        {
            var p = l.Split(',');
            if (p.Length != 4 || !double.TryParse(p[1], NumberStyles.Float, CultureInfo.InvariantCulture, out var lo)
                || !double.TryParse(p[3], NumberStyles.Float, CultureInfo.InvariantCulture, out var hi))
                throw new InputException($"{path}:{i + 2}", $"bad row {MessageText.Quote(l)}", "band,start_nm,centre_nm,end_nm");
            return (lo, hi);
        }).ToArray();
        try { return new BandGrid(rows[0].lo, rows[^1].hi, rows.Length); }
        catch (ArgumentOutOfRangeException e) { throw new InputException(path, e.Message, "wavelengths.csv lists evenly spaced, ascending band edges: render the folder again"); }
    }
}
