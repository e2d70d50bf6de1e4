using System.Numerics;
using static SpectralRenderer.Validation.CaseScenes;

namespace SpectralRenderer.Validation;

/// <summary>
/// CIE 171:2006-style direct lighting (test cases of the kind "point light source" and "area light source", and sky
/// components): a point source over a plane out to grazing angles, Lambertian rectangles parallel and perpendicular to
/// the plane by their form factors, and a uniform and a CIE overcast sky on horizontal and vertical planes and through a
/// roof opening and a window — each illuminance the engine's (<see cref="Rendering.Illumination.Illuminance.Direct"/>), each reference
/// in closed form.
/// </summary>
internal static class LightingCases
{
    const double Sampled = 0.005;
    const string SampledWhy = "the issue's bar for the CIE 171 cases: within 0.5 % and within 3σ of the sampled estimate";

    internal static IEnumerable<ValidationCase> All =>
        [PointOverPlane, RectangleParallel, RectanglePerpendicular, SkyHorizontal, SkyVertical, SkyRoofOpening, SkyWindow,
            OvercastHorizontal, OvercastVertical, OvercastRoofOpening, OvercastWindow];

    static ValidationCase PointOverPlane => new()
    {
        Name = "point-plane",
        Group = "lighting",
        Title = "a 1000 cd point source 2 m above a horizontal plane: illuminance from the nadir out to 89°",
        Reference = "E = I·cos³θ/h² (the inverse-square law with the cosine of incidence, d = h/cos θ)",
        Source = "CIE 171:2006 test case 5.1 (point light source); CIE S 017:2020 17-21-050 (illuminance)",
        Tolerance = 1e-4,
        ToleranceWhy = "an exact light and one shadow ray per point: only float32 positions and directions remain (cos 89° = 0.017 "
            + "keeps 5 digits)",
        XLabel = "angle from the nadir θ (°)",
        Quantity = "illuminance (lx)",
        Measure = context =>
        {
            const double h = 2, intensity = 1000;
            double[] angles = context.Quick
                ? [0, 15, 30, 45, 60, 75, 85, 88]
                : [.. Enumerable.Range(0, 18).Select(i => 5.0 * i), 86, 87, 88, 89];
            var scene = Load($$"""
                { "radiometry": "physical", "bands": "380:780:40",
                  "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 2, "height": 2 },
                  "lights": [ { "type": "point", "position": [0, {{F(h)}}, 0], "spectrum": "D65",
                                "luminous_intensity": {{Light(intensity)}} } ],
                  "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": { "diffuse": 0 } } ] }
                """);
            var points = angles.Select(a => (new Vector3((float)(h * Math.Tan(a * Math.PI / 180)), 0, 0), Vector3.UnitY)).ToList();
            var e = Direct(scene, points, 1, context);
            return [.. angles.Select((a, i) =>
            {
                double c = Math.Cos(a * Math.PI / 180);
                return ValidationPoint.Relative(a, Closed.Deg(a), intensity * c * c * c / (h * h), e[i].Mean);
            })];
        },
    };

