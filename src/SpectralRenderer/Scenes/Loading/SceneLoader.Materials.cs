using System.Globalization;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Materials: named under "materials", given inline or as a spectrum name by an object; reflectances checked.
public sealed partial class SceneLoader
{
    Material ParseMaterial(JsonElement e, string path, string name)
    {
        if (e.ValueKind == JsonValueKind.String || e.ValueKind == JsonValueKind.Number || e.ValueKind == JsonValueKind.Array)
        {   // shorthand: a bare spectrum is a diffuse material
            var d = Reflectance(Spectrum(e, path), path);
            var bands = Bands(d, path);
            return DiffuseMaterial(name, bands, d);
        }
        Object(e, path);
        // The material model ("type", default eq2) reads its own keys; without "type" the keys are eq. 2's, as always.
        var model = MaterialModels.ByName[MaterialModels.Default];
        bool typed = TryGet(e, MaterialModels.KindKey, out var t);
        if (typed)
        {
            var type = String(t, $"{path}.{MaterialModels.KindKey}").ToLowerInvariant();
            var names = MaterialModels.ByName.Keys.ToArray();
            if (!MaterialModels.ByName.TryGetValue(type, out model))
                throw Error($"{path}.{MaterialModels.KindKey}", $"unknown material type '{type}'",
                    InputException.DidYouMean(type, names) ?? $"use {string.Join(", ", names)}");
        }
        // "emission" (an area light) and "fluorescence" (SceneLoader.Fluorescence.cs) are every model's keys.
        string[] common = [MaterialModels.EmissionKey, FluorescenceKey];
        Keys(e, path, typed ? [MaterialModels.KindKey, .. common, .. model!.Keys] : [.. common, .. model!.Keys]);
        var modelName = typed ? t.GetString()!.ToLowerInvariant() : MaterialModels.Default;
        var fluorescence = ParseFluorescence(e, path, modelName, out bool texelDiagonal);
        // A diffuse texture beside a matrix is the diagonal per texel: the model reads it as a texture (its mean the spectrum).
        var diagonal = texelDiagonal ? null : fluorescence?.Reflectance;
        var material = model.Make(new MaterialSource(this, e, path) { Name = name, Diagonal = diagonal });
        material.Emission = ParseEmission(e, path);
        material.Fluorescence = fluorescence;
        AttachTextures(material, path);   // issue 26: SceneLoader.Textures.cs
        if (texelDiagonal && material.DiffuseTexture is { } texels) CheckTexelPhotons(texels.Texture, fluorescence!, $"{path}.diffuse");
        return material;
    }

