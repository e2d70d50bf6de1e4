using System.Numerics;
using System.Text;
using static SpectralRenderer.Validation.CaseScenes;

namespace SpectralRenderer.Validation;

/// <summary>
/// Luminaires: the luminous flux of a point, a spot and an IES light integrated over a closed surface around them
/// (Gauss–Legendre quadrature of the engine's illuminance), and IES LM-63 and EULUMDAT candela read back at the table's
/// angles as E·d² (the inverse-square law at normal incidence).
/// </summary>
internal static class LuminaireCases
{
    internal static IEnumerable<ValidationCase> All => [FluxPoint, FluxSpot, FluxIes, IesReadBack, EulumdatReadBack];

    const string FluxWhy = "an exact light and Gauss–Legendre quadrature of a smooth integrand (converged beyond 1e-8): only float32 "
        + "positions and directions remain";

    static string LightScene(string light) => $$"""
        { "radiometry": "physical", "bands": "380:780:40",
          "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 2, "height": 2 },
          "lights": [ {{light}} ],
          "objects": [ { "type": "sphere", "center": [0, 1000, 0], "radius": 0.001, "material": { "diffuse": 0 } } ] }
        """;

    static ValidationCase FluxPoint => new()
    {
        Name = "flux-point",
        Group = "lighting",
        Title = "a point light of 1000 lm at the centre of a 2 m cube: the illuminance integrated over each face",
        Reference = "Φ_face = ∮ E dA = Φ/6 (each face subtends 4π/6 sr of an isotropic source; E = I·cos θ/d²)",
        Source = "the definition of luminous flux (CIE S 017:2020 17-21-039) and Gauss's theorem for a closed surface",
        Tolerance = 1e-4,
        ToleranceWhy = FluxWhy,
        XLabel = "face (1 −x, 2 +x, 3 −y, 4 +y, 5 −z, 6 +z; 7 all)",
        Quantity = "luminous flux (lm)",
        Measure = context =>
        {
            const double flux = 1000;
            int n = context.Quick ? 12 : 24;
            var scene =
                Load(LightScene($$"""{ "type": "point", "position": [0, 0, 0], "spectrum": "D65", "luminous_flux": {{Light(flux)}} }"""));
            var (x, w) = Closed.GaussLegendre(n, -1, 1);
            var points = new List<(Vector3, Vector3)>();
            var weights = new List<double>();
            for (int f = 0; f < 6; f++)
            {
                int a = f / 2;
                float side = f % 2 == 0 ? -1 : 1;
                for (int i = 0; i < n; i++)
                    for (int j = 0; j < n; j++)
                    {
                        var p = new float[3];
                        p[a] = side;
                        p[(a + 1) % 3] = (float)x[i];
                        p[(a + 2) % 3] = (float)x[j];
                        var normal = new float[3];
                        normal[a] = -side;
                        points.Add((new Vector3(p[0], p[1], p[2]), new Vector3(normal[0], normal[1], normal[2])));
                        weights.Add(w[i] * w[j]);
                    }
            }
            var e = Direct(scene, points, 1, context);
            var faces = Enumerable.Range(0, 6).Select(f => Enumerable.Range(f * n * n, n * n).Sum(i => e[i].Mean * weights[i])).ToArray();
            return [.. faces.Select((v, f) => ValidationPoint.Relative(f + 1, $"face {f + 1}", flux / 6, v)),
                ValidationPoint.Relative(7, "all", flux, faces.Sum())];
        },
    };

