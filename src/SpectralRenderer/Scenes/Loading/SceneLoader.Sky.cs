using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// The sky: a CIE daylight of a correlated colour temperature, as the radiance of every ray that escapes the scene.
public sealed partial class SceneLoader
{
    /// <summary>
    /// "sky": { "type": "daylight", "cct": K, "luminance": cd/m² | "radiance": W·m⁻²·sr⁻¹·nm⁻¹ at 560 nm, "distribution":
    /// "uniform" | "cie-overcast", "zenith": [x, y, z] } — a sky whose spectral radiance is the CIE D-series SPD of that CCT
    /// (CIE 015:2018 §4.1.2, S₀ + M₁S₁ + M₂S₂: <see cref="CieDaylight"/>), scaled to the luminance K_m∫V·L dλ or to the spectral
    /// radiance at 560 nm (where every D SPD is 100). Uniform (the default): the same in every direction. CIE overcast
    /// (<see cref="SkyDistribution.CieOvercast"/>): the luminance or radiance given is the zenith's, L(θ) = L_z·(1 + 2 cos θ)/3
    /// above the horizon and nothing below, the zenith +Y unless "zenith" turns it. It is the scene's background (what escaping
    /// rays see), which the path integrator also lights the scene with. Physical radiometry only; instead of "background".
    /// </summary>
    float[] ParseSky(JsonElement e)
    {
        const string path = "$.sky";
        Object(e, path);
        bool map = TryGet(e, "type", out var t) && t.ValueKind == JsonValueKind.String && t.GetString() == "envmap";
        if (map) Keys(e, path, "type", "file", "scale", "transform", "mapping");
        else Keys(e, path, "type", "cct", "luminance", "radiance", "distribution", "zenith");
        if (_radiometry != Radiometry.Physical)
            throw Error(path, "a sky is a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) and needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene (and render it with \"integrator\": \"path\")");
        var type = String(Required(e, "type", path), $"{path}.type");
        if (map) return ParseEnvironment(e, path);
        if (type != "daylight")
            throw Error($"{path}.type", $"unknown sky type '{type}'",
                "the sky types are: daylight (a CIE daylight by \"cct\"), envmap (a lat-long image by \"file\")");
        double cct = Number(e, "cct", path, 6504, CieDaylight.MinKelvin, CieDaylight.MaxKelvin);
        _skyDistribution = ParseDistribution(e, path);
        bool luminance = TryGet(e, "luminance", out _), radiance = TryGet(e, "radiance", out _);
        if (luminance == radiance)
            throw Error(path, luminance ? "gives both \"luminance\" and \"radiance\"" : "needs \"luminance\" or \"radiance\"",
                "give one: \"luminance\" in cd/m² (e.g. 5000 for an overcast sky) or \"radiance\" in W·m⁻²·sr⁻¹·nm⁻¹ at 560 nm");
        var spd = CieDaylight.Spectrum(cct);
        // Every D SPD is exactly 100 at 560 nm (S₁ = S₂ = 0 there), so radiance k is the factor k/100.
        double scale = radiance ? Number(e, "radiance", path, 0, 0) / 100 : Number(e, "luminance", path, 0, 0) / Photometry.Luminous(spd);
        return Bands(spd.Scaled(scale), path);
    }

    SkyDistribution _skyDistribution;
    Vector3 _zenith = Vector3.UnitY;

    /// <summary>The names of <see cref="SkyDistribution"/> in a scene file.</summary>
    static readonly (string Name, SkyDistribution Value)[] Distributions =
        [("uniform", SkyDistribution.Uniform), ("cie-overcast", SkyDistribution.CieOvercast)];

