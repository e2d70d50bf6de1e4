using System.Globalization;
using System.Runtime.CompilerServices;
using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Materials: named under "materials", given inline or as a spectrum name by an object; reflectances checked.
public sealed partial class SceneLoader
{
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

    [MethodImpl(MethodImplOptions.NoOptimization)]
    int MaterialOf(JsonElement e, string path, List<Material> materials, Dictionary<string, int> materialIndex)
    {
        var m = Required(e, "material", path);
        if (m.ValueKind == JsonValueKind.String && materialIndex.TryGetValue(m.GetString()!, out int i)) return i;
        if (m.ValueKind == JsonValueKind.String && !materialIndex.ContainsKey(m.GetString()!))
        {
            var name = m.GetString()!;
            // A built-in spectrum name stands for a diffuse material of that reflectance.
            if (name.StartsWith("colorchecker:", StringComparison.OrdinalIgnoreCase) || name.StartsWith("constant:", StringComparison.OrdinalIgnoreCase) || _namedSpectra.ContainsKey(name))
            {
                materials.Add(ParseMaterial(m, $"{path}.material", name));
                return materials.Count - 1;
            }
            throw Error($"{path}.material", $"unknown material '{name}'",
                InputException.DidYouMean(name, materialIndex.Keys) ?? (materialIndex.Count > 0 ? $"materials: {string.Join(", ", materialIndex.Keys)}" : "define it under \"materials\""));
        }
        materials.Add(ParseMaterial(m, $"{path}.material", $"{path}.material"));
        return materials.Count - 1;
    }
}
