using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>
/// What reaches the camera: an H × W × N cube of band radiance (pixel-interleaved, row 0 at the top), its band grid,
/// and the radiance scale s that makes a band value spectral radiance: L = s · value, in W·m⁻²·sr⁻¹·nm⁻¹. A render
/// in the paper's relative radiometry has no unit, so the scale is the user's statement of one.
/// </summary>
public sealed record RadianceCube(int Width, int Height, BandGrid Grid, float[] Data, double RadianceScale)
{
    public int Bands => Grid.Count;

    /// <summary>
    /// The exact route: per pixel and channel (H × W × C, the sensor's channel order), ∫ L(λ)·η_c(λ)·λ dλ over the
    /// grid (band units × nm², <see cref="ChannelWeights.ExactIntegral"/>), integrated at the spectra's full resolution
    /// from the render's eq. 2 terms, so the signals do not depend on the band count. Null: the band route (the
    /// channel weights on the band values), for cubes that are not renders.
    /// </summary>
    public float[]? ChannelIntegrals { get; init; }

    /// <summary>What made the channel signals, in words (camera.json's "signal_route").</summary>
    public string Route { get; init; } = BandRoute;

    /// <summary>The render camera's vertical field of view (degrees), which sets the field angle of each pixel (cos⁴); null when
    /// unknown.</summary>
    public double? FovDegrees { get; init; }

    /// <summary>
    /// Whether the sensor's optics (<see cref="Optics"/>: cos⁴, the Airy blur per band) are already in the data — the exact
    /// route applies them to its per-band integrals before summing the bands. Else <see cref="SensorSimulation.Run"/> applies them to the
    /// band cube.
    /// </summary>
    public bool OpticsApplied { get; init; }

    public const string BandRoute = "band cube: rate_c = sum_b w_c,b * L_b (channel weights prefiltered by the scene light per band)";
}

/// <summary>How to run the sensor: temporal-noise seed, noise on or off, threads (the result does not depend on them).</summary>
public sealed record SimulationOptions
{
    public ulong Seed { get; init; } = 1;
    /// <summary>
    /// Off: the expected signal only — no shot, dark, read, PRNU or DSNU noise, no dark current and no quantisation
    /// (raw values are real numbers); clipping at the full well and the white level stays.
    /// </summary>
    public bool Noise { get; init; } = true;
    public int Threads { get; init; } = -1;
    /// <summary>Photosite by photosite only, without the 8-lane path (which gives the same bits): for the tests that compare
    /// them.</summary>
    internal bool ScalarOnly { get; init; }
}

/// <summary>The sensor's output: digital numbers per pixel and plane (H × W × planes), and how it was exposed.</summary>
public sealed record RawFrame(int Width, int Height, int Planes, float[] Dn, double[] ExposureSeconds, double[] PeakElectrons,
    ChannelWeights Weights, SensorModel Sensor, SimulationOptions Options)
{
    /// <summary>The optics the capture went through (null when read back from raw.npy).</summary>
    public Optics.Plan? Optics { get; init; }
    public float this[int x, int y, int plane] => Dn[(y * Width + x) * Planes + plane];
    /// <summary>Per photosite: did its expected charge reach the full well (null when read back from raw.npy)?</summary>
    public bool[]? Saturated { get; init; }

    /// <summary>Is photosite i clipped: at the full well, at the white level, or (noise on) cut off at 0 DN?</summary>
    public bool Clipped(int i) => Saturated?[i] == true || Dn[i] >= Sensor.WhiteLevel || (Options.Noise && Dn[i] <= 0);
    /// <summary>The exposure time of channel c's signal.</summary>
    public double ExposureOf(int channel) => ExposureSeconds[Sensor.Arrangement == Arrangement.Wheel ? channel : 0];

    /// <summary>
    /// The shares of photosites clipped at the top (the full well or DN ≥ white, the ADC's top) and at the ADC's
    /// floor (DN ≤ 0 with noise on: a dark site's read noise below black, cut off).
    /// </summary>
    public (double AtWhite, double BelowBlack) ClippedFractions()
    {
        long top = 0, bottom = 0;
        double white = Sensor.WhiteLevel;
        for (int i = 0; i < Dn.Length; i++)
        {
            float v = Dn[i];
            if (v >= white || Saturated?[i] == true) top++;
            else if (v <= 0 && Options.Noise) bottom++;
        }
        return Dn.Length == 0 ? (0, 0) : ((double)top / Dn.Length, (double)bottom / Dn.Length);
    }

    /// <summary>The warning line when more than 1 % of the photosites clip at either end, else null.</summary>
    public string? ClippingWarning()
    {
        var (top, bottom) = ClippedFractions();
        if (top <= 0.01 && bottom <= 0.01) return null;
        var inv = System.Globalization.CultureInfo.InvariantCulture;
        var parts = new List<string>();
        if (top > 0.01)
            parts.Add(
                string.Create(inv, $"{top * 100:0.##} % of photosites clipped at the full well or the white level ({WhiteLevelText()})"));
        if (bottom > 0.01) parts.Add(string.Create(inv, $"{bottom * 100:0.##} % cut off below black at 0 DN"));
        string hint =
            top > 0.01 ? "try --exposure auto (or a shorter exposure)" : "a black level above 0 DN keeps the read noise of dark sites";
        return $"warning: {string.Join(", ", parts)}; their SNR is left out and their colour is wrong: {hint}";
    }

    string WhiteLevelText() => string.Create(System.Globalization.CultureInfo.InvariantCulture, $"{Sensor.WhiteLevel:0} DN");
}

