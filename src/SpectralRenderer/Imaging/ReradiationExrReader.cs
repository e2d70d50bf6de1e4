using System.Globalization;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Reads a re-radiation (Donaldson) matrix from a bispectral OpenEXR file in the layout of Fichet, Pacanowski &amp; Wilkie,
/// "An OpenEXR Layout for Spectral Images", JCGT 10(3) 2021, as the authors' reference code (afichet/spectral-exr,
/// EXRBiSpectralImage) and colour-science (read_spectral_image_Fichet2021) name its channels:
///   T.&lt;λ&gt;nm              the reflective diagonal D[λ, λ] (T.&lt;λ&gt;nm.&lt;λ&gt;nm is read as the same),
///   T.&lt;λi&gt;nm.&lt;λo&gt;nm      the re-radiation from excitation λi (the first wavelength) to emission λo.
/// A number has a comma (the layout's) or a point as decimal separator and an optional exponent; its unit is metres with an
/// SI prefix (nm, um, …) or hertz (λ = c/ν). The authors write only λi &lt; λo (Stokes shift); any pair is read, and a pair
/// not stored is 0. Values mean what the CSV layout's do (<see cref="ReradiationMatrix"/>, docs/scene-format.md
/// "Fluorescence"), with the same checks: finite, non-negative, the diagonal's wavelengths evenly spaced, and the photon
/// balance of each excitation column. Other channels (the RGB preview R, G, B, A; emissive S0–S3) are not read.
/// A material takes one matrix, so the image is one pixel or uniform (every pixel equal, as an image made by repeating one
/// measurement); a varying image is refused (a bispectral texture is not supported). Errors name the file and the channel.
/// </summary>
public static class ReradiationExrReader
{
    const string Number = @"(\d+(?:[.,]\d*)?(?:[eE][-+]?\d+)?|[.,]\d+(?:[eE][-+]?\d+)?)";
    const string Unit = @"(da|[YZEPTGMkhdcmunpfazy])?(m|Hz)";
    static readonly Regex Name = new($@"^T\.{Number}{Unit}(?:\.{Number}{Unit})?$", RegexOptions.CultureInvariant);

    /// <summary>Speed of light in vacuum, m/s (SI, exact).</summary>
    const double LightSpeed = 299_792_458;

    public static ReradiationMatrix Read(string path) => Read(InputFile.ReadAllBytes(path, "re-radiation matrix"), path);

