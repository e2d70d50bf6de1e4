using System.Text.Json.Nodes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>camera.json: every parameter the simulation used, the per-band channel weights, the exposures, the colour matrix.</summary>
public static class CameraManifest
{
    public const int Version = 1;

    public static JsonObject Build(RawFrame raw, ColourCorrection colour, BandGrid grid, string lightName, double radianceScale,
        string radianceScaleSource,
        string route = RadianceCube.BandRoute, string whiteScaleSource = "1: the light's band values (the paper's white)")
    {
        bool exact = route.StartsWith("exact", StringComparison.Ordinal);
        var s = raw.Sensor;
        var w = raw.Weights;
        var channels = new JsonArray();
        for (int c = 0; c < s.ChannelCount; c++)
        {
            var qe = s.Channels[c].QuantumEfficiency;
            channels.Add((JsonNode)new JsonObject
            {
                ["name"] = s.Channels[c].Name,
                ["source"] = s.Channels[c].Source,
                ["peak_qe"] = PeakQuantumEfficiency(s.Channels[c]),
                ["weights_e_per_s_per_band_unit"] = Array(w.Row(c).ToArray()),
                ["white_rate_e_per_s"] = colour.WhiteRate[c],
                ["exposure_s"] = raw.ExposureOf(c),
            });
        }
        JsonNode? pattern = null;
        if (s.Pattern is { } p)
        {
            var rows = new JsonArray();
            for (int y = 0; y < p.GetLength(0); y++)
            {
                var r = new JsonArray();
                for (int x = 0; x < p.GetLength(1); x++) r.Add((JsonNode)p[y, x]);
                rows.Add((JsonNode)r);
            }
            pattern = rows;
        }
        var matrix = new JsonArray();
        for (int i = 0; i < 3; i++)
        {
            var r = new JsonArray();
            for (int c = 0; c < s.ChannelCount; c++) r.Add((JsonNode)colour.Matrix[i, c]);
            matrix.Add((JsonNode)r);
        }
        return new JsonObject
        {
            ["tool"] = "SpectralRenderer camera",
            ["manifest_version"] = Version,
            ["sensor"] = new JsonObject
            {
                ["name"] = s.Name,
                ["source"] = s.Source,
                ["arrangement"] = s.Arrangement.ToString().ToLowerInvariant(),
                ["pattern"] = pattern,
                ["pattern_name"] = s.PatternName,
                ["f_number"] = s.FNumber,
                ["transmittance"] = s.OpticsTransmittance,
                ["transmittance_spectrum"] = s.TransmittanceSource,
                ["optics"] = OpticsJson(s, raw.Optics),
                ["pixel_size_um"] = s.PixelSizeMicrons,
                ["fill_factor"] = s.FillFactor,
                ["etendue_m2_sr"] = s.Etendue,
                ["conversion_gain_v_per_e"] = s.ConversionGain,
                ["voltage_swing_v"] = s.VoltageSwing,
                ["full_well_e"] = s.FullWellElectrons,
                ["read_noise_v"] = s.ReadNoiseVolts,
                ["read_noise_e"] = s.ReadNoiseElectrons,
                ["dark_voltage_v_per_s"] = s.DarkVoltage,
                ["dark_current_e_per_s"] = s.DarkCurrentElectronsPerSecond,
                ["prnu_percent"] = s.PrnuPercent,
                ["dsnu_v"] = s.DsnuVolts,
                ["analog_gain"] = s.AnalogGain,
                ["adc_bits"] = s.AdcBits,
                ["black_level_dn"] = s.BlackLevel,
                ["white_level_dn"] = s.WhiteLevel,
                ["system_gain_dn_per_e"] = s.SystemGain,
                ["dn_scale"] = "DN = black + V·G/V_swing·(white − black), white = 2^bits − 1: the voltage swing maps to white − black DN "
                    + "(ISETCam maps it to 2^bits without a black offset); K = g·G·(white − black)/V_swing DN per electron",
                ["exposure"] =
                    s.ExposureSeconds is null ? $"auto: brightest expected pixel at {s.AutoExposureFraction} of the full well" : "given",
                ["fixed_pattern_seed"] = s.FixedPatternSeed,
                ["channels"] = channels,
            },
            ["simulation"] = new JsonObject
            {
                ["seed"] = raw.Options.Seed,
                ["noise"] = raw.Options.Noise
                    ? "on: shot (Poisson), dark current (Poisson), read (Gaussian), PRNU, DSNU, full-well clip, quantisation"
                    : "off: expected signal only (no noise, no dark current, no quantisation); full-well and white clipping kept",
                ["exposure_s"] = Array(raw.ExposureSeconds),
                ["peak_expected_electrons"] = Array(raw.PeakElectrons),
                ["radiance_scale_w_m2_sr_nm_per_band_unit"] = radianceScale,
                ["radiance_scale_source"] = radianceScaleSource,
                ["light"] = lightName,
                ["bands"] = grid.ToString(),
                ["weights"] = "w_c,b = s·A·ff·πT/(1+4N²)·Δλ·∫_b η_c λ E dλ / (h c ∫_b E dλ): photo-electrons per second per band "
                    + "unit, prefiltered by the light E",
                ["signal_route"] = route,
                ["white_radiance_scale"] = colour.WhiteScale,
                ["white_radiance_scale_source"] = whiteScaleSource,
                ["electrons_formula"] = exact
                    ? "e = Poisson(t·ė_c·(1 + PRNU) + t·dark), ė_c = s·A·ff·πT/(1+4N²)·Σ_terms F·∫η_c·λ·E_k·m "
                        + "dλ/(h c), clipped at the full well"
                    : "e = Poisson(t·Σ_b w_c,b·L_b·(1 + PRNU) + t·dark), clipped at the full well",
                ["dn_formula"] = "DN = round(black + (e·g + DSNU + read)·G/V_swing·(white − black)), clipped to [0, white]",
            },
            ["processing"] = new JsonObject
            {
                ["white_balance"] = "each channel divided by its expected response to the white diffuser under the light (radiance: "
                    + "white_radiance_scale × the light)",
                ["colour_matrix_xyz_from_balanced"] = matrix,
                ["colour_matrix_fit"] = "least squares on the 24 ColorChecker (Ohta) patches under the light: simulated balanced "
                    + "signals → 1 nm CIE XYZ (white Y = 1)",
                ["output"] = "sRGB (IEC 61966-2-1), no chromatic adaptation",
            },
        };
    }