/// <summary>
/// The sensor model of <see cref="SensorModel"/> applied to a radiance cube: photo-electron rate from the channel
/// weights, exposure (given, or auto), then per photosite, from its own counter-based random stream:
/// e = Poisson(ė·t·(1 + PRNU) + dark·t) (photo and dark electrons, both Poisson), clipped at the full well; V = e·g + DSNU + N(0, σ_read);
/// DN = round(black + V·G/V_swing·(white − black)), clipped to [0, white].
/// </summary>
public static partial class SensorSimulation
{
    const ulong KindPrnu = 1, KindDsnu = 2, KindTemporal = 3;

    public static RawFrame Run(SensorModel sensor, RadianceCube cube, TabulatedSpectrum light, SimulationOptions? options = null)
    {
        options ??= new SimulationOptions();
        var weights = ChannelWeights.Compute(sensor, cube.Grid, light, cube.RadianceScale);
        int w = cube.Width, h = cube.Height, planes = sensor.Planes, exposures = sensor.Exposures;
        // The rates are computed into the output array and exposed in place: one H × W × planes array in all.
        var dn = GC.AllocateUninitializedArray<float>(w * h * planes);
        var rowPeaks = new float[h * planes];
        var parallel = new ParallelOptions { MaxDegreeOfParallelism = options.Threads };
        var layout = new Layout(sensor, weights, w);
        var optics = Optics.For(sensor, w, h, cube.FovDegrees, cube.Grid);
        if (cube.ChannelIntegrals is null && optics.Any)
        {   // The band route: the irradiance (each band of a copy of the cube) through the lens before the pixels sample it.
            var data = cube.Data.AsSpan(0, w * h * cube.Bands).ToArray();
            Optics.Apply(data, w, h, cube.Bands, optics.Illumination, optics.Kernels, options.Threads);
            cube = cube with { Data = data };
        }
        else if (cube.ChannelIntegrals is not null && optics.Any && !cube.OpticsApplied)
            throw new ArgumentException("exact channel integrals without the optics applied: give them per band through the optics "
                + "(Cli/ExactChannelSignals) or a sensor with off_axis and psf none");
        if (cube.ChannelIntegrals is { } exact)
        {
            if (exact.Length != w * h * sensor.ChannelCount)
                throw new ArgumentException($"{exact.Length} channel integrals for {w}×{h} pixels × {sensor.ChannelCount} channels");
            Parallel.For(0, h, parallel, y => ExactRates(layout, exact, weights.Factor, w, dn, rowPeaks, y));
        }
        else Parallel.For(0, h, parallel, y => Rates(layout, cube, dn, rowPeaks, y));

        // Exposure: given, or auto so that the brightest expected pixel of each exposure reaches a fraction of the full well.
        var peakRate = new double[exposures];
        for (int y = 0; y < h; y++)
            for (int k = 0; k < planes; k++)
                peakRate[exposures == 1 ? 0 : k] = Math.Max(peakRate[exposures == 1 ? 0 : k], rowPeaks[y * planes + k]);
        var t = new double[exposures];
        var peakElectrons = new double[exposures];
        for (int e = 0; e < exposures; e++)
        {
            t[e] = sensor.ExposureSeconds ?? (peakRate[e] > 0 ? sensor.AutoExposureFraction * sensor.FullWellElectrons / peakRate[e] : 1);
            peakElectrons[e] = peakRate[e] * t[e];
        }

        var readout = new Readout(sensor, options);
        var exposureOf = Array.ConvertAll(layout.ChannelOf, c => t[exposures == 1 ? 0 : c]);
        // Sites whose expected charge fills the full well (their DN sits at saturation, whatever the read noise does to it).
        var saturated = new bool[dn.Length];
        int rowSites = w * planes;
        Parallel.For(0, h, parallel, y =>
        {
            var te = exposureOf.AsSpan((y % layout.PatternRows) * rowSites, rowSites);
            for (int j = 0; j < rowSites; j++) saturated[y * rowSites + j] = dn[y * rowSites + j] * te[j] >= sensor.FullWellElectrons;
        });
        Parallel.For(0, h, parallel, y => Expose(readout, layout, exposureOf, w, y, dn));
        return new RawFrame(w, h, planes, dn, t, peakElectrons, weights, sensor, options) { Saturated = saturated, Optics = optics };
    }

