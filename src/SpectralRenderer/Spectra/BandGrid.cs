using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// The wavelength bands a render carries: <see cref="Count"/> equal bands between
/// <see cref="Start"/> and <see cref="End"/> nm (the paper's 380–780 nm in 20 bands of 20 nm).
/// Band b covers [Start + b·Width, Start + (b+1)·Width].
/// </summary>
public sealed class BandGrid : IEquatable<BandGrid>
{
    public const int MaxBands = 1024;

    public BandGrid(double start, double end, int count)
    {
        if (!(double.IsFinite(start) && double.IsFinite(end)) || start <= 0 || end <= start)
            throw new ArgumentOutOfRangeException(nameof(end), $"band range {start}–{end} nm is empty or not positive");
        if (count < 1 || count > MaxBands)
            throw new ArgumentOutOfRangeException(nameof(count), $"band count {count} is outside 1–{MaxBands}");
        Start = start;
        End = end;
        Count = count;
    }

    public static BandGrid Default { get; } = new(380, 780, 20);

    public double Start { get; }
    public double End { get; }
    public int Count { get; }
    public double Width => (End - Start) / Count;

    /// <summary>
    /// The number a person reads for the band at zero-based index <paramref name="index"/>: bands are numbered
    /// from 1 in every file name, table and message (band-01-….png, wavelengths.csv, probe, reconstruction).
    /// Arrays stay zero-based: band b is index b − 1 of a cube's band axis.
    /// </summary>
    public static int Number(int index) => index + 1;

    public double Lower(int band) => Start + band * Width;
    public double Upper(int band) => band == Count - 1 ? End : Start + (band + 1) * Width;
    public double Centre(int band) => 0.5 * (Lower(band) + Upper(band));

    /// <summary>The band edges, Count + 1 values.</summary>
    public double[] Edges()
    {
        var e = new double[Count + 1];
        for (int i = 0; i < Count; i++) e[i] = Lower(i);
        e[Count] = End;
        return e;
    }

    /// <summary>Parses band edges "start:end:count", e.g. "380:780:20" or "395:705:31" (31 bands of 10 nm; <see cref="ParseWave"/> for
    /// centres).</summary>
    public static BandGrid Parse(string text, string where = "--bands")
    {
        var parts = text.Split(':');
        const string hint = "write start:end:count in nm, e.g. 380:780:20";
        if (parts.Length != 3)
            throw new InputException(where, $"'{text}' is not a band grid", hint);
        if (!double.TryParse(parts[0], NumberStyles.Float, CultureInfo.InvariantCulture, out var start) ||
            !double.TryParse(parts[1], NumberStyles.Float, CultureInfo.InvariantCulture, out var end) ||
            !int.TryParse(parts[2], NumberStyles.Integer, CultureInfo.InvariantCulture, out var count))
            throw new InputException(where, $"'{text}' has a non-numeric part", hint);
        if (!double.IsFinite(start) || !double.IsFinite(end) || start <= 0 || end <= start)
            throw new InputException(where, $"band range {start}–{end} nm is empty or not positive", hint);
        if (count < 1 || count > MaxBands)
            throw new InputException(where, $"band count {count} is outside 1–{MaxBands}", hint);
        return new BandGrid(start, end, count);
    }

    /// <summary>
    /// Parses band centres in MATLAB/ISETCam colon notation "start:step:end" (nm), each band <c>step</c> wide:
    /// "400:10:700" is 31 bands centred on 400, 410, …, 700 nm, with edges 395–705 nm. As in MATLAB, the last
    /// centre is the last one not beyond <c>end</c>.
    /// </summary>
    public static BandGrid ParseWave(string text, string where = "--wave")
    {
        var parts = text.Split(':');
        const string hint = "write start:step:end band centres in nm, e.g. 400:10:700 (31 bands of 10 nm centred on 400…700)";
        if (parts.Length != 3)
            throw new InputException(where, $"'{text}' is not a list of band centres", hint);
        if (!double.TryParse(parts[0], NumberStyles.Float, CultureInfo.InvariantCulture, out var first) ||
            !double.TryParse(parts[1], NumberStyles.Float, CultureInfo.InvariantCulture, out var step) ||
            !double.TryParse(parts[2], NumberStyles.Float, CultureInfo.InvariantCulture, out var last))
            throw new InputException(where, $"'{text}' has a non-numeric part", hint);
        if (!double.IsFinite(first) || !double.IsFinite(step) || !double.IsFinite(last) || step <= 0)
            throw new InputException(where, $"'{text}' needs a positive step", hint);
        if (last < first)
            throw new InputException(where, $"'{text}' ends ({last} nm) before it starts ({first} nm)", hint);
        if (first - step / 2 <= 0)
            throw new InputException(where, $"the first band of '{text}' starts at or below 0 nm", hint);
        // The tolerance keeps 400:0.5:700 at 601 centres despite the binary fractions.
        double span = (last - first) / step;
        double steps = Math.Floor(span + 1e-9 * Math.Max(1, span));
        if (steps + 1 > MaxBands)
            throw new InputException(where, $"'{text}' gives {steps + 1} bands, more than {MaxBands}", hint);
        int count = (int)steps + 1;
        return new BandGrid(first - step / 2, first + (count - 1) * step + step / 2, count);
    }

    public override string ToString() =>
        string.Create(CultureInfo.InvariantCulture, $"{Start:0.###}:{End:0.###}:{Count}");

    public bool Equals(BandGrid? other) =>
        other is not null && other.Start == Start && other.End == End && other.Count == Count;
    public override bool Equals(object? obj) => Equals(obj as BandGrid);
    public override int GetHashCode() => HashCode.Combine(Start, End, Count);
}
