using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// CIE 224:2017 colour fidelity index R_f of a light source: the 99 colour evaluation samples
/// (data/reflectances-cie224-ces99.csv) under the test source and under the reference illuminant of the
/// same CCT (Planckian up to 4000 K, CIE daylight from 5000 K, between them the mix of both normalised to
/// equal Y with the daylight share (T − 4000)/1000), CIE 1964 10° observer, summation at 5 nm over
/// 380–780 nm (the samples' own table; the source linearly interpolated, zero outside its table as the
/// standard says); CIECAM02 with L_A = 100 cd/m², Y_b = 20, average surround, the illuminant discounted
/// (D = 1); ΔE_i in CAM02-UCS; R_f = 10 ln(exp((100 − 6.73 ΔĒ)/10) + 1). The CCT is from the 2° observer.
/// </summary>
public static class ColorFidelityIndex
{
    public sealed record Result(double Rf, double[] SampleIndices, double Cct, double Duv);

    const int First = 380, Last = 780, Step = 5, N = (Last - First) / Step + 1;

    public static Result Of(TabulatedSpectrum source)
    {
        var (cct, duv) = CorrelatedColorTemperature.Of(source);
        var test = Sampled(source.WithExtrapolation(Extrapolation.Zero));
        var refr = Reference(cct);
        var samples = SpectrumLibrary.DataTable("reflectances-cie224-ces99.csv");
        var o = Observer.Cie1964;
        var xbar = Sampled(o.XBar); var ybar = Sampled(o.YBar); var zbar = Sampled(o.ZBar);

        var camTest = new Ciecam02(Tristimulus(test, null, xbar, ybar, zbar), 100, 20, degreeOfAdaptation: 1);
        var camRef = new Ciecam02(Tristimulus(refr, null, xbar, ybar, zbar), 100, 20, degreeOfAdaptation: 1);
        int count = samples.Columns.Count;
        var de = new double[count];
        for (int i = 0; i < count; i++)
        {
            var rho = Sampled(samples[samples.Columns[i]]);
            var t = camTest.Ucs(Tristimulus(test, rho, xbar, ybar, zbar));
            var r = camRef.Ucs(Tristimulus(refr, rho, xbar, ybar, zbar));
            de[i] = Math.Sqrt((t.J - r.J) * (t.J - r.J) + (t.A - r.A) * (t.A - r.A) + (t.B - r.B) * (t.B - r.B));
        }
        return new Result(FromDeltaE(de.Average()), de.Select(FromDeltaE).ToArray(), cct, duv);
    }

    static double FromDeltaE(double de) => 10 * Math.Log(Math.Exp((100 - 6.73 * de) / 10) + 1);

    /// <summary>The CIE 224 reference illuminant at the 5 nm samples.</summary>
    static double[] Reference(double cct)
    {
        double[]? planck = cct <= 5000 ? Sampled(Planck.Spectrum(cct)) : null;
        double[]? day = null;
        if (cct >= 4000)
        {
            var (x, y) = CieDaylight.Chromaticity(Math.Min(cct, CieDaylight.MaxKelvin));
            day = Sampled(CieDaylight.FromChromaticity(x, y, "D"));
        }
        if (cct < 4000) return planck!;
        if (cct > 5000) return day!;
        // 4000–5000 K: both normalised to Y = 1 (2° observer), mixed linearly in CCT.
        Normalise(planck!); Normalise(day!);
        double m = (cct - 4000) / 1000;
        var mix = new double[N];
        for (int i = 0; i < N; i++) mix[i] = (1 - m) * planck![i] + m * day![i];
        return mix;
    }

    static void Normalise(double[] s)
    {
        var y = Sampled(Observer.Cie1931.YBar);
        double sum = 0;
        for (int i = 0; i < N; i++) sum += y[i] * s[i];
        for (int i = 0; i < N; i++) s[i] /= sum;
    }

    static double[] Sampled(TabulatedSpectrum s)
    {
        var v = new double[N];
        for (int i = 0; i < N; i++) v[i] = s.Evaluate(First + i * Step);
        return v;
    }

    static Xyz Tristimulus(double[] light, double[]? rho, double[] xbar, double[] ybar, double[] zbar)
    {
        double x = 0, y = 0, z = 0, yw = 0;
        for (int i = 0; i < N; i++)
        {
            double e = light[i], r = rho?[i] ?? 1;
            x += xbar[i] * e * r; y += ybar[i] * e * r; z += zbar[i] * e * r; yw += ybar[i] * e;
        }
        double k = 100 / yw;
        return new Xyz(x * k, y * k, z * k);
    }
}