    /// <summary>The channel weights in the two layouts the rate loops read, and the mosaic's pattern flattened.</summary>
    sealed class Layout
    {
        public readonly int Bands, Channels, Planes, Stride;
        public readonly bool Mosaic;
        /// <summary>Per channel, its weights over the bands padded with zeros to whole <see cref="Vector{T}"/>s (mosaic: one channel per
        /// photosite).</summary>
        public readonly float[] ByChannel;
        /// <summary>Per band, one <see cref="Vector{T}"/> of every channel's weight (full and wheel, up to Vector&lt;float&gt;.Count
        /// channels).</summary>
        public readonly float[] ByBand;
        /// <summary>The mosaic's channel at [row % rows, column % columns], row-major.</summary>
        public readonly int[] Pattern;
        public readonly int PatternRows, PatternColumns;
        /// <summary>For the flat index j of a row's photosites (x·planes + plane): the pixel x.</summary>
        public readonly int[] PixelOf;
        /// <summary>Per pattern row (one for full and wheel sensors), the channel of each flat index of a row.</summary>
        public readonly int[] ChannelOf;

        public Layout(SensorModel sensor, ChannelWeights w, int width)
        {
            int vc = Vector<float>.Count;
            Bands = w.Bands; Channels = w.Channels; Planes = sensor.Planes; Mosaic = sensor.Arrangement == Arrangement.Mosaic;
            Stride = (Bands + vc - 1) / vc * vc;
            ByChannel = new float[Channels * Stride];
            for (int c = 0; c < Channels; c++) for (int b = 0; b < Bands; b++) ByChannel[c * Stride + b] = (float)w[c, b];
            ByBand = new float[Bands * vc];
            if (Channels <= vc) for (int b = 0; b < Bands; b++) for (int c = 0; c < Channels; c++) ByBand[b * vc + c] = (float)w[c, b];
            PatternRows = Mosaic ? sensor.Pattern!.GetLength(0) : 1;
            PatternColumns = Mosaic ? sensor.Pattern!.GetLength(1) : 1;
            Pattern = new int[PatternRows * PatternColumns];
            if (Mosaic)
                for (int r = 0; r < PatternRows; r++)
                    for (int c = 0; c < PatternColumns; c++)
                        Pattern[r * PatternColumns + c] = sensor.Pattern![r, c];
            int n = width * Planes;
            PixelOf = new int[n];
            ChannelOf = new int[PatternRows * n];
            for (int j = 0; j < n; j++) PixelOf[j] = j / Planes;
            for (int r = 0; r < PatternRows; r++)
                for (int j = 0; j < n; j++) ChannelOf[r * n + j] = Mosaic ? Pattern[r * PatternColumns + j % PatternColumns] : j % Planes;
        }
    }