    /// <summary>
    /// Σ over a sphere of radius 1 about the light of E·w_μ·w_φ: Gauss–Legendre in μ = cos γ on each of
    /// <paramref name="segments"/> (γ from the −y axis, in degrees) and <paramref name="phi"/> equal steps in C — the
    /// luminous flux through each segment.
    /// </summary>
    static double[] SphereFlux(Scenes.Scene scene, double[] segments, int nodes, int phi, CaseContext context)
    {
        var points = new List<(Vector3, Vector3)>();
        var weights = new List<double>();
        var segmentOf = new List<int>();
        for (int s = 0; s + 1 < segments.Length; s++)
        {
            var (g, w) = Closed.GaussLegendre(nodes, segments[s] * Math.PI / 180, segments[s + 1] * Math.PI / 180);
            for (int i = 0; i < nodes; i++)
                for (int c = 0; c < phi; c++)
                {
                    var d = Closed.TypeC((c + 0.5) * 360.0 / phi, g[i] * 180 / Math.PI);
                    points.Add((d, -d));
                    weights.Add(w[i] * Math.Sin(g[i]) * 2 * Math.PI / phi);   // dΩ = sin γ dγ dC
                    segmentOf.Add(s);
                }
        }
        var e = Direct(scene, points, 1, context);
        var flux = new double[segments.Length - 1];
        for (int i = 0; i < points.Count; i++) flux[segmentOf[i]] += e[i].Mean * weights[i];
        return flux;
    }

    static ValidationCase FluxSpot => new()
    {
        Name = "flux-spot",
        Group = "lighting",
        Title = "a spot of 1000 lm (cut-off 40°, c_spot = cos²θ) integrated over a sphere around it, inside and outside its cone",
        Reference = "∮ E dA = Φ inside the cone, 0 outside",
        Source = "the definition of luminous flux (CIE S 017:2020 17-21-039); the spot's c_spot = cos^e θ within its cut-off "
            + "(docs/scene-format.md)",
        Tolerance = 1e-4,
        ToleranceWhy = FluxWhy + "; the quadrature's segments meet at the cut-off, so the jump there is integrated exactly",
        ErrorKind = ErrorKind.Relative,
        XLabel = "segment of the angle from the axis (°)",
        Quantity = "luminous flux (lm)",
        Measure = context =>
        {
            const double flux = 1000, cutoff = 40;
            var scene = Load(LightScene($$"""
                { "type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "cutoff": {{F(cutoff)}}, "exponent": 2,
                  "spectrum": "D65", "luminous_flux": {{Light(flux)}} }
                """));
            double[] segments = [0, 10, 20, 30, cutoff, 180];
            var measured = SphereFlux(scene, segments, context.Quick ? 8 : 16, 8, context);
            // The closed form per segment: I₀·2π ∫cos²γ sin γ dγ = I₀·2π (cos³a − cos³b)/3, I₀ = Φ·3/(2π(1 − cos³θc)).
            double cc = Math.Cos(cutoff * Math.PI / 180), i0 = flux * 3 / (2 * Math.PI * (1 - cc * cc * cc));
            double Part(double a, double b)
            {
                if (a >= cutoff) return 0;
                double ca = Math.Cos(a * Math.PI / 180), cb = Math.Cos(b * Math.PI / 180);
                return i0 * 2 * Math.PI * (ca * ca * ca - cb * cb * cb) / 3;
            }
            var list = new List<ValidationPoint>();
            for (int s = 0; s + 1 < segments.Length; s++)
            {
                double expected = Part(segments[s], segments[s + 1]);
                string label = $"{Closed.Deg(segments[s])}–{Closed.Deg(segments[s + 1])}";
                list.Add(expected > 0
                    ? ValidationPoint.Relative(segments[s + 1], label, expected, measured[s])
                    : new ValidationPoint(segments[s + 1], label + " (error relative to Φ)", 0, measured[s], measured[s] / flux, null));
            }
            list.Add(ValidationPoint.Relative(360, "all", flux, measured.Sum()));
            return list;
        },
    };