    /// <summary>
    /// The index of refraction per band: a number, {"cauchy": [A, B]} for n(λ) = A + B/λ², {"sellmeier": {"B1" … "C3"}}
    /// for n²(λ) = 1 + Σ B_i·λ²/(λ² − C_i) (λ in µm) (<see cref="RefractiveIndex"/>), or {"spectrum": S} a tabulated n(λ),
    /// each at the band centres.
    /// </summary>
    (float[] Ior, bool Dispersive) Ior(JsonElement e, string path)
    {
        float[] ior = Const(1.5f);
        bool dispersive = false;
        if (TryGet(e, "ior", out var iorE))
        {
            if (iorE.ValueKind == JsonValueKind.Number) ior = Const((float)Number(iorE, $"{path}.ior", 1e-3, 100));
            else if (iorE.ValueKind == JsonValueKind.Object)
            {
                Keys(iorE, $"{path}.ior", "cauchy", "sellmeier", "spectrum");
                bool cauchy = TryGet(iorE, "cauchy", out var c), sellmeier = TryGet(iorE, "sellmeier", out var s);
                bool tabulated = TryGet(iorE, "spectrum", out var t);
                if ((cauchy ? 1 : 0) + (sellmeier ? 1 : 0) + (tabulated ? 1 : 0) != 1)
                    throw Error($"{path}.ior",
                        cauchy || sellmeier || tabulated
                            ? "more than one of \"cauchy\", \"sellmeier\" and \"spectrum\": give one dispersion formula"
                            : "expected \"cauchy\" or \"sellmeier\" (a formula) or \"spectrum\" (a table of n(λ))",
                        "e.g. \"ior\": {\"cauchy\": [1.5, 4200]}");
                Func<double, double> n;
                if (tabulated)
                {
                    // A measured index n(λ) (e.g. pbrt-v4's glass-BK7 table): its linear interpolant at each band centre.
                    var table = Spectrum(t, $"{path}.ior.spectrum");
                    table.RequireCoverage(_grid.Centre(0), _grid.Centre(_grid.Count - 1), Where($"{path}.ior.spectrum"));
                    n = table.Evaluate;
                }
                else if (cauchy)
                {
                    if (c.ValueKind != JsonValueKind.Array || c.GetArrayLength() != 2)
                        throw Error($"{path}.ior.cauchy", "expected [A, B] with n(λ) = A + B/λ², λ in nm (B in nm²)",
                            "e.g. \"ior\": {\"cauchy\": [1.5, 4200]}");
                    double a = Number(c[0], $"{path}.ior.cauchy[0]", 1e-3, 100), b = Number(c[1], $"{path}.ior.cauchy[1]", -1e7, 1e7);
                    n = l => RefractiveIndex.Cauchy(a, b, l);
                    dispersive = b != 0 && _grid.Count > 1;
                }
                else
                {
                    const string Example = "e.g. Schott N-BK7: {\"B1\": 1.03961212, \"B2\": 0.231792344, \"B3\": 1.01046945, \"C1\": "
                        + "0.00600069867, \"C2\": 0.0200179144, \"C3\": 103.560653}";
                    string sp = $"{path}.ior.sellmeier";
                    if (s.ValueKind != JsonValueKind.Object)
                        throw Error(sp, $"expected an object of B1, B2, B3 and C1, C2, C3 (C in µm²), found {Kind(s)}", Example);
                    Keys(s, sp, "B1", "B2", "B3", "C1", "C2", "C3");
                    var bs = new double[3];
                    var cs = new double[3];
                    for (int i = 0; i < 3; i++)
                    {
                        bs[i] = Number(s, $"B{i + 1}", sp, 0, -100, 100);
                        cs[i] = Number(s, $"C{i + 1}", sp, 0, 0, 1e6);
                    }
                    n = l => RefractiveIndex.Sellmeier(bs, cs, l);
                }
                ior = new float[SpectralMath.Padded(_grid.Count)];
                for (int i = 0; i < _grid.Count; i++)
                {
                    double v = n(_grid.Centre(i));
                    if (!(v >= 1e-3 && v <= 100))
                        throw Error($"{path}.ior",
                            string.Create(CultureInfo.InvariantCulture,
                                $"the index of refraction is {v:0.####} at {_grid.Centre(i):0.###} nm (band {i + 1}): outside 0.001–100 (a "
                                    + $"Sellmeier resonance C_i = λ² in µm² inside the bands?)"),
                            "check the coefficients' units: Cauchy B in nm², Sellmeier C_i in µm²");
                    ior[i] = (float)v;
                }
                if (sellmeier || tabulated)
                    for (int i = 1; i < _grid.Count; i++) dispersive |= ior[i] != ior[0];
            }
            else
                throw Error($"{path}.ior",
                    $"expected a number, {{\"cauchy\": [A, B]}}, {{\"sellmeier\": {{…}}}} or {{\"spectrum\": …}}, found {Kind(iorE)}",
                    "e.g. \"ior\": 1.5");
        }
        return (ior, dispersive);
    }

    /// <summary>
    /// A reflectance (or transmittance) must lie in [0, 1]: a maximum ≥ 2 over the bands is the symptom of percent and
    /// is refused, as is a value below −1e-9; a maximum in (1, 2) — a fluorescent or glossy sample measured as a
    /// reflectance factor — is rendered as given with a one-line warning.
    /// </summary>
    TabulatedSpectrum Reflectance(TabulatedSpectrum s, string path)
    {
        if (!s.Covers(_grid.Start, _grid.End)) return s;   // Bands() reports the coverage
        var (min, max) = s.Range(_grid.Start, _grid.End);
        var inv = CultureInfo.InvariantCulture;
        if (max >= 2)
            throw Error(path,
                $"reflectance '{s.Name}' reaches {max.ToString("0.###", inv)} over {_grid.Start:0.###}–{_grid.End:0.###} nm: a reflectance "
                    + $"cannot exceed 1 (this looks like percent)",
                $"give the spectrum as an object with \"scale\": 0.01, e.g. {{ \"csv\": \"…\", \"column\": \"…\", \"scale\": 0.01 }}");
        if (min < -1e-9)
            throw Error(path, $"reflectance '{s.Name}' goes down to {min.ToString("G4", inv)}: a reflectance cannot be negative",
                "fix the table (noise below zero should be clipped to 0 before use)");
        if (max > 1)
            _warnings.Add($"{Where(path)}: warning: reflectance '{s.Name}' reaches {max.ToString("0.###", inv)} > 1 (a reflectance factor "
                + $"of a fluorescent or glossy sample?); rendered as given");
        return s;
    }

    /// <summary>A purely diffuse material (m_amb = m_diff, no specular, mirror or transmission lobe).</summary>
    Material DiffuseMaterial(string name, float[] bands, TabulatedSpectrum? spectrum, Bsdf? bsdf = null) => new()
    {
        Name = name,
        Ambient = bands,
        Diffuse = bands,
        Specular = Zero(),
        Mirror = Zero(),
        Transmit = Zero(),
        Ior = Const(1),
        DiffuseSpectrum = spectrum,
        Bsdf = bsdf!,   // null: eq. 2's own view
    };