    /// <summary>
    /// ė_c = max(0, Σ_b w_c,b·L_b) for row y, written to <paramref name="rates"/> (H × W × planes) with the row's
    /// highest rate per plane. A mosaic photosite needs one channel: a dot product in SIMD over the bands (whole
    /// vectors of the pixel's spectrum times the padded weights; the lanes past the last band read the next pixel's
    /// values and multiply zeros, and a pixel too close to the cube's end for that takes the scalar sum). Full and
    /// wheel pixels need every channel: SIMD over the channels, each band's radiance times the vector of the channels'
    /// weights for that band. Which path a pixel takes depends only on the sensor and the pixel's position.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Rates(Layout l, RadianceCube cube, float[] rates, float[] rowPeaks, int y)
    {
        int n = l.Bands, planes = l.Planes, w = cube.Width, vc = Vector<float>.Count, nv = l.Stride / vc, stride = l.Stride;
        var data = cube.Data;
        int rowStart = y * w * planes, rowEnd = rowStart + w * planes;
        if (l.Mosaic)
        {
            var pattern = l.Pattern.AsSpan((y % l.PatternRows) * l.PatternColumns, l.PatternColumns);
            float peak = 0;
            for (int x = 0, px = 0; x < w; x++)
            {
                int c = pattern[px];
                if (++px == pattern.Length) px = 0;
                int off = (y * w + x) * n, wo = c * stride;
                float s;
                if (off + stride <= data.Length)
                {
                    var acc = Vector<float>.Zero;
                    for (int j = 0; j < nv; j++) acc += new Vector<float>(data, off + j * vc) * new Vector<float>(l.ByChannel, wo + j * vc);
                    s = Vector.Sum(acc);
                }
                else
                {
                    s = 0;
                    for (int b = 0; b < n; b++) s += l.ByChannel[wo + b] * data[off + b];
                }
                s = Math.Max(0, s);
                rates[rowStart + x] = s;
                peak = Math.Max(peak, s);
            }
            rowPeaks[y] = peak;
            return;
        }
        if (planes <= vc)
        {
            var byBand = l.ByBand;
            var peaks = Vector<float>.Zero;
            for (int x = 0; x < w; x++)
            {
                int off = (y * w + x) * n, o = rowStart + x * planes;
                var acc = Vector<float>.Zero;
                for (int b = 0; b < n; b++) acc += new Vector<float>(data[off + b]) * new Vector<float>(byBand, b * vc);
                acc = Vector.Max(acc, Vector<float>.Zero);
                peaks = Vector.Max(peaks, acc);
                // A whole-vector store spills zeros into the next pixel's slots (rewritten next); not past the row.
                if (o + vc <= rowEnd) acc.CopyTo(rates, o);
                else for (int k = 0; k < planes; k++) rates[o + k] = acc[k];
            }
            for (int k = 0; k < planes; k++) rowPeaks[y * planes + k] = peaks[k];
            return;
        }
        // More channels than lanes: one dot product per channel.
        for (int k = 0; k < planes; k++) rowPeaks[y * planes + k] = 0;
        for (int x = 0; x < w; x++)
        {
            int off = (y * w + x) * n;
            bool vector = off + stride <= data.Length;
            for (int k = 0; k < planes; k++)
            {
                float s;
                if (vector)
                {
                    var acc = Vector<float>.Zero;
                    for (int j = 0; j < nv; j++)
                        acc += new Vector<float>(data, off + j * vc) * new Vector<float>(l.ByChannel, k * stride + j * vc);
                    s = Vector.Sum(acc);
                }
                else
                {
                    s = 0;
                    for (int b = 0; b < n; b++) s += l.ByChannel[k * stride + b] * data[off + b];
                }
                s = Math.Max(0, s);
                rates[rowStart + x * planes + k] = s;
                rowPeaks[y * planes + k] = Math.Max(rowPeaks[y * planes + k], s);
            }
        }
    }

    /// <summary>ė_c = max(0, factor · ∫ L η_c λ dλ) of row y from the exact channel integrals (a mosaic photosite: its
    /// channel's).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ExactRates(Layout l, float[] exact, double factor, int w, float[] rates, float[] rowPeaks, int y)
    {
        int planes = l.Planes, cc = l.Channels, n = w * planes, rowStart = y * w * planes;
        var channels = l.ChannelOf.AsSpan((y % l.PatternRows) * n, n);
        for (int k = 0; k < planes; k++) rowPeaks[y * planes + k] = 0;
        for (int j = 0; j < n; j++)
        {
            int x = l.PixelOf[j], k = l.Mosaic ? 0 : j % planes;
            float s = (float)Math.Max(0, factor * exact[((long)y * w + x) * cc + channels[j]]);
            rates[rowStart + j] = s;
            rowPeaks[y * planes + k] = Math.Max(rowPeaks[y * planes + k], s);
        }
    }

