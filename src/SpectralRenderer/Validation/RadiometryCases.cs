using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using static SpectralRenderer.Validation.CaseScenes;

namespace SpectralRenderer.Validation;

/// <summary>
/// Radiometry and light transport, per band, from camera rays the case aims itself (<see cref="IIntegrator.Radiance"/>):
/// the white furnace, Fresnel furnaces (a smooth glass sphere, a dispersive one), the inverse-square law, a conductor at
/// normal incidence from n and k, and dispersion by Snell's law with a Sellmeier index through a thick slab.
/// </summary>
internal static class RadiometryCases
{
    internal static IEnumerable<ValidationCase> All => [WhiteFurnace, FresnelFurnace, DispersiveFurnace, InverseSquare, Conductor, Snell];

    /// <summary>Schott N-BK7's Sellmeier coefficients (λ in µm; C in µm²), from Schott's data sheet.</summary>
    static readonly double[] B = [1.03961212, 0.231792344, 1.01046945], C = [0.00600069867, 0.0200179144, 103.560653];

    const string Bk7 = "{ \"sellmeier\": { \"B1\": 1.03961212, \"B2\": 0.231792344, \"B3\": 1.01046945, "
        + "\"C1\": 0.00600069867, \"C2\": 0.0200179144, \"C3\": 103.560653 } }";

    /// <summary>n(λ) of N-BK7: n² = 1 + Σ B_i λ²/(λ² − C_i) (Sellmeier 1871; Schott's coefficients).</summary>
    static double SellmeierBk7(double nm)
    {
        double l2 = nm * nm * 1e-6, n2 = 1;
        for (int i = 0; i < 3; i++) n2 += B[i] * l2 / (l2 - C[i]);
        return Math.Sqrt(n2);
    }

    /// <summary>The unpolarised Fresnel reflectance of a dielectric interface from index 1 to n at incidence θ (Snell's
    /// law for cos θ_t; Born &amp; Wolf §1.5.2).</summary>
    static double FresnelR(double n, double cosI)
    {
        double sinT2 = (1 - cosI * cosI) / (n * n), cosT = Math.Sqrt(1 - sinT2);
        double rs = (cosI - n * cosT) / (cosI + n * cosT), rp = (cosT - n * cosI) / (cosT + n * cosI);
        return (rs * rs + rp * rp) / 2;
    }

    /// <summary>Camera rays the case aims: per band, the mean radiance over <paramref name="rays"/> and its standard error.</summary>
    static (double Mean, double Sigma)[] Radiance(Scene scene, string integratorName, Func<int, Ray> ray, int rays, CaseContext context)
    {
        var integrator = Integrators.Create(scene, new SceneGeometry(scene), integratorName);
        int bands = scene.Bands;
        var sum = new double[bands];
        var sum2 = new double[bands];
        var sync = new object();
        var options =
            new ParallelOptions { MaxDegreeOfParallelism = context.Threads > 0 ? context.Threads : -1, CancellationToken = context.Cancel };
        Parallel.For(0, (rays + 255) / 256, options, block =>
        {
            var result = new float[scene.PaddedBands];
            var scratch = new float[integrator.ScratchLength];
            var counters = new RayCounters();
            var s = new double[bands];
            var s2 = new double[bands];
            for (int i = block * 256; i < Math.Min(rays, (block + 1) * 256); i++)
            {
                Array.Clear(result);
                integrator.Radiance(new CameraSample(i % 1024, i / 1024, 0, ray(i)), result, scratch, ref counters);
                for (int b = 0; b < bands; b++) { s[b] += result[b]; s2[b] += (double)result[b] * result[b]; }
            }
            lock (sync)
                for (int b = 0; b < bands; b++) { sum[b] += s[b]; sum2[b] += s2[b]; }
        });
        return [.. Enumerable.Range(0, bands).Select(b =>
        {
            double mean = sum[b] / rays, variance = Math.Max(0, (sum2[b] / rays - mean * mean) * rays / (rays - 1));
            return (mean, Math.Sqrt(variance / rays));
        })];
    }

