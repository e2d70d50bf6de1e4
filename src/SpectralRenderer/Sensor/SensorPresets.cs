using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>
/// The named sensors. Every preset uses ISETCam's default pixel (pixelCreate/sensorCreate: 2.8 µm, fill factor
/// 0.75, conversion gain 1e-4 V/e⁻, voltage swing 1 V so a 10 000 e⁻ full well, read noise 1 mV, dark voltage
/// 1 mV/s) and ISETCam's default f/4 lens of transmittance 1; a 12-bit ADC. Relative sensitivity data are
/// turned into quantum efficiency by one factor per sensor: the highest channel peaks at <see cref="DefaultPeakQe"/>.
/// </summary>
public static class SensorPresets
{
    public const double DefaultPeakQe = 0.5;

    /// <summary>The preset names: the built-in ones in this order, then those registered at run time.</summary>
    public static string[] Names
    {
        get { lock (Presets) return [.. Presets.Select(p => p.Name)]; }
    }

    /// <summary>
    /// Adds a preset (a plug-in, a test): <c>--sensor NAME</c>, a sensor file's <c>"preset"</c> and a scene's
    /// <c>camera.sensor</c> then find it. <paramref name="create"/> makes a new model per use, named <paramref name="name"/>;
    /// its curves are quantum efficiencies (or <c>PerEnergy</c> responses), as a sensor file's.
    /// </summary>
    public static void Register(string name, Func<SensorModel> create)
    {
        ArgumentNullException.ThrowIfNull(create);
        if (string.IsNullOrEmpty(name) || name != name.ToLowerInvariant() || name.EndsWith(".json", StringComparison.Ordinal)
            || !name.All(c => char.IsAsciiLetterOrDigit(c) || c is '-' or '_' or '.'))
            throw new ArgumentException($"a preset name is lower-case letters, digits, '-', '_' or '.', not '{name}'", nameof(name));
        lock (Presets)
        {
            if (Presets.Any(p => p.Name == name)) throw new ArgumentException($"the preset '{name}' is already registered", nameof(name));
            Presets.Add((name, create));
        }
    }

    public static SensorModel Get(string name, string where = "--sensor")
    {
        string key = name.ToLowerInvariant();
        Func<SensorModel>? create;
        lock (Presets) create = Presets.FirstOrDefault(p => p.Name == key).Create;
        if (create is not null) return create();
        var names = Names;
        throw new InputException(where, $"unknown sensor '{name}'",
            InputException.DidYouMean(name, names) is { } s ? s : $"presets: {string.Join(", ", names)}, or a sensor JSON file");
    }

    /// <summary>The built-in presets, then the registered ones; one line each.</summary>
    static readonly List<(string Name, Func<SensorModel> Create)> Presets =
    [
        ("isetcam", () => new SensorModel
        {
            Name = "isetcam",
            Arrangement = Arrangement.Full,
            Source =
                "ISETCam pixelCreate/sensorCreate defaults: monochrome, quantum efficiency 1 at every wavelength (pixel 'spectralQE' ones)",
            Channels = [new SensorChannel("Y", new TabulatedSpectrum("qe 1", [1.0, 1e5], [1.0, 1.0], Extrapolation.Clamp), "QE 1")],
        }),
        ("nikon-d5100", () => Bayer("nikon-d5100", "camera-nikon-5100-npl.csv", ["red", "green", "blue"],
            "Nikon D5100 sensitivities, Darrodi et al., JOSA A 32(3) 381 (2015), NPL; RGGB Bayer layout")),
        ("canon-5d-mark-ii", () => Bayer("canon-5d-mark-ii", "camera-canon-5d-mark-ii.csv", ["R", "G", "B"],
            "Canon EOS 5D Mark II sensitivities, AMPAS rawtoaces (Apache 2.0); RGGB Bayer layout")),
        // The Sigma's sensitivities behind an RGGB Bayer mosaic, as issue 12 specifies the preset: the NPL curves on the
        // same photosite layout as the Nikon and the Canon, so the three RGB cameras differ by their curves only.
        ("sigma-sd-merrill", () => Bayer("sigma-sd-merrill", "camera-sigma-sdmerill-npl.csv", ["red", "green", "blue"],
            "Sigma SD Merrill sensitivities, Darrodi et al., JOSA A 32(3) 381 (2015), NPL; 400–680 nm, zero outside; on an RGGB Bayer "
                + "layout (the camera itself is a Foveon X3: sigma-sd-merrill-x3)")),
        // The camera as built: a Foveon X3 stacks three photodiodes in each pixel, so every channel at every pixel, no mosaic.
        ("sigma-sd-merrill-x3", () => new SensorModel
        {
            Name = "sigma-sd-merrill-x3",
            Arrangement = Arrangement.Full,
            Source = "Sigma SD Merrill (Foveon X3, three stacked layers per pixel) sensitivities, Darrodi et al., JOSA A 32(3) 381 "
                + "(2015), NPL; 400–680 nm, zero outside",
            Channels = FromCsv("camera-sigma-sdmerill-npl.csv", ["red", "green", "blue"], ["R", "G", "B"]),
        }),
        ("wheel-6", () => new SensorModel
        {
            Name = "wheel-6",
            Arrangement = Arrangement.Wheel,
            Source = "a monochrome sensor behind a wheel of 6 Gaussian filters, 420–670 nm every 50 nm, FWHM 40 nm (the 5–7 "
                + "filter practice the paper cites)",
            Channels = Scale(Enumerable.Range(0, 6).Select(i => Gaussian($"F{420 + 50 * i}", 420 + 50 * i, 40)).ToArray(), DefaultPeakQe),
        }),
        ("mosaic-16", () => new SensorModel
        {
            Name = "mosaic-16",
            Arrangement = Arrangement.Mosaic,
            PatternName = "4x4",
            Source = "a 4 × 4 snapshot multispectral mosaic: 16 Gaussian filters 410–690 nm evenly spaced (18.67 "
                + "nm), FWHM 25 nm, in raster order",
            Channels = Scale(Enumerable.Range(0, 16).Select(i => { double c = 410 + 280.0 / 15 * i; return Gaussian($"F{c:0}", c, 25); })
                .ToArray(),
                DefaultPeakQe),
            Pattern = new int[4, 4] { { 0, 1, 2, 3 }, { 4, 5, 6, 7 }, { 8, 9, 10, 11 }, { 12, 13, 14, 15 } },
        }),
        ("cie-xyz", () => new SensorModel
        {
            Name = "cie-xyz",
            Arrangement = Arrangement.Full,
            Source = "an ideal colorimetric sensor: η_c(λ) ∝ CMF_c(λ)·(555 nm / λ) (CIE 1931 2°), so the electron "
                + "count ∝ ∫ L·CMF dλ, i.e. ∝ XYZ",
            Channels = CieXyz(),
        }),
    ];

