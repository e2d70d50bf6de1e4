namespace SpectralRenderer.Spectra;

/// <summary>The columns of one spectral CSV file, each a <see cref="TabulatedSpectrum"/> over the same wavelengths.</summary>
public sealed class SpectralTable
{
    public SpectralTable(string path, IReadOnlyList<string> columns, IReadOnlyDictionary<string, TabulatedSpectrum> spectra)
    {
        Path = path;
        Columns = columns;
        _spectra = spectra;
    }

    readonly IReadOnlyDictionary<string, TabulatedSpectrum> _spectra;

    public string Path { get; }
    /// <summary>Value column names in file order (without the wavelength column).</summary>
    public IReadOnlyList<string> Columns { get; }
    public TabulatedSpectrum this[string column] => _spectra[column];
    public bool TryGet(string column, out TabulatedSpectrum spectrum) => _spectra.TryGetValue(column, out spectrum!);
}
