namespace SpectralRenderer.Scenes.Loading;

/// <summary>A medium type of the scene file: the keys it takes (beyond "type") and how it builds its <see cref="Medium"/>.</summary>
public sealed record MediumType(string[] Keys, Func<SceneLoader.MediumSource, Medium> Make);

/// <summary>
/// The medium types a scene file can name (a <c>"medium"</c>'s "type", on an object for its interior or at the top for the
/// space around the objects; <see cref="Default"/> when it names none): the one registration point for a new kind of
/// participating medium (ARCHITECTURE.md, "Extending").
/// </summary>
public static class MediumTypes
{
    /// <summary>The type of a <c>"medium"</c> that names none.</summary>
    public const string Default = "homogeneous";

    static readonly Lock Gate = new();
    static Dictionary<string, MediumType> s_byName = new(StringComparer.Ordinal)
    {
        // σ_a and σ_s, or α and σ_t, per band and per scene length unit, and a phase function (Scenes/HomogeneousMedium.cs).
        [Default] = new(["sigma_a", "sigma_s", "albedo", "sigma_t", "phase"], Homogeneous),
        // The same coefficients at density 1, scaled by a density grid from a .vol or .npy "file" placed in "bounds"
        // (Scenes/GridMedium.cs, Scenes/DensityGrid.cs, Scenes/Loading/DensityGridReader.cs).
        ["grid"] = new(["sigma_a", "sigma_s", "albedo", "sigma_t", "phase", "file", "bounds", "resolution", "scale"], Grid),
    };

    public static IReadOnlyDictionary<string, MediumType> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a medium type under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, MediumType type) => Registry.Add(ref s_byName, Gate, name, type);

    /// <summary>
    /// A grid medium: the homogeneous medium of its coefficients where the density is 1, times the grid's density (times
    /// "scale", default 1). Placed in "bounds" ([[min], [max]], scene units), else in the box about the object whose interior
    /// it fills, else in the .vol file's own bounding box; a .npy grid in the scene's medium needs "bounds". "resolution"
    /// [nx, ny, nz], when given, must match the file's.
    /// </summary>
    static Medium Grid(SceneLoader.MediumSource s)
    {
        var unit = Homogeneous(s);
        var file = s.File("file");
        var samples = DensityGridReader.Read(Diagnostics.InputFile.ReadAllBytes(file, "density grid"), file);
        if (s.Resolution("resolution") is { } r && (r[0] != samples.Nx || r[1] != samples.Ny || r[2] != samples.Nz))
            throw s.Error("resolution", $"the grid declares {r[0]} × {r[1]} × {r[2]} samples, {Path.GetFileName(file)} holds "
                + $"{samples.Nx} × {samples.Ny} × {samples.Nz}", "fix \"resolution\" or the file (x, y, z: a .npy's shape reversed)");
        var bounds = s.Box("bounds") ?? s.ObjectBounds ?? samples.Bounds
            ?? throw s.Error("file", "a .npy grid in the scene's medium has no placement",
                "give \"bounds\": [[x, y, z], [x, y, z]] in scene units");
        float scale = (float)s.Number("scale", 1, 0, 1e30);
        var data = samples.Data;
        if (scale != 1) for (int i = 0; i < data.Length; i++) data[i] *= scale;
        if (data.Any(v => !float.IsFinite(v)))
            throw s.Error("scale", $"the densities times {scale} are too large for single precision", "give a smaller \"scale\"");
        var medium = new GridMedium(unit, new DensityGrid(data, samples.Nx, samples.Ny, samples.Nz, bounds.Min, bounds.Max));
        if (medium.Scattering is { } m && !float.IsFinite(m.Majorant))
            throw s.Error("file", "the largest density times the largest σ_t is too large for single precision",
                "lower the coefficients, the densities or \"scale\"");
        return medium;
    }

    static HomogeneousMedium Homogeneous(SceneLoader.MediumSource s)
    {
        bool albedoForm = s.Has("albedo") || s.Has("sigma_t");
        if (albedoForm && (s.Has("sigma_a") || s.Has("sigma_s")))
            throw s.Error(s.Has("sigma_a") ? "sigma_a" : "sigma_s", "a medium gives both σ_a/σ_s and albedo/σ_t",
                "give either \"sigma_a\" and \"sigma_s\", or \"albedo\" and \"sigma_t\"");
        if (!albedoForm && !s.Has("sigma_a") && !s.Has("sigma_s"))
            throw s.Error("sigma_a", "a medium has no coefficients",
                "give \"sigma_a\" and/or \"sigma_s\" (per scene length unit), or \"albedo\" and \"sigma_t\"");
        var (first, second) = albedoForm
            ? (s.Coefficient("albedo", required: true, max: 1), s.Coefficient("sigma_t", required: true))
            : (s.Coefficient("sigma_a", required: false), s.Coefficient("sigma_s", required: false));
        return new HomogeneousMedium(first, second, albedoForm, s.Phase(), s.Grid.Count);
    }
}