    /// <summary>A ray from 5 m in front of the origin to a point of the disc of radius 0.9 about it (a Fibonacci spiral).</summary>
    static Ray AtSphere(int i, int n)
    {
        double r = 0.9 * Math.Sqrt((i + 0.5) / n), a = i * 2.399963229728653;
        var target = new Vector3((float)(r * Math.Cos(a)), (float)(r * Math.Sin(a)), 0);
        var origin = new Vector3(0, 0, 5);
        return new Ray(origin, Vector3.Normalize(target - origin));
    }

    static string FurnaceScene(string material) => $$"""
        { "radiometry": "physical", "bands": "400:700:15", "background": { "constant": {{Light(1)}} },
          "integrator": "path",
          "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 2, "height": 2 },
          "materials": { "m": {{material}} },
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] }
        """;

    static ValidationCase Furnace(string name, string title, string material, double albedo, string reference, string source,
        string why) => new()
        {
            Name = name,
            Group = "radiometry",
            Title = title,
            Reference = reference,
            Source = source,
            Tolerance = 0.005,
            ToleranceWhy = why,
            XLabel = "band centre (nm)",
            Quantity = "radiance (W·m⁻²·sr⁻¹·nm⁻¹)",
            Statistical = true,
            Measure = context =>
            {
                var scene = Load(FurnaceScene(material));
                int rays = context.Quick ? 16384 : 65536;
                var l = Radiance(scene, "path", i => AtSphere(i, rays), rays, context);
                return [.. l.Select((v, b) => ValidationPoint.Relative(scene.Grid.Centre(b),
                $"{F(scene.Grid.Centre(b))} nm", albedo, v.Mean, v.Sigma))];
            },
        };

    const string FurnaceWhy = "within 0.5 % and within 3σ of the path tracer's estimate";

    static ValidationCase WhiteFurnace => Furnace("white-furnace",
        "a Lambertian sphere of albedo 0.8 inside a uniform environment of radiance 1: its radiance seen from outside, per band",
        """{ "type": "lambertian", "reflectance": 0.8 }""", 0.8,
        "L = ρ·L_env (a convex Lambertian surface lit by the same radiance from every direction)",
        "the white furnace test (e.g. pbrt-v4 §13.7 / Mitsuba's furnace tests): energy conservation of the BSDF and the estimator",
        FurnaceWhy);

    static ValidationCase FresnelFurnace => Furnace("fresnel-furnace",
        "a smooth non-absorbing glass sphere (n = 1.5) in a uniform environment of radiance 1: its radiance, per band",
        """{ "diffuse": 0, "ambient": 0, "mirror": 1, "transmit": 1, "fresnel": true, "ior": 1.5 }""", 1,
        "L = L_env (Fresnel reflection and refraction lose no energy: R + T = 1 at every interface, the radiance n² in and 1/n² out)",
        "the Fresnel furnace (Born & Wolf §1.5.3: R + T = 1 for a non-absorbing dielectric; Veach 1997 §5.2 for n² and radiance)",
        FurnaceWhy);

    static ValidationCase DispersiveFurnace => Furnace("dispersion-furnace",
        "a smooth N-BK7 sphere (Sellmeier index, split per band) in a uniform environment of radiance 1: its radiance, per band",
        $$"""{ "diffuse": 0, "ambient": 0, "mirror": 1, "transmit": 1, "fresnel": true, "ior": {{Bk7}} }""", 1,
        "L = L_env in every band (each band's own Fresnel factors and refraction: R + T = 1)",
        "Born & Wolf §1.5.3; Schott N-BK7 Sellmeier coefficients", FurnaceWhy);

