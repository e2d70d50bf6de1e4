using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>
/// A sensor as JSON (docs/camera.md): a preset name, or an object whose keys override a preset's (<c>"preset"</c>,
/// default <c>isetcam</c>). Errors name the file and the JSON path.
/// </summary>
public static class SensorFile
{
    static readonly string[] Keys =
    [
        "name", "preset", "source", "channels", "peak_qe", "arrangement", "pattern", "f_number", "transmittance", "pixel_size_um",
        "fill_factor", "conversion_gain_v_per_e", "voltage_swing_v", "read_noise_v", "dark_voltage_v_per_s", "prnu_percent",
        "dsnu_v", "analog_gain", "adc_bits", "black_level_dn", "exposure_s", "auto_exposure_fraction", "fixed_pattern_seed",
        "off_axis", "psf",
    ];

    /// <summary>The name a sensor inline in a scene takes unless it says "name".</summary>
    public const string InlineName = "scene-camera";
    /// <summary>The --sensor value (and camera.json's sensor_argument) that means the sensor of the scene's camera object.</summary>
    public const string SceneArgument = "scene";

    /// <summary>
    /// The sensor of a scene's camera object, <c>"camera": { …, "sensor": NAME | FILE | { … } }</c>, from the resolved
    /// scene render.json keeps: a preset name, a sensor file (relative to the scene's folder) or a sensor object inline
    /// (the keys of a sensor file; errors name <c>scene.json: $.camera.sensor.key</c>). Null when the camera has none.
    /// </summary>
    public static SensorModel? FromScene(JsonObject? resolvedScene, string sceneFile)
    {
        if ((resolvedScene?["camera"] as JsonObject)?["sensor"] is not JsonNode node) return null;
        string? baseDirectory = sceneFile.Length > 0 ? Path.GetDirectoryName(Path.GetFullPath(sceneFile)) : null;
        const string root = "$.camera.sensor";
        return node switch
        {
            JsonObject o => Parse(o, sceneFile, baseDirectory, root),
            JsonValue v when v.TryGetValue(out string? name) && name.Length > 0 =>
                SensorPresets.Names.Contains(name.ToLowerInvariant()) || baseDirectory is null || Path.IsPathRooted(name)
                    ? Resolve(name) : Resolve(Path.Combine(baseDirectory, name)),
            _ => throw new InputException($"{sceneFile}: {root}", "must be a preset name, a sensor file or a sensor object",
                $"e.g. \"mosaic-16\" or {{ \"preset\": \"wheel-6\", \"f_number\": 2.8 }}"),
        };
    }

    /// <summary>A preset name, or a path to a JSON file.</summary>
    public static SensorModel Resolve(string nameOrFile)
    {
        if (!nameOrFile.EndsWith(".json", StringComparison.OrdinalIgnoreCase) && !File.Exists(nameOrFile))
            return SensorPresets.Get(nameOrFile);
        var text = InputFile.ReadAllText(nameOrFile, "sensor file");
        JsonNode? node;
        try
        {
            node = JsonNode.Parse(text,
                documentOptions: new JsonDocumentOptions
                {
                    CommentHandling = JsonCommentHandling.Skip,
                    AllowTrailingCommas = true,
                    AllowDuplicateProperties = false
                });
        }
        catch (JsonException e)
        {
            var reader = new JsonReaderOptions { CommentHandling = JsonCommentHandling.Skip, AllowTrailingCommas = true };
            throw new InputException($"{nameOrFile}:{JsonFields.Place(e, text, reader)}",
                $"broken JSON: {e.Message}",
                    e.LineNumber is null
                        ? "give each key once in its object"
                        : "check for a missing comma, quote or bracket just before this place");
        }
        if (node is not JsonObject obj)
            throw new InputException(nameOrFile, "is not a JSON object", "a sensor file is { \"preset\": …, \"channels\": […], … }");
        return Parse(obj, nameOrFile, Path.GetDirectoryName(Path.GetFullPath(nameOrFile)));
    }

