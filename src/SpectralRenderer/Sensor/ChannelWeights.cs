using System.Globalization;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>
/// Per channel c and band b, the photo-electron rate per unit of band radiance (e⁻/s per band unit):
/// <code>  w_c,b = s · A·ff·πT/(1 + 4N²) · Δλ · Σ_b η_c(λ) λ E(λ) / (h c ∫_b E(λ) dλ)</code>
/// with s the radiance scale (W·m⁻²·sr⁻¹·nm⁻¹ per band unit) and E the scene light. A band value is the mean
/// radiance over the band, and within the band the radiance is taken to have the light's spectral shape —
/// spectral prefiltering, as the colorimeter's eq. 3 weights do — so a narrow-band light's peak meets the
/// sensitivity at full resolution instead of at the band's mean. The numerator is CIE 015's 1 nm sum, the rule colour uses
/// (<see cref="ExactIntegral"/>, <see cref="CieSummation"/>), the denominator the band integral the band values are means
/// of, so the weights applied to the light's band means give its 1 nm sum. A band where the light is dark falls back to
/// the plain Σ_b η λ.
/// </summary>
public sealed class ChannelWeights
{
    /// <summary>Planck constant (J·s) and speed of light (m/s), CODATA 2018 exact values.</summary>
    public const double H = 6.62607015e-34, C = 299792458;

    ChannelWeights(int channels, int bands, double[] values, double factor)
    {
        Channels = channels;
        Bands = bands;
        Values = values;
        Factor = factor;
    }

    /// <summary>s · A·ff·πT/(1 + 4N²) · 10⁻⁹/(h c): e⁻/s per unit of ∫ L(λ) η(λ) λ dλ (L in band units, λ in nm).</summary>
    public double Factor { get; }

    public int Channels { get; }
    public int Bands { get; }
    /// <summary>Row-major [channel, band], e⁻/s per band unit.</summary>
    public double[] Values { get; }
    public double this[int c, int b] => Values[c * Bands + b];
    public ReadOnlySpan<double> Row(int c) => Values.AsSpan(c * Bands, Bands);

    public static ChannelWeights Compute(SensorModel sensor, BandGrid grid, TabulatedSpectrum light, double radianceScale)
    {
        int n = grid.Count, m = sensor.ChannelCount;
        var values = new double[m * n];
        double factor = FactorOf(sensor, radianceScale);
        var e = new double[n];
        double peak = 0;
        for (int b = 0; b < n; b++) { e[b] = light.Integrate(grid.Lower(b), grid.Upper(b)); peak = Math.Max(peak, e[b]); }
        for (int c = 0; c < m; c++)
        {
            var ch = sensor.Channels[c];
            for (int b = 0; b < n; b++)
            {
                double lo = grid.Lower(b), hi = grid.Upper(b), width = hi - lo;
                double w = e[b] > 1e-12 * peak
                    ? ExactIntegral(ch, light, null, lo, hi) / e[b] * width
                    : ExactIntegral(ch, null, null, lo, hi);
                values[c * n + b] = factor * w;
            }
            // A channel blind to every band would give no signal to expose, calibrate or recover with.
            if (values.AsSpan(c * n, n).IndexOfAnyExcept(0.0) < 0)
                throw new InputException(sensor.Source,
                    string.Create(CultureInfo.InvariantCulture,
                        $"channel '{ch.Name}' ({ch.Source}) has no response within the render's {grid.Start:0.##}–{grid.End:0.##} nm"),
                    "give channels that respond inside the render's bands, or render wider bands (--bands START:END:COUNT)");
        }
        return new ChannelWeights(m, n, values, factor);
    }

    /// <summary>s · A·ff·πT/(1 + 4N²) · 10⁻⁹/(h c) (λ in nm → m): the rate per unit of <see cref="ExactIntegral"/>.</summary>
    public static double FactorOf(SensorModel sensor, double radianceScale) => radianceScale * sensor.Etendue * 1e-9 / (H * C);

    /// <summary>
    /// Σ η_c(λ)·λ·a(λ)·b(λ) over [lo, hi] (nm² × the units of a·b; a or b null = 1), CIE 015's 1 nm sum of the tables'
    /// interpolants (<see cref="CieSummation"/>): the channel's signal from a radiance a·b, by the rule exact colour sums x̄·E·m by
    /// (a per-energy channel: 555 nm·R(λ) in place of η·λ; times the channel's lens transmittance T(λ) when it has one).
    /// The sum runs within a zero-extrapolated table's range (<see cref="CieSummation.Clip"/>); any other table is its end value beyond it.
    /// </summary>
    public static double ExactIntegral(SensorChannel channel, TabulatedSpectrum? a, TabulatedSpectrum? b, double lo, double hi)
    {
        var qe = channel.QuantumEfficiency;
        var lens = channel.Lens;
        CieSummation.Clip(qe, ref lo, ref hi); CieSummation.Clip(a, ref lo, ref hi);
        CieSummation.Clip(b, ref lo, ref hi); CieSummation.Clip(lens, ref lo, ref hi);
        return CieSummation.Of(x => (channel.PerEnergy ? SensorChannel.EnergyReferenceNm * At(qe, x) : At(qe, x) * x)
            * (a is null ? 1 : At(a, x)) * (b is null ? 1 : At(b, x)) * (lens is null ? 1 : At(lens, x)), lo, hi);
    }

    static double At(TabulatedSpectrum s, double x) => Outside(s, x) ? 0 : Value(s, x);

    /// <summary>
    /// ∫_lo^hi η_c(λ)·λ dλ (× T(λ) with a lens; 555 nm·R(λ) for a per-energy channel), exactly: the channel's weight for a
    /// radiance constant over [lo, hi] — the path film's sub-band means, a fluorescent term's emission cells — as colour weights
    /// those by ∫ x̄ dλ. Between merged knots the integrand is a polynomial of degree ≤ 3, which 3-point Gauss–Legendre
    /// integrates without error.
    /// </summary>
    public static double BoxIntegral(SensorChannel channel, double lo, double hi)
    {
        var qe = channel.QuantumEfficiency;
        var lens = channel.Lens;
        var knots = new List<double> { lo, hi };
        foreach (var s in (ReadOnlySpan<TabulatedSpectrum?>)[qe, lens])
            if (s is not null) foreach (var x in s.Wavelengths) if (x > lo && x < hi) knots.Add(x);
        knots.Sort();
        const double G = 0.7745966692414834;   // √(3/5)
        double sum = 0;
        for (int i = 0; i + 1 < knots.Count; i++)
        {
            double x0 = knots[i], x1 = knots[i + 1];
            if (x1 <= x0) continue;
            double xm = 0.5 * (x0 + x1), r = 0.5 * (x1 - x0);
            sum += r * (5.0 / 9 * F(xm - G * r) + 8.0 / 9 * F(xm) + 5.0 / 9 * F(xm + G * r));
        }
        return sum;

        double F(double x) => (channel.PerEnergy ? SensorChannel.EnergyReferenceNm * At(qe, x) : At(qe, x) * x)
            * (lens is null ? 1 : At(lens, x));
    }

    /// <summary>Outside a zero-extrapolated table the factor is 0.</summary>
    static bool Outside(TabulatedSpectrum s, double x) => s.Extrapolation == Extrapolation.Zero && (x < s.First || x > s.Last);

    /// <summary>The interpolant at λ, its end values beyond the table.</summary>
    static double Value(TabulatedSpectrum s, double x) => x <= s.First ? s.Values[0] : x >= s.Last ? s.Values[^1] : s.Evaluate(x);
}