    static ValidationCase InverseSquare => new()
    {
        Name = "inverse-square",
        Group = "radiometry",
        Title = "a point light of 1 W·sr⁻¹·nm⁻¹ on the normal of a Lambertian plane (ρ = 0.5) at 0.1 m to 100 m: the plane's radiance "
            + "under the Whitted integrator",
        Reference = "L = ρ·I/(π·d²)",
        Source = "the inverse-square law and the Lambertian BRDF ρ/π (CIE S 017:2020 17-21-050, 17-29-057)",
        Tolerance = 1e-5,
        ToleranceWhy = "deterministic: one shadow ray, float32 radiance (7 digits)",
        XLabel = "distance (m, log scale as index)",
        Quantity = "radiance (W·m⁻²·sr⁻¹·nm⁻¹)",
        Measure = context =>
        {
            double[] ds = context.Quick ? [0.1, 1, 10, 100] : [0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100];
            const double rho = 0.5;
            return [.. ds.Select((d, i) =>
            {
                var scene = Load($$"""
                    { "radiometry": "physical", "bands": "400:700:6",
                      "camera": { "position": [0, 0, {{F(d)}}], "look_at": [0, 0, 0], "width": 2, "height": 2 },
                      "lights": [ { "type": "point", "position": [0, 0, {{F(d)}}], "spectrum": { "constant": 1 },
                                    "intensity": {{Light(1)}} } ],
                      "objects": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
                                     "material": { "diffuse": {{F(rho)}}, "ambient": 0 } } ] }
                    """);
                var l = Radiance(scene, "whitted", _ => new Ray(new Vector3(0, 0, (float)d), -Vector3.UnitZ), 1, context);
                return ValidationPoint.Relative(Math.Log10(d), $"{F(d)} m", rho / (Math.PI * d * d), l.Average(v => v.Mean));
            })];
        },
    };

    static readonly (double N, double K)[] Metals = [(1.5, 0), (0.2, 3.0), (0.05, 4.0), (1.0, 5.0), (2.5, 3.5), (1.37, 7.6), (3.0, 0.5)];

    static ValidationCase Conductor => new()
    {
        Name = "conductor-normal",
        Group = "radiometry",
        Title = "smooth conductors of given n + ik seen at normal incidence against an emitter of radiance 1",
        Reference = "R = ((n − 1)² + k²)/((n + 1)² + k²)",
        Source = "the Fresnel equations for an absorbing medium at normal incidence (Born & Wolf §14.2)",
        Tolerance = 1e-5,
        ToleranceWhy = "deterministic: a delta reflection onto the emitter, float32 radiance (7 digits)",
        XLabel = "material (index)",
        Quantity = "reflectance",
        Measure = context =>
        {
            var materials = string.Join(", ", Metals.Select((m, i) =>
                $$"""
                "c{{i}}": { "type": "conductor", "conductor": { "n": { "constant": {{F(m.N)}} }, "k": { "constant": {{F(m.K)}} } } }
                """));
            var objects = string.Concat(Metals.Select((_, i) =>
                $$""", { "type": "quad", "center": [{{2 * i}}, 0, 0], "size": 1, "normal": [0, 1, 0], "up": [0, 0, -1],"""
                    + $$""" "material": "c{{i}}" }"""));
            var scene = Load($$"""
                { "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
                  "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 2, "height": 2 },
                  "materials": { {{materials}},
                    "sky": { "type": "lambertian", "reflectance": 0,
                             "emission": { "spectrum": { "constant": 1 }, "radiance": {{Light(1)}} } } },
                  "objects": [ { "type": "quad", "center": [6, 2, 0], "size": 40, "normal": [0, -1, 0], "up": [0, 0, 1],
                                 "material": "sky" }{{objects}} ] }
                """);
            return [.. Metals.Select((m, i) =>
            {
                var l = Radiance(scene, "path", _ => new Ray(new Vector3(2 * i, 1, 0), -Vector3.UnitY), 1, context);
                double r = ((m.N - 1) * (m.N - 1) + m.K * m.K) / ((m.N + 1) * (m.N + 1) + m.K * m.K);
                return ValidationPoint.Relative(i, $"n {F(m.N)}, k {F(m.K)}", r, l.Average(v => v.Mean));
            })];
        },
    };