    /// <param name="root">where the sensor object sits in <paramref name="file"/>: "$" for a sensor file, "$.camera.sensor" inline in a
    /// scene.</param>
    public static SensorModel Parse(JsonObject o, string file, string? baseDirectory = null, string root = "$")
    {
        string at = $"{file}: {root}";
        foreach (var (key, _) in o)
            if (!Keys.Contains(key))
                throw new InputException($"{at}.{key}", "unknown key",
                    InputException.DidYouMean(key, Keys) ?? $"keys: {string.Join(", ", Keys)}");
        var s = SensorPresets.Get(Str(o, "preset", at) ?? "isetcam", $"{at}.preset");
        double peak = Num(o, "peak_qe", at, 0, 1) ?? SensorPresets.DefaultPeakQe;
        if (o["channels"] is JsonNode ch)
        {
            if (ch is not JsonArray arr || arr.Count == 0)
                throw new InputException($"{at}.channels", "must be a non-empty array of channels",
                    "e.g. \"channels\": [{\"name\": \"R\", \"gaussian\": {\"centre_nm\": 600, \"fwhm_nm\": 40}}]");
            var channels = arr.Select((c, i) => Channel(c, $"{at}.channels[{i}]", baseDirectory)).ToArray();
            s = s with { Channels = SensorPresets.Scale(channels, peak) };
        }
        else if (o["peak_qe"] is not null) s = s with { Channels = SensorPresets.Scale(s.Channels, peak) };
        if (Str(o, "arrangement", at) is { } a)
            s = s with
            {
                Arrangement = a switch
                {
                    "full" => Arrangement.Full,
                    "mosaic" => Arrangement.Mosaic,
                    "wheel" => Arrangement.Wheel,
                    _ => throw new InputException($"{at}.arrangement", $"'{a}' is not an arrangement", "full, mosaic or wheel"),
                },
            };
        if (o["pattern"] is JsonNode p)
            s = s with { Pattern = Pattern(p, s, $"{at}.pattern"), PatternName = p is JsonValue ? Str(o, "pattern", at) : "custom" };
        if (s.Arrangement == Arrangement.Mosaic)
        {
            if (s.Pattern is null) throw new InputException($"{at}.pattern", "a mosaic needs a pattern", "e.g. \"RGGB\" or [[0,1],[1,2]]");
            foreach (var v in s.Pattern)
                if (v < 0 || v >= s.ChannelCount)
                    throw new InputException($"{at}.pattern", $"channel {v} does not exist", $"channels 0–{s.ChannelCount - 1}");
        }
        double? exposure = null;
        bool auto = false;
        if (o["exposure_s"] is JsonNode e)
        {
            if (e is JsonValue v && v.TryGetValue(out string? t) && t == "auto") auto = true;
            else exposure = Num(o, "exposure_s", at, 1e-9, 1e6);
        }
        // "transmittance": a constant, or a spectrum T(λ) (a name or CSV column) that multiplies every channel's η(λ).
        double? transmittance = null;
        if (o["transmittance"] is JsonValue tv && tv.TryGetValue(out string? tName))
        {
            var t = SpectrumLibrary.Resolve(tName, baseDirectory, $"{at}.transmittance");
            foreach (var v in t.Values)
                if (v < 0 || v > 1)
                    throw new InputException($"{at}.transmittance", $"spectrum '{tName}' has values outside 0–1",
                        "a transmittance is a fraction at each wavelength");
            s = s with { Channels = s.Channels.Select(c => c with { Lens = t }).ToArray(), TransmittanceSource = tName };
            transmittance = 1;
        }
        else transmittance = Num(o, "transmittance", at, 0, 1);
        var model = s with
        {
            OffAxis = Str(o, "off_axis", at) is { } oa ? ParseOffAxis(oa, $"{at}.off_axis") : s.OffAxis,
            Psf = Str(o, "psf", at) is { } ps ? ParsePsf(ps, $"{at}.psf") : s.Psf,
            Name = Str(o, "name", at)
                ?? (root != "$"
                    ? InlineName
                    : file.EndsWith(".json", StringComparison.OrdinalIgnoreCase)
                    ? Path.GetFileNameWithoutExtension(file)
                    : s.Name),
            Source = Str(o, "source", at) ?? $"{(root != "$" ? $"{file} {root}" : file)} (over preset {s.Name})",
            FNumber = Num(o, "f_number", at, 0.1, 1000) ?? s.FNumber,
            OpticsTransmittance = transmittance ?? s.OpticsTransmittance,
            PixelSizeMicrons = Num(o, "pixel_size_um", at, 0.01, 1000) ?? s.PixelSizeMicrons,
            FillFactor = Num(o, "fill_factor", at, 0, 1) ?? s.FillFactor,
            ConversionGain = Num(o, "conversion_gain_v_per_e", at, 1e-12, 1) ?? s.ConversionGain,
            VoltageSwing = Num(o, "voltage_swing_v", at, 1e-6, 1000) ?? s.VoltageSwing,
            ReadNoiseVolts = Num(o, "read_noise_v", at, 0, 10) ?? s.ReadNoiseVolts,
            DarkVoltage = Num(o, "dark_voltage_v_per_s", at, 0, 1000) ?? s.DarkVoltage,
            PrnuPercent = Num(o, "prnu_percent", at, 0, 100) ?? s.PrnuPercent,
            DsnuVolts = Num(o, "dsnu_v", at, 0, 10) ?? s.DsnuVolts,
            AnalogGain = Num(o, "analog_gain", at, 1e-6, 1e6) ?? s.AnalogGain,
            AdcBits = (int?)Num(o, "adc_bits", at, 1, 16, whole: true) ?? s.AdcBits,
            BlackLevel = Num(o, "black_level_dn", at, 0, 65535) ?? s.BlackLevel,
            ExposureSeconds = auto ? null : exposure ?? s.ExposureSeconds,
            AutoExposureFraction = Num(o, "auto_exposure_fraction", at, 1e-6, 1) ?? s.AutoExposureFraction,
            FixedPatternSeed = (ulong?)Num(o, "fixed_pattern_seed", at, 0, 1e15, whole: true) ?? s.FixedPatternSeed,
        };
        // The black level is an offset inside the ADC's range: at or above its white level no signal is left.
        if (model.BlackLevel >= model.WhiteLevel)
            throw new InputException($"{at}.black_level_dn",
                string.Create(CultureInfo.InvariantCulture,
                    $"black level {model.BlackLevel} DN is not below the white level {model.WhiteLevel} DN of {model.AdcBits}-bit samples"),
                $"give a black level below 2^adc_bits − 1 = {model.WhiteLevel}");
        return model;
    }

