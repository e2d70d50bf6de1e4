using System.Text.Json;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Loading;

// The integrator a scene asks for and its settings, and what a surface emits (area lights).
public sealed partial class SceneLoader
{
    /// <summary>
    /// "integrator": a registered name or { "type": name, "max_depth": N, "rr_depth": N, "spectral_grid": nm,
    /// "sampler": "sobol" | "independent", "seed": N, "light_tree": true | false }: every key an integrator's settings may have is read
    /// here; the name, and the keys given against the keys its registration takes, are checked when the render is built (RenderJob).
    /// </summary>
    IntegratorSettings? ParseIntegrator(JsonElement root)
    {
        if (!TryGet(root, "integrator", out var e)) return null;
        const string path = "$.integrator";
        if (e.ValueKind == JsonValueKind.String) return new IntegratorSettings(String(e, path).ToLowerInvariant());
        if (e.ValueKind != JsonValueKind.Object)
            throw Error(path, $"expected a name or an object, found {Kind(e)}",
                "e.g. \"integrator\": \"path\" or { \"type\": \"path\", \"max_depth\": 8 }");
        Keys(e, path, "type", "max_depth", "rr_depth", "spectral_grid", "sampler", "seed", "light_tree");
        var name = String(Required(e, "type", path), $"{path}.type").ToLowerInvariant();
        int maxDepth = Integer(e, "max_depth", path, -1, -1, 1_000_000);
        int rrDepth = Integer(e, "rr_depth", path, IntegratorSettings.DefaultRrDepth, 0, 1_000_000);
        // The internal grid: every output band split into equal sub-bands of at most this width (1 nm allowed); without
        // the key, the default width's sub-bands placed where the scene's spectra need them (IntegratorSettings.AdaptiveGrid).
        double grid = Number(e, "spectral_grid", path, IntegratorSettings.DefaultSpectralGrid, 1, 1000);
        SamplerKind? sampler = null;
        if (TryGet(e, "sampler", out var se))
        {
            var text = String(se, $"{path}.sampler");
            if (!Samplers.TryParse(text, out var kind))
                throw Error($"{path}.sampler", $"unknown sampler '{text}'",
                    InputException.DidYouMean(text, Samplers.Names) ?? $"samplers: {string.Join(", ", Samplers.Names)}");
            sampler = kind;
        }
        // The seed changes every random number (independent renders of the same scene); 0 is the default's.
        uint seed = (uint)Integer(e, "seed", path, 0, 0, int.MaxValue);
        // A light tree among many emitters: absent, the path tracer's rule (by their number); true or false forces it.
        bool? lightTree = TryGet(e, "light_tree", out _) ? Bool(e, "light_tree", path, false) : null;
        var given = e.EnumerateObject().Where(p => p.Name != "type").Select(p => (p.Name, Where($"{path}.{p.Name}"))).ToArray();
        return new IntegratorSettings(name, maxDepth, rrDepth, grid, sampler, seed, lightTree)
        {
            Keys = given,
            AdaptiveGrid = !TryGet(e, "spectral_grid", out _),
        };
    }

