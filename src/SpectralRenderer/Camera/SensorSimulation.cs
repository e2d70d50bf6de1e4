using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Camera;

/// <summary>
/// What reaches the camera: an H × W × N cube of band radiance (pixel-interleaved, row 0 at the top), its band grid,
/// and the radiance scale s that makes a band value spectral radiance: L = s · value, in W·m⁻²·sr⁻¹·nm⁻¹. A render
/// in the paper's relative radiometry has no unit, so the scale is the user's statement of one.
/// </summary>
public sealed record RadianceCube(int Width, int Height, BandGrid Grid, float[] Data, double RadianceScale)
{
    public int Bands => Grid.Count;
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
}

/// <summary>The sensor's output: digital numbers per pixel and plane (H × W × planes), and how it was exposed.</summary>
public sealed record RawFrame(int Width, int Height, int Planes, float[] Dn, double[] ExposureSeconds, double[] PeakElectrons,
    ChannelWeights Weights, SensorModel Sensor, SimulationOptions Options)
{
    public float this[int x, int y, int plane] => Dn[(y * Width + x) * Planes + plane];
    /// <summary>The exposure time of channel c's signal.</summary>
    public double ExposureOf(int channel) => ExposureSeconds[Sensor.Arrangement == Arrangement.Wheel ? channel : 0];
}

/// <summary>
/// The sensor model of <see cref="SensorModel"/> applied to a radiance cube: photo-electron rate from the channel
/// weights, exposure (given, or auto), then per photosite, from its own counter-based random stream:
/// e = Poisson(ė·t·(1 + PRNU) + dark·t) (photo and dark electrons, both Poisson), clipped at the full well; V = e·g + DSNU + N(0, σ_read);
/// DN = round(black + V·G/V_swing·(white − black)), clipped to [0, white].
/// </summary>
public static class SensorSimulation
{
    const ulong KindPrnu = 1, KindDsnu = 2, KindTemporal = 3;

    public static RawFrame Run(SensorModel sensor, RadianceCube cube, TabulatedSpectrum light, SimulationOptions? options = null)
    {
        options ??= new SimulationOptions();
        var weights = ChannelWeights.Compute(sensor, cube.Grid, light, cube.RadianceScale);
        int w = cube.Width, h = cube.Height, planes = sensor.Planes;
        var rates = new float[w * h * planes];
        var parallel = new ParallelOptions { MaxDegreeOfParallelism = options.Threads };
        var padded = PaddedWeights(weights);
        Parallel.For(0, h, parallel, y => Rates(sensor, cube, padded, rates, y));

        // Exposure: given, or auto so that the brightest expected pixel of each exposure reaches a fraction of the full well.
        int exposures = sensor.Exposures;
        var peakRate = new double[exposures];
        for (int i = 0; i < rates.Length; i++)
        {
            int e = exposures == 1 ? 0 : i % planes;
            if (rates[i] > peakRate[e]) peakRate[e] = rates[i];
        }
        var t = new double[exposures];
        var peakElectrons = new double[exposures];
        for (int e = 0; e < exposures; e++)
        {
            t[e] = sensor.ExposureSeconds ?? (peakRate[e] > 0 ? sensor.AutoExposureFraction * sensor.FullWellElectrons / peakRate[e] : 1);
            peakElectrons[e] = peakRate[e] * t[e];
        }

        var dn = new float[rates.Length];
        Parallel.For(0, h, parallel, y => Expose(sensor, options, w, y, planes, rates, t, dn));
        return new RawFrame(w, h, planes, dn, t, peakElectrons, weights, sensor, options);
    }

    /// <summary>Each channel's weights as float, padded with zeros to whole <see cref="Vector{T}"/>s.</summary>
    static float[] PaddedWeights(ChannelWeights w)
    {
        int vc = Vector<float>.Count, stride = (w.Bands + vc - 1) / vc * vc;
        var p = new float[w.Channels * stride];
        for (int c = 0; c < w.Channels; c++) for (int b = 0; b < w.Bands; b++) p[c * stride + b] = (float)w[c, b];
        return p;
    }

    /// <summary>
    /// ė = Σ_b w_c,b·L_b per photosite, in SIMD over the bands: whole vectors of the pixel's spectrum times the padded
    /// weights (the lanes past the last band read the next pixel's values and multiply zeros). A pixel too close to the
    /// end of the cube for that takes the scalar sum; which path a pixel takes depends only on its position.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Rates(SensorModel sensor, RadianceCube cube, float[] padded, float[] rates, int y)
    {
        int n = cube.Bands, planes = sensor.Planes, w = cube.Width, vc = Vector<float>.Count, nv = (n + vc - 1) / vc, stride = nv * vc;
        bool mosaic = sensor.Arrangement == Arrangement.Mosaic;
        var data = cube.Data;
        for (int x = 0; x < w; x++)
        {
            int p = y * w + x, off = p * n;
            bool vector = off + stride <= data.Length;
            for (int k = 0; k < planes; k++)
            {
                int c = mosaic ? sensor.ChannelAt(x, y) : k;
                float s;
                if (vector)
                {
                    var acc = Vector<float>.Zero;
                    for (int j = 0; j < nv; j++) acc += new Vector<float>(data, off + j * vc) * new Vector<float>(padded, c * stride + j * vc);
                    s = Vector.Sum(acc);
                }
                else
                {
                    s = 0;
                    for (int b = 0; b < n; b++) s += padded[c * stride + b] * data[off + b];
                }
                rates[p * planes + k] = Math.Max(0, s);
            }
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Expose(SensorModel sensor, SimulationOptions o, int w, int y, int planes, float[] rates, double[] t, float[] dn)
    {
        double fullWell = sensor.FullWellElectrons, k = sensor.SystemGain, black = sensor.BlackLevel, white = sensor.WhiteLevel;
        double voltToDn = sensor.AnalogGain / sensor.VoltageSwing * (white - black);
        double dark = sensor.DarkCurrentElectronsPerSecond, prnu = sensor.PrnuPercent / 100, dsnu = sensor.DsnuVolts, read = sensor.ReadNoiseVolts;
        bool mosaic = sensor.Arrangement == Arrangement.Mosaic;
        for (int x = 0; x < w; x++)
        {
            long p = (long)y * w + x;
            for (int k2 = 0; k2 < planes; k2++)
            {
                int i = (int)p * planes + k2;
                int c = mosaic ? sensor.ChannelAt(x, y) : k2;
                double te = t[planes == 1 || t.Length == 1 ? 0 : k2];
                double mean = rates[i] * te;
                double v;
                if (!o.Noise)
                {
                    v = Math.Min(mean, fullWell) * k + black;
                    dn[i] = (float)Math.Min(v, white);
                    continue;
                }
                double gain = 1, offset = 0;
                if (prnu > 0) { var f = new NoiseStream(sensor.FixedPatternSeed, KindPrnu, p, c); gain = Math.Max(0, 1 + prnu * f.Normal()); }
                if (dsnu > 0) { var f = new NoiseStream(sensor.FixedPatternSeed, KindDsnu, p, c); offset = dsnu * f.Normal(); }
                var r = new NoiseStream(o.Seed, KindTemporal, p, c);
                // Photo-electrons and dark electrons are independent Poisson counts: their sum is one Poisson count.
                double electrons = r.Poisson(mean * gain + dark * te);
                electrons = Math.Min(electrons, fullWell);
                double volts = electrons * sensor.ConversionGain + offset + read * r.Normal();
                v = Math.Round(black + volts * voltToDn, MidpointRounding.AwayFromZero);
                dn[i] = (float)Math.Clamp(v, 0, white);
            }
        }
    }
}
