namespace SpectralRenderer.Scenes.Loading;

/// <summary>A material model of the scene file: the keys it takes (beyond "type") and how it builds its <see cref="Material"/>.</summary>
public sealed record MaterialModel(string[] Keys, Func<SceneLoader.MaterialSource, Material> Make);

/// <summary>
/// The material models a scene file can name (a material's "type"; "model" is the specular lobe's shape within eq. 2): the
/// one registration point for a new kind of material. Each builds a <see cref="Material"/> — eq. 2's lobes, which the
/// Whitted integrator uses — and may give it its own <see cref="Bsdf"/> (else eq. 2's view, <see cref="Eq2Bsdf"/>).
/// </summary>
public static class MaterialModels
{
    /// <summary>The key that names a material's model.</summary>
    public const string KindKey = "type";
    /// <summary>The key every model takes for what its surface emits (<see cref="Emission"/>).</summary>
    public const string EmissionKey = "emission";
    /// <summary>The model of a material without "type".</summary>
    public const string Default = "eq2";

    static readonly Lock Gate = new();
    static Dictionary<string, MaterialModel> s_byName = new(StringComparer.Ordinal)
    {
        [Default] = new(["diffuse", "ambient", "specular", "shininess", "model", "mirror", "transmit", "ior", "fresnel"], Eq2),
        ["lambertian"] = new(["reflectance"], Lambertian),
        ["conductor"] = new(ConductorMaterial.Keys, ConductorMaterial.Make),
        ["plastic"] = new(PlasticMaterial.Keys, PlasticMaterial.Make),
    };

    public static IReadOnlyDictionary<string, MaterialModel> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a material model under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, MaterialModel model) => Registry.Add(ref s_byName, Gate, name, model);

    /// <summary>The paper's eq. 2: m_amb, m_diff, m_spec with its specular model and shininess, k_r and k_t, IOR, Fresnel.</summary>
    static Material Eq2(SceneLoader.MaterialSource s)
    {
        // Every reflectance is checked before any is projected (the order of the errors and warnings).
        foreach (var component in new[] { "ambient", "specular", "mirror", "transmit" }) s.Reflectance(component);
        var diffuseSpectrum = s.Reflectance("diffuse");
        var diffuse = diffuseSpectrum is null ? s.Zero() : s.Bands(diffuseSpectrum, "diffuse");
        var ambient = s.Bands("ambient", diffuse);   // m_amb defaults to m_diff
        var specular = s.Bands("specular");
        float shininess = (float)s.Number("shininess", 32, 0, 1e6);
        var model = SpecularModels.Default;
        if (s.Has("model"))
        {
            var given = s.String("model").ToLowerInvariant();
            if (!SpecularModels.ByName.TryGetValue(given, out model))
                throw s.Error("model", $"unknown specular model '{given}'", ByName.ContainsKey(given)
                    ? $"'{given}' is a material type: write \"type\": \"{given}\" (\"model\" shapes eq. 2's specular lobe)"
                    : $"use {string.Join(" or ", SpecularModels.ByName.Values.Select(x => x.Name).Distinct())}");
        }
        var mirror = s.Bands("mirror");
        var transmit = s.Bands("transmit");
        var (ior, dispersive) = s.Ior();
        bool fresnel = s.Bool("fresnel", false);
        return new Material
        {
            Name = s.Name,
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

    /// <summary>A Lambertian reflector, f = ρ/π: in eq. 2, m_diff = m_amb = ρ and no other lobe.</summary>
    static Material Lambertian(SceneLoader.MaterialSource s)
    {
        var rho = s.RequiredReflectance("reflectance");
        var bands = s.Bands(rho, "reflectance");
        return s.Diffuse(bands, rho, new LambertianBsdf(bands));
    }
}

/// <summary>Copy-on-write registration for the name → kind tables read by every scene load (readers never lock).</summary>
static class Registry
{
    public static void Add<T>(ref Dictionary<string, T> table, Lock gate, string name, T kind)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(name);
        ArgumentNullException.ThrowIfNull(kind);
        if (name != name.ToLowerInvariant()) throw new ArgumentException($"a scene-file name is lower case: '{name}'", nameof(name));
        lock (gate)
        {
            if (table.ContainsKey(name)) throw new ArgumentException($"'{name}' is already registered", nameof(name));
            var copy = new Dictionary<string, T>(table, StringComparer.Ordinal) { [name] = kind };
            Volatile.Write(ref table, copy);
        }
    }
}
