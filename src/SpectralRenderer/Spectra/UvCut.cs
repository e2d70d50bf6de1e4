namespace SpectralRenderer.Spectra;

/// <summary>
/// The UV-cut filter of ISO 13655:2017 measurement condition M2 ("UV excluded": the illuminant has no substantial
/// radiation below 400 nm), as opposed to M1 (D50 including its UV part). Modelled as a long-pass edge whose transmittance
/// rises linearly from 0 at 395 nm to 1 at 405 nm (half at 400 nm), the shape of a real UV-cut filter's edge.
/// </summary>
public static class UvCut
{
    public const string Name = "uv-cut";
    public const double EdgeStart = 395, EdgeEnd = 405;

    /// <summary>The filter's transmittance at λ.</summary>
    public static double Transmittance(double wavelength) =>
        wavelength <= EdgeStart ? 0 : wavelength >= EdgeEnd ? 1 : (wavelength - EdgeStart) / (EdgeEnd - EdgeStart);

    /// <summary>The spectrum times the filter: the product at the spectrum's knots and the edge's (inside its table).</summary>
    public static TabulatedSpectrum Apply(TabulatedSpectrum s)
    {
        var knots = new SortedSet<double>(s.Wavelengths.ToArray());
        foreach (var k in new[] { EdgeStart, EdgeEnd })
            if (k > s.First && k < s.Last) knots.Add(k);
        var l = knots.ToArray();
        var v = new double[l.Length];
        for (int i = 0; i < l.Length; i++) v[i] = s.Evaluate(l[i]) * Transmittance(l[i]);
        return new TabulatedSpectrum($"{s.Name} ({Name})", l, v, s.Extrapolation);
    }
}