    public static ReradiationMatrix Read(byte[] bytes, string path)
    {
        var (width, height, channels, planes, _, _, _, _) = ExrReader.ReadChannels(bytes, path);
        var diagonal = new List<(double Lambda, int Channel)>();
        var shifted = new List<(double In, double Out, int Channel)>();
        for (int c = 0; c < channels.Count; c++)
        {
            string name = channels[c].Name;
            if (!name.StartsWith("T.", StringComparison.Ordinal)) continue;
            var m = Name.Match(name);
            if (!m.Success)
                throw Error(path, name, "is not a reflective channel name T.<λ>nm or T.<λin>nm.<λout>nm",
                    "name the diagonal T.550,000000nm and the re-radiation from 350 nm to 440 nm T.350,000000nm.440,000000nm");
            double a = Nanometres(m.Groups[1].Value, m.Groups[2].Value, m.Groups[3].Value);
            if (!m.Groups[4].Success) { diagonal.Add((a, c)); continue; }
            double b = Nanometres(m.Groups[4].Value, m.Groups[5].Value, m.Groups[6].Value);
            if (!(a > 0) || !(b > 0) || !double.IsFinite(a) || !double.IsFinite(b))
                throw Error(path, name, "names a wavelength that is not positive and finite", "wavelengths in nm, e.g. T.350nm.440nm");
            if (Math.Abs(a - b) <= 1e-9 * a) diagonal.Add((a, c)); else shifted.Add((a, b, c));
        }
        if (diagonal.Count == 0)
            throw new InputException($"{path}: header attribute 'channels'", "no reflective diagonal channels T.<λ>nm",
                "a bispectral matrix (Fichet et al. 2021) stores its reflectance as T.<λ>nm and the re-radiation as T.<λin>nm.<λout>nm");
        diagonal.Sort((x, y) => x.Lambda.CompareTo(y.Lambda));
        foreach (var (lambda, c) in diagonal)
            if (!(lambda > 0) || !double.IsFinite(lambda))
                throw Error(path, channels[c].Name, "names a wavelength that is not positive and finite",
                    "wavelengths in nm, e.g. T.550nm");
        if (diagonal.Count < 2)
            throw Error(path, channels[diagonal[0].Channel].Name, "is the only diagonal channel",
                "a matrix needs at least two wavelengths");
        int n = diagonal.Count;
        var wl = diagonal.Select(x => x.Lambda).ToArray();
        double spacing = double.PositiveInfinity;
        for (int j = 1; j < n; j++)
        {
            if (Math.Abs(wl[j] - wl[j - 1]) <= 1e-9 * wl[j])
                throw Error(path, channels[diagonal[j].Channel].Name, $"gives the diagonal at {Nm(wl[j])} nm a second time (also " +
                    $"{channels[diagonal[j - 1].Channel].Name})", "keep one channel per diagonal wavelength");
            spacing = Math.Min(spacing, wl[j] - wl[j - 1]);
        }
        for (int j = 1; j < n; j++)
        {
            double gap = wl[j] - wl[j - 1], k = Math.Round(gap / spacing);
            if (Math.Abs(gap - spacing) <= 1e-6 * spacing) continue;
            string name = channels[diagonal[j].Channel].Name, previous = channels[diagonal[j - 1].Channel].Name;
            throw k >= 2 && Math.Abs(gap - k * spacing) <= 1e-6 * k * spacing
                ? Error(path, name,
                    $"follows {previous}: no diagonal channel at {Nm(wl[j - 1] + spacing)} nm (the matrix's step is {Nm(spacing)} nm)",
                    "every wavelength of the matrix needs its diagonal channel T.<λ>nm, the reflectance (0 where it reflects nothing)")
                : Error(path, name,
                    $"follows {previous}: the diagonal's wavelengths are not evenly spaced (smallest step {Nm(spacing)} nm)",
                    "give the matrix on one evenly spaced wavelength list");
        }
        int Index(double lambda)
        {
            double k = Math.Round((lambda - wl[0]) / spacing);
            return k >= 0 && k < n && Math.Abs(wl[(int)k] - lambda) <= 1e-6 * spacing ? (int)k : -1;
        }

        var d = new double[n * n];
        var source = new int[n * n];
        Array.Fill(source, -1);
        for (int j = 0; j < n; j++) source[j * n + j] = diagonal[j].Channel;
        foreach (var (a, b, c) in shifted)
        {
            int i = Index(a), o = Index(b);
            if (i < 0 || o < 0)
                throw Error(path, channels[c].Name,
                    $"{(i < 0 ? "excitation" : "emission")} {Nm(i < 0 ? a : b)} nm has no diagonal channel T.<λ>nm",
                    $"the matrix's wavelengths are its diagonal's, {Nm(wl[0])}–{Nm(wl[^1])} nm every {Nm(spacing)} nm: "
                        + $"add the diagonal or fix the name");
            if (source[o * n + i] >= 0)
                throw Error(path, channels[c].Name, $"gives D[{Nm(b)}, {Nm(a)}] a second time (also {channels[source[o * n + i]].Name})",
                    "keep one channel per pair of wavelengths");
            source[o * n + i] = c;
        }
        for (int k = 0; k < n * n; k++)
        {
            if (source[k] < 0) continue;
            string name = channels[source[k]].Name;
            var plane = planes[source[k]];
            for (int p = 0; p < plane.Length; p++)
            {
                float v = plane[p];
                if (!float.IsFinite(v))
                    throw Error(path, name, $"pixel ({p % width}, {p / width}) is not finite ({v.ToString(CultureInfo.InvariantCulture)})",
                        "a re-radiation matrix holds finite numbers");
                if (v < 0)
                    throw Error(path, name,
                        $"pixel ({p % width}, {p / width}) is negative ({v.ToString("G4", CultureInfo.InvariantCulture)})",
                        "a re-radiation matrix is non-negative");
                if (v != plane[0])
                    throw Error(path, name, $"differs between pixels (0, 0) and ({p % width}, {p / width}) of the {width}×{height} image",
                        "a material takes one matrix: give a 1×1 image (or a uniform one), e.g. oiiotool "
                            + "in.exr --cut 1x1+X+Y -o pixel.exr");
            }
            d[k] = plane[0];
        }
        var matrix = new ReradiationMatrix(Path.GetFileName(path), wl, d);
        int bad = matrix.PhotonExcess(ReradiationCsvReader.PhotonTolerance, out double emitted, out double absorbed);
        if (bad >= 0)
            throw Error(path, channels[diagonal[bad].Channel].Name,
                $"excitation {Nm(wl[bad])} nm re-emits {emitted / wl[bad]:G4} photons per incident photon but absorbs only "
                    + $"{absorbed / wl[bad]:G4} (1 − D[i,i])",
                "a passive surface emits at most the photons it absorbs: Σ_o D[o,i]·λo ≤ (1 − D[i,i])·λi over the channels T.λi.λo");
        return matrix;
    }

    /// <summary>A wavelength in nm from the layout's number, SI prefix and unit (m or Hz).</summary>
    static double Nanometres(string number, string prefix, string unit)
    {
        double v = double.Parse(number.Replace(',', '.'), NumberStyles.Float, CultureInfo.InvariantCulture);
        double scale = prefix switch
        {
            "Y" => 1e24,
            "Z" => 1e21,
            "E" => 1e18,
            "P" => 1e15,
            "T" => 1e12,
            "G" => 1e9,
            "M" => 1e6,
            "k" => 1e3,
            "h" => 1e2,
            "da" => 1e1,
            "d" => 1e-1,
            "c" => 1e-2,
            "m" => 1e-3,
            "u" => 1e-6,
            "n" => 1e-9,
            "p" => 1e-12,
            "f" => 1e-15,
            "a" => 1e-18,
            "z" => 1e-21,
            "y" => 1e-24,
            _ => 1,
        };
        if (unit == "Hz") return LightSpeed / (v * scale) * 1e9;
        return prefix == "n" ? v : v * scale * 1e9;
    }

    static string Nm(double v) => v.ToString("0.######", CultureInfo.InvariantCulture);

    static InputException Error(string path, string channel, string what, string hint) =>
        new($"{path}: channel {MessageText.Quote(channel, 60)}", what, hint);
}
