using System.Globalization;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

public sealed partial class SceneLoader
{
    // ---- spectra --------------------------------------------------------------------------------

    /// <summary>
    /// A spectrum value: a number (constant), a name (the scene's "spectra" first, then built-ins and
    /// file.csv:column), inline pairs [[λ, v], …], or an object {name|csv+column|values, scale, extrapolate}.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
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
                            throw Error(path, $"spectrum names refer to each other in a cycle: {cycle}", "a spectrum name must lead, through other names, to a value");
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
            case JsonValueKind.Object:
                {
                    Keys(e, path, "name", "csv", "column", "values", "constant", "scale", "extrapolate");
                    int given = (TryGet(e, "name", out _) ? 1 : 0) + (TryGet(e, "csv", out _) ? 1 : 0) + (TryGet(e, "values", out _) ? 1 : 0) + (TryGet(e, "constant", out _) ? 1 : 0);
                    if (given != 1) throw Error(path, "a spectrum object needs exactly one of name, csv (+ column), values, constant", "e.g. {\"name\": \"D65\", \"scale\": 2}");
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
                    if (TryGet(e, "scale", out var sc)) s = s.Scaled(Number(sc, $"{path}.scale", 0));
                    break;
                }
            default:
                throw Error(path, $"expected a spectrum (a name, a number, [[λ, v], …] or an object), found {Kind(e)}", "e.g. \"D65\", 0.5, [[400, 0.1], [700, 0.9]] or {\"csv\": \"f.csv\", \"column\": \"r\"}");
        }
        return s;
    }

    [MethodImpl(MethodImplOptions.NoOptimization)]
    TabulatedSpectrum Inline(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.Array) throw Error(path, $"expected inline pairs [[λ, v], …], found {Kind(e)}", "e.g. [[400, 0.1], [700, 0.9]]");
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
            if (pair.ValueKind != JsonValueKind.Array || pair.GetArrayLength() != 2) throw Error(p, $"expected a pair [wavelength_nm, value], found {Kind(pair)}", "e.g. [550, 0.4]");
            wl[i] = Number(pair[0], $"{p}[0]", 1e-9);
            v[i] = Number(pair[1], $"{p}[1]");
            if (v[i] < 0) throw Error($"{p}[1]", $"negative value {v[i].ToString(CultureInfo.InvariantCulture)}", "reflectances and powers cannot be negative");
            if (i > 0 && wl[i] <= wl[i - 1]) throw Error($"{p}[0]", $"wavelength {wl[i].ToString(CultureInfo.InvariantCulture)} nm does not follow {wl[i - 1].ToString(CultureInfo.InvariantCulture)} nm", "list the pairs in strictly ascending wavelength");
        }
        return new TabulatedSpectrum($"inline@{path}", wl, v);
    }

    /// <summary>A spectrum as padded band values on the scene's grid (the scheme's projection).</summary>
    float[] Bands(JsonElement e, string path) => Bands(Spectrum(e, path), path);

    [MethodImpl(MethodImplOptions.NoOptimization)]
    float[] Bands(TabulatedSpectrum s, string path)
    {
        if (!s.Covers(_grid.Start, _grid.End))
            throw Error(path, $"spectrum '{s.Name}' covers {s.First:0.###}–{s.Last:0.###} nm but the bands need {_grid.Start:0.###}–{_grid.End:0.###} nm",
                "choose bands inside its range or give it \"extrapolate\": \"clamp\" or \"zero\"");
        var bands = SpectralMath.ToPadded(_colorimeter!.Project(s));
        for (int i = 0; i < _grid.Count; i++)
            if (!(Math.Abs(bands[i]) <= MaxMagnitude))
                throw Error(path, $"spectrum {MessageText.Quote(s.Name)} is {bands[i]:g3} in band {i} ({_grid.Lower(i):0.#}–{_grid.Upper(i):0.#} nm), beyond {MaxMagnitude:g}",
                    "lower its values or its \"scale\"");
        _spectra[bands] = s;
        return bands;
    }

    [MethodImpl(MethodImplOptions.NoOptimization)]
    float[] OptionalBands(JsonElement obj, string name, string path, float[]? fallback = null) =>
        TryGet(obj, name, out var v) ? Bands(v, $"{path}.{name}") : fallback ?? new float[SpectralMath.Padded(_grid.Count)];

    // ---- materials ------------------------------------------------------------------------------

    [MethodImpl(MethodImplOptions.NoOptimization)]
    Material ParseMaterial(JsonElement e, string path, string name)
    {
        if (e.ValueKind == JsonValueKind.String || e.ValueKind == JsonValueKind.Number || e.ValueKind == JsonValueKind.Array)
        {   // shorthand: a bare spectrum is a diffuse material
            var d = Reflectance(Spectrum(e, path), path);
            var bands = Bands(d, path);
            return DiffuseMaterial(name, bands, d);
        }
        Object(e, path);
        Keys(e, path, "diffuse", "ambient", "specular", "shininess", "model", "mirror", "transmit", "ior", "fresnel");
        foreach (var component in new[] { "ambient", "specular", "mirror", "transmit" })
            if (TryGet(e, component, out var c)) Reflectance(Spectrum(c, $"{path}.{component}"), $"{path}.{component}");
        TabulatedSpectrum? diffuseSpectrum = TryGet(e, "diffuse", out var ds) ? Reflectance(Spectrum(ds, $"{path}.diffuse"), $"{path}.diffuse") : null;
        var diffuse = diffuseSpectrum is null ? Zero() : Bands(diffuseSpectrum, $"{path}.diffuse");
        var ambient = OptionalBands(e, "ambient", path, diffuse);  // m_amb defaults to m_diff
        var specular = OptionalBands(e, "specular", path);
        float shininess = (float)Number(e, "shininess", path, 32, 0, 1e6);
        var model = SpecularModels.Default;
        if (TryGet(e, "model", out var m))
        {
            var given = String(m, $"{path}.model").ToLowerInvariant();
            if (!SpecularModels.ByName.TryGetValue(given, out model))
                throw Error($"{path}.model", $"unknown specular model '{given}'", $"use {string.Join(" or ", SpecularModels.ByName.Values.Select(x => x.Name).Distinct())}");
        }
        var mirror = OptionalBands(e, "mirror", path);
        var transmit = OptionalBands(e, "transmit", path);
        float[] ior = Const(1.5f);
        bool dispersive = false;
        if (TryGet(e, "ior", out var iorE))
        {
            if (iorE.ValueKind == JsonValueKind.Number) ior = Const((float)Number(iorE, $"{path}.ior", 1e-3, 100));
            else if (iorE.ValueKind == JsonValueKind.Object)
            {
                Keys(iorE, $"{path}.ior", "cauchy");
                var c = Required(iorE, "cauchy", $"{path}.ior");
                if (c.ValueKind != JsonValueKind.Array || c.GetArrayLength() != 2) throw Error($"{path}.ior.cauchy", "expected [A, B] with n(λ) = A + B/λ², λ in nm (B in nm²)", "e.g. \"ior\": {\"cauchy\": [1.5, 4200]}");
                double a = Number(c[0], $"{path}.ior.cauchy[0]", 1e-3, 100), b = Number(c[1], $"{path}.ior.cauchy[1]", -1e7, 1e7);
                ior = new float[SpectralMath.Padded(_grid.Count)];
                for (int i = 0; i < _grid.Count; i++) { double l = _grid.Centre(i); ior[i] = (float)(a + b / (l * l)); }
                dispersive = b != 0 && _grid.Count > 1;
            }
            else throw Error($"{path}.ior", $"expected a number or {{\"cauchy\": [A, B]}}, found {Kind(iorE)}", "e.g. \"ior\": 1.5");
        }
        bool fresnel = Bool(e, "fresnel", path, false);
        return new Material
        {
            Name = name,
            Ambient = ambient,
            Diffuse = diffuse,
            Specular = specular,
            Shininess = shininess,
            Model = model,
            Mirror = mirror,
            Transmit = transmit,
            Ior = ior,
            Dispersive = dispersive,
            Fresnel = fresnel,
            DiffuseSpectrum = diffuseSpectrum,
        };
    }

    /// <summary>
    /// A reflectance (or transmittance) must lie in [0, 1]: a maximum ≥ 2 over the bands is the symptom of percent and
    /// is refused, as is a value below −1e-9; a maximum in (1, 2) — a fluorescent or glossy sample measured as a
    /// reflectance factor — is rendered as given with a one-line warning.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    TabulatedSpectrum Reflectance(TabulatedSpectrum s, string path)
    {
        if (!s.Covers(_grid.Start, _grid.End)) return s;   // Bands() reports the coverage
        var (min, max) = s.Range(_grid.Start, _grid.End);
        var inv = CultureInfo.InvariantCulture;
        if (max >= 2)
            throw Error(path, $"reflectance '{s.Name}' reaches {max.ToString("0.###", inv)} over {_grid.Start:0.###}–{_grid.End:0.###} nm: a reflectance cannot exceed 1 (this looks like percent)",
                $"give the spectrum as an object with \"scale\": 0.01, e.g. {{ \"csv\": \"…\", \"column\": \"…\", \"scale\": 0.01 }}");
        if (min < -1e-9)
            throw Error(path, $"reflectance '{s.Name}' goes down to {min.ToString("G4", inv)}: a reflectance cannot be negative",
                "fix the table (noise below zero should be clipped to 0 before use)");
        if (max > 1)
            _warnings.Add($"{Where(path)}: warning: reflectance '{s.Name}' reaches {max.ToString("0.###", inv)} > 1 (a reflectance factor of a fluorescent or glossy sample?); rendered as given");
        return s;
    }

    /// <summary>A purely diffuse material (m_amb = m_diff, no specular, mirror or transmission lobe).</summary>
    [MethodImpl(MethodImplOptions.NoOptimization)]
    Material DiffuseMaterial(string name, float[] bands, TabulatedSpectrum? spectrum) => new()
    {
        Name = name,
        Ambient = bands,
        Diffuse = bands,
        Specular = Zero(),
        Mirror = Zero(),
        Transmit = Zero(),
        Ior = Const(1),
        DiffuseSpectrum = spectrum,
    };

    float[] Zero() => new float[SpectralMath.Padded(_grid.Count)];
    [MethodImpl(MethodImplOptions.NoOptimization)]
    float[] Const(float v)
    {
        var a = new float[SpectralMath.Padded(_grid.Count)];
        Array.Fill(a, v, 0, _grid.Count);
        return a;
    }

    // ---- lights ---------------------------------------------------------------------------------

    [MethodImpl(MethodImplOptions.NoOptimization)]
    Light ParseLight(JsonElement e, string path, int index)
    {
        Object(e, path);
        var type = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        var names = LightTypes.ByName.Keys.ToArray();
        if (!LightTypes.ByName.TryGetValue(type, out var kind))
            throw Error($"{path}.type", $"unknown light type '{type}'", InputException.DidYouMean(type, names) ?? $"use {string.Join(", ", names)}");
        Keys(e, path, [.. LightTypes.CommonKeys, .. kind.Keys]);
        var name = TryGet(e, "name", out var n) ? String(n, $"{path}.name") : $"light-{index}";
        var spectrum = Spectrum(Required(e, "spectrum", path), $"{path}.spectrum");
        float intensity = (float)Number(e, "intensity", path, 1, 0);
        var bands = Bands(spectrum, $"{path}.spectrum");
        for (int i = 0; i < bands.Length; i++)
        {
            bands[i] *= intensity;
            if (!(bands[i] <= MaxMagnitude))
                throw Error($"{path}.intensity", $"intensity × spectrum is {bands[i]:g3} in band {i}, beyond {MaxMagnitude:g}", "lower the intensity or the spectrum's scale");
        }
        _spectra[bands] = spectrum.Scaled(intensity);
        var ambient = OptionalBands(e, "ambient", path);
        // Physical radiometry: a point or spot light's spectrum × intensity is radiant intensity, so irradiance falls as 1/r².
        var falloff = _radiometry == Radiometry.Physical ? new DistanceFalloff(0, 0, 1) : DistanceFalloff.None;
        if (TryGet(e, "attenuation", out var att))
        {
            if (att.ValueKind != JsonValueKind.Array || att.GetArrayLength() != 3) throw Error($"{path}.attenuation", "expected [c0, c1, c2] with d = 1/(c0 + c1·r + c2·r²)", "e.g. \"attenuation\": [1, 0, 0.1]");
            float c0 = (float)Number(att[0], $"{path}.attenuation[0]", 0);
            float c1 = (float)Number(att[1], $"{path}.attenuation[1]", 0);
            float c2 = (float)Number(att[2], $"{path}.attenuation[2]", 0);
            if (c0 + c1 + c2 <= 0) throw Error($"{path}.attenuation", "all attenuation coefficients are zero", "use [1, 0, 0] for no attenuation");
            falloff = new DistanceFalloff(c0, c1, c2);
        }
        return kind.Make(new LightSource(this, e, path)
        {
            Name = name,
            Intensity = bands,
            Ambient = ambient,
            HasAmbient = SpectralMath.Any(ambient),
            Spectrum = spectrum,
            Falloff = falloff,
            Scale = intensity,
        });
    }

    /// <summary>
    /// What a light type's factory (<see cref="LightTypes"/>) gets: the parts every light has, already parsed, and
    /// readers for its own keys that report bad input with the file, line:column and JSON path.
    /// </summary>
    public sealed class LightSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal LightSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public required string Name { get; init; }
        /// <summary>I_k: the spectrum's band values × intensity.</summary>
        public required float[] Intensity { get; init; }
        public required float[] Ambient { get; init; }
        public required bool HasAmbient { get; init; }
        public required TabulatedSpectrum Spectrum { get; init; }
        /// <summary>The "intensity" factor the spectrum's band values were multiplied by.</summary>
        public required float Scale { get; init; }
        /// <summary>The "attenuation" [c0, c1, c2], or none.</summary>
        public required DistanceFalloff Falloff { get; init; }
        /// <summary>What every light emits, for the light type's constructor.</summary>
        public LightEmission Emission => new(Name, Intensity, Ambient, HasAmbient, Scale, Spectrum);

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A required point [x, y, z].</summary>
        public Vector3 Point(string key) => _loader.Vec3(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A required non-zero vector, normalised.</summary>
        public Vector3 Direction(string key) => _loader.Direction(_loader.Required(_e, key, _path), $"{_path}.{key}");
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
    }

    [MethodImpl(MethodImplOptions.NoOptimization)]
    Vector3 Direction(JsonElement e, string path)
    {
        var v = Vec3(e, path);
        if (v.LengthSquared() == 0) throw Error(path, "the direction is the zero vector", "give a non-zero direction such as [0, -1, 0]");
        return Vector3.Normalize(v);
    }
}