    static ValidationCase Snell => new()
    {
        Name = "dispersion-snell",
        Group = "radiometry",
        Title = "a ray at 60° through a 100 m N-BK7 slab onto a 0.3 m emitting stripe below it: each band lands where Snell's law "
            + "and the Sellmeier index put it, transmitted T² of the way",
        Reference = "lateral shift s = t·sin(θ_i − θ_t)/cos θ_t with sin θ_t = sin θ_i/n(λ), n² = 1 + Σ B_i λ²/(λ² − C_i); "
            + "L = T(θ_i, n)²·L_e on the stripe, 0 beside it",
        Source = "Snell's law; Sellmeier's formula with Schott's N-BK7 coefficients; the Fresnel equations (Born & Wolf §1.5)",
        Tolerance = 0.005,
        ToleranceWhy = "within 0.5 % and within 3σ of the path tracer's estimate (the Fresnel lobe is sampled); a band's landing "
            + "misses the stripe's edge by half the bands' spacing (≈ 2 cm of 70 m) if Snell and Sellmeier hold",
        XLabel = "band centre (nm)",
        Quantity = "radiance relative to the emitter's (error relative to T²)",
        Statistical = true,
        Measure = context =>
        {
            const double thick = 100, incidence = 60, gap = 1;   // the stripe 1 m below the slab: beyond any ray offset
            var grid = Spectra.BandGrid.Parse("400:700:16");
            double sinI = Math.Sin(incidence * Math.PI / 180), cosI = Math.Cos(incidence * Math.PI / 180);
            // Where each band leaves the slab's lower face and meets the emitter's plane, x from the entry point.
            var landing = Enumerable.Range(0, grid.Count).Select(b =>
            {
                double n = SellmeierBk7(grid.Centre(b)), sinT = sinI / n, tanT = sinT / Math.Sqrt(1 - sinT * sinT);
                return thick * tanT + gap * sinI / cosI;
            }).ToArray();
            // The stripe spans bands 4 to 11: its edges halfway between neighbouring bands' landings (≥ 1.8 cm from each);
            // the slab no bigger than it must be, so that the rays' offsets from surfaces (1e-5 of the scene's extent) move
            // a landing by a few millimetres only.
            double a = (landing[3] + landing[4]) / 2, b = (landing[11] + landing[12]) / 2, lo = Math.Min(a, b), hi = Math.Max(a, b);
            var scene = Load($$"""
                { "radiometry": "physical", "bands": "400:700:16", "integrator": "path",
                  "camera": { "position": [0, 5, 5], "look_at": [0, 0, 0], "width": 2, "height": 2 },
                  "materials": { "glass": { "diffuse": 0, "ambient": 0, "mirror": 1, "transmit": 1, "fresnel": true, "ior": {{Bk7}} },
                    "stripe": { "type": "lambertian", "reflectance": 0,
                                "emission": { "spectrum": { "constant": 1 }, "radiance": {{Light(1)}} } } },
                  "objects": [ { "type": "box", "center": [100, {{F(-thick / 2)}}, 0], "size": [240, {{F(thick)}}, 2],
                                 "material": "glass" },
                               { "type": "quad", "center": [{{F((lo + hi) / 2)}}, {{F(-thick - gap)}}, 0], "size": [{{F(hi - lo)}}, 1],
                                 "normal": [0, 1, 0], "up": [0, 0, -1], "material": "stripe" } ] }
                """);
            var dir = new Vector3((float)sinI, (float)-cosI, 0);
            var origin = -10 * dir;
            int rays = context.Quick ? 32768 : 131072;
            var l = Radiance(scene, "path", _ => new Ray(origin, dir), rays, context);
            return [.. Enumerable.Range(0, grid.Count).Select(b =>
            {
                double t = 1 - FresnelR(SellmeierBk7(grid.Centre(b)), cosI), lit = b is >= 4 and <= 11 ? 1 : 0;
                string label = $"{F(grid.Centre(b))} nm ({(lit > 0 ? "on" : "beside")} the stripe)";
                return new ValidationPoint(grid.Centre(b), label, lit * t * t, l[b].Mean, (l[b].Mean - lit * t * t) / (t * t),
                    l[b].Sigma / (t * t));
            })];
        },
    };
}