    /// <summary>"cos4th" or "none" (<see cref="OffAxisModel"/>); <paramref name="where"/> names the key or option in the error.</summary>
    public static OffAxisModel ParseOffAxis(string value, string where) => value switch
    {
        "cos4th" => OffAxisModel.Cos4th,
        "none" => OffAxisModel.None,
        _ => throw new InputException(where, $"'{value}' is not an off-axis model", "cos4th (ISETCam's default fall-off) or none"),
    };

    /// <summary>"diffraction" or "none" (<see cref="PsfModel"/>).</summary>
    public static PsfModel ParsePsf(string value, string where) => value switch
    {
        "diffraction" => PsfModel.Diffraction,
        "none" => PsfModel.None,
        _ => throw new InputException(where, $"'{value}' is not a point spread model",
            "diffraction (the Airy pattern at the f-number) or none"),
    };

    static SensorChannel Channel(JsonNode? node, string where, string? baseDirectory)
    {
        if (node is not JsonObject c)
            throw new InputException(where, "a channel is an object",
                "{ \"name\": \"F1\", \"gaussian\": { \"centre_nm\": 450, \"fwhm_nm\": 40 } }");
        var name = Str(c, "name", where) ?? throw new InputException(where, "a channel needs a \"name\"", "give each channel a \"name\"");
        if (name.Length == 0) throw new InputException($"{where}.name", "is empty", "give each channel a name, e.g. \"R\"");
        if (c["gaussian"] is JsonObject g)
        {
            double centre = Num(g, "centre_nm", where + ".gaussian", 100, 3000)
                ?? throw new InputException(where + ".gaussian", "needs centre_nm",
                    "e.g. \"gaussian\": {\"centre_nm\": 550, \"fwhm_nm\": 40}");
            double fwhm = Num(g, "fwhm_nm", where + ".gaussian", 0.1, 2000)
                ?? throw new InputException(where + ".gaussian", "needs fwhm_nm",
                    "e.g. \"gaussian\": {\"centre_nm\": 550, \"fwhm_nm\": 40}");
            return SensorPresets.Gaussian(name, centre, fwhm);
        }
        if (c["box"] is JsonNode boxNode)
        {
            if (boxNode is not JsonArray { Count: 2 } box)
                throw new InputException(where + ".box", "must be two wavelengths", "[lower_nm, upper_nm], e.g. [400, 500]");
            double lo = Nm(box[0], where + ".box[0]"), hi = Nm(box[1], where + ".box[1]");
            if (!(hi > lo)) throw new InputException(where + ".box", $"[{lo}, {hi}] is empty", "[lower_nm, upper_nm]");
            return SensorPresets.Box(name, lo, hi);
        }
        if (Str(c, "spectrum", where) is { } spec)
        {
            var s = SpectrumLibrary.Resolve(spec, baseDirectory, where + ".spectrum");
            return new SensorChannel(name, s.WithExtrapolation(Extrapolation.Zero), spec);
        }
        throw new InputException(where, "a channel needs one of \"gaussian\", \"box\" or \"spectrum\"",
            "e.g. \"spectrum\": \"my-camera.csv:red\"");
    }