    static SensorModel Bayer(string name, string file, string[] columns, string source) => new()
    {
        Name = name,
        Arrangement = Arrangement.Mosaic,
        PatternName = "RGGB",
        Source = source,
        Channels = FromCsv(file, columns, ["R", "G", "B"]),
        Pattern = new int[2, 2] { { 0, 1 }, { 1, 2 } },
    };

    static SensorChannel[] FromCsv(string file, string[] columns, string[] names)
    {
        var table = SpectrumLibrary.DataTable(file);
        return Scale(columns.Select((c, i) => new SensorChannel(names[i], table[c].WithExtrapolation(Extrapolation.Zero), $"{file}:{c}"))
            .ToArray(),
            DefaultPeakQe);
    }

    /// <summary>A Gaussian transmittance of centre μ and full width at half maximum w (σ = w / (2√(2 ln 2))), tabulated every 0.5 nm to ±4
    /// w.</summary>
    public static SensorChannel Gaussian(string name, double centre, double fwhm)
    {
        double sigma = fwhm / (2 * Math.Sqrt(2 * Math.Log(2)));
        int n = (int)Math.Ceiling(8 * fwhm / 0.5) + 1;
        var wl = new double[n];
        var v = new double[n];
        for (int i = 0; i < n; i++)
        {
            wl[i] = centre - 4 * fwhm + 0.5 * i;
            double d = (wl[i] - centre) / sigma;
            v[i] = Math.Exp(-0.5 * d * d);
        }
        return new SensorChannel(name, new TabulatedSpectrum(name, wl, v, Extrapolation.Zero),
            $"Gaussian {centre:0.##} nm, FWHM {fwhm:0.##} nm");
    }

    /// <summary>A box transmittance: 1 on [lo, hi], 0 outside.</summary>
    public static SensorChannel Box(string name, double lo, double hi) =>
        new(name, new TabulatedSpectrum(name, [lo, hi], [1.0, 1.0], Extrapolation.Zero), $"box {lo:0.##}–{hi:0.##} nm");

    /// <summary>The CMFs as responses per unit energy: η(λ) = CMF(λ)·555 nm/λ, applied exactly in the weights.</summary>
    public static SensorChannel[] CieXyz(int observerDegrees = 2)
    {
        var obs = observerDegrees == 10 ? Observer.Cie1964 : Observer.Cie1931;
        SensorChannel Of(string n, TabulatedSpectrum cmf) =>
            new(n, cmf.WithExtrapolation(Extrapolation.Zero), $"{obs.Name} {n.ToLowerInvariant()}-bar per unit energy (η = CMF·555/λ)",
                PerEnergy: true);
        return Scale([Of("X", obs.XBar), Of("Y", obs.YBar), Of("Z", obs.ZBar)], DefaultPeakQe);
    }

    /// <summary>All channels multiplied by one factor so the highest peak is <paramref name="peak"/>.</summary>
    public static SensorChannel[] Scale(SensorChannel[] channels, double peak)
    {
        double max = channels.Max(c => c.QuantumEfficiency.Values.ToArray().Max());
        if (!(max > 0)) return channels;
        return channels.Select(c => c with { QuantumEfficiency = c.QuantumEfficiency.Scaled(peak / max) }).ToArray();
    }
}