    /// <summary>A Lambertian rectangle of luminance L: E = L·∫cos θ dω (its form factor × πL) at points of the floor.</summary>
    static ValidationCase Rectangle(string name, string title, Vector3 centre, Vector3 normal, Vector3 up, double width, double height,
        Func<double, Vector3> at, string xLabel, double[] full, double[] quick) => new()
        {
            Name = name,
            Group = "lighting",
            Title = title,
            Reference = "E = L·∫cos θ dω = L·½|Σ Γ_i n·(v_i × v_{i+1})/|v_i × v_{i+1}|| (Lambert's polygon formula: π·L·F_dA→A)",
            Source = "CIE 171:2006 test case 5.2 (area light source); Lambert's formula for the configuration factor of a "
            + "differential area to a polygon (Howell, Mengüç & Siegel, Thermal Radiation Heat Transfer)",
            Tolerance = Sampled,
            ToleranceWhy = SampledWhy,
            XLabel = xLabel,
            Quantity = "illuminance (lx)",
            Statistical = true,
            Measure = context =>
            {
                const double luminance = 1000;
                var xs = context.Quick ? quick : full;
                var scene = Load($$"""
                { "radiometry": "physical", "bands": "380:780:40",
                  "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 2, "height": 2, "spp": 4096 },
                  "materials": { "panel": { "type": "lambertian", "reflectance": 0,
                                            "emission": { "spectrum": "D65", "luminance": {{Light(luminance)}} } } },
                  "objects": [ { "type": "quad", "center": {{V(centre)}}, "size": [{{F(width)}}, {{F(height)}}],
                                 "normal": {{V(normal)}}, "up": {{V(up)}}, "material": "panel" } ] }
                """);
                var right = Vector3.Normalize(Vector3.Cross(up, normal));
                var corners = Closed.Rectangle(centre, right, up, width, height);
                var points = xs.Select(x => (at(x), Vector3.UnitY)).ToList();
                var e = Direct(scene, points, context.Quick ? 64 : 256, context);
                return [.. xs.Select((x, i) => ValidationPoint.Relative(x, $"{F(x)} m",
                luminance * Closed.ProjectedSolidAngle(points[i].Item1, Vector3.UnitY, corners), e[i].Mean, e[i].Sigma))];
            },
        };

    static ValidationCase RectangleParallel => Rectangle("rectangle-parallel",
        "a Lambertian 2 m × 1 m panel of 1000 cd/m² facing down 1 m above the floor: illuminance along the floor",
        new Vector3(0, 1, 0), -Vector3.UnitY, Vector3.UnitZ, 2, 1, x => new Vector3((float)x, 0, 0.25f),
        "distance along the floor from below the panel's centre (m)",
        [0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 2, 2.5, 3], [0, 0.5, 1, 1.5, 2.5]);

    static ValidationCase RectanglePerpendicular => Rectangle("rectangle-perpendicular",
        "a Lambertian 2 m × 1 m panel of 1000 cd/m² standing on the floor, facing along it: illuminance on the floor in front",
        new Vector3(0, 0.5f, 0), Vector3.UnitZ, Vector3.UnitY, 2, 1, z => new Vector3(0.5f, 0, (float)z),
        "distance along the floor from the panel (m)",
        [0.25, 0.5, 0.75, 1, 1.5, 2, 3], [0.25, 0.5, 1, 2]);

    /// <summary>A uniform sky of luminance L (the scene's background), or the CIE overcast sky of zenith luminance L_z
    /// (a daylight sky of 6504 K, its "distribution" "cie-overcast"), over a black ground plane.</summary>
    static string Sky(double luminance, int spp, string objects, bool overcast = false) => $$"""
        { "radiometry": "physical", "bands": "380:780:40",
          {{(overcast ? OvercastSky(luminance) : $"\"background\": {{ \"spectrum\": \"D65\", \"luminance\": {Light(luminance)} }},")}}
          "camera": { "position": [0, 5, 9], "look_at": [0, 0, 0], "width": 2, "height": 2, "spp": {{spp}} },
          "materials": { "black": { "diffuse": 0 } },
          "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "black" }{{objects}} ] }
        """;

    /// <summary>"sky": the CIE overcast daylight sky (6504 K) of zenith luminance <paramref name="zenith"/>.</summary>
    static string OvercastSky(double zenith) =>
        $"\"sky\": {{ \"type\": \"daylight\", \"cct\": 6504, \"luminance\": {Light(zenith)}, \"distribution\": \"cie-overcast\" }},";

    /// <summary>A sky component case: illuminance (lx) at free points, sampled (the 0.5 % bar and 3σ).</summary>
    static ValidationCase SkyCase(string name, string title, string reference, string source, string xLabel,
        Func<CaseContext, IReadOnlyList<ValidationPoint>> measure) => new()
        {
            Name = name,
            Group = "lighting",
            Title = title,
            Reference = reference,
            Source = source,
            Tolerance = Sampled,
            ToleranceWhy = SampledWhy,
            XLabel = xLabel,
            Quantity = "illuminance (lx)",
            Statistical = true,
            Measure = measure,
        };