    /// <summary>
    /// A material's "emission": { "spectrum": …, "radiance": k, "two_sided": false } — spectral radiance spectrum × k in
    /// W·m⁻²·sr⁻¹·nm⁻¹, physical radiometry only; or "luminance": cd/m² instead of "radiance", k = L_v/(K_m ∫V·S dλ); or
    /// "luminous_flux": lm, the total flux of the objects made of the material (<see cref="ScaleFluxEmission"/>).
    /// </summary>
    Emission? ParseEmission(JsonElement material, string materialPath)
    {
        if (!TryGet(material, "emission", out var e)) return null;
        string path = $"{materialPath}.emission";
        Object(e, path);
        Keys(e, path, "spectrum", "radiance", "luminance", "luminous_flux", "two_sided");
        if (_radiometry != Radiometry.Physical)
            throw Error(path, "emission is a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) and needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene (and render it with \"integrator\": \"path\")");
        var spectrum = Spectrum(Required(e, "spectrum", path), $"{path}.spectrum");
        bool twoSided = Bool(e, "two_sided", path, false);
        if (TryGet(e, "luminous_flux", out _))
        {
            if (_pendingTextures.ContainsKey($"{path}.spectrum"))
                throw Error($"{path}.luminous_flux",
                    "a textured emission is scaled by \"radiance\" or \"luminance\" (of the texture's mean), not by luminous_flux",
                    "give \"radiance\": k (the texels' multiplier) or \"luminance\": cd/m²");
            foreach (var other in new[] { "radiance", "luminance" })
                if (TryGet(e, other, out _))
                    throw Error($"{path}.luminous_flux", $"both {other} and luminous_flux are given",
                        "give one: luminous_flux (lm) sets the radiance");
            double flux = Number(e, "luminous_flux", path, 0, 0);
            double luminous = Color.Photometry.Luminous(spectrum);
            if (!(luminous > 0))
                throw Error($"{path}.spectrum",
                    $"spectrum '{spectrum.Name}' emits no visible light (∫V·S dλ = 0), so luminous_flux cannot scale it",
                    "give \"radiance\" (radiometric) for an invisible emitter");
            _fluxEmissions.Add((materialPath, flux, luminous, spectrum, twoSided));
            return new Emission(Bands(spectrum, $"{path}.spectrum"), twoSided);   // scaled once the objects' area is known
        }
        double k = Luminance(e, path, spectrum) ?? Number(e, "radiance", path, 1, 0);
        var radiance = Bands(spectrum.Scaled(k), $"{path}.spectrum");
        return new Emission(radiance, twoSided) { Texture = EmissionTexture(path, k) };   // issue 26: SceneLoader.Textures.cs
    }

    /// <summary>Emissions given by luminous flux: the material's path, Φ_v (lm), K_m∫V·S dλ, the spectrum and its sides.</summary>
    readonly List<(string Path, double Flux, double Luminous, Spectra.TabulatedSpectrum Spectrum, bool TwoSided)> _fluxEmissions = [];

    /// <summary>
    /// Gives each emission set by "luminous_flux" its radiance: a Lambertian emitter of luminance L_v sends π·L_v·A lm
    /// from each emitting side of area A, so L_v = Φ_v/(π·A·sides) over the total area A of the objects made of the
    /// material (<see cref="SurfaceArea"/>), and k = L_v/(K_m ∫V·S dλ) on the spectrum.
    /// </summary>
    void ScaleFluxEmission(List<Material> materials, Dictionary<string, int> materialIndex, List<SceneObject> objects)
    {
        foreach (var (path, flux, luminous, spectrum, twoSided) in _fluxEmissions)
        {
            const string Named = "$.materials.";
            if (!path.StartsWith(Named, StringComparison.Ordinal) || !materialIndex.TryGetValue(path[Named.Length..], out int m))
                throw Error($"{path}.emission.luminous_flux", "luminous_flux is the flux of every object of a named material",
                    "define the material under \"materials\" and name it in the objects, or use \"luminance\" (cd/m²)");
            string name = path[Named.Length..];
            // A scene loaded without its meshes' triangles (relighting reads lights only): no area, nothing rendered.
            if (objects.Any(o => o.Material == m && o.Mesh is null && o.Shape is null)) continue;
            double area = 0;
            foreach (var o in objects)
                if (o.Material == m) area += SurfaceArea(o);
            if (!(area > 0))
                throw Error($"{path}.emission.luminous_flux", $"no object of material '{name}' has an area to send {flux} lm from",
                    "give the material to a sphere, quad, box or mesh, or use \"luminance\" (cd/m²)");
            double k = flux / (Math.PI * area * (twoSided ? 2 : 1)) / luminous;
            materials[m].Emission = new Emission(Bands(spectrum.Scaled(k), $"{path}.emission.spectrum"), twoSided);
        }
    }