    /// <summary>"distribution" (uniform unless given) and, for a sky that varies with direction, "zenith" (+Y unless given).</summary>
    SkyDistribution ParseDistribution(JsonElement e, string path)
    {
        var distribution = SkyDistribution.Uniform;
        if (TryGet(e, "distribution", out var d))
        {
            var name = String(d, $"{path}.distribution");
            var known = Distributions.Select(k => k.Name).ToArray();
            int i = Array.IndexOf(known, name);
            if (i < 0)
                throw Error($"{path}.distribution", $"unknown sky distribution '{name}'",
                    InputException.DidYouMean(name, known) ?? "the distributions are: uniform (the same luminance everywhere), "
                    + "cie-overcast (the CIE standard overcast sky, \"luminance\" its zenith's)");
            distribution = Distributions[i].Value;
        }
        if (TryGet(e, "zenith", out var z))
        {
            if (distribution == SkyDistribution.Uniform)
                throw Error($"{path}.zenith", "a uniform sky has no zenith", "drop \"zenith\", or give \"distribution\": \"cie-overcast\"");
            _zenith = Direction(z, $"{path}.zenith");
        }
        return distribution;
    }

    EnvironmentMap? _environment;

    /// <summary>
    /// "sky": { "type": "envmap", "file": "sky.exr" | "sky.hdr" | "sky.pfm", "scale": s, "transform": {…} } — the radiance of
    /// escaping rays from a lat-long image in Mitsuba 3's conventions (<see cref="EnvironmentMap"/>: +Y up, linear sRGB uplifted
    /// as a D65 illuminant), its directions turned by the transform's linear part. The path integrator samples it by its
    /// luminance; the background (what the Whitted integrator sees, and the sky's spectrum in power and summaries) is the
    /// uplift of its solid-angle mean colour. "mapping": "equal-area" reads the image as pbrt-v4's equal-area octahedral square
    /// instead (<see cref="EqualAreaSquare"/>: square, its centre along the map's +Z, each pixel constant over 4π/N²).
    /// </summary>
    float[] ParseEnvironment(JsonElement e, string path)
    {
        var file = String(Required(e, "file", path), $"{path}.file");
        var full = Path.IsPathRooted(file) ? file : Path.Combine(_dir, file);
        if (!File.Exists(full))
            throw Error($"{path}.file", $"environment map '{file}' not found", "the path is relative to the scene file");
        double scale = Number(e, "scale", path, 1, 0, MaxMagnitude);
        var toWorld = TryGet(e, "transform", out var t) ? Transform(t, $"{path}.transform") : Matrix4x4.Identity;
        var mapping = EnvironmentMapping.LatLong;
        if (TryGet(e, "mapping", out var how))
        {
            var name = String(how, $"{path}.mapping");
            mapping = name switch
            {
                "lat-long" => EnvironmentMapping.LatLong,
                "equal-area" => EnvironmentMapping.EqualArea,
                _ => throw Error($"{path}.mapping", $"unknown mapping '{name}'",
                    "\"lat-long\" (Mitsuba's equirectangular image, the default) or \"equal-area\" (pbrt-v4's octahedral square)"),
            };
        }
        var image = RgbImage.Read(full);
        for (int i = 0; i < image.Rgb.Length; i++)
            if (!float.IsFinite(image.Rgb[i]) || image.Rgb[i] < 0)
                throw Error($"{path}.file", $"{file}: pixel ({i / 3 % image.Width}, {i / 3 / image.Width}) holds {image.Rgb[i]}",
                    "an environment map holds finite radiances ≥ 0: fix or clip the image");
        if (mapping == EnvironmentMapping.EqualArea && image.Width != image.Height)
            throw Error($"{path}.file", $"{file} is {image.Width} × {image.Height} pixels",
                "an equal-area map (pbrt-v4's) is square: N × N pixels");
        if (mapping == EnvironmentMapping.LatLong && (image.Width < 2 || image.Height < 3))
            throw Error($"{path}.file", $"{file} is {image.Width} × {image.Height} pixels", "a lat-long map needs at least 2 × 3");
        _environment = new EnvironmentMap(full, image.Width, image.Height, image.Rgb, scale, toWorld, mapping);
        var mean = _environment.MeanRgb();
        double m = Math.Max(mean[0], Math.Max(mean[1], mean[2]));
        if (m == 0) return Const(0);
        var d65 = SpectrumLibrary.Resolve("D65");
        double factor = IlluminantUplift.LuminanceFactor(ref d65);
        var r = IlluminantUplift.Reflectance(mean[0] / (2 * m), mean[1] / (2 * m), mean[2] / (2 * m));
        return Bands(IlluminantUplift.Product($"mean of {Path.GetFileName(file)}", r, 2 * m, d65, factor), path);
    }
}