    const double SkyLuminance = 5000;

    static ValidationCase SkyHorizontal => SkyCase("sky-horizontal",
        "a uniform sky of 5000 cd/m²: illuminance on the open ground",
        "E = π·L (∫cos θ dω over the upper hemisphere = π)",
        "CIE 171:2006 (sky component of a uniform sky on an unobstructed horizontal plane); CIE 110-1994 (uniform sky)",
        "point along the ground (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 256, ""));
            double[] xs = [0, 1, 5, 20];
            var e = Direct(scene, [.. xs.Select(x => (new Vector3((float)x, 0, 0), Vector3.UnitY))], 8, context);
            return [.. xs.Select((x, i) => ValidationPoint.Relative(x, $"{F(x)} m", Math.PI * SkyLuminance, e[i].Mean, e[i].Sigma))];
        });

    static ValidationCase SkyVertical => SkyCase("sky-vertical",
        "a uniform sky of 5000 cd/m² over black ground: illuminance on vertical planes facing the four horizons",
        "E = π·L/2 (the sky fills the upper half of a vertical plane's hemisphere, which holds half its ∫cos θ dω)",
        "CIE 171:2006 (sky component on a vertical plane); CIE 110-1994 (uniform sky)",
        "azimuth of the plane's normal (°)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, ""));
            double[] azimuths = [0, 90, 180, 270];
            var points = azimuths.Select(a => (new Vector3(0, 1, 0),
                new Vector3((float)Math.Cos(a * Math.PI / 180), 0, (float)Math.Sin(a * Math.PI / 180)))).ToList();
            var e = Direct(scene, points, context.Quick ? 128 : 256, context);
            return [.. azimuths.Select((a, i) =>
                ValidationPoint.Relative(a, Closed.Deg(a), Math.PI * SkyLuminance / 2, e[i].Mean, e[i].Sigma))];
        });

    // A closed black room 6 m × 6 m × 2 m (x, z ∈ [−3, 3], y ∈ [0, 2]) on the black ground.
    static string Quad(Vector3 centre, double w, double h, Vector3 normal, Vector3 up) =>
        $$""", { "type": "quad", "center": {{V(centre)}}, "size": [{{F(w)}}, {{F(h)}}], "normal": {{V(normal)}}, "up": {{V(up)}},"""
            + """ "material": "black" }""";

    static string Walls(bool north) =>
        Quad(new(-3, 1, 0), 6, 2, Vector3.UnitX, Vector3.UnitY) + Quad(new(3, 1, 0), 6, 2, -Vector3.UnitX, Vector3.UnitY)
        + Quad(new(0, 1, 3), 6, 2, -Vector3.UnitZ, Vector3.UnitY)
        + (north ? Quad(new(0, 1, -3), 6, 2, Vector3.UnitZ, Vector3.UnitY) : "");

    /// <summary>The room's roof (y = 2) around a 3 m × 3 m opening x, z ∈ [−1.5, 1.5].</summary>
    static string Roof => Quad(new(-2.25f, 2, 0), 1.5, 6, -Vector3.UnitY, Vector3.UnitZ)
        + Quad(new(2.25f, 2, 0), 1.5, 6, -Vector3.UnitY, Vector3.UnitZ)
        + Quad(new(0, 2, -2.25f), 3, 1.5, -Vector3.UnitY, Vector3.UnitZ)
        + Quad(new(0, 2, 2.25f), 3, 1.5, -Vector3.UnitY, Vector3.UnitZ);

    /// <summary>The north wall (z = −3) around a window x ∈ [−1.5, 1.5], y ∈ [0.5, 1.75]; the roof closed.</summary>
    static string WindowWall => Quad(new(-2.25f, 1, -3), 1.5, 2, Vector3.UnitZ, Vector3.UnitY)
        + Quad(new(2.25f, 1, -3), 1.5, 2, Vector3.UnitZ, Vector3.UnitY)
        + Quad(new(0, 0.25f, -3), 3, 0.5, Vector3.UnitZ, Vector3.UnitY)
        + Quad(new(0, 1.875f, -3), 3, 0.25, Vector3.UnitZ, Vector3.UnitY)
        + Quad(new(0, 2, 0), 6, 6, -Vector3.UnitY, Vector3.UnitZ);

    static ValidationCase SkyRoofOpening => SkyCase("sky-roof-opening",
        "a closed black room 6 m × 6 m × 2 m with a 3 m × 3 m opening in its roof under a uniform sky: illuminance on "
            + "the floor",
        "E = L·∫cos θ dω of the opening (Lambert's polygon formula): the sky component of a uniform sky",
        "CIE 171:2006 (sky component through an unglazed opening in a roof); Lambert's polygon formula",
        "distance along the floor from below the opening's centre (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, Walls(true) + Roof));
            double[] xs = context.Quick ? [0, 1.25, 2.5] : [0, 0.5, 1, 1.5, 2, 2.5];
            var opening = Closed.Rectangle(new(0, 2, 0), Vector3.UnitX, Vector3.UnitZ, 3, 3);
            var points = xs.Select(x => (new Vector3((float)x, 0, 0.4f), Vector3.UnitY)).ToList();
            var e = Direct(scene, points, context.Quick ? 256 : 512, context);
            return [.. xs.Select((x, i) => ValidationPoint.Relative(x, $"{F(x)} m",
                SkyLuminance * Closed.ProjectedSolidAngle(points[i].Item1, Vector3.UnitY, opening), e[i].Mean, e[i].Sigma))];
        });

    static ValidationCase SkyWindow => SkyCase("sky-window",
        "the same room closed at the top with a 3 m × 1.25 m window in its north wall: illuminance on the floor",
        "E = L·∫cos θ dω of the window (Lambert's polygon formula): the sky component of a uniform sky",
        "CIE 171:2006 (sky component through an unglazed vertical opening); Lambert's polygon formula",
        "distance along the floor from the window wall (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, Walls(false) + WindowWall));
            double[] ds = context.Quick ? [0.5, 1, 2] : [0.25, 0.5, 1, 1.5, 2, 2.5];
            var window = Closed.Rectangle(new(0, 1.125f, -3), Vector3.UnitX, Vector3.UnitY, 3, 1.25);
            var points = ds.Select(d => (new Vector3(0.3f, 0, (float)(d - 3)), Vector3.UnitY)).ToList();
            var e = Direct(scene, points, context.Quick ? 512 : 1024, context);
            return [.. ds.Select((d, i) => ValidationPoint.Relative(d, $"{F(d)} m",
                SkyLuminance * Closed.ProjectedSolidAngle(points[i].Item1, Vector3.UnitY, window), e[i].Mean, e[i].Sigma))];
        });

    const string OvercastSource = "CIE S 011/E:2003 (ISO 15469:2004) sky type 1, the CIE standard overcast sky in its traditional "
        + "form (Moon & Spencer 1942)";

    static ValidationCase OvercastHorizontal => SkyCase("overcast-horizontal",
        "a CIE overcast sky of zenith luminance 5000 cd/m²: illuminance on the open ground",
        "E = L_z·∫(1 + 2 cos θ)/3·cos θ dω = (7π/9)·L_z",
        OvercastSource + "; CIE 171:2006 (sky component on an unobstructed horizontal plane)",
        "point along the ground (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 4096, "", overcast: true));
            double[] xs = [0, 1, 5, 20];
            var e = Direct(scene, [.. xs.Select(x => (new Vector3((float)x, 0, 0), Vector3.UnitY))], context.Quick ? 32 : 64, context);
            return [.. xs.Select((x, i) =>
                ValidationPoint.Relative(x, $"{F(x)} m", Closed.OvercastHorizontal * SkyLuminance, e[i].Mean, e[i].Sigma))];
        });

    static ValidationCase OvercastVertical => SkyCase("overcast-vertical",
        "a CIE overcast sky of zenith luminance 5000 cd/m² over black ground: illuminance on vertical planes facing the "
            + "four horizons",
        "E = L_z·∫(1 + 2 cos θ)/3·sin θ cos φ dω over the sky in front of the plane = (π/6 + 4/9)·L_z",
        OvercastSource + "; CIE 171:2006 (sky component on a vertical plane)",
        "azimuth of the plane's normal (°)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, "", overcast: true));
            double[] azimuths = [0, 90, 180, 270];
            var points = azimuths.Select(a => (new Vector3(0, 1, 0),
                new Vector3((float)Math.Cos(a * Math.PI / 180), 0, (float)Math.Sin(a * Math.PI / 180)))).ToList();
            var e = Direct(scene, points, context.Quick ? 128 : 256, context);
            return [.. azimuths.Select((a, i) =>
                ValidationPoint.Relative(a, Closed.Deg(a), Closed.OvercastVertical * SkyLuminance, e[i].Mean, e[i].Sigma))];
        });

    static ValidationCase OvercastRoofOpening => SkyCase("overcast-roof-opening",
        "the closed black room with the 3 m × 3 m roof opening under a CIE overcast sky of zenith luminance 5000 cd/m²: "
            + "illuminance on the floor",
        "E = L_z/3·∫∫(h²/r⁴ + 2h³/r⁵) dA over the opening at height h, in closed form per corner rectangle: "
            + "½[a/√(a²+h²)·atan(b/√(a²+h²)) + b/√(b²+h²)·atan(a/√(b²+h²))] + ⅔[Ω + h·ab(a²+b²+2h²)/(R(a²+h²)(b²+h²))], "
            + "Ω = atan(ab/(hR)), R = √(a²+b²+h²)",
        OvercastSource + "; CIE 171:2006 (sky component through an unglazed opening in a roof)",
        "distance along the floor from below the opening's centre (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, Walls(true) + Roof, overcast: true));
            double[] xs = context.Quick ? [0, 1.25, 2.5] : [0, 0.5, 1, 1.5, 2, 2.5];
            var points = xs.Select(x => (new Vector3((float)x, 0, 0.4f), Vector3.UnitY)).ToList();
            var e = Direct(scene, points, context.Quick ? 256 : 512, context);
            return [.. xs.Select((x, i) =>
            {
                var p = points[i].Item1;
                double expected = SkyLuminance * Closed.OvercastRoof(2, -1.5 - p.X, 1.5 - p.X, -1.5 - p.Z, 1.5 - p.Z);
                return ValidationPoint.Relative(x, $"{F(x)} m", expected, e[i].Mean, e[i].Sigma);
            })];
        });

    static ValidationCase OvercastWindow => SkyCase("overcast-window",
        "the room closed at the top with the 3 m × 1.25 m window in its north wall under a CIE overcast sky of zenith "
            + "luminance 5000 cd/m²: illuminance on the floor",
        "E = L_z/3·∫dφ [s²/2 + 2s³/3] from s(y0) to s(y1), s(y) = y·cos φ/√(d² + y²cos²φ) the sine of the "
            + "elevation of the window's edges at azimuth φ (the inner integral exact, the outer by 64-point Gauss–Legendre)",
        OvercastSource + "; CIE 171:2006 (sky component through an unglazed vertical opening)",
        "distance along the floor from the window wall (m)",
        context =>
        {
            var scene = Load(Sky(SkyLuminance, 8192, Walls(false) + WindowWall, overcast: true));
            double[] ds = context.Quick ? [0.5, 1, 2] : [0.25, 0.5, 1, 1.5, 2, 2.5];
            var points = ds.Select(d => (new Vector3(0.3f, 0, (float)(d - 3)), Vector3.UnitY)).ToList();
            var e = Direct(scene, points, context.Quick ? 512 : 1024, context);
            return [.. ds.Select((d, i) =>
            {
                var p = points[i].Item1;
                double expected = SkyLuminance * Closed.SkyWindow(p.Z + 3, -1.5 - p.X, 1.5 - p.X, 0.5, 1.75, overcast: true);
                return ValidationPoint.Relative(d, $"{F(d)} m", expected, e[i].Mean, e[i].Sigma);
            })];
        });
}
