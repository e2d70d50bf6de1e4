using System.Globalization;
using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Spectrum values (numbers, names, inline pairs, objects) resolved and projected onto the scene's bands.
public sealed partial class SceneLoader
{
    /// <summary>
    /// A spectrum value: a number (constant), a name (the scene's "spectra" first, then built-ins and
    /// file.csv:column), inline pairs [[λ, v], …], or an object {name|csv+column|values, scale, extrapolate}.
    /// </summary>
    TabulatedSpectrum Spectrum(JsonElement e, string path)
    {
        RuntimeHelpers.EnsureSufficientExecutionStack();
        TabulatedSpectrum s;
        switch (e.ValueKind)
        {
            case JsonValueKind.Number:
                s = TabulatedSpectrum.Constant(Number(e, path, 0), $"constant:{e.GetRawText()}");
                break;
            case JsonValueKind.String:
                {
                    var name = e.GetString()!;
                    if (_resolvedNamed.TryGetValue(name, out var cached)) return cached;
                    if (_namedSpectra.TryGetValue(name, out var named))
                    {
                        // Depth-first search over the names: a name met again while it is still being resolved
                        // closes a cycle (any chain without one resolves, however long).
                        int onPath = _resolving.IndexOf(name);
                        if (onPath >= 0)
                        {
                            var cycle = string.Join(" → ", _resolving.Skip(onPath).Append(name).Select(n => MessageText.Quote(n, 24)));
                            throw Error(path, $"spectrum names refer to each other in a cycle: {cycle}",
                                "a spectrum name must lead, through other names, to a value");
                        }
                        _resolving.Add(name);
                        try { s = Spectrum(named.Element, named.Path); }
                        finally { _resolving.RemoveAt(_resolving.Count - 1); }
                        s = new TabulatedSpectrum(name, s.Wavelengths.ToArray(), s.Values.ToArray(), s.Extrapolation);
                        _resolvedNamed[name] = s;
                        return s;
                    }
                    try { s = SpectrumLibrary.Resolve(name, _dir, Where(path)); }
                    catch (InputException ex) when (ex.What.StartsWith("unknown spectrum", StringComparison.Ordinal))
                    {
                        throw Error(path, $"unknown spectrum {MessageText.Quote(name)}",
                            InputException.DidYouMean(name, _namedSpectra.Keys.Concat(SpectrumLibrary.KnownNames)) ??
                            "name one in \"spectra\", a built-in (D65, A, FL11, led-blue, colorchecker:14, …) or file.csv:column");
                    }
                    break;
                }
            case JsonValueKind.Array:
                s = Inline(e, path);
                break;
            case JsonValueKind.Object when IsTexture(e):
                return TextureSpectrum(e, path);   // issue 26: SceneLoader.Textures.cs
            case JsonValueKind.Object when TryGet(e, "rgb", out _):
                return RgbSpectrum(e, path);
            case JsonValueKind.Object:
                {
                    Keys(e, path, "name", "csv", "column", "values", "constant", "scale", "extrapolate");
                    int given = (TryGet(e, "name", out _) ? 1 : 0) + (TryGet(e, "csv", out _) ? 1 : 0)
                        + (TryGet(e, "values", out _) ? 1 : 0) + (TryGet(e, "constant", out _) ? 1 : 0);
                    if (given != 1)
                        throw Error(path, "a spectrum object needs exactly one of name, csv (+ column), values, constant",
                            "e.g. {\"name\": \"D65\", \"scale\": 2}");
                    if (TryGet(e, "name", out var n)) s = Spectrum(n, $"{path}.name");
                    else if (TryGet(e, "values", out var v)) s = Inline(v, $"{path}.values");
                    else if (TryGet(e, "constant", out var c)) s = TabulatedSpectrum.Constant(Number(c, $"{path}.constant", 0));
                    else
                    {
                        var csv = String(Required(e, "csv", path), $"{path}.csv");
                        var column = String(Required(e, "column", path), $"{path}.column");
                        s = SpectrumLibrary.Resolve($"{csv}:{column}", _dir, Where(path));
                    }
                    if (TryGet(e, "extrapolate", out var x))
                    {
                        var policy = String(x, $"{path}.extrapolate").ToLowerInvariant() switch
                        {
                            "clamp" => Extrapolation.Clamp,
                            "zero" => Extrapolation.Zero,
                            "error" or "none" => Extrapolation.Error,
                            var other => throw Error($"{path}.extrapolate", $"unknown extrapolation '{other}'", "use clamp, zero or error"),
                        };
                        s = s.WithExtrapolation(policy);
                    }
                    if (TryGet(e, "scale", out var sc))
                        s = sc.ValueKind != JsonValueKind.String ? s.Scaled(Number(sc, $"{path}.scale", 0))
                            : sc.GetString() == "luminous" ? SpectrumLibrary.OnLightScale(s, where: Where($"{path}.scale"))
                            : throw Error($"{path}.scale", $"unknown scale {MessageText.Quote(sc.GetString()!)}",
                                "a number, or \"luminous\" (the built-in lights' scale: ∫V·S dλ = D65's)");
                    break;
                }
            default:
                throw Error(path, $"expected a spectrum (a name, a number, [[λ, v], …] or an object), found {Kind(e)}",
                    "e.g. \"D65\", 0.5, [[400, 0.1], [700, 0.9]] or {\"csv\": \"f.csv\", \"column\": \"r\"}");
        }
        return s;
    }