    /// <summary>Row y of the rates (e⁻/s) in <paramref name="dn"/> exposed and read out in place.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Expose(Readout r, Layout l, double[] exposureOf, int w, int y, float[] dn)
    {
        int planes = l.Planes, rowStart = y * w * planes, n = w * planes;
        var channels = l.ChannelOf.AsSpan((y % l.PatternRows) * n, n);
        var te = exposureOf.AsSpan((y % l.PatternRows) * n, n);
        if (!r.Noise)
        {
            for (int j = 0; j < n; j++)
                dn[rowStart + j] = (float)Math.Min(Math.Min(dn[rowStart + j] * te[j], r.FullWell) * r.SystemGain + r.Black, r.White);
            return;
        }
        int done = r.Lanes ? ExposeLanes(r, l.PixelOf, channels, te, w, y, dn) : 0;
        for (int j = done; j < n; j++) dn[rowStart + j] = r.Photosite(dn[rowStart + j], te[j], (long)y * w + l.PixelOf[j], channels[j]);
    }

    /// <summary>Everything the read-out of a photosite needs, from the sensor and the options.</summary>
    sealed class Readout
    {
        public readonly double FullWell, SystemGain, Black, White, VoltToDn, ConversionGain, Dark, Prnu, Dsnu, Read;
        public readonly ulong PrnuFamily, DsnuFamily, Temporal;
        public readonly bool Noise, Lanes;

        public Readout(SensorModel sensor, SimulationOptions o)
        {
            FullWell = sensor.FullWellElectrons; SystemGain = sensor.SystemGain; Black = sensor.BlackLevel; White = sensor.WhiteLevel;
            VoltToDn = sensor.AnalogGain / sensor.VoltageSwing * (White - Black); ConversionGain = sensor.ConversionGain;
            Dark = sensor.DarkCurrentElectronsPerSecond;
            Prnu = sensor.PrnuPercent / 100;
            Dsnu = sensor.DsnuVolts;
            Read = sensor.ReadNoiseVolts;
            PrnuFamily = NoiseStream.Family(sensor.FixedPatternSeed, KindPrnu);
            DsnuFamily = NoiseStream.Family(sensor.FixedPatternSeed, KindDsnu);
            Temporal = NoiseStream.Family(o.Seed, KindTemporal);
            Noise = o.Noise;
            Lanes = !o.ScalarOnly && Vector512.IsHardwareAccelerated;
        }

        /// <summary>
        /// One photosite of channel c at pixel p, from its own streams: e = min(Poisson(ė·t·(1 + PRNU) + dark·t), full
        /// well) — photo and dark electrons are independent Poisson counts, so their sum is one —, V = e·g + DSNU +
        /// N(0, σ_read), DN = round(black + V·G/V_swing·(white − black)) in [0, white] (<see cref="Quantise"/>).
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public float Photosite(double rate, double te, long p, int c)
        {
            double mean = rate * te, gain = 1, offset = 0;
            if (Prnu > 0) { var f = new NoiseStream(PrnuFamily, p, c); gain = Math.Max(0, 1 + Prnu * f.Normal()); }
            if (Dsnu > 0) { var f = new NoiseStream(DsnuFamily, p, c); offset = Dsnu * f.Normal(); }
            var r = new NoiseStream(Temporal, p, c);
            double electrons = Math.Min(r.Poisson(mean * gain + Dark * te), FullWell);
            double volts = electrons * ConversionGain + offset + Read * r.Normal();
            return (float)Quantise(Black + volts * VoltToDn, White);
        }
    }

    /// <summary>Round half away from zero (as <see cref="Math.Round(double, MidpointRounding)"/> does it: truncate x + 0.5⁻) after clipping
    /// at 0, then at the white level.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static double Quantise(double x, double white) => Math.Min(Math.Floor(Math.Max(x, 0) + HalfBelow), white);

    /// <summary>The double just below 0.5.</summary>
    const double HalfBelow = 0.49999999999999994;
}
