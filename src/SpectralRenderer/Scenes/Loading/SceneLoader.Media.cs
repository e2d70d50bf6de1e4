using System.Text.Json;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Participating media: an object's "medium" (its interior) and the scene's "medium" (around the objects), each
// { "type": NAME, …its keys } of a registered medium type (MediumTypes.cs; "homogeneous" when it names none).
public sealed partial class SceneLoader
{
    /// <summary>The scene's media in the order they were read (<see cref="Scene.Media"/>).</summary>
    readonly List<Medium> _media = [];

    /// <summary>The medium <paramref name="e"/> at <paramref name="path"/>, added to the scene's media: its index there.</summary>
    /// <param name="interiorOf">The objects whose interior it fills (a grid medium's default placement: their bounds).</param>
    int ParseMedium(JsonElement e, string path, IReadOnlyList<SceneObject>? interiorOf = null)
    {
        Object(e, path);
        var type = TryGet(e, "type", out var t) ? String(t, $"{path}.type").ToLowerInvariant() : MediumTypes.Default;
        var registered = MediumTypes.ByName;
        if (!registered.TryGetValue(type, out var kind))
        {
            var types = registered.Keys.Order(StringComparer.Ordinal).ToArray();
            throw Error($"{path}.type", $"unknown medium type '{type}'",
                InputException.DidYouMean(type, types) ?? $"types: {string.Join(", ", types)}");
        }
        Keys(e, path, ["type", .. kind.Keys]);
        _media.Add(kind.Make(new MediumSource(this, e, path) { ObjectBounds = BoundsOf(interiorOf) }));
        return _media.Count - 1;
    }

    /// <summary>The box about <paramref name="objects"/> (null: none, or one with no volume).</summary>
    static (System.Numerics.Vector3 Min, System.Numerics.Vector3 Max)? BoundsOf(IReadOnlyList<SceneObject>? objects)
    {
        if (objects is null || objects.Count == 0) return null;
        var box = Geometry.Bounds3.Empty;
        foreach (var o in objects)
        {
            if (o.Shape is { } shape) box.Include(shape.Bounds);
            if (o.Mesh is { } mesh) foreach (var p in mesh.Positions) box.Include(p);
        }
        return box.Min.X < box.Max.X && box.Min.Y < box.Max.Y && box.Min.Z < box.Max.Z ? (box.Min, box.Max) : null;
    }

    /// <summary>
    /// Does <paramref name="o"/> enclose a volume, so that a ray crossing it goes in or out (an interior medium's boundary)?
    /// A sphere and a box do, a plane, quad, chart or registered open shape (disk, tube) does not, and a mesh does when it is
    /// watertight: every edge, its vertices welded by position, shared by exactly two triangles.
    /// </summary>
    static bool Encloses(SceneObject o)
    {
        if (o.Shape is { } shape) return shape.Kind is Geometry.ShapeKind.Sphere or Geometry.ShapeKind.Box;
        if (o.Mesh is not { } mesh) return false;
        var welded = new Dictionary<System.Numerics.Vector3, int>();
        var edges = new Dictionary<(int, int), int>();
        int Weld(int v) => welded.TryGetValue(mesh.Positions[v], out int w) ? w : welded[mesh.Positions[v]] = welded.Count;
        for (int t = 0; t < mesh.TriangleCount; t++)
        {
            int a = Weld(mesh.Indices[3 * t]), b = Weld(mesh.Indices[3 * t + 1]), c = Weld(mesh.Indices[3 * t + 2]);
            foreach (var (p, q) in new[] { (a, b), (b, c), (c, a) })
            {
                var key = p < q ? (p, q) : (q, p);
                edges[key] = edges.GetValueOrDefault(key) + 1;
            }
        }
        return edges.Count > 0 && edges.Values.All(n => n == 2);
    }

    /// <summary>
    /// What a medium type's factory (<see cref="MediumTypes"/>) gets: readers for its own keys that resolve spectra onto the
    /// scene's bands and report bad input with the file, line:column and JSON path. Coefficients are per scene length unit.
    /// </summary>
    public sealed class MediumSource
    {
        readonly SceneLoader _loader;
        readonly JsonElement _e;
        readonly string _path;

        internal MediumSource(SceneLoader loader, JsonElement e, string path) { _loader = loader; _e = e; _path = path; }

