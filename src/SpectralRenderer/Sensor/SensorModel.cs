using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>How the channels are laid out on the sensor.</summary>
public enum Arrangement
{
    /// <summary>Every channel at every pixel (an ideal or a three-layer sensor), one exposure.</summary>
    Full,
    /// <summary>A colour-filter array: one channel per pixel, repeating <see cref="SensorModel.Pattern"/> (Bayer RGGB, a 4 × 4 snapshot
    /// mosaic …).</summary>
    Mosaic,
    /// <summary>A monochrome sensor behind a filter wheel: one exposure per filter, every pixel each time.</summary>
    Wheel,
}

/// <summary>
/// One channel: its quantum efficiency η(λ) (electrons per photon reaching the pixel) and where it comes from.
/// With <paramref name="PerEnergy"/> the table is instead a response per unit energy R(λ), in the units of
/// a quantum efficiency at 555 nm: η(λ) = R(λ)·555 nm/λ exactly (an ideal colorimetric sensor's CMFs).
/// </summary>
public sealed record SensorChannel(string Name, TabulatedSpectrum QuantumEfficiency, string Source, bool PerEnergy = false)
{
    public const double EnergyReferenceNm = 555;

    /// <summary>
    /// The lens transmittance T(λ) in front of the channel (a sensor's <c>"transmittance"</c> given as a spectrum), which
    /// multiplies η(λ) wherever the channel is integrated; null: the sensor's constant <see cref="SensorModel.OpticsTransmittance"/> only.
    /// </summary>
    public TabulatedSpectrum? Lens { get; init; }
}

/// <summary>
/// A camera: optics, pixel, channels and read-out, in the units of ISETCam's sensor model (Farrell, Catrysse &amp;
/// Wandell 2012). The photo-electron rate of channel c at a pixel seeing spectral radiance L(λ) is
/// <code>  ė_c = A·ff · π·T / (1 + 4N²) · ∫ L(λ) η_c(λ) λ / (h c) dλ        (thin lens, object at infinity)</code>
/// with A the pixel area, ff the fill factor, T the optics' transmittance, N the f-number. A pixel collects
/// e = ė·t (plus the dark current), saturates at the full well V_swing / g (g the conversion gain, V per e⁻),
/// is read as V = e·g + DSNU + read noise, amplified by the analog gain and digitised:
/// <code>  DN = black + V·G / V_swing · (white − black),   white = 2^bits − 1.</code>
/// The system gain is K = g·G·(white − black)/V_swing DN per electron.
/// </summary>
public sealed record SensorModel
{
    public required string Name { get; init; }
    /// <summary>Where the values come from (paper, data file, ISETCam default).</summary>
    public required string Source { get; init; }
    public required SensorChannel[] Channels { get; init; }
    public Arrangement Arrangement { get; init; } = Arrangement.Full;
    /// <summary>For <see cref="Arrangement.Mosaic"/>: channel index at [row, column] of the repeating tile (row 0 at the image
    /// top).</summary>
    public int[,]? Pattern { get; init; }
    /// <summary>The pattern's name as written (e.g. "RGGB"), for the manifest and the DNG.</summary>
    public string? PatternName { get; init; }

    public double FNumber { get; init; } = 4;
    /// <summary>The lens's constant transmittance T (a spectrum T(λ), when given, is each channel's <see cref="SensorChannel.Lens"/>, and
    /// this is 1).</summary>
    public double OpticsTransmittance { get; init; } = 1;
    /// <summary>Where T(λ) came from (a spectrum name or CSV column), null for a constant.</summary>
    public string? TransmittanceSource { get; init; }
    /// <summary>The off-axis fall-off (<see cref="Optics"/>): cos⁴ of the field angle by default, as ISETCam's default optics.</summary>
    public OffAxisModel OffAxis { get; init; } = OffAxisModel.Cos4th;
    /// <summary>The point spread (<see cref="Optics"/>): the diffraction-limited Airy pattern at the f-number by default.</summary>
    public PsfModel Psf { get; init; } = PsfModel.Diffraction;
    /// <summary>Pixel pitch (µm), square pixels.</summary>
    public double PixelSizeMicrons { get; init; } = 2.8;
    public double FillFactor { get; init; } = 0.75;
    /// <summary>g: volts per electron at the sense node.</summary>
    public double ConversionGain { get; init; } = 1e-4;
    /// <summary>Voltage swing (V): the full well is V_swing / g electrons.</summary>
    public double VoltageSwing { get; init; } = 1;
    /// <summary>Read noise, standard deviation in volts (temporal, per read).</summary>
    public double ReadNoiseVolts { get; init; } = 1e-3;
    /// <summary>Dark voltage (V/s): dark current = dark voltage / g electrons per second.</summary>
    public double DarkVoltage { get; init; } = 1e-3;
    /// <summary>Photo-response non-uniformity: standard deviation of the per-pixel gain, in percent.</summary>
    public double PrnuPercent { get; init; }
    /// <summary>Dark-signal non-uniformity: standard deviation of the per-pixel offset, in volts.</summary>
    public double DsnuVolts { get; init; }
    public double AnalogGain { get; init; } = 1;
    public int AdcBits { get; init; } = 12;
    /// <summary>Digital number of zero signal.</summary>
    public double BlackLevel { get; init; }
    /// <summary>Exposure time (s); null for auto: the brightest expected pixel at <see cref="AutoExposureFraction"/> of the full
    /// well.</summary>
    public double? ExposureSeconds { get; init; }
    public double AutoExposureFraction { get; init; } = 0.8;
    /// <summary>Seed of the fixed-pattern noise (PRNU, DSNU): one sensor, the same pattern in every frame.</summary>
    public ulong FixedPatternSeed { get; init; } = 1;

    public int ChannelCount => Channels.Length;
    public double FullWellElectrons => VoltageSwing / ConversionGain;
    public double WhiteLevel => (1 << AdcBits) - 1;
    /// <summary>K, digital numbers per electron.</summary>
    public double SystemGain => ConversionGain * AnalogGain / VoltageSwing * (WhiteLevel - BlackLevel);
    public double DarkCurrentElectronsPerSecond => DarkVoltage / ConversionGain;
    public double ReadNoiseElectrons => ReadNoiseVolts / ConversionGain;
    /// <summary>Pixel area × fill factor × π·T / (1 + 4N²): m²·sr turning radiance into the power on the photosensitive area.</summary>
    public double Etendue =>
        PixelSizeMicrons * 1e-6 * PixelSizeMicrons * 1e-6 * FillFactor * Math.PI * OpticsTransmittance / (1 + 4 * FNumber * FNumber);

    /// <summary>Independent exposures: one per filter for a wheel, else one.</summary>
    public int Exposures => Arrangement == Arrangement.Wheel ? ChannelCount : 1;
    /// <summary>Values per pixel in the raw frame: 1 for a mosaic, else one per channel.</summary>
    public int Planes => Arrangement == Arrangement.Mosaic ? 1 : ChannelCount;

    /// <summary>The channel measured at pixel (x, y) of a mosaic.</summary>
    public int ChannelAt(int x, int y) => Pattern![y % Pattern.GetLength(0), x % Pattern.GetLength(1)];

    public bool IsBayer =>
        Arrangement == Arrangement.Mosaic && ChannelCount == 3 && Pattern is { } p && p.GetLength(0) == 2 && p.GetLength(1) == 2;
}