    /// <summary>An axially symmetric LM-63-2002 file: absolute photometry, multiplier 1, ballast factor 1.</summary>
    static string Ies(double[] gamma, Func<double, double> candela) => $"""
        IESNA:LM-63-2002
        [TEST] spectral validate
        TILT=NONE
        1 -1 1 {gamma.Length} 1 1 2 0.1 0.1 0
        1 1 20
        {string.Join(" ", gamma.Select(F))}
        0
        {string.Join(" ", gamma.Select(g => F(candela(g))))}

        """;

    static double Downlight(double g) => 500 + 400 * Math.Cos(g * Math.PI / 180) + 150 * Math.Sin(2 * g * Math.PI / 180);

    static ValidationCase FluxIes => new()
    {
        Name = "flux-ies",
        Group = "lighting",
        Title = "an axial IES LM-63 luminaire (γ every 15°) integrated over a sphere around it, per 15° zone",
        Reference = "Φ_zone = 2π ∫ I(γ) sin γ dγ with I linear between the table's angles: 2π [−A cos γ + B (sin γ − γ cos γ)] "
            + "over each zone (I = A + Bγ)",
        Source = "IES LM-63-2002 (type C photometry); the zonal-lumen method (IES Lighting Handbook, 10th ed., §9)",
        Tolerance = 1e-4,
        ToleranceWhy = FluxWhy,
        XLabel = "zone's upper angle γ (°)",
        Quantity = "luminous flux (lm)",
        Measure = context =>
        {
            var gamma = Enumerable.Range(0, 13).Select(i => 15.0 * i).ToArray();
            using var folder = new Folder();
            folder.Write("lamp.ies", Ies(gamma, Downlight));
            var scene = Load(LightScene($$"""
                { "type": "goniometric", "position": [0, 0, 0], "file": "lamp.ies", "spectrum": "D65", "intensity": {{Light(1)}} }
                """), folder.Path);
            var measured = SphereFlux(scene, gamma, context.Quick ? 4 : 8, 4, context);
            var list = new List<ValidationPoint>();
            for (int s = 0; s + 1 < gamma.Length; s++)
            {
                double a =
                    gamma[s] * Math.PI / 180, b = gamma[s + 1] * Math.PI / 180, ia = Downlight(gamma[s]), ib = Downlight(gamma[s + 1]);
                double slope = (ib - ia) / (b - a), intercept = ia - slope * a;
                double Anti(double g) => -intercept * Math.Cos(g) + slope * (Math.Sin(g) - g * Math.Cos(g));
                list.Add(ValidationPoint.Relative(gamma[s + 1], $"{Closed.Deg(gamma[s])}–{Closed.Deg(gamma[s + 1])}",
                    2 * Math.PI * (Anti(b) - Anti(a)), measured[s]));
            }
            return list;
        },
    };

    /// <summary>A distribution with structure in C and γ, the same in every plane at the nadir and the zenith (cd).</summary>
    static double Shaped(double c, double g)
    {
        double cr = c * Math.PI / 180, gr = g * Math.PI / 180;
        return 500 + 300 * Math.Cos(gr) + 120 * Math.Sin(gr) * (1 + Math.Cos(cr)) + 40 * Math.Sin(gr) * Math.Sin(2 * cr);
    }

    /// <summary>E·d² at d = 3 m along each (C, γ), the receiver facing the light: the candela there.</summary>
    static IReadOnlyList<ValidationPoint> ReadBack(string name, string text, IReadOnlyList<(double C, double G)> angles,
        Func<double, double, double> candela, CaseContext context)
    {
        using var folder = new Folder();
        folder.Write(name, text);
        var scene = Load(LightScene($$"""
            { "type": "goniometric", "position": [0, 0, 0], "file": "{{name}}", "spectrum": "D65", "intensity": {{Light(1)}} }
            """), folder.Path);
        const float d = 3;
        var points = angles.Select(a => { var v = Closed.TypeC(a.C, a.G); return (v * d, -v); }).ToList();
        var e = Direct(scene, points, 1, context);
        return [.. angles.Select((a, i) => ValidationPoint.Relative(i, $"C {Closed.Deg(a.C)} γ {Closed.Deg(a.G)}",
            candela(a.C, a.G), e[i].Mean * d * d))];
    }