    static int[,] Pattern(JsonNode node, SensorModel s, string where)
    {
        if (node is JsonValue v && v.TryGetValue(out string? text))
        {
            // Letters name channels by their first letter (RGGB, GRBG …), row by row of a square tile.
            int side = (int)Math.Round(Math.Sqrt(text.Length));
            if (side * side != text.Length || side == 0 || side > MaxPatternSide)
                throw new InputException(where, $"'{text}' is not a square pattern", "e.g. RGGB");
            var p = new int[side, side];
            for (int i = 0; i < text.Length; i++)
            {
                int c = Array.FindIndex(s.Channels, ch => char.ToUpperInvariant(ch.Name[0]) == char.ToUpperInvariant(text[i]));
                if (c < 0)
                    throw new InputException(where, $"'{text[i]}' names no channel",
                        $"channels: {string.Join(", ", s.Channels.Select(ch => ch.Name))}");
                p[i / side, i % side] = c;
            }
            return p;
        }
        if (node is JsonArray rows && rows.Count is > 0 and <= MaxPatternSide
            && rows[0] is JsonArray { Count: > 0 and <= MaxPatternSide } first
            && rows.All(r => r is JsonArray ra && ra.Count == first.Count))
        {
            var p = new int[rows.Count, first.Count];
            for (int y = 0; y < rows.Count; y++)
                for (int x = 0; x < p.GetLength(1); x++)
                {
                    if (rows[y]![x] is not JsonValue cell || !cell.TryGetValue(out double d) || d != Math.Floor(d) || d < 0
                        || d >= s.ChannelCount)
                        throw new InputException($"{where}[{y}][{x}]", "must be a channel index",
                            $"a whole number 0–{s.ChannelCount - 1}");
                    p[y, x] = (int)d;
                }
            return p;
        }
        throw new InputException(where, "a pattern is letters (\"RGGB\") or rows of channel indices", "e.g. [[0,1],[1,2]]");
    }

    /// <summary>The largest mosaic tile side: a colour filter array repeats a small tile (Bayer 2, X-Trans 6, a 16-band 4).</summary>
    const int MaxPatternSide = 64;

    /// <summary>A wavelength in nm within the range a channel may cover.</summary>
    static double Nm(JsonNode? n, string where)
    {
        if (n is not JsonValue v || !v.TryGetValue(out double d) || !double.IsFinite(d) || d < 100 || d > 3000)
            throw new InputException(where, "must be a wavelength in nm", "a number in 100–3000");
        return d;
    }

    static string? Str(JsonObject o, string key, string at) => o[key] switch
    {
        null => null,
        JsonValue v when v.TryGetValue(out string? s) => s,
        _ => throw new InputException($"{at}.{key}", "must be a string", "write it in double quotes"),
    };

    static double? Num(JsonObject o, string key, string where, double min, double max, bool whole = false)
    {
        if (o[key] is not JsonNode n) return null;
        string path = where.Contains(": $") ? $"{where}.{key}" : $"{where}: $.{key}";
        if (n is not JsonValue v || !v.TryGetValue(out double d) || !double.IsFinite(d))
            throw new InputException(path, "must be a number", "write a plain finite number");
        if (d < min || d > max || (whole && d != Math.Floor(d)))
            throw new InputException(path,
                string.Create(CultureInfo.InvariantCulture, $"{d} is outside {min}–{max}{(whole ? " or not whole" : "")}"),
                $"give a value in {min}–{max}");
        return d;
    }
}
