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

    /// <summary>Band <paramref name="b"/>'s columns of <see cref="Header"/> (number from 1, edges and centre in nm, round-trip exact),
    /// without a line end: the one writer of band rows.</summary>
    public static StringBuilder AppendRow(StringBuilder sb, BandGrid grid, int b)
    {
        var inv = CultureInfo.InvariantCulture;
        return sb.Append(inv,
            $"{BandGrid.Number(b)},{grid.Lower(b).ToString("R", inv)},{grid.Centre(b).ToString("R", inv)},"
                + $"{grid.Upper(b).ToString("R", inv)}");
    }

    public static void Write(string path, BandGrid grid) => AtomicFile.WriteAllText(path, Format(grid));

    /// <summary>Reads the grid back (evenly spaced bands).</summary>
    public static BandGrid Read(string path)
    {
        // Rows keep their line numbers (blank lines skipped) so a message names the file's own row:column.
        var lines = InputFile.ReadAllText(path, "wavelengths.csv").Split('\n').Select((l, i) => (Text: l.TrimEnd('\r'), Row: i + 1))
            .Where(l => l.Text.Trim().Length > 0).ToArray();
        if (lines.Length < 2 || lines[0].Text.Trim() != Header)
            throw new InputException(lines.Length == 0 ? $"{path}:1:1" : $"{path}:{lines[0].Row}:1", "not a wavelengths.csv",
                $"the first line must be {Header}");
        var rows = lines.Skip(1).Select(l =>
        {
            var p = l.Text.Split(',');
            if (p.Length != 4)
                throw new InputException($"{path}:{l.Row}:{Math.Min(p.Length, 4) + 1}",
                    $"bad row {MessageText.Quote(l.Text)}: {p.Length} cells, not 4", "band,start_nm,centre_nm,end_nm");
            if (!double.TryParse(p[1], NumberStyles.Float, CultureInfo.InvariantCulture, out var lo))
                throw new InputException($"{path}:{l.Row}:2", $"start_nm {MessageText.Quote(p[1])} is not a number",
                    "band,start_nm,centre_nm,end_nm");
            if (!double.TryParse(p[3], NumberStyles.Float, CultureInfo.InvariantCulture, out var hi))
                throw new InputException($"{path}:{l.Row}:4", $"end_nm {MessageText.Quote(p[3])} is not a number",
                    "band,start_nm,centre_nm,end_nm");
            return (lo, hi);
        }).ToArray();
        try { return new BandGrid(rows[0].lo, rows[^1].hi, rows.Length); }
        catch (ArgumentOutOfRangeException e)
        {
            throw new InputException(path, e.Message, "wavelengths.csv lists evenly spaced, ascending band edges: render the folder again");
        }
    }
}
