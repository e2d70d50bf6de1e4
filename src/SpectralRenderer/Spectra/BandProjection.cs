namespace SpectralRenderer.Spectra;

/// <summary>Turns a tabulated spectrum into band values on a <see cref="BandGrid"/>.</summary>
public static class BandProjection
{
    /// <summary>
    /// The exact band mean: ∫_b S(λ) dλ / Δλ of the piecewise-linear interpolant (guide §2).
    /// </summary>
    public static double[] Means(TabulatedSpectrum s, BandGrid grid)
    {
        var v = new double[grid.Count];
        for (int b = 0; b < grid.Count; b++) v[b] = s.Mean(grid.Lower(b), grid.Upper(b));
        return v;
    }

    /// <summary>
    /// The exact band mean of a product, ∫_b a·b dλ / Δλ: the band value of the radiance of a light a on a
    /// surface b (not the product of their band means, which differs wherever both vary inside a band).
    /// </summary>
    public static double[] MeansOfProduct(TabulatedSpectrum a, TabulatedSpectrum b, BandGrid grid)
    {
        var v = new double[grid.Count];
        for (int i = 0; i < grid.Count; i++) v[i] = TabulatedSpectrum.MeanOfProduct(a, b, grid.Lower(i), grid.Upper(i));
        return v;
    }

    /// <summary>
    /// The paper's band value: the mean of the spectrum's 1 nm samples (of its linear interpolant at
    /// whole nanometres) in [lo, hi), the last band also taking its upper edge — the definition used by
    /// data/reference/colorchecker-ohta-d65-2deg-bands20.csv. A band narrower than 1 nm that holds no
    /// whole nanometre falls back to the exact mean.
    /// </summary>
    public static double[] SampleMeans1nm(TabulatedSpectrum s, BandGrid grid)
    {
        var v = new double[grid.Count];
        for (int b = 0; b < grid.Count; b++)
        {
            double lo = grid.Lower(b), hi = grid.Upper(b);
            int first = (int)Math.Ceiling(lo - 1e-9);
            int last = b == grid.Count - 1 ? (int)Math.Floor(hi + 1e-9) : (int)Math.Ceiling(hi - 1e-9) - 1;
            if (last < first) { v[b] = s.Mean(lo, hi); continue; }
            double sum = 0;
            for (int l = first; l <= last; l++) sum += s.Evaluate(l);
            v[b] = sum / (last - first + 1);
        }
        return v;
    }
}