    /// <summary>
    /// The area (m²) of an object's surface as the path tracer's emitter samples it: a sphere 4πr², a quad |m·x × m·y|
    /// of its unit square, a box its six faces, a registered kind its own (disk, cylinder), a mesh Σ ½|e₁ × e₂| over its
    /// triangles; an infinite plane 0.
    /// </summary>
    static double SurfaceArea(SceneObject o)
    {
        if (o.Mesh is { } mesh)
        {
            double sum = 0;
            for (int t = 0; t < mesh.TriangleCount; t++)
            {
                var (p0, p1, p2) = mesh.Triangle(t);
                sum += 0.5 * System.Numerics.Vector3.Cross(p1 - p0, p2 - p0).Length();
            }
            return sum;
        }
        var shape = o.Shape!;
        var m = shape.ObjectToWorld;
        System.Numerics.Vector3 X = System.Numerics.Vector3.TransformNormal(System.Numerics.Vector3.UnitX, m),
            Y = System.Numerics.Vector3.TransformNormal(System.Numerics.Vector3.UnitY, m),
            Z = System.Numerics.Vector3.TransformNormal(System.Numerics.Vector3.UnitZ, m);
        double Face(System.Numerics.Vector3 u, System.Numerics.Vector3 v) => System.Numerics.Vector3.Cross(u, v).Length();
        return shape.Kind switch
        {
            Geometry.ShapeKind.Sphere => 4 * Math.PI * X.LengthSquared(),
            Geometry.ShapeKind.Quad => Face(X, Y),
            Geometry.ShapeKind.Box => 2 * (Face(X, Y) + Face(Y, Z) + Face(Z, X)),
            Geometry.ShapeKind.Registered => shape.Area,
            _ => 0,
        };
    }

    /// <summary>
    /// A radiance given as "luminance" (cd/m²) in <paramref name="e"/>: the factor k on <paramref name="spectrum"/> whose
    /// K_m ∫V·(k·S) dλ is it (683 lm/W, CIE 1924 V), or null when the key is absent; with "radiance" too, an error.
    /// </summary>
    double? Luminance(JsonElement e, string path, Spectra.TabulatedSpectrum spectrum)
    {
        if (!TryGet(e, "luminance", out _)) return null;
        if (TryGet(e, "radiance", out _))
            throw Error($"{path}.luminance", "both radiance and luminance are given", "give one: luminance (cd/m²) sets the radiance");
        double value = Number(e, "luminance", path, 0, 0);
        double luminous = Color.Photometry.Luminous(spectrum);
        if (!(luminous > 0))
            throw Error($"{path}.spectrum",
                $"spectrum '{spectrum.Name}' emits no visible light (∫V·S dλ = 0), so luminance cannot scale it",
                "give \"radiance\" (radiometric) for an invisible emitter");
        return value / luminous;
    }

    /// <summary>
    /// "background": a spectrum (radiance of escaping rays), or { "spectrum": …, "luminance": cd/m² } — a uniform sky of that
    /// luminance (physical radiometry).
    /// </summary>
    float[] ParseBackground(JsonElement bg)
    {
        const string path = "$.background";
        if (bg.ValueKind != JsonValueKind.Object || !TryGet(bg, "luminance", out _)) return Bands(bg, path);
        Keys(bg, path, "spectrum", "luminance");
        if (_radiometry != Radiometry.Physical)
            throw Error($"{path}.luminance", "luminance (cd/m²) needs physical radiometry",
                "add \"radiometry\": \"physical\" to the scene, or give the background as a spectrum");
        var spectrum = Spectrum(Required(bg, "spectrum", path), $"{path}.spectrum");
        return Bands(spectrum.Scaled(Luminance(bg, path, spectrum)!.Value), $"{path}.spectrum");
    }
}
