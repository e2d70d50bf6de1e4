using System.Text.Json.Nodes;

namespace SpectralRenderer.Output;

/// <summary>
/// render.json's "sampling": the sampler and seed of the camera samples, and how exact the render is — the summary of
/// each pixel's standard error (<see cref="ManifestNoise"/>) and adaptive sampling's samples per pixel
/// (<see cref="ManifestAdaptive"/>). Written only when the sampler is not the independent one of seed 0 or when there are
/// per-pixel statistics, so renders without them keep their render.json.
/// </summary>
public sealed record ManifestSampling(string Sampler, uint Seed, ManifestNoise? Noise, ManifestAdaptive? Adaptive)
{
    /// <summary>How each pixel's standard error was estimated from its own samples, for its sampler (docs/scene-format.md,
    /// "Error estimates"; Rendering/Renderer.Statistics.cs), and what the adaptive stop decided on.</summary>
    public string Estimator => (Sampler == "sobol"
        ? "standard error of each pixel's mean from the spread of its 8 independent randomisations of the Owen-scrambled "
            + "Sobol sequence (sample s in scramble s mod 8): sqrt(sum_g (mean_g - mean)^2 / (8 * 7))"
        : Adaptive is null
            ? "standard error of each pixel's mean from its stratified jitter cells (one sample each): sqrt(sigma^2 / n), "
                + "sigma^2 = sum of (x_s - x_{s-1})^2 over neighbouring cells in a row / (2 * pairs) (collapsed strata, conservative)"
            : "standard error of each pixel's mean from its own n independent samples: s/sqrt(n), s^2 the unbiased sample variance")
        + (Adaptive is null ? "" : "; the adaptive stop decided on s/sqrt(n) * (1 + 2/sqrt(2(n - 1))) <= target * mean");
    public const string RelativeUnit = "1 (a fraction: the standard error of the pixel's mean luminance Y divided by that mean)";

    public JsonObject ToJson()
    {
        var o = new JsonObject { ["sampler"] = Sampler, ["seed"] = Seed };
        if (Noise is { } n)
            o["noise"] = new JsonObject
            {
                ["estimator"] = Estimator,
                ["band_unit"] = n.BandUnit,
                ["luminance_unit"] = n.LuminanceUnit,
                ["relative_error_of_luminance"] = new JsonObject
                {
                    ["unit"] = RelativeUnit,
                    ["mean"] = n.MeanRelative,
                    ["max"] = n.MaxRelative,
                    ["pixels"] = n.Pixels,
                    ["note"] = "over the pixels whose mean luminance is above 0",
                },
            };
        if (Adaptive is { } a)
            o["adaptive"] = new JsonObject
            {
                ["target_error"] = a.TargetError,
                ["target_unit"] = RelativeUnit,
                ["spp_cap"] = a.Cap,
                ["spp_min"] = a.Min,
                ["spp_mean"] = a.Mean,
                ["spp_max"] = a.Max,
            };
        return o;
    }

    /// <summary>render.json's "sampling" read back; null when absent.</summary>
    public static ManifestSampling? Parse(JsonObject? o)
    {
        if (o is null) return null;
        static double? Num(JsonObject? x, string k) => x?[k] is JsonValue v && v.TryGetValue(out double d) ? d : null;
        static string? Str(JsonObject? x, string k) => x?[k] is JsonValue v && v.TryGetValue(out string? s) ? s : null;
        var n = o["noise"] as JsonObject;
        var rel = n?["relative_error_of_luminance"] as JsonObject;
        var a = o["adaptive"] as JsonObject;
        return new ManifestSampling(Str(o, "sampler") ?? "independent", (uint)(Num(o, "seed") ?? 0),
            n is null
                ? null
                : new ManifestNoise(Str(n, "band_unit") ?? "", Str(n, "luminance_unit") ?? "", Num(rel, "mean"), Num(rel, "max"),
                (long)(Num(rel, "pixels") ?? 0)),
            a is null
                ? null
                : new ManifestAdaptive(Num(a, "target_error") ?? 0, (int)(Num(a, "spp_cap") ?? 0), (int)(Num(a, "spp_min") ?? 0),
                Num(a, "spp_mean") ?? 0, (int)(Num(a, "spp_max") ?? 0)));
    }
}

/// <summary>The per-pixel standard errors summed up: the mean and largest relative standard error of luminance over the
/// <paramref name="Pixels"/> pixels whose mean luminance is above 0 (null when there are none).</summary>
public sealed record ManifestNoise(string BandUnit, string LuminanceUnit, double? MeanRelative, double? MaxRelative, long Pixels)
{
    /// <summary>The summary of a render's per-pixel standard errors (N + 1 per pixel, Y last) against its pixels' XYZ.</summary>
    public static ManifestNoise Of(float[] noise, float[] xyz, int bands, string bandUnit, string luminanceUnit)
    {
        long pixels = 0;
        double sum = 0, max = 0;
        int n = xyz.Length / 3;
        for (int i = 0; i < n; i++)
        {
            double y = xyz[3 * i + 1];
            if (!(y > 0)) continue;
            double r = noise[i * (bands + 1) + bands] / y;
            sum += r;
            max = Math.Max(max, r);
            pixels++;
        }
        return new ManifestNoise(bandUnit, luminanceUnit, pixels > 0 ? sum / pixels : null, pixels > 0 ? max : null, pixels);
    }
}

/// <summary>Adaptive sampling: the target relative standard error of luminance, the spp cap and the samples pixels took.</summary>
public sealed record ManifestAdaptive(double TargetError, int Cap, int Min, double Mean, int Max)
{
    public static ManifestAdaptive Of(double target, int cap, int[] used) =>
        new(target, cap, used.Min(), used.Average(), used.Max());
}