        public bool Has(string key) => TryGet(_e, key, out _);
        /// <summary>A required spectrum.</summary>
        public TabulatedSpectrum Spectrum(string key) => _loader.Spectrum(_loader.Required(_e, key, _path), $"{_path}.{key}");
        /// <summary>A spectrum's padded band values on the scene's grid (a renderer resamples its tabulated spectrum exactly).</summary>
        public float[] Bands(TabulatedSpectrum s, string key) => _loader.Bands(s, $"{_path}.{key}");
        public double Number(string key, double fallback, double min, double max) => _loader.Number(_e, key, _path, fallback, min, max);
        public InputException Error(string key, string what, string hint) => _loader.Error($"{_path}.{key}", what, hint);
        public BandGrid Grid => _loader._grid;
        /// <summary>The box about the object(s) whose interior this medium fills (null: the scene's medium).</summary>
        public (System.Numerics.Vector3 Min, System.Numerics.Vector3 Max)? ObjectBounds { get; init; }

        /// <summary>A required file name, resolved against the scene file's folder; it must exist.</summary>
        public string File(string key)
        {
            var name = _loader.String(_loader.Required(_e, key, _path), $"{_path}.{key}");
            var full = Path.IsPathRooted(name) ? name : Path.Combine(_loader._dir, name);
            if (!System.IO.File.Exists(full)) throw Error(key, $"file '{name}' not found", "the path is relative to the scene file");
            return full;
        }

        /// <summary>An optional box [[x, y, z], [x, y, z]] (min and max corners, scene units).</summary>
        public (System.Numerics.Vector3 Min, System.Numerics.Vector3 Max)? Box(string key)
        {
            if (!TryGet(_e, key, out var v)) return null;
            string path = $"{_path}.{key}";
            if (v.ValueKind != JsonValueKind.Array || v.GetArrayLength() != 2)
                throw _loader.Error(path, $"expected [[x, y, z], [x, y, z]], found {Kind(v)}", "the box's min and max corners");
            var (min, max) = (_loader.Vec3(v[0], $"{path}[0]"), _loader.Vec3(v[1], $"{path}[1]"));
            DensityGridReader.CheckBounds(min, max, _loader.Where(path));
            return (min, max);
        }

        /// <summary>An optional [nx, ny, nz] of positive integers.</summary>
        public int[]? Resolution(string key)
        {
            if (!TryGet(_e, key, out var v)) return null;
            string path = $"{_path}.{key}";
            if (v.ValueKind != JsonValueKind.Array || v.GetArrayLength() != 3)
                throw _loader.Error(path, $"expected [nx, ny, nz], found {Kind(v)}", "the grid's samples along x, y and z");
            return [.. Enumerable.Range(0, 3).Select(i => (int)_loader.Number(v[i], $"{path}[{i}]", 1, int.MaxValue))];
        }

        /// <summary>
        /// A coefficient spectrum's padded band values (0 when absent and not <paramref name="required"/>): every value of
        /// it finite and in [0, <paramref name="max"/>] (a coefficient per scene length unit, or an albedo).
        /// </summary>
        public float[] Coefficient(string key, bool required, double max = double.MaxValue)
        {
            if (!required && !Has(key)) return new float[SpectralMath.Padded(Grid.Count)];
            var spectrum = Spectrum(key);
            foreach (double v in spectrum.Values)
                if (!(v >= 0 && v <= max && double.IsFinite(v)))
                    throw Error(key, max < double.MaxValue ? $"the value {v} is outside [0, {max}]"
                        : $"a coefficient is {(double.IsFinite(v) ? "negative" : "not finite")} ({v})",
                        max < double.MaxValue ? "an albedo is σ_s/σ_t, between 0 and 1"
                            : "give coefficients ≥ 0 per scene length unit (m⁻¹ when a unit is a metre)");
            return Bands(spectrum, key);
        }

        /// <summary>
        /// Its "phase": { "type": "hg", "g": g } (Henyey–Greenstein, |g| &lt; 1) or { "type": "isotropic" }; isotropic when
        /// absent.
        /// </summary>
        public HenyeyGreenstein Phase()
        {
            if (!TryGet(_e, "phase", out var phase)) return new HenyeyGreenstein(0);
            string path = $"{_path}.phase";
            _loader.Object(phase, path);
            var type = TryGet(phase, "type", out var t) ? _loader.String(t, $"{path}.type").ToLowerInvariant() : "hg";
            if (type is not ("hg" or "isotropic"))
                throw _loader.Error($"{path}.type", $"unknown phase function '{type}'", "types: hg, isotropic");
            _loader.Keys(phase, path, type == "hg" ? ["type", "g"] : ["type"]);
            if (type == "isotropic") return new HenyeyGreenstein(0);
            double g = _loader.Number(phase, "g", path, 0);
            if (!(Math.Abs(g) < 1))
                throw _loader.Error($"{path}.g", $"the asymmetry g = {g} is not inside (−1, 1)",
                    "Henyey–Greenstein needs |g| < 1 (0: isotropic, 0.7–0.9: fog and haze)");
            return new HenyeyGreenstein((float)g);
        }
    }
}