    TabulatedSpectrum Inline(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.Array)
            throw Error(path, $"expected inline pairs [[λ, v], …], found {Kind(e)}", "e.g. [[400, 0.1], [700, 0.9]]");
        int n = e.GetArrayLength();
        if (n < 2) throw Error(path, "an inline spectrum needs at least two [λ, v] pairs", "e.g. [[400, 0.1], [700, 0.9]]");
        var wl = new double[n];
        var v = new double[n];
        int i = -1;
        // Enumerated, not indexed: e[i] of an array of arrays walks from the start, which made long spectra quadratic.
        foreach (var pair in e.EnumerateArray())
        {
            i++;
            string p = $"{path}[{i}]";
            if (pair.ValueKind != JsonValueKind.Array || pair.GetArrayLength() != 2)
                throw Error(p, $"expected a pair [wavelength_nm, value], found {Kind(pair)}", "e.g. [550, 0.4]");
            wl[i] = Number(pair[0], $"{p}[0]", 1e-9);
            v[i] = Number(pair[1], $"{p}[1]");
            if (v[i] < 0)
                throw Error($"{p}[1]", $"negative value {v[i].ToString(CultureInfo.InvariantCulture)}",
                    "reflectances and powers cannot be negative");
            if (i > 0 && wl[i] <= wl[i - 1])
                throw Error($"{p}[0]",
                    $"wavelength {wl[i].ToString(CultureInfo.InvariantCulture)} nm does not follow "
                        + $"{wl[i - 1].ToString(CultureInfo.InvariantCulture)} nm",
                    "list the pairs in strictly ascending wavelength");
        }
        return new TabulatedSpectrum($"inline@{path}", wl, v);
    }

    /// <summary>A spectrum as padded band values on the scene's grid (the scheme's projection).</summary>
    float[] Bands(JsonElement e, string path) => Bands(Spectrum(e, path), path);

    float[] Bands(TabulatedSpectrum s, string path)
    {
        if (!s.Covers(_grid.Start, _grid.End))
            throw Error(path,
                $"spectrum '{s.Name}' covers {s.First:0.###}–{s.Last:0.###} nm but the bands need {_grid.Start:0.###}–{_grid.End:0.###} nm",
                "choose bands inside its range or give it \"extrapolate\": \"clamp\" or \"zero\"");
        var bands = SpectralMath.ToPadded(_colorimeter!.Project(s));
        for (int i = 0; i < _grid.Count; i++)
            if (!(Math.Abs(bands[i]) <= MaxMagnitude))
                throw Error(path,
                    $"spectrum {MessageText.Quote(s.Name)} is {bands[i]:g3} in band {i} "
                        + $"({_grid.Lower(i):0.#}–{_grid.Upper(i):0.#} nm), beyond {MaxMagnitude:g}",
                    "lower its values or its \"scale\"");
        _spectra[bands] = s;
        return bands;
    }

    float[] OptionalBands(JsonElement obj, string name, string path, float[]? fallback = null) =>
        TryGet(obj, name, out var v) ? Bands(v, $"{path}.{name}") : fallback ?? new float[SpectralMath.Padded(_grid.Count)];

    float[] Zero() => new float[SpectralMath.Padded(_grid.Count)];
    float[] Const(float v)
    {
        var a = new float[SpectralMath.Padded(_grid.Count)];
        Array.Fill(a, v, 0, _grid.Count);
        return a;
    }

    /// <summary>
    /// { "rgb": [r, g, b] }: a linear sRGB reflectance (each in [0, 1]) uplifted by the sigmoid polynomial
    /// (<see cref="SigmoidUplift"/>: the smooth reflectance whose colour under D65 is that colour). With "illuminant": a spectrum
    /// value I, an emission: S(λ) = s·r(λ)·I(λ)/Ȳ_I, where s = 2·max(r, g, b), r(λ) the uplift of rgb/s (at most ½, away from
    /// the sigmoid's ends) and Ȳ_I = ∫ȳ·I dλ / ∫ȳ dλ (CIE 1931), so a white [1, 1, 1] is I scaled to luminance factor Y = 1
    /// — Mitsuba 3's and pbrt-v4's illuminant uplift (Mitsuba's MI_CIE_D65_NORMALIZATION is 1/Ȳ of D65). "scale" multiplies.
    /// </summary>
    TabulatedSpectrum RgbSpectrum(JsonElement e, string path)
    {
        Keys(e, path, "rgb", "illuminant", "scale");
        var a = Required(e, "rgb", path);
        if (a.ValueKind != JsonValueKind.Array || a.GetArrayLength() != 3)
            throw Error($"{path}.rgb", $"expected [r, g, b], found {Kind(a)}", "three linear sRGB values, e.g. [0.8, 0.2, 0.1]");
        bool emission = TryGet(e, "illuminant", out var ill);
        var c = new double[3];
        for (int i = 0; i < 3; i++)
            c[i] = Number(a[i], $"{path}.rgb[{i}]", 0, emission ? MaxMagnitude : 1);
        string label = string.Create(CultureInfo.InvariantCulture, $"rgb({c[0]:R}, {c[1]:R}, {c[2]:R})");
        TabulatedSpectrum s;
        if (!emission)
            s = new TabulatedSpectrum(label, SigmoidUplift.Wavelengths, IlluminantUplift.Reflectance(c[0], c[1], c[2]),
                Extrapolation.Clamp);
        else
        {
            var illuminant = Spectrum(ill, $"{path}.illuminant");
            double m = Math.Max(c[0], Math.Max(c[1], c[2]));
            if (m == 0) s = TabulatedSpectrum.Constant(0, label);
            else
            {
                double scale = 2 * m;
                double luminanceFactor = IlluminantUplift.LuminanceFactor(ref illuminant);
                if (!(luminanceFactor > 0))
                    throw Error($"{path}.illuminant", "the illuminant has no luminance (∫ȳ·I dλ = 0)",
                        "name a visible light, e.g. \"D65\"");
                var r = IlluminantUplift.Reflectance(c[0] / scale, c[1] / scale, c[2] / scale);
                s = IlluminantUplift.Product($"{label} × {illuminant.Name}", r, scale, illuminant, luminanceFactor);
            }
        }
        if (TryGet(e, "scale", out var sc)) s = s.Scaled(Number(sc, $"{path}.scale", 0));
        return s;
    }
}
