using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// Reflectances a recovery learns from (its prior), as band means on the render's grid: the named sets in data/
/// (data/README.md gives their sources) or every column of a CSV file (first column wavelength_nm). The spectra as
/// tabulated stay too, for the exact route's forward model at full resolution (<see cref="ForwardModel"/>).
/// </summary>
public sealed class TrainingSet
{
    public static readonly (string Name, string File, string What)[] Named =
    [
        ("rawtoaces-190", "reflectances-rawtoaces-190.csv", "the 190 training patches of the ACES rawtoaces project"),
        ("cie224-ces99", "reflectances-cie224-ces99.csv", "the 99 colour evaluation samples of CIE 224:2017"),
        ("colorchecker", ColorChecker.File, "the 24 ColorChecker patches (Ohta): the test chart itself, an optimistic prior"),
    ];

    TrainingSet(string name, double[][] samples, TabulatedSpectrum[] spectra) { Name = name; Samples = samples; Spectra = spectra; }

    public string Name { get; }
    /// <summary>T samples × N band means (or, from <see cref="WithSamples"/>, a forward model's coordinates).</summary>
    public double[][] Samples { get; }
    /// <summary>The T reflectances as tabulated (piecewise linear between the file's wavelengths).</summary>
    public TabulatedSpectrum[] Spectra { get; }
    public int Count => Samples.Length;

    public static TrainingSet Load(string nameOrCsv, BandGrid grid)
    {
        var named = Named.FirstOrDefault(n => string.Equals(n.Name, nameOrCsv, StringComparison.OrdinalIgnoreCase));
        string path;
        if (named.Name is not null) path = DataDirectory.File_(named.File);
        else if (nameOrCsv.EndsWith(".csv", StringComparison.OrdinalIgnoreCase)) path = nameOrCsv;
        else throw new InputException("--training", $"unknown training set '{nameOrCsv}'",
            InputException.DidYouMean(nameOrCsv, Named.Select(n => n.Name))
                ?? $"one of {string.Join(", ", Named.Select(n => n.Name))}, or a CSV file");
        var table = SpectrumLibrary.Table(path);
        var samples = new List<double[]>();
        var spectra = new List<TabulatedSpectrum>();
        for (int c = 0; c < table.Columns.Count; c++)
        {
            var s = table[table.Columns[c]];
            s.RequireCoverage(grid.Start, grid.End, $"{path}:1:{c + 2} (column {table.Columns[c]})");
            // Tiny negatives left by the source's processing (|v| ≤ 3e-16 in rawtoaces) count as 0.
            samples.Add(BandProjection.Means(s, grid).Select(v => Math.Max(0, v)).ToArray());
            spectra.Add(s);
        }
        if (samples.Count < 2)
            throw new InputException(path, "a training set needs at least two reflectances", "list two or more reflectance spectra");
        return new TrainingSet(named.Name ?? Path.GetFileNameWithoutExtension(path), samples.ToArray(), spectra.ToArray());
    }

    /// <summary>
    /// The same reflectances given by other coordinates (T × M), e.g. their values at knots: Mean and Covariance are then in those.
    /// </summary>
    public TrainingSet WithSamples(double[][] samples) => new(Name, samples, Spectra);

    public double[] Mean()
    {
        int n = Samples[0].Length;
        var m = new double[n];
        foreach (var s in Samples) for (int b = 0; b < n; b++) m[b] += s[b];
        for (int b = 0; b < n; b++) m[b] /= Count;
        return m;
    }

    /// <summary>The sample covariance (1/(T − 1)).</summary>
    public double[,] Covariance()
    {
        var m = Mean();
        int n = m.Length;
        var c = new double[n, n];
        foreach (var s in Samples)
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) c[i, j] += (s[i] - m[i]) * (s[j] - m[j]);
        for (int i = 0; i < n; i++) for (int j = 0; j < n; j++) c[i, j] /= Count - 1;
        return c;
    }
}
