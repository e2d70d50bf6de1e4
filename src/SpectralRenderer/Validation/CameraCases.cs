using System.Numerics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Validation;

/// <summary>
/// The camera model (Sensor): the lens's cos⁴ fall-off against the render camera's own ray angles, the diffraction-limited
/// Airy pattern and its encircled energy against Bessel functions computed here by their integral, and the EMVA 1288
/// photon-transfer curve of simulated frames against the shot noise of the electrons counted from the radiometry.
/// </summary>
internal static class CameraCases
{
    internal static IEnumerable<ValidationCase> All => [Cos4, Airy, PhotonTransfer];

    static ValidationCase Cos4 => new()
    {
        Name = "cos4-falloff",
        Group = "camera",
        Title = "the relative illumination of a 64 × 48 film with a 60° vertical field, along its diagonal and its edges",
        Reference = "E(θ)/E(0) = cos⁴θ, θ the angle between the render camera's pixel-centre ray and its axis",
        Source = "the cos⁴ law of a thin lens's off-axis irradiance (Slater, Remote Sensing, §5; Kingslake, Optical System Design)",
        Tolerance = 1e-5,
        ToleranceWhy = "deterministic: the camera's float32 ray directions (7 digits)",
        XLabel = "field angle θ (°)",
        Quantity = "relative illumination",
        Measure = _ =>
        {
            const int w = 64, h = 48;
            const float fov = 60;
            var camera = new Camera(new Vector3(0, 0, 10), Vector3.Zero, Vector3.UnitY, fov, w, h, 1);
            var r = Optics.RelativeIllumination(w, h, fov);
            var axis = Vector3.Normalize(-camera.Position);
            var pixels = Enumerable.Range(0, 24).Select(i => (x: 32 + i, y: 24 + i))        // the diagonal
                .Concat(Enumerable.Range(0, 8).Select(i => (x: 8 * i, y: 0)))                 // the top edge
                .Concat(Enumerable.Range(0, 6).Select(i => (x: 63, y: 8 * i)));               // the right edge
            return [.. pixels.Select(p =>
            {
                var d = Vector3.Normalize(camera.Generate(p.x + 0.5f, p.y + 0.5f).Direction);
                double cos = Vector3.Dot(d, axis), theta = Math.Acos(Math.Min(1, cos)) * 180 / Math.PI;
                return ValidationPoint.Relative(theta, $"pixel ({p.x}, {p.y})", Math.Pow(cos, 4), r[p.y * w + p.x]);
            })];
        },
    };

    /// <summary>J_n(x) = (1/π)∫₀^π cos(nτ − x sin τ) dτ (Bessel's integral, DLMF 10.9.2) by the trapezoid rule on 4000
    /// steps — a periodic integrand, so the rule converges spectrally.</summary>
    static double Bessel(int n, double x)
    {
        const int m = 4000;
        double s = 0;
        for (int i = 0; i <= m; i++)
        {
            double tau = Math.PI * i / m, f = Math.Cos(n * tau - x * Math.Sin(tau));
            s += i == 0 || i == m ? f / 2 : f;
        }
        return s / m;
    }

    static ValidationCase Airy => new()
    {
        Name = "airy-kernel",
        Group = "camera",
        Title = "the diffraction-limited point spread at f/2.8 for 450, 550 and 650 nm: its irradiance and encircled energy",
        Reference = "I(r) = π/(4(λN)²)·[2J₁(v)/v]², v = πr/(λN); encircled energy 1 − J₀²(v) − J₁²(v) (J_n by Bessel's integral)",
        Source = "Airy (1835); Born & Wolf §8.5.2 (Rayleigh's encircled energy); DLMF 10.9.2",
        Tolerance = 1e-6,
        ToleranceWhy = "deterministic double precision; the irradiance's error is relative to its peak (it has zeros)",
        XLabel = "radius r/(λN) (+ 0, 10, 20 for 450, 550, 650 nm; encircled energy + 30, 40, 50)",
        Quantity = "irradiance (µm⁻², per unit power) or encircled energy",
        Measure = _ =>
        {
            const double n = 2.8;
            var points = new List<ValidationPoint>();
            double[] lambdas = [450, 550, 650];
            for (int li = 0; li < lambdas.Length; li++)
            {
                double lambda = lambdas[li], ln = lambda * 1e-3 * n, peak = Math.PI / (4 * ln * ln);
                for (int i = 0; i <= 40; i++)
                {
                    double k = 0.1 * i, v = Math.PI * k, j1 = Bessel(1, v);
                    double expected = i == 0 ? peak : peak * Math.Pow(2 * j1 / v, 2), measured = Optics.Airy(k * ln, lambda, n);
                    points.Add(new ValidationPoint(10 * li + k, $"{lambda} nm, r = {k:0.0} λN", expected, measured,
                        (measured - expected) / peak, null));
                }
                for (int i = 1; i <= 10; i++)
                {
                    double k = 0.5 * i, v = Math.PI * k, j0 = Bessel(0, v), j1 = Bessel(1, v);
                    points.Add(ValidationPoint.Relative(30 + 10 * li + k, $"{lambda} nm, energy within {k:0.0} λN",
                        1 - j0 * j0 - j1 * j1, Optics.EncircledEnergy(k * ln, lambda, n)));
                }
            }
            return points;
        },
    };

