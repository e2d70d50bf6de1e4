using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// The 24 patches of the Macbeth ColorChecker (Ohta / Munsell Color Science Laboratory reflectances,
/// 380–780 nm at 5 nm — the data the paper's §3 uses), by number 1–24 or by name.
/// </summary>
public static class ColorChecker
{
    public const string File = "colorchecker-ohta.csv";
    public const int PatchCount = 24;

    /// <summary>The column header of patch n (1-based), e.g. "14 green".</summary>
    public static string Column(int number) => DataTable.Columns[number - 1];

    /// <summary>The patch's short name, e.g. "green" or "white 9.5 (.05 D)".</summary>
    public static string Name(int number) => Column(number)[3..];

    /// <summary>The keys accepted after "colorchecker:": numbers and short names (first word of the neutrals too).</summary>
    public static IEnumerable<string> PatchKeys =>
        Enumerable.Range(1, PatchCount).Select(i => i.ToString()).Concat(Enumerable.Range(1, PatchCount).Select(Key));

    /// <summary>A name usable after "colorchecker:": "green", "dark-skin", "white", "neutral-8", "black".</summary>
    public static string Key(int number)
    {
        var name = Name(number);
        int paren = name.IndexOf('(');
        if (paren > 0) name = name[..paren].Trim();
        var words = name.Split(' ');
        if (words.Length == 2
            && double.TryParse(words[1], System.Globalization.NumberStyles.Float, System.Globalization.CultureInfo.InvariantCulture, out _))
            return words[0] == "neutral" ? $"neutral-{words[1]}" : words[0]; // "white 9.5" → white, "neutral 8" → neutral-8
        return string.Join('-', words);
    }

    static SpectralTable DataTable => SpectrumLibrary.DataTable(File);

    public static TabulatedSpectrum Patch(int number) =>
        number is >= 1 and <= PatchCount
            ? Rename(DataTable[Column(number)], number)
            : throw new ArgumentOutOfRangeException(nameof(number));

    /// <summary>Resolves "14", "green", "dark skin", "dark-skin", "neutral-8" (case-insensitive).</summary>
    public static TabulatedSpectrum Patch(string key, string where = "spectrum")
    {
        key = key.Trim();
        if (int.TryParse(key, out int n))
        {
            if (n is >= 1 and <= PatchCount) return Patch(n);
            throw new InputException(where, $"ColorChecker patch {n} does not exist", "patches are numbered 1 to 24");
        }
        var normal = key.Replace(' ', '-').ToLowerInvariant();
        for (int i = 1; i <= PatchCount; i++)
            if (Key(i) == normal || Name(i).Replace(' ', '-').ToLowerInvariant() == normal)
                return Patch(i);
        throw new InputException(where, $"unknown ColorChecker patch '{key}'",
            InputException.DidYouMean(key, Enumerable.Range(1, PatchCount).Select(Key))
                ?? "use 1–24 or a name such as green, dark-skin, neutral-8");
    }

    static TabulatedSpectrum Rename(TabulatedSpectrum s, int number) =>
        new($"colorchecker:{number}", s.Wavelengths.ToArray(), s.Values.ToArray(), s.Extrapolation);
}