    static ValidationCase IesReadBack => new()
    {
        Name = "ies-readback",
        Group = "lighting",
        Title = "a full IES LM-63 table (C every 45°, γ every 30°): the candela read back as E·d² at 3 m along each table angle",
        Reference = "I(C, γ) = E·d² at normal incidence (the table's own values; type C frame: γ from the nadir, C = 0 towards +x, "
            + "C = 90° towards −z)",
        Source = "IES LM-63-2002 §5 (type C photometry); CIE 121-1996 (photometry of luminaires)",
        Tolerance = 1e-4,
        ToleranceWhy = "the table's angles are read exactly (no interpolation); an exact light and one shadow ray per point",
        XLabel = "table angle (index, C fastest within γ)",
        Quantity = "luminous intensity (cd)",
        Measure = context =>
        {
            var c = Enumerable.Range(0, 9).Select(i => 45.0 * i).ToArray();
            var g = Enumerable.Range(0, 7).Select(i => 30.0 * i).ToArray();
            var text = new StringBuilder(
                $"IESNA:LM-63-2002\n[TEST] spectral validate\nTILT=NONE\n1 -1 1 {g.Length} {c.Length} 1 2 0.1 0.1 0\n1 1 20\n")
                .Append(string.Join(" ", g.Select(F))).Append('\n').Append(string.Join(" ", c.Select(F))).Append('\n');
            foreach (var h in c) text.Append(string.Join(" ", g.Select(v => F(Shaped(h, v))))).Append('\n');
            var angles = g.SelectMany(v => c.Take(c.Length - 1).Select(h => (h, v))).ToList();
            return ReadBack("table.ies", text.ToString(), angles, Shaped, context);
        },
    };

    static ValidationCase EulumdatReadBack => new()
    {
        Name = "eulumdat-readback",
        Group = "lighting",
        Title = "an EULUMDAT table (Isym 0: C every 30°, γ every 15°, cd/klm of 2000 lm): the candela read back as E·d² at 3 m",
        Reference = "I(C, γ) = value (cd/klm) × 2000 lm/1000 × CFLI 1 = E·d² at normal incidence",
        Source = "EULUMDAT (Stockmar 1990: the format's Isym, Mc, Dc, Ng, Dg fields and cd/klm values); CIE 121-1996",
        Tolerance = 1e-4,
        ToleranceWhy = "the table's angles are read exactly (no interpolation); an exact light and one shadow ray per point",
        XLabel = "table angle (index, C fastest within γ)",
        Quantity = "luminous intensity (cd)",
        Measure = context =>
        {
            int mc = 12, ng = 13;
            var c = Enumerable.Range(0, mc).Select(i => i * 30.0).ToArray();
            var g = Enumerable.Range(0, ng).Select(i => i * 15.0).ToArray();
            var sb = new StringBuilder();
            foreach (var l in new[] { "spectral validate", "1", "0", $"{mc}", "30", $"{ng}", "15", "report", "luminaire", "0", "t.ldt",
                         "today", "100", "100", "50", "100", "100", "0", "0", "0", "0", "100", "80", "1", "0", "1", "1", "LED", "2000",
                         "4000K", "80", "20" })
                sb.Append(l).Append('\n');
            for (int i = 0; i < 10; i++) sb.Append("0.5\n");
            foreach (var x in c) sb.Append(F(x)).Append('\n');
            foreach (var x in g) sb.Append(F(x)).Append('\n');
            foreach (var h in c) foreach (var v in g) sb.Append(F(Shaped(h, v) / 2)).Append('\n');   // cd/klm of 2000 lm
            var angles = g.SelectMany(v => c.Select(h => (h, v))).ToList();
            return ReadBack("table.ldt", sb.ToString(), angles, Shaped, context);
        },
    };
}