    int MaterialOf(JsonElement e, string path, List<Material> materials, Dictionary<string, int> materialIndex)
    {
        var m = Required(e, "material", path);
        if (m.ValueKind == JsonValueKind.String && materialIndex.TryGetValue(m.GetString()!, out int i)) return i;
        if (m.ValueKind == JsonValueKind.String && !materialIndex.ContainsKey(m.GetString()!))
        {
            var name = m.GetString()!;
            // A built-in spectrum name stands for a diffuse material of that reflectance.
            if (name.StartsWith("colorchecker:", StringComparison.OrdinalIgnoreCase)
                || name.StartsWith("constant:", StringComparison.OrdinalIgnoreCase) || _namedSpectra.ContainsKey(name))
            {
                materials.Add(ParseMaterial(m, $"{path}.material", name));
                return materials.Count - 1;
            }
            throw Error($"{path}.material", $"unknown material '{name}'",
                InputException.DidYouMean(name, materialIndex.Keys)
                    ?? (materialIndex.Count > 0 ? $"materials: {string.Join(", ", materialIndex.Keys)}" : "define it under \"materials\""));
        }
        materials.Add(ParseMaterial(m, $"{path}.material", $"{path}.material"));
        return materials.Count - 1;
    }

    /// <summary>
    /// What a material model's factory (<see cref="MaterialModels"/>) gets: the material's name and readers for its own keys
    /// that resolve spectra onto the scene's bands and report bad input with the file, line:column and JSON path.
    /// </summary>
    public sealed class MaterialSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal MaterialSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public required string Name { get; init; }
        /// <summary>A re-radiation matrix's diagonal, which stands for the diffuse reflectance ("diffuse", "reflectance").</summary>
        internal TabulatedSpectrum? Diagonal { get; init; }
        bool IsDiagonal(string key) => Diagonal is not null && key is "diffuse" or "reflectance";

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A reflectance or transmittance spectrum, checked to lie in [0, 1] (a warning up to 2); null when absent.</summary>
        public TabulatedSpectrum? Reflectance(string key) => IsDiagonal(key) ? Diagonal :
            TryGet(_e, key, out var v) ? _loader.Reflectance(_loader.Spectrum(v, $"{_path}.{key}"), $"{_path}.{key}") : null;
        /// <summary>A required reflectance.</summary>
        public TabulatedSpectrum RequiredReflectance(string key) => IsDiagonal(key) ? Diagonal! :
            _loader.Reflectance(_loader.Spectrum(_loader.Required(_e, key, _path), $"{_path}.{key}"), $"{_path}.{key}");
        /// <summary>A spectrum's padded band values on the scene's grid (the integrator integrates its products exactly).</summary>
        public float[] Bands(TabulatedSpectrum s, string key) => _loader.Bands(s, $"{_path}.{key}");
        /// <summary>The key's spectrum as padded band values, or <paramref name="fallback"/> (zero when null) when absent.</summary>
        public float[] Bands(string key, float[]? fallback = null) => _loader.OptionalBands(_e, key, _path, fallback);
        public float[] Zero() => _loader.Zero();
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public bool Bool(string key, bool fallback) => _loader.Bool(_e, key, _path, fallback);
        /// <summary>A required string.</summary>
        public string String(string key) => _loader.String(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>"ior": a number, {"cauchy": [A, B]}, {"sellmeier": {…}} or {"spectrum": …}; 1.5 when absent.</summary>
        public (float[] Ior, bool Dispersive) Ior() => _loader.Ior(_e, _path);
        /// <summary>A purely diffuse material of these band values (m_amb = m_diff), with its own BSDF or eq. 2's view.</summary>
        public Material Diffuse(float[] bands, TabulatedSpectrum? spectrum, Bsdf? bsdf = null) =>
            _loader.DiffuseMaterial(Name, bands, spectrum, bsdf);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
        /// <summary>The scene's band grid (band values are padded beyond its count).</summary>
        public BandGrid Grid => _loader._grid;
        /// <summary>The key is given as a JSON string.</summary>
        public bool IsString(string key) => TryGet(_e, key, out var v) && v.ValueKind == JsonValueKind.String;
        /// <summary>A required non-negative spectrum that is not a reflectance (an optical constant such as n or k).</summary>
        public TabulatedSpectrum Spectrum(string key) => _loader.Spectrum(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A required object under <paramref name="key"/> with only the keys <paramref name="keys"/>, read as a source of its
        /// own.</summary>
        public MaterialSource Object(string key, params string[] keys)
        {
            var o = _loader.Object(_loader.Required(_e, key, _path), $"{_path}.{key}");
            _loader.Keys(o, $"{_path}.{key}", keys);
            return new MaterialSource(_loader, o, $"{_path}.{key}") { Name = Name };
        }
    }
}