    /// <summary>What the lens did (<see cref="Optics"/>): the models, their sources, the focal length from the render's field of view, the
    /// kernels.</summary>
    static JsonObject OpticsJson(SensorModel s, Optics.Plan? plan)
    {
        var o = new JsonObject
        {
            ["off_axis"] = s.OffAxis == OffAxisModel.Cos4th ? "cos4th" : "none",
            ["psf"] = s.Psf == PsfModel.Diffraction ? "diffraction" : "none",
            ["field_of_view_deg"] = plan?.FovDegrees,
            ["focal_length_mm"] = plan?.FocalLengthMm,
            ["focal_length_source"] =
                "f = rows × pixel pitch / (2 tan(fov/2)): the sensor under the render camera's vertical field of view",
        };
        if (s.OffAxis == OffAxisModel.Cos4th)
        {
            o["off_axis_formula"] =
                "irradiance × cos⁴φ, tan²φ = s_x² + s_y² at the pixel centre (the render camera's ray); ISETCam cos4th.m (distant image)";
            o["min_relative_illumination"] = plan?.MinIllumination;
        }
        if (s.Psf == PsfModel.Diffraction && plan?.Kernels is { } ks)
        {
            o["psf_formula"] = "Airy pattern π/(4(λN)²)·[2J1(v)/v]², v = πr/(λN), at each band's centre "
                + "(Goodman, Fourier Optics, eq. 4-31), "
                + "against the pixel-pair triangle, cut where the encircled energy reaches "
                    + Optics.PsfEnergy.ToString(System.Globalization.CultureInfo.InvariantCulture)
                + " and normalised to 1; edges clamped";
            o["psf_first_zero_um"] = Array(ks.Select(k => 1.2196698912665045 * k.WavelengthNm * 1e-3 * s.FNumber));
            o["psf_kernel_radius_px"] = new JsonArray(ks.Select(k => (JsonNode)k.Radius).ToArray());
            o["psf_kernel_energy"] = Array(ks.Select(k => k.CapturedEnergy));
        }
        return o;
    }

    /// <summary>The largest η(λ) the channel uses (a per-energy channel: R(λ)·555 nm/λ over its table), electrons per photon.</summary>
    public static double PeakQuantumEfficiency(SensorChannel channel)
    {
        var qe = channel.QuantumEfficiency;
        double peak = 0;
        for (int i = 0; i < qe.Values.Length; i++)
            peak = Math.Max(peak, channel.PerEnergy ? qe.Values[i] * SensorChannel.EnergyReferenceNm / qe.Wavelengths[i] : qe.Values[i]);
        return peak;
    }

    static JsonArray Array(IEnumerable<double> values) => new(values.Select(v => (JsonNode)v).ToArray());
}