    static ValidationCase PhotonTransfer => new()
    {
        Name = "emva1288-ptc",
        Group = "camera",
        Title = "the photon-transfer curve of simulated 64 × 64 frames (the isetcam sensor, 500–600 nm, 5 % to 55 % of the full well)",
        Reference = "σ²_y − σ²_y,dark = K²·μ_e with μ_e = ė·t and ė = L·A·ff·πT/(1 + 4N²)·∫λ/(hc) dλ (shot noise of the "
            + "electrons counted from the radiometry; σ²_y = var(A − B)/2 cancels PRNU and DSNU)",
        Source = "EMVA Standard 1288 release 4.0 (photon transfer); Janesick, Photon Transfer (SPIE 2007)",
        Tolerance = 0.03,
        ToleranceWhy = "within 3 % and within 3σ: the temporal variance of 2 × 64 × 64 pixels × pairs has a relative standard error "
            + "√(2/n) (≈ 0.8 % for 8 pairs)",
        XLabel = "mean electrons μ_e",
        Quantity = "temporal variance (DN²)",
        Statistical = true,
        Measure = context =>
        {
            const int size = 64;
            int pairs = context.Quick ? 4 : 16;
            const double radiance = 0.05;
            var grid = new BandGrid(500, 600, 1);
            var flat = TabulatedSpectrum.Constant(1);
            SensorModel Sensor(double? t) => SensorPresets.Get("isetcam") with
            {
                PrnuPercent = 1,
                DsnuVolts = 1e-3,
                AnalogGain = 0.8,
                BlackLevel = 64,
                ExposureSeconds = t,
            };
            var s0 = Sensor(null);
            double etendue = Math.Pow(s0.PixelSizeMicrons * 1e-6, 2) * s0.FillFactor * Math.PI * s0.OpticsTransmittance
                / (1 + 4 * s0.FNumber * s0.FNumber);
            double rate = radiance * etendue * (600.0 * 600 - 500.0 * 500) / 2 * 1e-9 / (6.62607015e-34 * 299792458);
            double tSat = s0.FullWellElectrons / rate, k = s0.SystemGain;
            (double Mean, double Variance) Stats(SensorModel s, double l, ulong seed)
            {
                double mean = 0, variance = 0;
                for (int p = 0; p < pairs; p++)
                {
                    var data = new float[size * size];
                    Array.Fill(data, (float)(l * Perturbation.LightScale));
                    var cube = new RadianceCube(size, size, grid, data, 1);
                    var a = SensorSimulation.Run(s, cube, flat, new SimulationOptions { Seed = seed + 2 * (ulong)p }).Dn;
                    var b = SensorSimulation.Run(s, cube, flat, new SimulationOptions { Seed = seed + 2 * (ulong)p + 1 }).Dn;
                    double m = 0, d = 0, dd = 0;
                    for (int i = 0; i < a.Length; i++) { m += a[i] + b[i]; double x = a[i] - b[i]; d += x; dd += x * x; }
                    mean += m / (2 * a.Length);
                    variance += (dd - d * d / a.Length) / (a.Length - 1) / 2;
                }
                return (mean / pairs, variance / pairs);
            }
            var points = new List<ValidationPoint>();
            for (int level = 0; level < 6; level++)
            {
                double t = tSat * (0.05 + 0.1 * level), electrons = rate * t;
                var s = Sensor(t);
                var (_, v) = Stats(s, radiance, 1000 + 100 * (ulong)level);
                var (_, vd) = Stats(s, 0, 5000 + 100 * (ulong)level);
                double expected = k * k * electrons, n = 2.0 * size * size * pairs;
                // The variance of a variance estimate: 2σ⁴/n for each of the light and dark terms.
                double sigma = Math.Sqrt(2 * (v * v + vd * vd) / n);
                points.Add(ValidationPoint.Relative(electrons, $"{0.05 + 0.1 * level:P0} of the full well", expected, v - vd, sigma));
            }
            return points;
        },
    };
}
